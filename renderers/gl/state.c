/* The GL state cache (state.h). */
#include "renderers/gl/state_internal.h"

#include "renderers/gl/target.h"

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

// >>the cache (its object: state_internal.h)

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
    GL_OBJECTS_DELETE(GLO_VERTEX_ARRAY, &s->empty_vertex_array);
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

/* glEnable or glDisable of cap through the cache (*cached, under key k); true if it
 * was applied. */
static bool apply_enabled(gl_state *s, unsigned k, bool *cached, GLenum cap, bool on)
{
    if (!need(s, k, *cached != on))
        return false;
    *cached = on;
    if (on)
        gl.Enable(cap);
    else
        gl.Disable(cap);
    return true;
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
    bool changed = apply_enabled(s, K_BLEND_ON, &s->gl.blend_on, GL_BLEND, b->enabled);
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
    bool changed = apply_enabled(s, K_DEPTH_ON, &s->gl.depth_on, GL_DEPTH_TEST, on);
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
    bool changed =
        apply_enabled(s, K_STENCIL_ON, &s->gl.stencil_on, GL_STENCIL_TEST, st->enabled);
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
    bool changed = apply_enabled(s, K_CULL_ON, &s->gl.cull_on, GL_CULL_FACE, on);
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

gls_cull gl_state_cull_current(const gl_state *s)
{
    if (!s->gl.cull_on)
        return GLS_CULL_NONE;
    return s->gl.cull_face == GL_FRONT ? GLS_CULL_FRONT : GLS_CULL_BACK;
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

// >>draws and clears

void gl_state_dispatch(gl_state *s, GLuint x, GLuint y, GLuint z)
{
    gl_state_check_feedback(s, "dispatch");
    gl.DispatchCompute(x, y, z);
    count_dispatch(s);
}

static const void *offset_ptr(size_t offset)
{
    return (const void *)(uintptr_t)offset;
}

void gl_state_draw_arrays(gl_state *s, GLenum mode, GLint first, GLsizei count)
{
    gl_state_check_feedback(s, "draw");
    gl.DrawArrays(mode, first, count);
    count_draw(s);
}

void gl_state_draw_arrays_instanced(gl_state *s, GLenum mode, GLint first, GLsizei count,
                                    GLsizei instances)
{
    gl_state_check_feedback(s, "draw");
    gl.DrawArraysInstanced(mode, first, count, instances);
    count_draw(s);
}

void gl_state_draw_elements(gl_state *s, GLenum mode, GLsizei count, GLenum type, size_t offset)
{
    gl_state_check_feedback(s, "draw");
    gl.DrawElements(mode, count, type, offset_ptr(offset));
    count_draw(s);
}

void gl_state_draw_elements_instanced(gl_state *s, GLenum mode, GLsizei count, GLenum type,
                                      size_t offset, GLsizei instances)
{
    gl_state_check_feedback(s, "draw");
    gl.DrawElementsInstanced(mode, count, type, offset_ptr(offset), instances);
    count_draw(s);
}

void gl_state_draw_elements_base_vertex(gl_state *s, GLenum mode, GLsizei count, GLenum type,
                                        size_t offset, GLint base_vertex)
{
    gl_state_check_feedback(s, "draw");
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
