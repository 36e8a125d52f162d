/* Headless GL contexts (context.h): what every backend shares. The backends
 * (context_egl.c, context_osmesa.c) create a context and make it current; this
 * file loads the GL table, fills gl_info, sets up debug output, checks the
 * requested size against the context's limits and creates the off-screen
 * framebuffer.
 *
 * Debug contexts: desc->debug, or the environment variable SHADESWEEP_GL_DEBUG
 * set to anything but "" or "0" (the test suite sets SHADESWEEP_GL_DEBUG=1, so
 * that every GL error in a test is seen). A debug context enables GL_DEBUG_OUTPUT
 * and GL_DEBUG_OUTPUT_SYNCHRONOUS and installs a callback that counts each
 * message of type GL_DEBUG_TYPE_ERROR in gl_context_error_count() and prints it
 * as "GL error: <source> <id>: <message>" on stderr; every other message type is
 * disabled (stderr stays quiet). On EGL the context must carry
 * GL_CONTEXT_FLAG_DEBUG_BIT; OSMesa has no way to ask for it, so there debug
 * output is enabled on a plain core context and gl_info.debug_context is false. */
#include "renderers/gl/context_internal.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/target.h"

#include <inttypes.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

// >>errors

static const char *gl_error_name(GLenum e)
{
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
    default: return "unknown GL error";
    }
}

static const char *debug_source_name(GLenum source)
{
    switch (source) {
    case GL_DEBUG_SOURCE_API: return "API";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window-system";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader-compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third-party";
    case GL_DEBUG_SOURCE_APPLICATION: return "application";
    default: return "other";
    }
}

/* Synchronous debug output: runs on the thread whose GL call raised the message. */
static void APIENTRY debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity,
                                    GLsizei length, const GLchar *message, const void *user)
{
    (void)severity;
    (void)length;   /* the message is NUL-terminated as well */
    if (type != GL_DEBUG_TYPE_ERROR)
        return;
    /* The pointer we registered: our own, non-const context. */
    gl_context *ctx = (gl_context *)user;
    ctx->errors++;
    ctx->callback_errors++;
    fprintf(stderr, "GL error: %s %u: %s\n", debug_source_name(source), (unsigned)id,
            message ? message : "(no message)");
}

uint64_t gl_context_error_count(const gl_context *ctx)
{
    return ctx ? ctx->errors : 0;
}

/* Every error is counted once. With our debug callback installed it has already
 * counted and printed the errors that glGetError() now returns (the error flags
 * are still set after a callback), so the poll only drains them and reports how
 * many the callback saw since the last poll; errors the callback never saw are
 * counted and printed here. */
unsigned gl_context_poll_errors(gl_context *ctx, const char *where)
{
    if (!ctx || !gl.GetError)
        return 0;
    GLenum codes[16];
    unsigned ncodes = 0;
    /* Bounded: a lost context may return GL_CONTEXT_LOST forever. */
    for (unsigned i = 0; i < 64; i++) {
        GLenum e = gl.GetError();
        if (e == GL_NO_ERROR)
            break;
        if (ncodes < sizeof codes / sizeof codes[0])
            codes[ncodes++] = e;
        if (e == GL_CONTEXT_LOST)
            break;
    }
    uint64_t seen = ctx->callback_errors - ctx->callback_errors_polled;
    ctx->callback_errors_polled = ctx->callback_errors;
    if (seen > 0) {
        fprintf(stderr, "GL error: %" PRIu64 " error%s above found by the check at %s\n", seen,
                seen == 1 ? "" : "s", where ? where : "?");
        return seen > UINT_MAX ? UINT_MAX : (unsigned)seen;
    }
    for (unsigned i = 0; i < ncodes; i++)
        fprintf(stderr, "GL error: %s (0x%04x) at %s\n", gl_error_name(codes[i]),
                (unsigned)codes[i], where ? where : "?");
    ctx->errors += ncodes;
    return ncodes;
}

// >>info

static void copy_gl_string(GLenum name, char *out, size_t outlen)
{
    const GLubyte *s = gl.GetString(name);
    snprintf(out, outlen, "%s", s ? (const char *)s : "");
}

typedef struct gl_extensions {
    bool arb_timer_query, arb_pipeline_statistics_query, khr_debug;
} gl_extensions;

