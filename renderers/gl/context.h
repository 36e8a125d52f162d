#pragma once
/* Headless GL 4.5 core contexts: EGL (Mesa surfaceless by default, or an EGL device
 * by index) and OSMesa. Creating a context also loads the GL function table
 * (loader.h) and creates the run's off-screen framebuffer (RGBA8 colour +
 * depth24-stencil8 renderbuffers) at width x height, left bound. One context is
 * current per process at a time. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

typedef enum gl_backend { GL_BACKEND_EGL = 0, GL_BACKEND_OSMESA } gl_backend;

typedef struct gl_context_desc {
    gl_backend backend;
    int device;          /* EGL only: -1 = Mesa surfaceless platform; N >= 0 = EGL device N */
    bool debug;          /* debug context: KHR_debug callback, synchronous, every GL error counted */
    int width, height;   /* the off-screen framebuffer; 0x0 = none (for `info`) */
} gl_context_desc;

typedef struct gl_info {
    const char *backend;          /* "egl-surfaceless", "egl-device", "osmesa" */
    char device[256];             /* EGL device name / extension string, or "" */
    char vendor[128], renderer[256], version[256], glsl_version[128];
    int max_draw_buffers, max_color_attachments, max_samples;
    int max_uniform_block_size, max_texture_size, max_renderbuffer_size;
    int max_viewport_dims[2];
    bool timer_query;             /* GL_ARB_timer_query or GL >= 3.3 */
    bool pipeline_statistics;     /* GL_ARB_pipeline_statistics_query */
    bool debug_context;           /* CONTEXT_FLAG_DEBUG_BIT is set */
} gl_info;

typedef struct gl_context gl_context;

/* NULL on failure with a message in err (no EGL display, no GL 4.5, size beyond
 * the context's limits, ...). */
gl_context *gl_context_create(const gl_context_desc *desc, char *err, size_t errlen);
void gl_context_destroy(gl_context *ctx);   /* NULL is fine */

const gl_info *gl_context_info(const gl_context *ctx);
unsigned gl_context_framebuffer(const gl_context *ctx);   /* the off-screen FBO name */
/* Binds the off-screen framebuffer again (after a renderer made or bound its own). */
void gl_context_bind_default(const gl_context *ctx);
/* Waits until the GPU has finished every command issued so far: glFinish (fence
 * false), or a fence waited on in 0.1 s steps for at most timeout_s. False with a
 * message when the fence fails or the commands are not done in time. */
bool gl_context_sync(bool fence, double timeout_s, char *err, size_t errlen);

/* GL errors seen so far: through the debug callback (debug contexts) plus those
 * found by gl_context_poll_errors(). Each is also printed as "GL error: ..." on stderr. */
uint64_t gl_context_error_count(const gl_context *ctx);
/* Drains glGetError(); returns the number of errors found, printing each with `where`. */
unsigned gl_context_poll_errors(gl_context *ctx, const char *where);

/* Reads the off-screen framebuffer's colour as RGBA8, row 0 at the top. */
bool gl_context_read_rgba8(gl_context *ctx, uint8_t *pixels, char *err, size_t errlen);

/* Number of EGL devices (EGL_EXT_device_enumeration), or -1 with a message. */
int gl_egl_device_count(char *err, size_t errlen);

/* Prints `info` output (one "key: value" per line) for ctx. */
void gl_context_print_info(const gl_context *ctx, FILE *out);

/* A second off-screen framebuffer like the context's (RGBA8 colour + depth24-stencil8
 * renderbuffers) at width x height: the supersampled error reference's output
 * (error.reference.supersample). The size is checked against the limits the context's
 * own framebuffer is checked against, with the same message; created, it is left bound
 * as the draw and read framebuffer. gl_offscreen_destroy on a zeroed one is fine. */
typedef struct gl_offscreen {
    unsigned fbo, color_rb, depth_stencil_rb;
    int width, height;
} gl_offscreen;
bool gl_offscreen_create(gl_context *ctx, int width, int height, gl_offscreen *out, char *err,
                         size_t errlen);
void gl_offscreen_destroy(gl_offscreen *o);
