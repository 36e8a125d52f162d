/* The GL state cache (state.h). */
#include "renderers/gl/state.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

// >>tables

static const char *const category_names[GLS_CAT_COUNT] = {
    [GLS_CAT_PROGRAM] = "program",
    [GLS_CAT_TEXTURE] = "texture",
    [GLS_CAT_FRAMEBUFFER] = "framebuffer",
    [GLS_CAT_BLEND] = "blend",
    [GLS_CAT_DEPTH] = "depth",
    [GLS_CAT_STENCIL] = "stencil",
    [GLS_CAT_CULL] = "cull",
    [GLS_CAT_VIEWPORT] = "viewport",
    [GLS_CAT_VERTEX_ARRAY] = "vertex_array",
    [GLS_CAT_BUFFER] = "buffer",
    [GLS_CAT_IMAGE] = "image",
    [GLS_CAT_BARRIER] = "barrier",
};

const char *gl_state_category_name(gls_category c)
{
    if ((unsigned)c >= GLS_CAT_COUNT)
        return "unknown";
    return category_names[c];
}

static const GLenum compare_gl[GLS_COMPARE_COUNT] = {
    [GLS_COMPARE_DEFAULT] = GL_ALWAYS, [GLS_COMPARE_NEVER] = GL_NEVER,
    [GLS_COMPARE_LESS] = GL_LESS,      [GLS_COMPARE_EQUAL] = GL_EQUAL,
    [GLS_COMPARE_LEQUAL] = GL_LEQUAL,  [GLS_COMPARE_GREATER] = GL_GREATER,
    [GLS_COMPARE_NOTEQUAL] = GL_NOTEQUAL, [GLS_COMPARE_GEQUAL] = GL_GEQUAL,
    [GLS_COMPARE_ALWAYS] = GL_ALWAYS,
};

static const GLenum factor_gl[GLS_BLEND_FACTOR_COUNT] = {
    [GLS_BLEND_DEFAULT] = GL_ONE,    /* not used: factor() resolves DEFAULT per use */
    [GLS_BLEND_ZERO] = GL_ZERO,
    [GLS_BLEND_ONE] = GL_ONE,
    [GLS_BLEND_SRC_COLOR] = GL_SRC_COLOR,
    [GLS_BLEND_ONE_MINUS_SRC_COLOR] = GL_ONE_MINUS_SRC_COLOR,
    [GLS_BLEND_DST_COLOR] = GL_DST_COLOR,
    [GLS_BLEND_ONE_MINUS_DST_COLOR] = GL_ONE_MINUS_DST_COLOR,
    [GLS_BLEND_SRC_ALPHA] = GL_SRC_ALPHA,
    [GLS_BLEND_ONE_MINUS_SRC_ALPHA] = GL_ONE_MINUS_SRC_ALPHA,
    [GLS_BLEND_DST_ALPHA] = GL_DST_ALPHA,
    [GLS_BLEND_ONE_MINUS_DST_ALPHA] = GL_ONE_MINUS_DST_ALPHA,
};

static const GLenum blend_op_gl[GLS_BLEND_OP_COUNT] = {
    [GLS_BLEND_OP_DEFAULT] = GL_FUNC_ADD,
    [GLS_BLEND_OP_ADD] = GL_FUNC_ADD,
    [GLS_BLEND_OP_SUBTRACT] = GL_FUNC_SUBTRACT,
    [GLS_BLEND_OP_REVERSE_SUBTRACT] = GL_FUNC_REVERSE_SUBTRACT,
    [GLS_BLEND_OP_MIN] = GL_MIN,
    [GLS_BLEND_OP_MAX] = GL_MAX,
};

static const GLenum stencil_op_gl[GLS_STENCIL_OP_COUNT] = {
    [GLS_STENCIL_OP_DEFAULT] = GL_KEEP,  [GLS_STENCIL_OP_KEEP] = GL_KEEP,
    [GLS_STENCIL_OP_ZERO] = GL_ZERO,     [GLS_STENCIL_OP_REPLACE] = GL_REPLACE,
    [GLS_STENCIL_OP_INCR_CLAMP] = GL_INCR, [GLS_STENCIL_OP_DECR_CLAMP] = GL_DECR,
    [GLS_STENCIL_OP_INVERT] = GL_INVERT, [GLS_STENCIL_OP_INCR_WRAP] = GL_INCR_WRAP,
    [GLS_STENCIL_OP_DECR_WRAP] = GL_DECR_WRAP,
};

