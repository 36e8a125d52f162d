#include "common/grow.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

bool grow_array(void *pp, size_t *cap, size_t need, size_t elem_size, size_t first)
{
    if (need <= *cap)
        return true;
    size_t n = *cap ? *cap : (first ? first : 1);
    while (n < need) {
        if (n > SIZE_MAX / 2)
            return false;
        n *= 2;
    }
    if (elem_size && n > SIZE_MAX / elem_size)
        return false;
    /* *pp is a pointer to some object type: read and written through memcpy, so that
     * any T ** may be passed (all object pointers share one representation here) */
    void *old;
    memcpy(&old, pp, sizeof old);
    void *p = realloc(old, n * elem_size);
    if (!p)
        return false;
    memcpy(pp, &p, sizeof p);
    *cap = n;
    return true;
}
