/* Fills the GL function table (loader.h) from gl_funcs.h. */
#include "renderers/gl/loader.h"

#include <stdio.h>
#include <string.h>

struct gl_api gl;

/* GetProcAddress hands back object pointers here (void *); POSIX guarantees that
 * they convert to function pointers losslessly, which these asserts check. */
_Static_assert(sizeof(void *) == sizeof(void (*)(void)),
               "function and object pointers differ in size");

bool gl_load(void *(*getproc)(const char *name), char *err, size_t errlen)
{
    struct gl_api api;
    memset(&api, 0, sizeof api);
    void *p;

#define GL_FUNC(ret, name, params)                                                        \
    p = getproc("gl" #name);                                                              \
    if (!p) {                                                                             \
        snprintf(err, errlen, "GL: gl%s not found by the backend's GetProcAddress", #name); \
        goto fail;                                                                        \
    }                                                                                     \
    memcpy(&api.name, &p, sizeof api.name);
#include "renderers/gl/gl_funcs.h"
#undef GL_FUNC

    gl = api;
    return true;

fail:
    gl_unload();
    return false;
}

void gl_unload(void)
{
    memset(&gl, 0, sizeof gl);
}

size_t gl_func_count(void)
{
    return 0
#define GL_FUNC(ret, name, params) + 1
#include "renderers/gl/gl_funcs.h"
#undef GL_FUNC
        ;
}