/* An enum value out of range is a bug in the caller: it gets the default and a message. */
static GLenum lookup(const GLenum *table, unsigned n, unsigned v, const char *what)
{
    if (v >= n) {
        fprintf(stderr, "bug: gl_state: %s value %u out of range, using the default\n", what, v);
        v = 0;
    }
    return table[v];
}

#define LOOKUP(table, v, what) lookup(table, sizeof table / sizeof table[0], (unsigned)(v), what)

/* A blend factor; DEFAULT (and, after a message, a value out of range) gives dflt. */
static GLenum factor(gls_blend_factor f, GLenum dflt)
{
    if ((unsigned)f >= GLS_BLEND_FACTOR_COUNT)
        fprintf(stderr, "bug: gl_state: blend factor value %u out of range, using the default\n",
                (unsigned)f);
    if (f == GLS_BLEND_DEFAULT || (unsigned)f >= GLS_BLEND_FACTOR_COUNT)
        return dflt;
    return factor_gl[f];
}

// >>the cache

/* Parts of the state, each known or not (a bit in gl_state.known). */
enum {
    K_PROGRAM,
    K_FRAMEBUFFER,
    K_VERTEX_ARRAY,
    K_VIEWPORT,
    K_BLEND_ON,
    K_BLEND_FUNC,        /* equations and factors */
    K_COLOR_MASK,
    K_DEPTH_ON,
    K_DEPTH_FUNC,
    K_DEPTH_WRITE,
    K_STENCIL_ON,
    K_STENCIL_FUNC_FRONT,
    K_STENCIL_FUNC_BACK,
    K_STENCIL_OP_FRONT,
    K_STENCIL_OP_BACK,
    K_STENCIL_WRITE,
    K_CULL_ON,
    K_CULL_FACE,
    K_COUNT
};
_Static_assert(K_COUNT <= 32, "known bits fit in 32");

typedef struct stencil_func {
    GLenum func;
    GLint ref;
    GLuint mask;
} stencil_func;

typedef struct stencil_ops {
    GLenum sfail, dpfail, dppass;
} stencil_ops;

/* What GL holds, as far as the bits of known say. */
typedef struct gl_values {
    GLuint program, framebuffer, vertex_array;
    GLint viewport[4];
    GLuint texture[GLS_MAX_TEXTURE_UNITS];
    GLuint buffer[GLS_MAX_BUFFER_BINDINGS];
    struct image_binding {
        GLuint texture;
        GLenum access, format;
    } image[GLS_MAX_IMAGE_UNITS];
    bool blend_on;
    GLenum blend_func[6];            /* op rgb, op alpha, src rgb, dst rgb, src alpha, dst alpha */
    bool color_mask[4];
    bool depth_on;
    GLenum depth_func;
    bool depth_write;
    bool stencil_on;
    stencil_func stencil_func[2];    /* [0] front, [1] back */
    stencil_ops stencil_ops[2];
    GLuint stencil_write;
    bool cull_on;
    GLenum cull_face;
} gl_values;

enum { GLS_SAMPLED_PROGRAMS = 32, GLS_SAMPLERS = 16 };

/* The active sampler uniforms of one program (the feedback-loop check). */
typedef struct sampled_program {
    GLuint program;
    unsigned n;
    struct {
        GLuint unit;
        GLenum binding;              /* GL_TEXTURE_BINDING_2D, ... for the sampler's type */
        char name[32];
    } sampler[GLS_SAMPLERS];
} sampled_program;

struct gl_state {
    bool force;
    GLuint empty_vertex_array;
    GLint max_viewport[2];           /* GL_MAX_VIEWPORT_DIMS */
    uint32_t known;                  /* 1 << K_* */
    uint32_t texture_known;          /* 1 << unit */
    uint32_t buffer_known;           /* 1 << storage binding */
    uint32_t image_known;            /* 1 << image unit */
    gl_values gl;

    bool in_pass;
    const char *pass_name;
    struct timespec pass_start;
    gls_counts pass, total;

    /* >>the feedback-loop check (state.h) */
    bool feedback_check;
    int max_color_attachments;       /* GL_MAX_COLOR_ATTACHMENTS, at most 8 */
    uint64_t feedback_loops;
    char feedback_message[768];
    unsigned nsampled;               /* programs in sampled[], forgotten by invalidate */
    sampled_program sampled[GLS_SAMPLED_PROGRAMS];
};

gl_state *gl_state_create(void)
{
    gl_state *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    gl.CreateVertexArrays(1, &s->empty_vertex_array);
    gl.ObjectLabel(GL_VERTEX_ARRAY, s->empty_vertex_array, -1, "gl_state empty vertex array");
    gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, s->max_viewport);
    GLint mca = 0;
    gl.GetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &mca);
    s->max_color_attachments = mca < 0 ? 0 : mca > 8 ? 8 : (int)mca;
    s->feedback_check = gl.IsEnabled(GL_DEBUG_OUTPUT) == GL_TRUE;
    return s;
}