static void scan_extensions(gl_extensions *out)
{
    memset(out, 0, sizeof *out);
    GLint n = 0;
    gl.GetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++) {
        const char *e = (const char *)gl.GetStringi(GL_EXTENSIONS, (GLuint)i);
        if (!e)
            continue;
        if (strcmp(e, "GL_ARB_timer_query") == 0)
            out->arb_timer_query = true;
        else if (strcmp(e, "GL_ARB_pipeline_statistics_query") == 0)
            out->arb_pipeline_statistics_query = true;
        else if (strcmp(e, "GL_KHR_debug") == 0)
            out->khr_debug = true;
    }
}

static bool version_at_least(const gl_context *ctx, int major, int minor)
{
    return ctx->gl_major > major || (ctx->gl_major == major && ctx->gl_minor >= minor);
}

static void fill_info(gl_context *ctx, const gl_extensions *ext)
{
    gl_info *info = &ctx->info;
    copy_gl_string(GL_VENDOR, info->vendor, sizeof info->vendor);
    copy_gl_string(GL_RENDERER, info->renderer, sizeof info->renderer);
    copy_gl_string(GL_VERSION, info->version, sizeof info->version);
    copy_gl_string(GL_SHADING_LANGUAGE_VERSION, info->glsl_version, sizeof info->glsl_version);
    gl.GetIntegerv(GL_MAX_DRAW_BUFFERS, &info->max_draw_buffers);
    gl.GetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &info->max_color_attachments);
    gl.GetIntegerv(GL_MAX_SAMPLES, &info->max_samples);
    GLint64 ubo = 0;
    gl.GetInteger64v(GL_MAX_UNIFORM_BLOCK_SIZE, &ubo);
    info->max_uniform_block_size = ubo > INT_MAX ? INT_MAX : (int)ubo;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &info->max_texture_size);
    gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &info->max_renderbuffer_size);
    gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, info->max_viewport_dims);
    info->timer_query = version_at_least(ctx, 3, 3) || ext->arb_timer_query;
    info->pipeline_statistics = ext->arb_pipeline_statistics_query;
    GLint flags = 0;
    gl.GetIntegerv(GL_CONTEXT_FLAGS, &flags);
    info->debug_context = (flags & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;
}

static bool setup_debug_output(gl_context *ctx, const gl_extensions *ext, char *err,
                               size_t errlen)
{
    if (!version_at_least(ctx, 4, 3) && !ext->khr_debug) {
        snprintf(err, errlen, "GL: debug output needs GL 4.3 or GL_KHR_debug; this is GL %d.%d",
                 ctx->gl_major, ctx->gl_minor);
        return false;
    }
    if (ctx->backend == GL_BACKEND_EGL && !ctx->info.debug_context) {
        snprintf(err, errlen, "GL: a debug context was requested, but GL_CONTEXT_FLAGS lacks "
                              "GL_CONTEXT_FLAG_DEBUG_BIT");
        return false;
    }
    gl.Enable(GL_DEBUG_OUTPUT);
    gl.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    gl.DebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, NULL, GL_FALSE);
    gl.DebugMessageControl(GL_DONT_CARE, GL_DEBUG_TYPE_ERROR, GL_DONT_CARE, 0, NULL, GL_TRUE);
    gl.DebugMessageCallback(debug_callback, ctx);
    ctx->debug_output = true;
    return true;
}

// >>framebuffer

static bool check_limit(int width, int height, int size, int limit, const char *what,
                        char *err, size_t errlen)
{
    if (size <= limit)
        return true;
    snprintf(err, errlen, "resolution %dx%d exceeds this context's limit of %d (%s)", width,
             height, limit, what);
    return false;
}

static bool check_size(const gl_context *ctx, int w, int h, char *err, size_t errlen)
{
    const gl_info *i = &ctx->info;
    int longer = w > h ? w : h;
    return check_limit(w, h, longer, i->max_renderbuffer_size, "GL_MAX_RENDERBUFFER_SIZE", err,
                       errlen) &&
           check_limit(w, h, longer, i->max_texture_size, "GL_MAX_TEXTURE_SIZE", err, errlen) &&
           check_limit(w, h, w, i->max_viewport_dims[0], "GL_MAX_VIEWPORT_DIMS", err, errlen) &&
           check_limit(w, h, h, i->max_viewport_dims[1], "GL_MAX_VIEWPORT_DIMS", err, errlen);
}

