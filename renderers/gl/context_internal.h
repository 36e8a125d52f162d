#pragma once
/* Private to renderers/gl/context*.c: the context object and the backends' entry
 * points. No GL or EGL header here: context_osmesa.c includes <GL/osmesa.h>,
 * which pulls in <GL/gl.h>, and that does not mix with <GL/glcorearb.h>. */
#include "config.h"
#include "renderers/gl/context.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct gl_context {
    gl_backend backend;
    bool debug_requested;           /* desc->debug or SHADESWEEP_GL_DEBUG */

    /* Filled by the backend's open function. */
    void *native;                   /* the backend's own state */
    void (*native_close)(void *native);
    void *(*getproc)(const char *name);

    bool loaded;                    /* gl_load() filled the table for this context */
    gl_info info;
    int gl_major, gl_minor;         /* GL_MAJOR_VERSION, GL_MINOR_VERSION */
    bool debug_output;              /* our callback is installed */
    uint64_t errors;                /* every GL error counted once */
    uint64_t callback_errors;       /* of which the callback reported ... */
    uint64_t callback_errors_polled;/* ... and those a poll has accounted for */

    int width, height;
    unsigned fbo, color_rb, depth_stencil_rb;
};

/* Backends. open creates a context of at least GL 3.3 core (4.5 core for EGL),
 * with the debug flag when ctx->debug_requested (where the backend can), makes it
 * current, and sets ctx->native, native_close, getproc, info.backend and
 * info.device. On failure nothing is left behind and err says why. */
bool gl_egl_open(gl_context *ctx, int device, char *err, size_t errlen);
void gl_egl_close(void *native);
#if HAVE_OSMESA
bool gl_osmesa_open(gl_context *ctx, char *err, size_t errlen);
void gl_osmesa_close(void *native);
#endif