void gl_state_destroy(gl_state *s)
{
    if (!s)
        return;
    if (s->empty_vertex_array && gl.DeleteVertexArrays)
        gl.DeleteVertexArrays(1, &s->empty_vertex_array);
    free(s);
}

void gl_state_set_force(gl_state *s, bool force)
{
    s->force = force;
}

bool gl_state_force(const gl_state *s)
{
    return s->force;
}

void gl_state_invalidate(gl_state *s)
{
    s->known = 0;
    s->texture_known = 0;
    s->buffer_known = 0;
    s->image_known = 0;
    s->nsampled = 0;   /* programs may have been deleted and their names reused */
}

// >>counting

static void count_change(gl_state *s, gls_category c)
{
    s->total.category[c]++;
    if (s->in_pass)
        s->pass.category[c]++;
    if (c < GLS_CAT_STATE_CHANGES_END) {
        s->total.state_changes++;
        if (s->in_pass)
            s->pass.state_changes++;
    }
}

static void count_draw(gl_state *s)
{
    s->total.draw_calls++;
    if (s->in_pass)
        s->pass.draw_calls++;
}

static void count_dispatch(gl_state *s)
{
    s->total.dispatches++;
    if (s->in_pass)
        s->pass.dispatches++;
}

/* Whether part k must be applied: forced, unknown, or different. Marks it known. */
static bool need(gl_state *s, unsigned k, bool differs)
{
    bool apply = s->force || !(s->known & (1u << k)) || differs;
    s->known |= 1u << k;
    return apply;
}

static void set_enabled(GLenum cap, bool on)
{
    if (on)
        gl.Enable(cap);
    else
        gl.Disable(cap);
}

// >>setters

void gl_state_program(gl_state *s, GLuint program)
{
    if (!need(s, K_PROGRAM, s->gl.program != program))
        return;
    s->gl.program = program;
    gl.UseProgram(program);
    count_change(s, GLS_CAT_PROGRAM);
}

void gl_state_texture(gl_state *s, unsigned unit, GLuint texture)
{
    if (unit >= GLS_MAX_TEXTURE_UNITS) {
        fprintf(stderr, "bug: gl_state_texture: unit %u of %d\n", unit, GLS_MAX_TEXTURE_UNITS);
        return;
    }
    uint32_t bit = 1u << unit;
    bool apply = s->force || !(s->texture_known & bit) || s->gl.texture[unit] != texture;
    s->texture_known |= bit;
    if (!apply)
        return;
    s->gl.texture[unit] = texture;
    gl.BindTextureUnit(unit, texture);
    count_change(s, GLS_CAT_TEXTURE);
}

void gl_state_framebuffer(gl_state *s, GLuint framebuffer)
{
    if (!need(s, K_FRAMEBUFFER, s->gl.framebuffer != framebuffer))
        return;
    s->gl.framebuffer = framebuffer;
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    count_change(s, GLS_CAT_FRAMEBUFFER);
}

void gl_state_blend(gl_state *s, const gls_blend *blend)
{
    static const gls_blend off;
    const gls_blend *b = blend ? blend : &off;
    bool changed = false;
    if (need(s, K_BLEND_ON, s->gl.blend_on != b->enabled)) {
        s->gl.blend_on = b->enabled;
        set_enabled(GL_BLEND, b->enabled);
        changed = true;
    }
    if (b->enabled) {
        GLenum src = factor(b->src, GL_ONE);
        GLenum dst = factor(b->dst, GL_ZERO);
        GLenum src_a = factor(b->src_alpha, src);
        GLenum dst_a = factor(b->dst_alpha, dst);
        GLenum op = LOOKUP(blend_op_gl, b->op, "blend op");
        GLenum op_a = b->op_alpha ? LOOKUP(blend_op_gl, b->op_alpha, "blend op") : op;
        GLenum f[6] = {op, op_a, src, dst, src_a, dst_a};
        if (need(s, K_BLEND_FUNC, memcmp(f, s->gl.blend_func, sizeof f) != 0)) {
            bool ops = s->force || memcmp(f, s->gl.blend_func, 2 * sizeof f[0]) != 0;
            bool factors = s->force || memcmp(f + 2, s->gl.blend_func + 2, 4 * sizeof f[0]) != 0;
            /* Unknown before: both go out. */
            if (!ops && !factors)
                ops = factors = true;
            memcpy(s->gl.blend_func, f, sizeof f);
            if (ops)
                gl.BlendEquationSeparate(op, op_a);
            if (factors)
                gl.BlendFuncSeparate(src, dst, src_a, dst_a);
            changed = true;
        }
    }
    if (changed || s->force)
        count_change(s, GLS_CAT_BLEND);
}

