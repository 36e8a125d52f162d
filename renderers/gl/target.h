#pragma once
/* Render targets: one table of pixel formats, 2D textures of those formats, and
 * framebuffers of up to GLT_MAX_COLOR colour targets plus an optional depth
 * (-stencil) target, with byte accounting for renderer_describe.
 *
 * Use, ownership, direct state access, what a texture is made with and multisampled
 * targets: the comment above the format table below. Needs a current GL 4.5 context
 * whose GL table is loaded. */
#include "renderers/gl/loader.h"
#include "renderers/gl/stats.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/*     gl_target albedo, depth;
 *     gl_framebuffer gbuf;
 *     if (!gl_target_create(&albedo, &(gl_target_desc){.name = "albedo",
 *             .format = gl_format_find("rgba8"), .width = w, .height = h}, err, len) || ...
 *         !gl_framebuffer_create(&gbuf, &(gl_framebuffer_desc){.name = "gbuffer",
 *             .color = {&albedo, &normal}, .depth_stencil = &depth}, err, len))
 *         fail;
 *     ... gl_state_framebuffer(state, gbuf.fbo); gl_state_texture(state, 0, albedo.texture) ...
 *     gl_framebuffer_destroy(&gbuf); gl_target_destroy(&albedo); ...
 *
 * Objects are plain structs owned by the caller; a zeroed one is "none", and
 * destroying a zeroed or already destroyed one does nothing. Everything is made
 * with direct state access (GL 4.5), so creating a target or a framebuffer binds
 * nothing and leaves the state cache's idea of the bindings (state.h) true.
 *
 * Textures have one mip level, GL_NEAREST filtering (GL_LINEAR with .linear) and
 * GL_CLAMP_TO_EDGE wrapping; depth formats are sampled as depth (no compare mode).
 * A target with .samples > 1 is a GL_TEXTURE_2D_MULTISAMPLE of that many samples at
 * fixed sample locations (no sampler state: read with texelFetch and a sample index);
 * its bytes count every sample.
 * Needs a current GL 4.5 context whose GL table is loaded. */

// >>formats

/* The format table, one row per format (the enum and the table cannot drift):
 * X(id, name as in manifests, GL internal format, pixel transfer format, type,
 *   bytes per pixel, colour, depth, stencil) */
#define GLT_FORMATS(X)                                                                           \
    X(GLT_FORMAT_RGBA8, "rgba8", GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4, true, false, false)     \
    X(GLT_FORMAT_RGB10A2, "rgb10a2", GL_RGB10_A2, GL_RGBA, GL_UNSIGNED_INT_2_10_10_10_REV, 4,    \
      true, false, false)                                                                        \
    X(GLT_FORMAT_RG8, "rg8", GL_RG8, GL_RG, GL_UNSIGNED_BYTE, 2, true, false, false)             \
    X(GLT_FORMAT_RGBA16F, "rgba16f", GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT, 8, true, false, false)  \
    X(GLT_FORMAT_RG16F, "rg16f", GL_RG16F, GL_RG, GL_HALF_FLOAT, 4, true, false, false)          \
    X(GLT_FORMAT_R16F, "r16f", GL_R16F, GL_RED, GL_HALF_FLOAT, 2, true, false, false)            \
    X(GLT_FORMAT_RGBA32F, "rgba32f", GL_RGBA32F, GL_RGBA, GL_FLOAT, 16, true, false, false)      \
    X(GLT_FORMAT_R32F, "r32f", GL_R32F, GL_RED, GL_FLOAT, 4, true, false, false)                 \
    X(GLT_FORMAT_R32UI, "r32ui", GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, 4, true, false,        \
      false)                                                                                       \
    X(GLT_FORMAT_DEPTH24_STENCIL8, "depth24-stencil8", GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL,    \
      GL_UNSIGNED_INT_24_8, 4, false, true, true)                                                \
    X(GLT_FORMAT_DEPTH32F_STENCIL8, "depth32f-stencil8", GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, \
      GL_FLOAT_32_UNSIGNED_INT_24_8_REV, 8, false, true, true)

/* 0 is "no format" (a zeroed desc names none and is refused). */
typedef enum gl_format {
    GLT_FORMAT_NONE = 0,
#define GLT_FORMAT_ENUM(id, name, ifmt, fmt, type, bpp, color, depth, stencil) id,
    GLT_FORMATS(GLT_FORMAT_ENUM)
#undef GLT_FORMAT_ENUM
    GLT_FORMAT_COUNT
} gl_format;

typedef struct gl_format_info {
    gl_format id;
    const char *name;            /* "rgba16f" */
    GLenum internal_format;      /* GL_RGBA16F */
    GLenum format, type;         /* for reading back / uploading whole pixels */
    unsigned bytes_per_pixel;    /* what the format holds, not what a driver may pad to */
    bool color, depth, stencil;
} gl_format_info;

/* The row of a format; NULL for GLT_FORMAT_NONE or out of range. */
const gl_format_info *gl_format_get(gl_format f);
/* The format called name (exactly, as in the table: "depth24-stencil8"), or
 * GLT_FORMAT_NONE. */
gl_format gl_format_find(const char *name);
/* "rgba16f"; "none" for GLT_FORMAT_NONE or out of range. */
const char *gl_format_name(gl_format f);
/* width * height * bytes per pixel; 0 for no format or a size <= 0. */
uint64_t gl_format_bytes(gl_format f, int width, int height);

