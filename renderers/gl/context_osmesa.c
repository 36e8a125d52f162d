/* OSMesa backend (compiled only when meson found OSMesa; config.h's HAVE_OSMESA).
 * OSMesa renders into a client buffer; we hand it a tiny one to make the context
 * current and render into the context's own framebuffer object instead.
 *
 * No GL or EGL types may come in here from elsewhere: <GL/osmesa.h> includes
 * <GL/gl.h>, which does not mix with <GL/glcorearb.h>. */
#include "renderers/gl/context_internal.h"
#include "renderers/gl/loader.h"

#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { OSMESA_BUFFER_SIZE = 4 };   /* width and height of the client buffer */

typedef struct osmesa_state {
    OSMesaContext ctx;
    unsigned char buffer[OSMESA_BUFFER_SIZE * OSMESA_BUFFER_SIZE * 4];
} osmesa_state;

/* OSMesaGetProcAddress as a void * (gl_proc_pointer). */
static void *osmesa_getproc(const char *name)
{
    return gl_proc_pointer(OSMesaGetProcAddress(name));
}

void gl_osmesa_close(void *native)
{
    osmesa_state *s = native;
    if (!s)
        return;
    if (s->ctx) {
        if (OSMesaGetCurrentContext() == s->ctx)
            OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
        OSMesaDestroyContext(s->ctx);
    }
    free(s);
}

/* OSMesa has no debug flag: a debug context here is a core context with
 * GL_DEBUG_OUTPUT enabled (context.c does that), and gl_info.debug_context says
 * that CONTEXT_FLAGS lacks the debug bit. */
bool gl_osmesa_open(gl_context *ctx, char *err, size_t errlen)
{
    /* 4.5 core first, then older core versions down to 3.3 (Mesa answers any
     * request with the highest version it has at or above the one asked for). */
    static const int versions[][2] = {{4, 5}, {4, 4}, {4, 3}, {4, 2}, {4, 1}, {4, 0}, {3, 3}};
    osmesa_state *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(err, errlen, "out of memory");
        return false;
    }
    for (size_t i = 0; i < sizeof versions / sizeof versions[0] && !s->ctx; i++) {
        const int attribs[] = {
            OSMESA_FORMAT, OSMESA_RGBA,
            OSMESA_DEPTH_BITS, 0,
            OSMESA_STENCIL_BITS, 0,
            OSMESA_ACCUM_BITS, 0,
            OSMESA_PROFILE, OSMESA_CORE_PROFILE,
            OSMESA_CONTEXT_MAJOR_VERSION, versions[i][0],
            OSMESA_CONTEXT_MINOR_VERSION, versions[i][1],
            0,
        };
        s->ctx = OSMesaCreateContextAttribs(attribs, NULL);
    }
    if (!s->ctx) {
        snprintf(err, errlen, "OSMesa: OSMesaCreateContextAttribs failed: "
                              "no core profile context of GL 3.3 or later");
        goto fail;
    }
    if (!OSMesaMakeCurrent(s->ctx, s->buffer, GL_UNSIGNED_BYTE, OSMESA_BUFFER_SIZE,
                           OSMESA_BUFFER_SIZE)) {
        snprintf(err, errlen, "OSMesa: OSMesaMakeCurrent failed");
        goto fail;
    }
    ctx->native = s;
    ctx->native_close = gl_osmesa_close;
    ctx->getproc = osmesa_getproc;
    ctx->info.backend = "osmesa";
    ctx->info.device[0] = '\0';
    return true;

fail:
    gl_osmesa_close(s);
    return false;
}