void gl_state_color_mask(gl_state *s, unsigned mask)
{
    bool m[4] = {(mask & GLS_COLOR_MASK_R) != 0, (mask & GLS_COLOR_MASK_G) != 0,
                 (mask & GLS_COLOR_MASK_B) != 0, (mask & GLS_COLOR_MASK_A) != 0};
    if (!need(s, K_COLOR_MASK, memcmp(m, s->gl.color_mask, sizeof m) != 0))
        return;
    memcpy(s->gl.color_mask, m, sizeof m);
    gl.ColorMask(m[0], m[1], m[2], m[3]);
    count_change(s, GLS_CAT_BLEND);
}

/* glDepthMask through the cache; true if it was applied. */
static bool apply_depth_write(gl_state *s, bool write)
{
    if (!need(s, K_DEPTH_WRITE, s->gl.depth_write != write))
        return false;
    s->gl.depth_write = write;
    gl.DepthMask(write ? GL_TRUE : GL_FALSE);
    return true;
}

void gl_state_depth(gl_state *s, const gls_depth *depth)
{
    static const gls_depth off;
    const gls_depth *d = depth ? depth : &off;
    GLenum func = LOOKUP(compare_gl, d->compare, "depth compare");
    bool on = !(func == GL_ALWAYS && !d->write);
    bool changed = false;
    if (need(s, K_DEPTH_ON, s->gl.depth_on != on)) {
        s->gl.depth_on = on;
        set_enabled(GL_DEPTH_TEST, on);
        changed = true;
    }
    if (on) {
        if (need(s, K_DEPTH_FUNC, s->gl.depth_func != func)) {
            s->gl.depth_func = func;
            gl.DepthFunc(func);
            changed = true;
        }
        changed |= apply_depth_write(s, d->write);
    }
    if (changed || s->force)
        count_change(s, GLS_CAT_DEPTH);
}

/* glStencilMask through the cache; true if it was applied. */
static bool apply_stencil_write(gl_state *s, GLuint mask)
{
    if (!need(s, K_STENCIL_WRITE, s->gl.stencil_write != mask))
        return false;
    s->gl.stencil_write = mask;
    gl.StencilMask(mask);
    return true;
}

void gl_state_stencil(gl_state *s, const gls_stencil *stencil)
{
    static const gls_stencil off;
    const gls_stencil *st = stencil ? stencil : &off;
    bool changed = false;
    if (need(s, K_STENCIL_ON, s->gl.stencil_on != st->enabled)) {
        s->gl.stencil_on = st->enabled;
        set_enabled(GL_STENCIL_TEST, st->enabled);
        changed = true;
    }
    if (st->enabled) {
        GLuint read = st->read_mask ? st->read_mask : 0xffu;
        GLuint write = st->write_mask ? st->write_mask : 0xffu;
        static const GLenum face_gl[2] = {GL_FRONT, GL_BACK};
        for (int f = 0; f < 2; f++) {
            const gls_stencil_face *sf = f == 1 && st->two_sided ? &st->back : &st->front;
            stencil_func fn = {LOOKUP(compare_gl, sf->compare, "stencil compare"), st->ref, read};
            stencil_ops ops = {LOOKUP(stencil_op_gl, sf->fail, "stencil op"),
                               LOOKUP(stencil_op_gl, sf->depth_fail, "stencil op"),
                               LOOKUP(stencil_op_gl, sf->pass, "stencil op")};
            stencil_func *cf = &s->gl.stencil_func[f];
            if (need(s, f ? K_STENCIL_FUNC_BACK : K_STENCIL_FUNC_FRONT,
                     cf->func != fn.func || cf->ref != fn.ref || cf->mask != fn.mask)) {
                *cf = fn;
                gl.StencilFuncSeparate(face_gl[f], fn.func, fn.ref, fn.mask);
                changed = true;
            }
            stencil_ops *co = &s->gl.stencil_ops[f];
            if (need(s, f ? K_STENCIL_OP_BACK : K_STENCIL_OP_FRONT,
                     co->sfail != ops.sfail || co->dpfail != ops.dpfail ||
                         co->dppass != ops.dppass)) {
                *co = ops;
                gl.StencilOpSeparate(face_gl[f], ops.sfail, ops.dpfail, ops.dppass);
                changed = true;
            }
        }
        changed |= apply_stencil_write(s, write);
    }
    if (changed || s->force)
        count_change(s, GLS_CAT_STENCIL);
}