/* glCheckFramebufferStatus's result for a message. */
static const char *framebuffer_status_name(GLenum s)
{
    return gl_framebuffer_status_name(s, "error in glCheckFramebufferStatus", "unknown status");
}

static void label(const gl_context *ctx, GLenum kind, GLuint name, const char *text)
{
    if (ctx->debug_output)
        gl.ObjectLabel(kind, name, -1, text);
}

/* An RGBA8 colour and a depth24-stencil8 renderbuffer of w x h attached to a new
 * framebuffer, left bound as both draw and read framebuffer, reading and drawing colour
 * 0. Labelled "shadesweep WHO colour (RGBA8)", "shadesweep WHO depth-stencil" and
 * fbo_label; messages name it "the WxH WHAT framebuffer". */
static bool renderbuffer_framebuffer(gl_context *ctx, int w, int h, const char *who,
                                     const char *fbo_label, const char *what, GLuint *color,
                                     GLuint *depth_stencil, GLuint *fbo, char *err,
                                     size_t errlen)
{
    char text[96];
    gl.GenRenderbuffers(1, color);
    gl.BindRenderbuffer(GL_RENDERBUFFER, *color);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    snprintf(text, sizeof text, "shadesweep %s colour (RGBA8)", who);
    label(ctx, GL_RENDERBUFFER, *color, text);
    gl.GenRenderbuffers(1, depth_stencil);
    gl.BindRenderbuffer(GL_RENDERBUFFER, *depth_stencil);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, w, h);
    snprintf(text, sizeof text, "shadesweep %s depth-stencil", who);
    label(ctx, GL_RENDERBUFFER, *depth_stencil, text);
    gl.BindRenderbuffer(GL_RENDERBUFFER, 0);

    gl.GenFramebuffers(1, fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, *fbo);
    label(ctx, GL_FRAMEBUFFER, *fbo, fbo_label);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, *color);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                               *depth_stencil);
    snprintf(text, sizeof text, "creating the %s framebuffer", what);
    if (gl_context_poll_errors(ctx, text) > 0) {
        snprintf(err, errlen, "GL: creating the %dx%d %s framebuffer raised GL errors", w, h,
                 what);
        return false;
    }
    GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(err, errlen, "GL: the %dx%d %s framebuffer is incomplete (%s)", w, h, what,
                 framebuffer_status_name(status));
        return false;
    }
    /* GL_FRAMEBUFFER bound it as both the draw and the read framebuffer. */
    gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    return true;
}

static bool create_framebuffer(gl_context *ctx, char *err, size_t errlen)
{
    int w = ctx->width, h = ctx->height;
    if (!renderbuffer_framebuffer(ctx, w, h, "output", "shadesweep output", "off-screen",
                                  &ctx->color_rb, &ctx->depth_stencil_rb, &ctx->fbo, err,
                                  errlen))
        return false;
    gl.Viewport(0, 0, w, h);
    return true;
}

// >>create

static bool debug_forced_by_env(void)
{
    const char *v = getenv("SHADESWEEP_GL_DEBUG");
    return v && v[0] != '\0' && strcmp(v, "0") != 0;
}