// >>targets

typedef struct gl_target_desc {
    const char *name;            /* for messages, describe and the GL object label; NULL: "target" */
    gl_format format;
    int width, height;           /* > 0 and within GL_MAX_TEXTURE_SIZE */
    bool linear;                 /* GL_LINEAR filtering instead of GL_NEAREST */
    int samples;                 /* 0 or 1: GL_TEXTURE_2D; > 1: GL_TEXTURE_2D_MULTISAMPLE */
} gl_target_desc;

typedef struct gl_target {
    char name[32];
    gl_format format;
    int width, height;
    int samples;                 /* 1, or the samples of a multisampled target: what the
                                    driver gave (GL_TEXTURE_SAMPLES), at least the desc's */
    uint64_t bytes;              /* gl_format_bytes(format, width, height) x samples */
    GLuint texture;              /* GL_TEXTURE_2D (GL_TEXTURE_2D_MULTISAMPLE with samples
                                    > 1); 0 when none */
} gl_target;

/* Creates the texture; false with a message naming the target (and the format
 * and size) on a bad desc: no format, size <= 0 or above GL_MAX_TEXTURE_SIZE, samples
 * < 0 or above the context's GL_MAX_COLOR_TEXTURE_SAMPLES / GL_MAX_DEPTH_TEXTURE_SAMPLES.
 * *t is zeroed on failure. */
bool gl_target_create(gl_target *t, const gl_target_desc *desc, char *err, size_t errlen);
void gl_target_destroy(gl_target *t);
/* Destroys each target of a NULL-ended list; GL_TARGETS_DESTROY(&a, &b) ends it. */
void gl_targets_destroy(gl_target *const *list);
#define GL_TARGETS_DESTROY(...) gl_targets_destroy((gl_target *const[]){__VA_ARGS__, NULL})

/* Deletes the GL objects of one kind whose names a NULL-ended list points at, those that
 * are not 0 (nothing without a loaded GL table), and zeroes the names:
 * GL_OBJECTS_DELETE(GLO_BUFFER, &m->vbo, &m->ibo). */
typedef enum gl_object_kind {
    GLO_BUFFER,
    GLO_TEXTURE,
    GLO_FRAMEBUFFER,
    GLO_RENDERBUFFER,
    GLO_VERTEX_ARRAY,
} gl_object_kind;
void gl_objects_delete(gl_object_kind kind, GLuint *const *names);
#define GL_OBJECTS_DELETE(KIND, ...) gl_objects_delete(KIND, (GLuint *const[]){__VA_ARGS__, NULL})

/* The pass_plan row of t: name, format name ("rgba16f", "rgba16f x4" when
 * multisampled), size, bytes. */
void gl_target_describe(const gl_target *t, target_plan_entry *out);

// >>framebuffers

/* The name of a glCheckFramebufferStatus result ("GL_FRAMEBUFFER_UNSUPPORTED", ...): the one
 * table of them (gl_framebuffer_create's and the contexts' messages); `failed` for 0 (the
 * check itself failed), `unknown` for a value GL does not define. */
const char *gl_framebuffer_status_name(GLenum status, const char *failed, const char *unknown);

enum { GLT_MAX_COLOR = 8 };

typedef struct gl_framebuffer_desc {
    const char *name;            /* NULL: "framebuffer" */
    /* Colour targets, attached as GL_COLOR_ATTACHMENT0.. and draw buffers 0..
     * in this order; the list ends at the first NULL. */
    const gl_target *color[GLT_MAX_COLOR];
    /* A depth or depth-stencil target, or NULL. */
    const gl_target *depth_stencil;
} gl_framebuffer_desc;

typedef struct gl_framebuffer {
    char name[32];
    GLuint fbo;                  /* 0 when none */
    int ncolor;
    int width, height;
    int samples;                 /* the attachments' (1: single-sampled) */
} gl_framebuffer;

/* Creates and checks the framebuffer. Refused, with a message that names the
 * framebuffer and every attachment's target, format and size: no attachment at
 * all, a target that was not created, a colour format as depth or a depth format
 * as colour, attachments of different sizes or sample counts, more colour targets than the context's
 * GL_MAX_COLOR_ATTACHMENTS / GL_MAX_DRAW_BUFFERS, and a framebuffer GL does not
 * call complete (with the status: "GL_FRAMEBUFFER_UNSUPPORTED"). *fb is zeroed
 * on failure. A framebuffer without colour targets draws to and reads from
 * GL_NONE. */
bool gl_framebuffer_create(gl_framebuffer *fb, const gl_framebuffer_desc *desc, char *err,
                           size_t errlen);
void gl_framebuffer_destroy(gl_framebuffer *fb);
/* Destroys each framebuffer of a NULL-ended list; GL_FRAMEBUFFERS_DESTROY(&a, &b) ends it. */
void gl_framebuffers_destroy(gl_framebuffer *const *list);
#define GL_FRAMEBUFFERS_DESTROY(...) \
    gl_framebuffers_destroy((gl_framebuffer *const[]){__VA_ARGS__, NULL})

/* Reads level 0 of a colour texture of w x h as RGBA floats, row 0 at the bottom,
 * tightly packed, without changing any binding the state cache knows (direct state
 * access; the pixel-pack state is put back), in bands of rows so that no call's byte
 * count exceeds a GLsizei. For the renderers' float light accumulation. */
void gl_texture_read_float(GLuint texture, int w, int h, float *rgba);