void gl_state_cull(gl_state *s, gls_cull cull)
{
    if ((unsigned)cull >= GLS_CULL_COUNT) {
        fprintf(stderr, "bug: gl_state_cull: value %u out of range, culling off\n",
                (unsigned)cull);
        cull = GLS_CULL_NONE;
    }
    bool on = cull != GLS_CULL_NONE;
    bool changed = false;
    if (need(s, K_CULL_ON, s->gl.cull_on != on)) {
        s->gl.cull_on = on;
        set_enabled(GL_CULL_FACE, on);
        changed = true;
    }
    if (on) {
        GLenum face = cull == GLS_CULL_FRONT ? GL_FRONT : GL_BACK;
        if (need(s, K_CULL_FACE, s->gl.cull_face != face)) {
            s->gl.cull_face = face;
            gl.CullFace(face);
            changed = true;
        }
    }
    if (changed || s->force)
        count_change(s, GLS_CAT_CULL);
}

void gl_state_viewport(gl_state *s, int x, int y, int width, int height)
{
    GLint v[4] = {x, y, width, height};
    if (!need(s, K_VIEWPORT, memcmp(v, s->gl.viewport, sizeof v) != 0))
        return;
    memcpy(s->gl.viewport, v, sizeof v);
    gl.Viewport(x, y, width, height);
    count_change(s, GLS_CAT_VIEWPORT);
}

void gl_state_vertex_array(gl_state *s, GLuint vertex_array)
{
    GLuint vao = vertex_array ? vertex_array : s->empty_vertex_array;
    if (!need(s, K_VERTEX_ARRAY, s->gl.vertex_array != vao))
        return;
    s->gl.vertex_array = vao;
    gl.BindVertexArray(vao);
    count_change(s, GLS_CAT_VERTEX_ARRAY);
}

void gl_state_storage_buffer(gl_state *s, unsigned binding, GLuint buffer)
{
    if (binding >= GLS_MAX_BUFFER_BINDINGS) {
        fprintf(stderr, "bug: gl_state_storage_buffer: binding %u of %d\n", binding,
                GLS_MAX_BUFFER_BINDINGS);
        return;
    }
    uint32_t bit = 1u << binding;
    bool apply = s->force || !(s->buffer_known & bit) || s->gl.buffer[binding] != buffer;
    s->buffer_known |= bit;
    if (!apply)
        return;
    s->gl.buffer[binding] = buffer;
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer);
    count_change(s, GLS_CAT_BUFFER);
}

void gl_state_image(gl_state *s, unsigned unit, GLuint texture, GLenum access, GLenum format)
{
    if (unit >= GLS_MAX_IMAGE_UNITS) {
        fprintf(stderr, "bug: gl_state_image: unit %u of %d\n", unit, GLS_MAX_IMAGE_UNITS);
        return;
    }
    uint32_t bit = 1u << unit;
    struct image_binding *b = &s->gl.image[unit];
    if (!texture)
        access = GL_READ_ONLY, format = GL_R8;   /* what GL holds for an empty unit */
    bool apply = s->force || !(s->image_known & bit) || b->texture != texture ||
                 b->access != access || b->format != format;
    s->image_known |= bit;
    if (!apply)
        return;
    *b = (struct image_binding){texture, access, format};
    gl.BindImageTexture(unit, texture, 0, GL_FALSE, 0, access, format);
    count_change(s, GLS_CAT_IMAGE);
}

void gl_state_barrier(gl_state *s, GLbitfield bits)
{
    gl.MemoryBarrier(bits);
    count_change(s, GLS_CAT_BARRIER);
}

// >>the feedback-loop check (state.h)

void gl_state_set_feedback_check(gl_state *s, bool on)
{
    s->feedback_check = on;
}

bool gl_state_feedback_check(const gl_state *s)
{
    return s->feedback_check;
}

uint64_t gl_state_feedback_loops(const gl_state *s)
{
    return s->feedback_loops;
}

const char *gl_state_feedback_message(const gl_state *s)
{
    return s->feedback_message;
}

/* The texture binding a sampler type reads, or 0 for a type that is no sampler (or
 * a buffer texture, which cannot be attached to a framebuffer). */