gl_context *gl_context_create(const gl_context_desc *desc, char *err, size_t errlen)
{
    if (desc->width < 0 || desc->height < 0 || (desc->width == 0) != (desc->height == 0)) {
        snprintf(err, errlen, "resolution %dx%d is invalid (both positive, or 0x0 for no "
                              "framebuffer)", desc->width, desc->height);
        return NULL;
    }
    gl_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    ctx->backend = desc->backend;
    ctx->debug_requested = desc->debug || debug_forced_by_env();
    ctx->width = desc->width;
    ctx->height = desc->height;

    bool opened = false;
    switch (desc->backend) {
    case GL_BACKEND_EGL:
        opened = gl_egl_open(ctx, desc->device, err, errlen);
        break;
    case GL_BACKEND_OSMESA:
#if HAVE_OSMESA
        opened = gl_osmesa_open(ctx, err, errlen);
#else
        snprintf(err, errlen, "OSMesa: this build has no OSMesa backend "
                              "(OSMesa was not found when it was configured)");
#endif
        break;
    default:
        snprintf(err, errlen, "bug: unknown GL backend %d", (int)desc->backend);
        break;
    }
    if (!opened)
        goto fail;
    if (!gl_load(ctx->getproc, err, errlen))
        goto fail;
    ctx->loaded = true;

    gl.GetIntegerv(GL_MAJOR_VERSION, &ctx->gl_major);
    gl.GetIntegerv(GL_MINOR_VERSION, &ctx->gl_minor);
    int need_major = ctx->backend == GL_BACKEND_EGL ? 4 : 3;
    int need_minor = ctx->backend == GL_BACKEND_EGL ? 5 : 3;
    if (!version_at_least(ctx, need_major, need_minor)) {
        snprintf(err, errlen, "GL: the context is GL %d.%d; %d.%d core is needed", ctx->gl_major,
                 ctx->gl_minor, need_major, need_minor);
        goto fail;
    }
    gl_extensions ext;
    scan_extensions(&ext);
    fill_info(ctx, &ext);
    if (ctx->debug_requested && !setup_debug_output(ctx, &ext, err, errlen))
        goto fail;
    if (gl_context_poll_errors(ctx, "context creation") > 0) {
        snprintf(err, errlen, "GL: setting up the context raised GL errors");
        goto fail;
    }
    if (ctx->width > 0) {
        if (!check_size(ctx, ctx->width, ctx->height, err, errlen))
            goto fail;
        if (!create_framebuffer(ctx, err, errlen))
            goto fail;
    }
    return ctx;

fail:
    gl_context_destroy(ctx);
    return NULL;
}

void gl_context_destroy(gl_context *ctx)
{
    if (!ctx)
        return;
    /* The table belongs to this context while it is current (one at a time). A
     * context whose creation failed before loading it leaves it alone. */
    if (ctx->loaded) {
        if (ctx->fbo) {
            gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
            gl.DeleteFramebuffers(1, &ctx->fbo);
        }
        if (ctx->color_rb)
            gl.DeleteRenderbuffers(1, &ctx->color_rb);
        if (ctx->depth_stencil_rb)
            gl.DeleteRenderbuffers(1, &ctx->depth_stencil_rb);
        if (ctx->debug_output) {
            gl.Disable(GL_DEBUG_OUTPUT);
            gl.DebugMessageCallback(NULL, NULL);
        }
        gl.Finish();
        gl_unload();
    }
    if (ctx->native_close)
        ctx->native_close(ctx->native);
    free(ctx);
}

// >>accessors

const gl_info *gl_context_info(const gl_context *ctx)
{
    return &ctx->info;
}

unsigned gl_context_framebuffer(const gl_context *ctx)
{
    return ctx->fbo;
}

void gl_context_bind_default(const gl_context *ctx)
{
    gl.BindFramebuffer(GL_FRAMEBUFFER, ctx->fbo);
}

// >>sync

static double monotonic_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

bool gl_context_sync(bool fence, double timeout_s, char *err, size_t errlen)
{
    if (!fence) {
        gl.Finish();
        return true;
    }
    GLsync f = gl.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!f) {
        snprintf(err, errlen, "glFenceSync failed");
        return false;
    }
    double t0 = monotonic_s();
    GLenum res;
    do {
        res = gl.ClientWaitSync(f, GL_SYNC_FLUSH_COMMANDS_BIT, 100000000u /* 0.1 s */);
    } while (res == GL_TIMEOUT_EXPIRED && monotonic_s() - t0 < timeout_s);
    gl.DeleteSync(f);
    if (res == GL_TIMEOUT_EXPIRED) {
        snprintf(err, errlen, "frame not finished after %.0f s", timeout_s);
        return false;
    }
    if (res == GL_WAIT_FAILED) {
        snprintf(err, errlen, "glClientWaitSync failed");
        return false;
    }
    return true;
}

// >>readback

