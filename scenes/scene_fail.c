/* See scenes/scene_fail.h. */
#include "scenes/scene_fail.h"

#include <stdarg.h>
#include <stdio.h>

bool scene_fail(char *err, size_t errlen, const char *fmt, ...)
{
    if (!err || !errlen)
        return false;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
    return false;
}