static GLenum sampler_binding(GLenum type)
{
    switch (type) {
    case GL_SAMPLER_1D: case GL_SAMPLER_1D_SHADOW: case GL_INT_SAMPLER_1D:
    case GL_UNSIGNED_INT_SAMPLER_1D:
        return GL_TEXTURE_BINDING_1D;
    case GL_SAMPLER_2D: case GL_SAMPLER_2D_SHADOW: case GL_INT_SAMPLER_2D:
    case GL_UNSIGNED_INT_SAMPLER_2D:
        return GL_TEXTURE_BINDING_2D;
    case GL_SAMPLER_3D: case GL_INT_SAMPLER_3D: case GL_UNSIGNED_INT_SAMPLER_3D:
        return GL_TEXTURE_BINDING_3D;
    case GL_SAMPLER_CUBE: case GL_SAMPLER_CUBE_SHADOW: case GL_INT_SAMPLER_CUBE:
    case GL_UNSIGNED_INT_SAMPLER_CUBE:
        return GL_TEXTURE_BINDING_CUBE_MAP;
    case GL_SAMPLER_1D_ARRAY: case GL_SAMPLER_1D_ARRAY_SHADOW: case GL_INT_SAMPLER_1D_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_1D_ARRAY:
        return GL_TEXTURE_BINDING_1D_ARRAY;
    case GL_SAMPLER_2D_ARRAY: case GL_SAMPLER_2D_ARRAY_SHADOW: case GL_INT_SAMPLER_2D_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY:
        return GL_TEXTURE_BINDING_2D_ARRAY;
    case GL_SAMPLER_CUBE_MAP_ARRAY: case GL_SAMPLER_CUBE_MAP_ARRAY_SHADOW:
    case GL_INT_SAMPLER_CUBE_MAP_ARRAY: case GL_UNSIGNED_INT_SAMPLER_CUBE_MAP_ARRAY:
        return GL_TEXTURE_BINDING_CUBE_MAP_ARRAY;
    case GL_SAMPLER_2D_RECT: case GL_SAMPLER_2D_RECT_SHADOW: case GL_INT_SAMPLER_2D_RECT:
    case GL_UNSIGNED_INT_SAMPLER_2D_RECT:
        return GL_TEXTURE_BINDING_RECTANGLE;
    case GL_SAMPLER_2D_MULTISAMPLE: case GL_INT_SAMPLER_2D_MULTISAMPLE:
    case GL_UNSIGNED_INT_SAMPLER_2D_MULTISAMPLE:
        return GL_TEXTURE_BINDING_2D_MULTISAMPLE;
    case GL_SAMPLER_2D_MULTISAMPLE_ARRAY: case GL_INT_SAMPLER_2D_MULTISAMPLE_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_2D_MULTISAMPLE_ARRAY:
        return GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY;
    default:
        return 0;
    }
}

/* The active sampler uniforms of prog and the units they read, asked of GL once per
 * program between invalidations. */
static const sampled_program *program_samplers(gl_state *s, GLuint prog)
{
    for (unsigned i = 0; i < s->nsampled; i++)
        if (s->sampled[i].program == prog)
            return &s->sampled[i];
    unsigned slot = s->nsampled < GLS_SAMPLED_PROGRAMS ? s->nsampled++
                                                        : prog % GLS_SAMPLED_PROGRAMS;
    sampled_program *p = &s->sampled[slot];
    memset(p, 0, sizeof *p);
    p->program = prog;
    GLint n = 0;
    gl.GetProgramInterfaceiv(prog, GL_UNIFORM, GL_ACTIVE_RESOURCES, &n);
    for (GLint i = 0; i < n && p->n < GLS_SAMPLERS; i++) {
        static const GLenum props[3] = {GL_TYPE, GL_ARRAY_SIZE, GL_LOCATION};
        GLint v[3] = {0, 0, -1};
        gl.GetProgramResourceiv(prog, GL_UNIFORM, (GLuint)i, 3, props, 3, NULL, v);
        GLenum binding = sampler_binding((GLenum)v[0]);
        if (!binding || v[2] < 0)
            continue;
        char name[32] = "";
        gl.GetProgramResourceName(prog, GL_UNIFORM, (GLuint)i, (GLsizei)sizeof name, NULL, name);
        for (GLint k = 0; k < v[1] && p->n < GLS_SAMPLERS; k++) {
            GLint unit = -1;
            gl.GetUniformiv(prog, v[2] + k, &unit);
            if (unit < 0)
                continue;
            p->sampler[p->n].unit = (GLuint)unit;
            p->sampler[p->n].binding = binding;
            snprintf(p->sampler[p->n].name, sizeof p->sampler[p->n].name, "%s", name);
            p->n++;
        }
    }
    return p;
}

