/* Pixel formats, render targets and framebuffers (target.h). */
#include "renderers/gl/target.h"

#include <limits.h>

#include <stdio.h>
#include <string.h>

// >>formats

static const gl_format_info formats[GLT_FORMAT_COUNT] = {
#define GLT_FORMAT_ROW(id_, name_, ifmt, fmt, type_, bpp, color_, depth_, stencil_)               \
    [id_] = {.id = id_, .name = name_, .internal_format = ifmt, .format = fmt, .type = type_,      \
             .bytes_per_pixel = bpp, .color = color_, .depth = depth_, .stencil = stencil_},
    GLT_FORMATS(GLT_FORMAT_ROW)
#undef GLT_FORMAT_ROW
};

const gl_format_info *gl_format_get(gl_format f)
{
    if (f <= GLT_FORMAT_NONE || f >= GLT_FORMAT_COUNT)
        return NULL;
    return &formats[f];
}

gl_format gl_format_find(const char *name)
{
    if (!name)
        return GLT_FORMAT_NONE;
    for (int f = GLT_FORMAT_NONE + 1; f < GLT_FORMAT_COUNT; f++)
        if (strcmp(formats[f].name, name) == 0)
            return (gl_format)f;
    return GLT_FORMAT_NONE;
}

const char *gl_format_name(gl_format f)
{
    const gl_format_info *i = gl_format_get(f);
    return i ? i->name : "none";
}

uint64_t gl_format_bytes(gl_format f, int width, int height)
{
    const gl_format_info *i = gl_format_get(f);
    if (!i || width <= 0 || height <= 0)
        return 0;
    return (uint64_t)width * (uint64_t)height * i->bytes_per_pixel;
}

// >>targets

static void set_name(char *dst, size_t size, const char *name, const char *fallback)
{
    snprintf(dst, size, "%s", name ? name : fallback);
}

bool gl_target_create(gl_target *t, const gl_target_desc *desc, char *err, size_t errlen)
{
    memset(t, 0, sizeof *t);
    const char *name = desc->name ? desc->name : "target";
    const gl_format_info *fi = gl_format_get(desc->format);
    if (!fi) {
        snprintf(err, errlen, "target %s: no pixel format given", name);
        return false;
    }
    GLint max_size = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (desc->width <= 0 || desc->height <= 0 || desc->width > max_size ||
        desc->height > max_size) {
        snprintf(err, errlen, "target %s (%s): size %dx%d is not within 1x1 .. %dx%d "
                 "(GL_MAX_TEXTURE_SIZE)", name, fi->name, desc->width, desc->height,
                 (int)max_size, (int)max_size);
        return false;
    }
    int samples = desc->samples > 1 ? desc->samples : 1;
    if (desc->samples < 0) {
        snprintf(err, errlen, "target %s (%s): %d samples", name, fi->name, desc->samples);
        return false;
    }
    if (samples > 1) {
        GLint max_samples = 0;
        gl.GetIntegerv(fi->color ? GL_MAX_COLOR_TEXTURE_SAMPLES : GL_MAX_DEPTH_TEXTURE_SAMPLES,
                       &max_samples);
        if (samples > max_samples) {
            snprintf(err, errlen, "target %s (%s): %d samples, the context allows %d (%s)",
                     name, fi->name, samples, (int)max_samples,
                     fi->color ? "GL_MAX_COLOR_TEXTURE_SAMPLES"
                               : "GL_MAX_DEPTH_TEXTURE_SAMPLES");
            return false;
        }
    }
    GLuint tex = 0;
    if (samples > 1) {
        /* no sampler state on a multisample texture: texelFetch only */
        gl.CreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &tex);
        gl.TextureStorage2DMultisample(tex, samples, fi->internal_format, desc->width,
                                       desc->height, GL_TRUE);
        /* the driver may give more samples than asked (llvmpipe: 4 for 2) */
        GLint got = 0;
        gl.GetTextureLevelParameteriv(tex, 0, GL_TEXTURE_SAMPLES, &got);
        if (got > samples)
            samples = (int)got;
    } else {
        gl.CreateTextures(GL_TEXTURE_2D, 1, &tex);
        gl.TextureStorage2D(tex, 1, fi->internal_format, desc->width, desc->height);
        GLint filter = desc->linear ? GL_LINEAR : GL_NEAREST;
        gl.TextureParameteri(tex, GL_TEXTURE_MIN_FILTER, filter);
        gl.TextureParameteri(tex, GL_TEXTURE_MAG_FILTER, filter);
        gl.TextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl.TextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    set_name(t->name, sizeof t->name, desc->name, "target");
    gl.ObjectLabel(GL_TEXTURE, tex, -1, t->name);
    t->format = desc->format;
    t->width = desc->width;
    t->height = desc->height;
    t->samples = samples;
    t->bytes = gl_format_bytes(desc->format, desc->width, desc->height) * (uint64_t)samples;
    t->texture = tex;
    return true;
}