bool gl_context_read_rgba8(gl_context *ctx, uint8_t *pixels, char *err, size_t errlen)
{
    if (!ctx->fbo) {
        snprintf(err, errlen, "GL: the context has no off-screen framebuffer to read "
                              "(it was created at 0x0)");
        return false;
    }
    size_t w = (size_t)ctx->width, h = (size_t)ctx->height;
    if (w > SIZE_MAX / 4 / h) {
        snprintf(err, errlen, "GL: a %zux%zu RGBA8 image does not fit in memory", w, h);
        return false;
    }
    size_t row = w * 4;
    uint8_t *tmp = malloc(row);
    if (!tmp) {
        snprintf(err, errlen, "out of memory");
        return false;
    }

    /* Read the output framebuffer whatever the renderer left bound, into client
     * memory, tightly packed; then put things back as they were. */
    GLint read_fbo = 0, pack_buffer = 0, alignment = 4, row_length = 0, skip_rows = 0,
          skip_pixels = 0;
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fbo);
    gl.GetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer);
    gl.GetIntegerv(GL_PACK_ALIGNMENT, &alignment);
    gl.GetIntegerv(GL_PACK_ROW_LENGTH, &row_length);
    gl.GetIntegerv(GL_PACK_SKIP_ROWS, &skip_rows);
    gl.GetIntegerv(GL_PACK_SKIP_PIXELS, &skip_pixels);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, ctx->fbo);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    gl.PixelStorei(GL_PACK_SKIP_ROWS, 0);
    gl.PixelStorei(GL_PACK_SKIP_PIXELS, 0);
    gl.ReadPixels(0, 0, ctx->width, ctx->height, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    gl.PixelStorei(GL_PACK_ALIGNMENT, alignment);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, row_length);
    gl.PixelStorei(GL_PACK_SKIP_ROWS, skip_rows);
    gl.PixelStorei(GL_PACK_SKIP_PIXELS, skip_pixels);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, (GLuint)pack_buffer);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)read_fbo);

    bool ok = gl_context_poll_errors(ctx, "gl_context_read_rgba8") == 0;
    if (!ok) {
        snprintf(err, errlen, "GL: glReadPixels of the %zux%zu framebuffer raised GL errors", w,
                 h);
        goto done;
    }
    /* GL's row 0 is the bottom one. */
    for (size_t top = 0, bottom = h - 1; top < bottom; top++, bottom--) {
        memcpy(tmp, pixels + top * row, row);
        memcpy(pixels + top * row, pixels + bottom * row, row);
        memcpy(pixels + bottom * row, tmp, row);
    }
done:
    free(tmp);
    return ok;
}

// >>print

void gl_context_print_info(const gl_context *ctx, FILE *out)
{
    const gl_info *i = &ctx->info;
    fprintf(out, "backend: %s\n", i->backend ? i->backend : "");
    fprintf(out, "device: %s\n", i->device[0] ? i->device : "none");
    fprintf(out, "vendor: %s\n", i->vendor);
    fprintf(out, "renderer: %s\n", i->renderer);
    fprintf(out, "version: %s\n", i->version);
    fprintf(out, "glsl: %s\n", i->glsl_version);
    fprintf(out, "max_draw_buffers: %d\n", i->max_draw_buffers);
    fprintf(out, "max_color_attachments: %d\n", i->max_color_attachments);
    fprintf(out, "max_samples: %d\n", i->max_samples);
    fprintf(out, "max_uniform_block_size: %d\n", i->max_uniform_block_size);
    fprintf(out, "max_texture_size: %d\n", i->max_texture_size);
    fprintf(out, "max_renderbuffer_size: %d\n", i->max_renderbuffer_size);
    fprintf(out, "max_viewport: %dx%d\n", i->max_viewport_dims[0], i->max_viewport_dims[1]);
    fprintf(out, "timer_query: %s\n", i->timer_query ? "yes" : "no");
    fprintf(out, "pipeline_statistics_query: %s\n", i->pipeline_statistics ? "yes" : "no");
    fprintf(out, "debug_context: %s\n", i->debug_context ? "yes" : "no");
}

// >>second framebuffer

bool gl_offscreen_create(gl_context *ctx, int width, int height, gl_offscreen *o, char *err,
                         size_t errlen)
{
    *o = (gl_offscreen){.width = width, .height = height};
    if (width < 1 || height < 1) {
        snprintf(err, errlen, "resolution %dx%d is invalid", width, height);
        return false;
    }
    if (!check_size(ctx, width, height, err, errlen))
        return false;
    return renderbuffer_framebuffer(ctx, width, height, "reference", "shadesweep reference output",
                                    "reference", &o->color_rb, &o->depth_stencil_rb, &o->fbo,
                                    err, errlen);
}

void gl_offscreen_destroy(gl_offscreen *o)
{
    GL_OBJECTS_DELETE(GLO_FRAMEBUFFER, &o->fbo);
    GL_OBJECTS_DELETE(GLO_RENDERBUFFER, &o->color_rb, &o->depth_stencil_rb);
    *o = (gl_offscreen){0};
}