static void object_label(GLenum kind, GLuint name, const char *what, char *out, size_t len)
{
    GLsizei n = 0;
    out[0] = '\0';
    gl.GetObjectLabel(kind, name, (GLsizei)len, &n, out);
    if (n <= 0)
        snprintf(out, len, "%s %u", what, (unsigned)name);
}

static void report_feedback(gl_state *s, const char *what, GLuint prog, GLuint fbo,
                            GLuint texture, const char *sampler, GLuint unit,
                            const char *attachment)
{
    s->feedback_loops++;
    if (s->feedback_loops > 8)
        return;   /* the run has failed already; the log need not fill up */
    char pl[128], fl[64], tl[64];
    object_label(GL_PROGRAM, prog, "program", pl, sizeof pl);
    object_label(GL_FRAMEBUFFER, fbo, "framebuffer", fl, sizeof fl);
    object_label(GL_TEXTURE, texture, "texture", tl, sizeof tl);
    snprintf(s->feedback_message, sizeof s->feedback_message,
             "feedback loop in pass %s: %s of program %s samples texture %s (sampler %s, "
             "unit %u) while it is attached to the draw framebuffer %s (%s); GL 4.5 section "
             "9.3 leaves the result undefined",
             s->in_pass && s->pass_name ? s->pass_name : "(none)", what, pl, tl, sampler,
             (unsigned)unit, fl, attachment);
    if (gl.IsEnabled(GL_DEBUG_OUTPUT))
        gl.DebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_ERROR, 9003,
                              GL_DEBUG_SEVERITY_HIGH, -1, s->feedback_message);
    else
        fprintf(stderr, "bug: %s\n", s->feedback_message);
}

/* Before a draw or dispatch: does the current program sample a texture that is
 * attached to the draw framebuffer? Asks GL, not the cache. */
static void check_feedback(gl_state *s, const char *what)
{
    if (!s->feedback_check)
        return;
    GLint prog = 0, fbo = 0;
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &prog);
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    if (prog <= 0 || fbo <= 0)
        return;   /* the default framebuffer has no texture attached */
    const sampled_program *p = program_samplers(s, (GLuint)prog);
    if (!p->n)
        return;
    GLuint attached[8 + 2];
    const char *point[8 + 2];
    static const char *const color_names[8] = {"colour 0", "colour 1", "colour 2", "colour 3",
                                               "colour 4", "colour 5", "colour 6", "colour 7"};
    unsigned na = 0;
    for (int i = 0; i < s->max_color_attachments + 2; i++) {
        GLenum a = i < s->max_color_attachments ? (GLenum)(GL_COLOR_ATTACHMENT0 + i)
                   : i == s->max_color_attachments ? GL_DEPTH_ATTACHMENT
                                                   : GL_STENCIL_ATTACHMENT;
        GLint type = GL_NONE, name = 0;
        gl.GetNamedFramebufferAttachmentParameteriv((GLuint)fbo, a,
                                                    GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
        if (type != GL_TEXTURE)
            continue;
        gl.GetNamedFramebufferAttachmentParameteriv((GLuint)fbo, a,
                                                    GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
        attached[na] = (GLuint)name;
        point[na++] = i < s->max_color_attachments ? color_names[i]
                      : i == s->max_color_attachments ? "depth" : "stencil";
    }
    if (!na)
        return;
    GLint active = GL_TEXTURE0;
    gl.GetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (unsigned j = 0; j < p->n; j++) {
        GLint bound = 0;
        gl.ActiveTexture(GL_TEXTURE0 + p->sampler[j].unit);
        gl.GetIntegerv(p->sampler[j].binding, &bound);
        for (unsigned k = 0; bound > 0 && k < na; k++)
            if ((GLuint)bound == attached[k]) {
                report_feedback(s, what, (GLuint)prog, (GLuint)fbo, (GLuint)bound,
                                p->sampler[j].name, p->sampler[j].unit, point[k]);
                j = p->n;   /* one report per draw */
                break;
            }
    }
    gl.ActiveTexture((GLenum)active);
}

// >>draws and clears

void gl_state_dispatch(gl_state *s, GLuint x, GLuint y, GLuint z)
{
    check_feedback(s, "dispatch");
    gl.DispatchCompute(x, y, z);
    count_dispatch(s);
}

static const void *offset_ptr(size_t offset)
{
    return (const void *)(uintptr_t)offset;
}

void gl_state_draw_arrays(gl_state *s, GLenum mode, GLint first, GLsizei count)
{
    check_feedback(s, "draw");
    gl.DrawArrays(mode, first, count);
    count_draw(s);
}

void gl_state_draw_arrays_instanced(gl_state *s, GLenum mode, GLint first, GLsizei count,
                                    GLsizei instances)
{
    check_feedback(s, "draw");
    gl.DrawArraysInstanced(mode, first, count, instances);
    count_draw(s);
}

void gl_state_draw_elements(gl_state *s, GLenum mode, GLsizei count, GLenum type, size_t offset)
{
    check_feedback(s, "draw");
    gl.DrawElements(mode, count, type, offset_ptr(offset));
    count_draw(s);
}

void gl_state_draw_elements_instanced(gl_state *s, GLenum mode, GLsizei count, GLenum type,
                                      size_t offset, GLsizei instances)
{
    check_feedback(s, "draw");
    gl.DrawElementsInstanced(mode, count, type, offset_ptr(offset), instances);
    count_draw(s);
}

void gl_state_draw_elements_base_vertex(gl_state *s, GLenum mode, GLsizei count, GLenum type,
                                        size_t offset, GLint base_vertex)
{
    check_feedback(s, "draw");
    gl.DrawElementsBaseVertex(mode, count, type, offset_ptr(offset), base_vertex);
    count_draw(s);
}

bool gl_state_fullscreen_unclipped_fits(const gl_state *s, int width, int height)
{
    return width > 0 && height > 0 && width <= s->max_viewport[0] / 2 &&
           height <= s->max_viewport[1] / 2;
}

bool gl_state_draw_fullscreen(gl_state *s, int width, int height, bool unclipped)
{
    if (unclipped) {
        if (!gl_state_fullscreen_unclipped_fits(s, width, height)) {
            fprintf(stderr, "bug: gl_state_draw_fullscreen: an unclipped triangle over %dx%d "
                    "needs a viewport of %dx%d, beyond GL_MAX_VIEWPORT_DIMS %dx%d\n", width,
                    height, 2 * width, 2 * height, (int)s->max_viewport[0],
                    (int)s->max_viewport[1]);
            return false;
        }
        gl_state_viewport(s, 0, 0, 2 * width, 2 * height);
    } else {
        gl_state_viewport(s, 0, 0, width, height);
    }
    gl_state_vertex_array(s, 0);
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);
    return true;
}