void gl_target_destroy(gl_target *t)
{
    if (!t)
        return;
    GL_OBJECTS_DELETE(GLO_TEXTURE, &t->texture);
    memset(t, 0, sizeof *t);
}

void gl_targets_destroy(gl_target *const *list)
{
    for (; *list; list++)
        gl_target_destroy(*list);
}

void gl_objects_delete(gl_object_kind kind, GLuint *const *names)
{
    void (*del)(GLsizei, const GLuint *) = kind == GLO_BUFFER         ? gl.DeleteBuffers
                                           : kind == GLO_TEXTURE      ? gl.DeleteTextures
                                           : kind == GLO_FRAMEBUFFER  ? gl.DeleteFramebuffers
                                           : kind == GLO_RENDERBUFFER ? gl.DeleteRenderbuffers
                                                                      : gl.DeleteVertexArrays;
    for (; *names; names++) {
        if (**names && del)
            del(1, *names);
        **names = 0;
    }
}

void gl_target_describe(const gl_target *t, target_plan_entry *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "%s", t->name);
    if (t->samples > 1)
        snprintf(out->format, sizeof out->format, "%s x%d", gl_format_name(t->format),
                 t->samples);
    else
        snprintf(out->format, sizeof out->format, "%s", gl_format_name(t->format));
    out->width = t->width;
    out->height = t->height;
    out->bytes = t->bytes;
}

// >>framebuffers

const char *gl_framebuffer_status_name(GLenum status, const char *failed, const char *unknown)
{
    switch (status) {
    case GL_FRAMEBUFFER_COMPLETE: return "GL_FRAMEBUFFER_COMPLETE";
    case GL_FRAMEBUFFER_UNDEFINED: return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
        return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS:
        return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    case 0: return failed;
    default: return unknown;
    }
}

/* "colour 0 albedo rgba8 64x48, depth-stencil depth depth24-stencil8 64x48" */
static void list_attachments(char *buf, size_t size, const gl_target *const *color, int ncolor,
                             const gl_target *ds)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i <= ncolor; i++) {
        const gl_target *t = i < ncolor ? color[i] : ds;
        if (!t)
            continue;
        char what[24];
        if (i < ncolor)
            snprintf(what, sizeof what, "colour %d", i);
        else
            snprintf(what, sizeof what, "depth-stencil");
        char samples[16] = "";
        if (t->samples > 1)
            snprintf(samples, sizeof samples, " x%d", t->samples);
        int n = snprintf(buf + used, size - used, "%s%s %s %s %dx%d%s", used ? ", " : "", what,
                         t->name[0] ? t->name : "(unnamed)", gl_format_name(t->format), t->width,
                         t->height, samples);
        if (n < 0 || (size_t)n >= size - used)
            return;
        used += (size_t)n;
    }
    if (!used)
        snprintf(buf, size, "no attachments");
}

