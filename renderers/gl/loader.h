#pragma once
/* The OpenGL function table. Every function the program calls is listed once in
 * gl_funcs.h; this header turns the list into struct gl_api, one function pointer
 * per entry, named like the GL function without its "gl" prefix:
 *
 *     gl.Clear(GL_COLOR_BUFFER_BIT);
 *
 * Types and enums come from <GL/glcorearb.h>. Nothing links libGL: the table is
 * filled by gl_load() through the GetProcAddress of the backend that created the
 * current context (context.c does this when it creates a context, and clears the
 * table when it destroys it). One context is current per process, so one table. */
#include <GL/glcorearb.h>
#include <stdbool.h>
#include <stddef.h>
#include <string.h>

struct gl_api {
#define GL_FUNC(ret, name, params) ret (APIENTRY *name) params;
#include "renderers/gl/gl_funcs.h"
#undef GL_FUNC
};

extern struct gl_api gl;

/* Resolves every entry of gl_funcs.h as "gl" + name through getproc
 * (eglGetProcAddress or OSMesaGetProcAddress, wrapped to this signature).
 * On failure the table is left all NULL and err names the first missing
 * function: "GL: glDrawBuffers not found by the backend's GetProcAddress".
 * Note that a NULL-free table does not prove the context supports every entry:
 * Mesa (and glvnd) hand out dispatch stubs for any "gl*" name. Check the
 * context's version or extensions before calling anything beyond it. */
bool gl_load(void *(*getproc)(const char *name), char *err, size_t errlen);

/* An entry point that eglGetProcAddress or OSMesaGetProcAddress returned, as the void *
 * a getproc gives gl_load: ISO C converts no function pointer to an object pointer, so
 * the bytes are copied (POSIX guarantees both have the same representation). */
static inline void *gl_proc_pointer(void (*f)(void))
{
    void *p;
    _Static_assert(sizeof p == sizeof f, "function and object pointers differ in size");
    memcpy(&p, &f, sizeof p);
    return p;
}

/* Clears the table (every member NULL), so that a call after the context is
 * gone fails loudly instead of dispatching into a dead context. */
void gl_unload(void);

/* Number of entries in gl_funcs.h (the members of struct gl_api). */
size_t gl_func_count(void);