void gl_state_clear(gl_state *s, GLbitfield mask, const float rgba[4], double depth,
                    int stencil)
{
    if (mask & GL_COLOR_BUFFER_BIT) {
        static const float zero[4];
        const float *c = rgba ? rgba : zero;
        gl_state_color_mask(s, GLS_COLOR_MASK_RGBA);
        gl.ClearColor(c[0], c[1], c[2], c[3]);
    }
    if (mask & GL_DEPTH_BUFFER_BIT) {
        if (apply_depth_write(s, true))
            count_change(s, GLS_CAT_DEPTH);
        gl.ClearDepth(depth);
    }
    if (mask & GL_STENCIL_BUFFER_BIT) {
        if (apply_stencil_write(s, 0xffu))
            count_change(s, GLS_CAT_STENCIL);
        gl.ClearStencil(stencil);
    }
    gl.Clear(mask);
}

// >>passes

static double seconds_between(const struct timespec *a, const struct timespec *b)
{
    return (double)(b->tv_sec - a->tv_sec) + (double)(b->tv_nsec - a->tv_nsec) / 1e9;
}

void gl_state_begin_pass(gl_state *s, const char *name)
{
    if (s->in_pass)
        fprintf(stderr, "bug: gl_state_begin_pass(%s) while pass %s is in progress\n",
                name ? name : "(null)", s->pass_name ? s->pass_name : "(null)");
    s->in_pass = true;
    s->pass_name = name;
    memset(&s->pass, 0, sizeof s->pass);
    clock_gettime(CLOCK_MONOTONIC, &s->pass_start);
}

void gl_state_end_pass(gl_state *s, pass_stats *out)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    if (!s->in_pass) {
        fprintf(stderr, "bug: gl_state_end_pass without gl_state_begin_pass\n");
        memset(&s->pass, 0, sizeof s->pass);
        s->pass_name = NULL;
        s->pass_start = now;
    }
    s->in_pass = false;
    if (out) {
        out->name = s->pass_name;
        out->draw_calls = s->pass.draw_calls;
        out->dispatches = s->pass.dispatches;
        out->state_changes = s->pass.state_changes;
        out->cpu_us = seconds_between(&s->pass_start, &now) * 1e6;
    }
}

const gls_counts *gl_state_pass_counts(const gl_state *s)
{
    return &s->pass;
}

const gls_counts *gl_state_total_counts(const gl_state *s)
{
    return &s->total;
}