bool gl_framebuffer_create(gl_framebuffer *fb, const gl_framebuffer_desc *desc, char *err,
                           size_t errlen)
{
    memset(fb, 0, sizeof *fb);
    const char *name = desc->name ? desc->name : "framebuffer";
    int ncolor = 0;
    while (ncolor < GLT_MAX_COLOR && desc->color[ncolor])
        ncolor++;
    for (int i = ncolor; i < GLT_MAX_COLOR; i++)
        if (desc->color[i]) {
            snprintf(err, errlen, "framebuffer %s: colour target %d follows an empty slot %d",
                     name, i, ncolor);
            return false;
        }
    const gl_target *ds = desc->depth_stencil;
    char list[512];
    list_attachments(list, sizeof list, desc->color, ncolor, ds);

    if (ncolor == 0 && !ds) {
        snprintf(err, errlen, "framebuffer %s: no attachments", name);
        return false;
    }
    int w = 0, h = 0, samples = 0;
    for (int i = 0; i <= ncolor; i++) {
        const gl_target *t = i < ncolor ? desc->color[i] : ds;
        if (!t)
            continue;
        const gl_format_info *fi = gl_format_get(t->format);
        if (!t->texture || !fi) {
            char what[24];
            if (i < ncolor)
                snprintf(what, sizeof what, "colour %d", i);
            else
                snprintf(what, sizeof what, "depth-stencil");
            snprintf(err, errlen, "framebuffer %s: %s is a target that was not created (%s)", name,
                     what, list);
            return false;
        }
        if (i < ncolor && !fi->color) {
            snprintf(err, errlen, "framebuffer %s: colour %d has the depth format %s (%s)", name,
                     i, fi->name, list);
            return false;
        }
        if (i == ncolor && fi->color) {
            snprintf(err, errlen, "framebuffer %s: the depth-stencil attachment has the colour "
                     "format %s (%s)", name, fi->name, list);
            return false;
        }
        int ts = t->samples > 1 ? t->samples : 1;
        if (w == 0) {
            w = t->width;
            h = t->height;
            samples = ts;
        } else if (t->width != w || t->height != h) {
            snprintf(err, errlen, "framebuffer %s: attachments differ in size (%s)", name, list);
            return false;
        } else if (ts != samples) {
            snprintf(err, errlen, "framebuffer %s: attachments differ in samples (%s)", name,
                     list);
            return false;
        }
    }
    GLint max_attach = 0, max_draw = 0;
    gl.GetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &max_attach);
    gl.GetIntegerv(GL_MAX_DRAW_BUFFERS, &max_draw);
    if (ncolor > max_attach || ncolor > max_draw) {
        snprintf(err, errlen, "framebuffer %s: %d colour targets, the context has %d colour "
                 "attachments and %d draw buffers (%s)", name, ncolor, (int)max_attach,
                 (int)max_draw, list);
        return false;
    }

    GLuint fbo = 0;
    gl.CreateFramebuffers(1, &fbo);
    GLenum bufs[GLT_MAX_COLOR];
    for (int i = 0; i < ncolor; i++) {
        bufs[i] = GL_COLOR_ATTACHMENT0 + (GLenum)i;
        gl.NamedFramebufferTexture(fbo, bufs[i], desc->color[i]->texture, 0);
    }
    if (ds) {
        const gl_format_info *fi = gl_format_get(ds->format);
        GLenum at = fi->depth && fi->stencil ? GL_DEPTH_STENCIL_ATTACHMENT
                    : fi->depth              ? GL_DEPTH_ATTACHMENT
                                             : GL_STENCIL_ATTACHMENT;
        gl.NamedFramebufferTexture(fbo, at, ds->texture, 0);
    }
    if (ncolor) {
        gl.NamedFramebufferDrawBuffers(fbo, ncolor, bufs);
        gl.NamedFramebufferReadBuffer(fbo, GL_COLOR_ATTACHMENT0);
    } else {
        GLenum none = GL_NONE;
        gl.NamedFramebufferDrawBuffers(fbo, 1, &none);
        gl.NamedFramebufferReadBuffer(fbo, GL_NONE);
    }
    GLenum status = gl.CheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(err, errlen, "framebuffer %s is not complete: %s (%s)", name,
                 gl_framebuffer_status_name(status, "an error while checking", "an unknown status"),
                 list);
        gl.DeleteFramebuffers(1, &fbo);
        return false;
    }
    set_name(fb->name, sizeof fb->name, desc->name, "framebuffer");
    gl.ObjectLabel(GL_FRAMEBUFFER, fbo, -1, fb->name);
    fb->fbo = fbo;
    fb->ncolor = ncolor;
    fb->width = w;
    fb->height = h;
    fb->samples = samples;
    return true;
}

void gl_framebuffer_destroy(gl_framebuffer *fb)
{
    if (!fb)
        return;
    GL_OBJECTS_DELETE(GLO_FRAMEBUFFER, &fb->fbo);
    memset(fb, 0, sizeof *fb);
}

void gl_framebuffers_destroy(gl_framebuffer *const *list)
{
    for (; *list; list++)
        gl_framebuffer_destroy(*list);
}

/* Reads a float colour texture (RGBA16F, RGBA32F...) of w x h as RGBA floats, row 0 at the bottom, tightly
 * packed: direct state access (no texture or framebuffer binding changes), the
 * pixel-pack state set for the read and put back. In bands of rows so that no
 * call's byte count exceeds a GLsizei. */
void gl_texture_read_float(GLuint texture, int w, int h, float *rgba)
{
    GLint pack_buffer = 0, alignment = 4, row_length = 0, skip_rows = 0, skip_pixels = 0;
    gl.GetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer);
    gl.GetIntegerv(GL_PACK_ALIGNMENT, &alignment);
    gl.GetIntegerv(GL_PACK_ROW_LENGTH, &row_length);
    gl.GetIntegerv(GL_PACK_SKIP_ROWS, &skip_rows);
    gl.GetIntegerv(GL_PACK_SKIP_PIXELS, &skip_pixels);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    gl.PixelStorei(GL_PACK_SKIP_ROWS, 0);
    gl.PixelStorei(GL_PACK_SKIP_PIXELS, 0);
    const size_t row = (size_t)w * 4;                 /* floats */
    const int band = (int)((size_t)INT_MAX / (row * sizeof *rgba));   /* >= 1 */
    for (int y = 0; y < h; y += band) {
        int n = h - y < band ? h - y : band;
        gl.GetTextureSubImage(texture, 0, 0, y, 0, w, n, 1, GL_RGBA, GL_FLOAT,
                              (GLsizei)((size_t)n * row * sizeof *rgba), rgba + (size_t)y * row);
    }
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, (GLuint)pack_buffer);
    gl.PixelStorei(GL_PACK_ALIGNMENT, alignment);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, row_length);
    gl.PixelStorei(GL_PACK_SKIP_ROWS, skip_rows);
    gl.PixelStorei(GL_PACK_SKIP_PIXELS, skip_pixels);
}
