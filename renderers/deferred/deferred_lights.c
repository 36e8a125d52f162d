/* The light passes of deferred and deferred-lighting (deferred_lights.h): the
 * light-volume modes as one table (MODES) of what differs per mode, the draws of a light
 * by it, the lighting programs, and with msaa > 1 the edge pass and its draw classes.
 * docs/notes/deferred.md has the passes, the stencil use and the draw counts. */
#include "renderers/deferred/deferred_lights.h"

#include "renderers/frame/frontend.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/state.h"
#include "renderers/frame/scene_gpu.h"
#include "renderers/frame/shading.h"
#include "renderers/frame/shadow.h"
#include "scenes/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(sizeof(gpu_light) == 80, "gpu_light is 5 vec4s, as lighting.inc's Light");

// >>the light-volume modes

/* The sky mask (the file's header): bit 7 marks a surface, bits 0-6 count light volumes;
 * with msaa > 1 bit 6 marks edge pixels and bits 0-5 count. */
enum { SURFACE_BIT = 0x80, VOLUME_BITS = 0x7f, EDGE_BIT = 0x40, MSAA_VOLUME_BITS = 0x3f };

/* msaa > 1: each shading draw runs twice, for the edge pixels (per sample, stencil
 * EDGE_BIT set) and then for the others (per pixel); single-sampled once, for all. */
typedef enum draw_class { CLASS_ALL, CLASS_EDGE, CLASS_PIXEL } draw_class;

/* What the shading draw of a point or spot light tests in the stencil. */
typedef enum shade_test {
    TEST_SURFACE,                    /* the full-screen passes': the sky mask, and the class */
    TEST_CLASS,                      /* the class alone (volume, hull) */
    TEST_COUNT_NONZERO,              /* stencil: counts != 0, ZERO on pass */
    TEST_COUNT_ZERO,                 /* stencil-two-pass: count == 0, INCR on pass */
} shade_test;

/* One stencil-marking draw of the volume (colour writes off, depth LEQUAL, no writes). */
typedef struct mark_draw {
    gls_cull cull;
    bool two_sided;                  /* back faces increment, front faces decrement */
    gls_stencil_op depth_fail;       /* one-sided: the front faces' op on depth fail */
} mark_draw;

/* What differs per light_volumes mode (the file's header); indexed by light_volume_mode. */
typedef struct volume_mode {
    const char *name;
    bool full_screen;                /* the full-screen triangle (else the volume's mesh) */
    bool scissor;                    /* the rectangle around the volume, GL_SCISSOR_TEST */
    int nmarks;                      /* marking draws before the shading draw */
    mark_draw mark[2];
    gls_cull cull;                   /* the shading draw's (volumes) */
    gls_compare depth;               /* the shading draw's depth test (volumes; 0: off) */
    shade_test test;
} volume_mode;

static const volume_mode MODES[] = {
    [LIGHT_VOLUMES_STENCIL] = {"stencil", false, false, 1,
                               {{GLS_CULL_NONE, true, GLS_STENCIL_OP_KEEP}},
                               GLS_CULL_FRONT, 0, TEST_COUNT_NONZERO},
    [LIGHT_VOLUMES_FULLSCREEN] = {"fullscreen", true, false, 0, {{0}}, GLS_CULL_NONE, 0,
                                  TEST_SURFACE},
    [LIGHT_VOLUMES_VOLUME] = {"volume", false, false, 0, {{0}}, GLS_CULL_FRONT,
                              GLS_COMPARE_GREATER, TEST_CLASS},
    [LIGHT_VOLUMES_STENCIL_TWO_PASS] = {"stencil-two-pass", false, false, 2,
                                        {{GLS_CULL_BACK, false, GLS_STENCIL_OP_INCR_WRAP},
                                         {GLS_CULL_FRONT, false, GLS_STENCIL_OP_DECR_WRAP}},
                                        GLS_CULL_FRONT, 0, TEST_COUNT_ZERO},
    [LIGHT_VOLUMES_HULL] = {"hull", false, false, 0, {{0}}, GLS_CULL_FRONT, 0, TEST_CLASS},
    [LIGHT_VOLUMES_SCISSOR] = {"scissor", true, true, 0, {{0}}, GLS_CULL_NONE, 0,
                               TEST_SURFACE},
};

static const volume_mode *mode_of(const deferred *r)
{
    return &MODES[r->d.b.opts.light_volumes];   /* create refused any other */
}

static const char *light_type_name(int t)
{
    return t == LIGHT_POINT ? "point" : t == LIGHT_SPOT ? "spot" : "directional";
}

static int nclasses(const deferred *r)
{
    return r->d.b.samples > 1 ? 2 : 1;
}

/* The i-th class of a draw (edges first: the stencil mode's edge draw must reset the
 * edge samples' counts before the per-pixel draw tests them), and starts counting its
 * draws' samples as per-sample or not. */
static draw_class class_begin(deferred *r, int i)
{
    if (r->d.b.samples <= 1)
        return CLASS_ALL;
    draw_class c = i == 0 ? CLASS_EDGE : CLASS_PIXEL;
    renderer_base_per_sample(&r->d.b, c == CLASS_EDGE);
    return c;
}

static GLuint class_program(draw_class c, GLuint pixel, GLuint sample)
{
    return c == CLASS_EDGE ? sample : pixel;
}

static const gls_stencil SURFACE_TEST = {
    .enabled = true, .front = {.compare = GLS_COMPARE_EQUAL}, .ref = SURFACE_BIT,
    .read_mask = SURFACE_BIT};   /* every op KEEP: writes nothing */

/* What a full-screen pass tests: the surface bit with the sky mask, else nothing; with a
 * class, the edge bit too (EQUAL: set for CLASS_EDGE, clear for CLASS_PIXEL). */
static const gls_stencil *class_stencil(const deferred *r, draw_class c, bool sky_mask,
                                        gls_stencil *buf)
{
    bool sky = sky_mask && r->d.b.opts.sky_stencil;
    if (c == CLASS_ALL)
        return sky ? &SURFACE_TEST : NULL;
    *buf = (gls_stencil){.enabled = true, .front = {.compare = GLS_COMPARE_EQUAL},
                         .ref = (uint8_t)((sky ? SURFACE_BIT : 0) |
                                          (c == CLASS_EDGE ? EDGE_BIT : 0)),
                         .read_mask = (uint8_t)((sky ? SURFACE_BIT : 0) | EDGE_BIT)};
    return buf;
}

/* The stencil modes' read and write masks: bits 0-6 with the sky mask, else 0 (0xff);
 * with msaa, bits 0-5. */
static uint8_t volume_bits(const deferred *r)
{
    if (r->d.b.samples > 1)
        return MSAA_VOLUME_BITS;
    return r->d.b.opts.sky_stencil ? VOLUME_BITS : 0;
}

/* The shading draw's stencil for class c under test t (buf: room for it). */
static const gls_stencil *shade_stencil(const deferred *r, shade_test t, draw_class c,
                                        gls_stencil *buf)
{
    uint8_t bits = volume_bits(r), edge = c == CLASS_EDGE ? EDGE_BIT : 0;
    switch (t) {
    case TEST_SURFACE:
        return class_stencil(r, c, true, buf);
    case TEST_CLASS:
        return class_stencil(r, c, false, buf);
    case TEST_COUNT_NONZERO:
        /* counts != 0; the edge draw first: EDGE_BIT < (edge | count) picks the lit edge
         * samples and zeroes their counts, then != 0 on the count bits alone picks the
         * lit samples of the other pixels */
        *buf = (gls_stencil){.enabled = true,
                             .front = {.compare = edge ? GLS_COMPARE_LESS : GLS_COMPARE_NOTEQUAL,
                                       .pass = GLS_STENCIL_OP_ZERO},
                             .ref = edge, .read_mask = (uint8_t)(bits | edge),
                             .write_mask = bits};
        return buf;
    case TEST_COUNT_ZERO:   /* count == 0, and with msaa the edge bit as the class has it */
        *buf = (gls_stencil){.enabled = true,
                             .front = {.compare = GLS_COMPARE_EQUAL,
                                       .pass = GLS_STENCIL_OP_INCR_WRAP},
                             .ref = edge,
                             .read_mask = (uint8_t)(bits | (c == CLASS_ALL ? 0 : EDGE_BIT)),
                             .write_mask = bits};
        return buf;
    }
    return NULL;
}

/* The marking draws of mode m for light li (shading nothing: not in the samples). */
static void mark_volume(deferred *r, const scene *s, int t, uint32_t li, const volume_mode *m)
{
    gl_state *st = r->d.b.st;
    renderer_base_shading(&r->d.b, false);
    gl_state_program(st, r->mark_program);
    gl_state_color_mask(st, GLS_COLOR_MASK_NONE);
    gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_LEQUAL, .write = false});
    for (int i = 0; i < m->nmarks; i++) {
        const mark_draw *k = &m->mark[i];
        gls_stencil sten = {.enabled = true, .read_mask = volume_bits(r),
                            .write_mask = volume_bits(r)};
        if (k->two_sided) {
            sten.two_sided = true;
            sten.front = (gls_stencil_face){.compare = GLS_COMPARE_ALWAYS,
                                            .depth_fail = GLS_STENCIL_OP_DECR_WRAP};
            sten.back = (gls_stencil_face){.compare = GLS_COMPARE_ALWAYS,
                                           .depth_fail = GLS_STENCIL_OP_INCR_WRAP};
        } else {
            sten.front = (gls_stencil_face){.compare = GLS_COMPARE_ALWAYS,
                                            .depth_fail = k->depth_fail};
        }
        gl_state_cull(st, k->cull);
        gl_state_stencil(st, &sten);
        scene_gpu_draw_light_volume(r->d.b.gpu, st, s, li);
    }
    r->mark_draws[t] += (uint64_t)m->nmarks;
    renderer_base_shading(&r->d.b, true);
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
}

/* Light li, whose shadow-map layer this frame is `layer` (FRONTEND_NO_SHADOW: none). */
static void set_light_uniform(const scene *s, uint32_t li, uint32_t layer)
{
    gpu_light pl;
    shading_pack_light(&s->lights[li], s->view, &pl);
    shading_set_shadow_layer(&pl, layer);
    gl.Uniform4fv(DEFERRED_UNIFORM_LIGHT, 5, &pl.v[0][0]);
}

/* Light li of type t: the full-screen draws of a directional light, or a point or spot
 * light by the light-volume mode m: its rectangle, its marks, then its shading draw for
 * each class. */
static void draw_light(deferred *r, const scene *s, int t, uint32_t li, uint32_t layer,
                       const volume_mode *m)
{
    gl_state *st = r->d.b.st;
    bool full = t == LIGHT_DIRECTIONAL || m->full_screen;
    shade_test test = t == LIGHT_DIRECTIONAL ? TEST_SURFACE : m->test;
    if (t != LIGHT_DIRECTIONAL && m->scissor) {
        int rect[4];
        r->scissor_area += deferred_scissor_rect(s, li, r->d.b.width, r->d.b.height, rect);
        gl.Scissor(rect[0], rect[1], rect[2], rect[3]);
    }
    if (!full) {
        gl_state_viewport(st, 0, 0, r->d.b.width, r->d.b.height);
        if (m->nmarks)
            mark_volume(r, s, t, li, m);
        gl_state_cull(st, m->cull);
        gl_state_depth(st, m->depth ? &(gls_depth){.compare = m->depth, .write = false} : NULL);
    }
    for (int i = 0; i < nclasses(r); i++) {
        gls_stencil sbuf;
        draw_class c = class_begin(r, i);
        gl_state_stencil(st, shade_stencil(r, test, c, &sbuf));
        gl_state_program(st, class_program(c, r->light_program[t], r->light_sample_program[t]));
        set_light_uniform(s, li, layer);
        if (full)
            deferred_fullscreen(&r->d);
        else
            scene_gpu_draw_light_volume(r->d.b.gpu, st, s, li);
        r->shade_draws[t]++;
    }
}

int64_t deferred_scissor_rect(const scene *s, uint32_t light, int w, int h, int rect[4])
{
    const scene_light *l = &s->lights[light];
    rect[0] = rect[1] = 0;
    rect[2] = w;
    rect[3] = h;
    sm_mat4 model, mv, mvp;
    frontend_light_volume_model(l, model);
    /* the volume mesh's box in the model's frame, with room to spare (deferred.h) */
    float lo[3], hi[3];
    if (l->type == LIGHT_POINT) {
        const float b = 1.05f;   /* the sphere's vertices lie within 1.0389 */
        lo[0] = lo[1] = lo[2] = -b;
        hi[0] = hi[1] = hi[2] = b;
    } else {
        const float b = 1.03f;   /* the cone's base: (1 + 2e-4) / cos(pi / 16) = 1.0198 */
        lo[0] = lo[1] = -b;
        hi[0] = hi[1] = b;
        lo[2] = -1.001f;
        hi[2] = 0.001f;
    }
    sm_mat4_mul(s->view, model, mv);
    sm_mat4_mul(s->proj, mv, mvp);
    float x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    float clip[8][4];
    int behind = 0;
    for (int c = 0; c < 8; c++) {
        float p[3] = {(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]};
        for (int k = 0; k < 4; k++)
            clip[c][k] = mvp[0][k] * p[0] + mvp[1][k] * p[1] + mvp[2][k] * p[2] + mvp[3][k];
        behind += clip[c][3] <= 1e-6f;
    }
    if (behind == 8) {   /* wholly behind the eye: nothing */
        rect[2] = rect[3] = 0;
        return 0;
    }
    if (behind)          /* the box reaches the eye's plane: the whole screen */
        return (int64_t)w * h;
    for (int c = 0; c < 8; c++) {
        const float *cl = clip[c];
        float x = (cl[0] / cl[3] * 0.5f + 0.5f) * (float)w;
        float y = (cl[1] / cl[3] * 0.5f + 0.5f) * (float)h;
        x0 = fminf(x0, x);
        x1 = fmaxf(x1, x);
        y0 = fminf(y0, y);
        y1 = fmaxf(y1, y);
    }
    /* whole pixels that the box's projection touches, on the screen */
    float fx0 = fmaxf(floorf(x0), 0.0f), fy0 = fmaxf(floorf(y0), 0.0f);
    float fx1 = fminf(ceilf(x1), (float)w), fy1 = fminf(ceilf(y1), (float)h);
    if (!(fx1 > fx0 && fy1 > fy0)) {
        rect[2] = rect[3] = 0;
        return 0;
    }
    rect[0] = (int)fx0;
    rect[1] = (int)fy0;
    rect[2] = (int)fx1 - rect[0];
    rect[3] = (int)fy1 - rect[1];
    return (int64_t)rect[2] * rect[3];
}

const gls_blend DEFERRED_BLEND_ADD = {.enabled = true, .src = GLS_BLEND_ONE, .dst = GLS_BLEND_ONE};

/* deferred-lighting: the light buffer (bound) starts the frame at zero: the first light
 * pass that runs clears it, or the material pass when none does. */
void deferred_clear_light_buffer(deferred *r)
{
    gl_state_clear(r->d.b.st, GL_COLOR_BUFFER_BIT, NULL, 1.0, 0);
    r->lbuf_cleared = true;
}

/* The pass of the lights of one type: directional full screen, point and spot by the mode.
 * Into the light target, or deferred-lighting's light buffer. */
static void light_pass(deferred *r, const scene *s, frame_stats *out, deferred_pass p, int type)
{
    gl_state *st = r->d.b.st;
    const volume_mode *m = mode_of(r);
    deferred_pass_begin(&r->d, out, p);
    gl_state_framebuffer(st, r->d.lpp ? r->d.fb_lbuf.fbo : r->d.fb_light.fbo);
    if (r->d.lpp && !r->lbuf_cleared)
        deferred_clear_light_buffer(r);   /* before the scissor test is on: all of it */
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    gl_state_blend(st, &DEFERRED_BLEND_ADD);
    bool volumes = type != LIGHT_DIRECTIONAL && !m->full_screen;
    bool scissor = type != LIGHT_DIRECTIONAL && m->scissor;
    r->scissor_area = 0;
    if (scissor)
        gl.Enable(GL_SCISSOR_TEST);   /* not state the cache keeps: off again below */
    if (!volumes) {
        gls_stencil sbuf;
        gl_state_depth(st, NULL);
        gl_state_stencil(st, class_stencil(r, CLASS_ALL, true, &sbuf));
        gl_state_cull(st, GLS_CULL_NONE);
        gl_state_program(st, r->light_program[type]);
    } else {
        gl.Enable(GL_DEPTH_CLAMP);
    }
    if (shadow_maps_for_type(&r->d.b.shadows, type))
        shadow_maps_bind(&r->d.b.shadows, st);
    const frontend *fe = &r->d.b.fe;
    for (uint32_t k = 0; k < fe->nlights; k++) {
        uint32_t li = fe->lights[k];
        if ((int)s->lights[li].type != type)
            continue;
        draw_light(r, s, type, li, fe->shadow_layer[k], m);
        out->lights_drawn++;
    }
    if (volumes) {
        gl.Disable(GL_DEPTH_CLAMP);
        gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    }
    if (scissor)
        gl.Disable(GL_SCISSOR_TEST);
    deferred_pass_end(&r->d, out);
    if (scissor)
        out->pass[out->npasses - 1].scissor_pixels = (double)r->scissor_area;
}

// >>programs and plan

/* The lighting programs: ambient, edges (msaa), one per light type that runs (its
 * vertex shader by the mode), the stencil modes' mark program, compose. */
bool deferred_compile_lighting(deferred *r, char *err, size_t errlen)
{
    deferred_renderer *d = &r->d;
    deferred_layout_defs ld;
    deferred_layout_defines(&d->layout, &ld);
    const char *fs_vert = "fullscreen.vert";
    const char *unclipped = d->unclipped ? "FULLSCREEN_UNCLIPPED" : NULL;
    /* deferred-lighting's light buffer: diffuse and specular light in two targets */
    const char *sep = d->b.opts.separate_specular || d->lpp ? "SEPARATE_SPECULAR" : NULL;
    if (!d->lpp) {   /* deferred-lighting: ambient and emissive in the material pass */
        const char *extra[3] = {NULL, NULL, NULL};
        int n = 0;
        if (unclipped)
            extra[n++] = unclipped;
        if (sep)
            extra[n++] = sep;
        if (!deferred_build_msaa(d, "deferred_ambient", fs_vert, "deferred_ambient.frag", &ld,
                                 extra, &r->ambient_program, &r->ambient_sample_program, err,
                                 errlen))
            return false;
    }
    if (d->run[PASS_EDGES]) {   /* msaa > 1, unless the edges are found elsewhere */
        const char *extra[2] = {unclipped, NULL};
        if (!deferred_build_msaa(d, "deferred_edges", fs_vert, "edge_mark.frag", &ld, extra,
                                 &r->edge_program, NULL, err, errlen))
            return false;
    }
    if (d->run[PASS_EDGES] && d->layout.position == DEFERRED_POSITION_DEPTH_BUFFER)
        deferred_set_sample_positions(d, d->fb_light.fbo, r->edge_program,
                                      DEFERRED_UNIFORM_LIGHT);
    static const deferred_pass light_pass_of[DEFERRED_LIGHT_TYPES] = {
        [LIGHT_POINT] = PASS_POINT, [LIGHT_SPOT] = PASS_SPOT,
        [LIGHT_DIRECTIONAL] = PASS_DIRECTIONAL};
    static const char *const type_define[DEFERRED_LIGHT_TYPES] = {
        [LIGHT_POINT] = "DEFERRED_LIGHT_TYPE 0", [LIGHT_SPOT] = "DEFERRED_LIGHT_TYPE 1",
        [LIGHT_DIRECTIONAL] = "DEFERRED_LIGHT_TYPE 2"};
    static const char *const display[DEFERRED_LIGHT_TYPES] = {
        [LIGHT_POINT] = "deferred_point", [LIGHT_SPOT] = "deferred_spot",
        [LIGHT_DIRECTIONAL] = "deferred_directional"};
    /* Shadow variants say so in their display name: the plan cuts a variant's name at
     * 63 characters, before the layout's defines end. */
    static const char *const display_shadowed[DEFERRED_LIGHT_TYPES] = {
        [LIGHT_POINT] = "deferred_point", [LIGHT_SPOT] = "deferred_spot_shadowed",
        [LIGHT_DIRECTIONAL] = "deferred_directional_shadowed"};
    bool volumes = false;
    for (int t = 0; t < DEFERRED_LIGHT_TYPES; t++) {
        if (!d->run[light_pass_of[t]])
            continue;
        bool full = t == LIGHT_DIRECTIONAL || mode_of(r)->full_screen;
        const char *extra[7] = {type_define[t], NULL, NULL, NULL, NULL, NULL, NULL};
        int n = 1;
        if (full && unclipped)
            extra[n++] = unclipped;
        if (sep)
            extra[n++] = sep;
        if (d->lpp)
            extra[n++] = "LIGHT_PREPASS";
        bool shadowed = shadow_maps_for_type(&d->b.shadows, t);
        if (shadowed)
            n += (int)shadow_maps_defines(&d->b.shadows, extra + n);
        if (!deferred_build_msaa(d, shadowed ? display_shadowed[t] : display[t],
                                 full ? fs_vert : "light_volume.vert", "deferred_light.frag",
                                 &ld, extra, &r->light_program[t], &r->light_sample_program[t],
                                 err, errlen))
            return false;
        if (!full)
            volumes = true;
    }
    if (volumes && mode_of(r)->nmarks &&
        !deferred_build_program(d, "deferred_stencil_mark", "light_volume.vert",
                                "stencil_mark.frag", NULL, NULL, &r->mark_program, err, errlen))
        return false;
    if (d->run[PASS_COMPOSE]) {
        const char *extra[2] = {unclipped, NULL};
        if (!deferred_build_msaa(d, "deferred_compose", fs_vert, "deferred_compose.frag", NULL,
                                 extra, &r->compose_program, &r->compose_sample_program, err,
                                 errlen))
            return false;
    }
    return true;
}

/* The plan's light passes: a pass per light type the scene has. */
void deferred_plan_lights(deferred *r)
{
    deferred_renderer *d = &r->d;
    const char *into = d->lpp ? ", into the light buffer" : "";
    if (d->count[LIGHT_DIRECTIONAL])
        deferred_plan(d, PASS_DIRECTIONAL, true, "%u directional lights, full screen each%s",
                      d->count[LIGHT_DIRECTIONAL], into);
    else
        deferred_plan(d, PASS_DIRECTIONAL, false, "no directional light in the scene");
    for (int t = LIGHT_POINT; t <= LIGHT_SPOT; t++) {
        deferred_pass p = t == LIGHT_POINT ? PASS_POINT : PASS_SPOT;
        if (d->count[t])
            deferred_plan(d, p, true, "%u %s lights, light volumes: %s%s", d->count[t],
                          light_type_name(t), mode_of(r)->name, into);
        else
            deferred_plan(d, p, false, "no %s light in the scene", light_type_name(t));
    }
}

/* The programs prepare made, forgotten (the cache that owns them is remade). */
void deferred_forget_programs(deferred *r)
{
    memset(r->light_program, 0, sizeof r->light_program);
    memset(r->light_sample_program, 0, sizeof r->light_sample_program);
    memset(r->material_program, 0, sizeof r->material_program);
    r->ambient_program = r->compose_program = r->mark_program = 0;
    r->ambient_sample_program = r->compose_sample_program = r->edge_program = 0;
}

bool deferred_lights_prepare_begin(deferred *r, const scene *s, char *err, size_t errlen)
{
    deferred_core_release(&r->d);
    deferred_forget_programs(r);
    if (deferred_prepare_scene(&r->d, s, err, errlen))
        return true;
    deferred_core_release(&r->d);
    return false;
}

bool deferred_lights_prepare_end(deferred *r, const scene *s,
                                 bool (*programs)(deferred *r, char *err, size_t errlen),
                                 bool (*translucent)(deferred *r, char *err, size_t errlen),
                                 char *err, size_t errlen)
{
    deferred_renderer *d = &r->d;
    if (!deferred_make_targets(d, err, errlen) || !deferred_compile_gbuffer(d, err, errlen) ||
        !deferred_compile_lighting(r, err, errlen) || (programs && !programs(r, err, errlen)) ||
        !deferred_compile_fog(d, err, errlen) ||
        !translucent_prepare(&d->translucent, &d->b, s, &d->b.shadows, translucent != NULL,
                             err, errlen) ||
        (translucent && !translucent(r, err, errlen)) ||
        !deferred_prepare_edge_aa(d, err, errlen)) {
        deferred_core_release(d);
        return false;
    }
    deferred_prepare_end(d);
    return true;
}

// >>per frame

bool deferred_lights_frame_begin(deferred *r, const scene *s, frame_stats *out)
{
    memset(r->mark_draws, 0, sizeof r->mark_draws);
    memset(r->shade_draws, 0, sizeof r->shade_draws);
    r->edges_pass = 0;
    if (!deferred_frame_begin(&r->d, s, out))
        return false;
    if (r->d.run[PASS_EDGES])
        deferred_edges_pass(r, out);
    return true;
}

void deferred_light_passes(deferred *r, const scene *s, frame_stats *out)
{
    if (r->d.run[PASS_DIRECTIONAL])
        light_pass(r, s, out, PASS_DIRECTIONAL, LIGHT_DIRECTIONAL);
    if (r->d.run[PASS_POINT])
        light_pass(r, s, out, PASS_POINT, LIGHT_POINT);
    if (r->d.run[PASS_SPOT])
        light_pass(r, s, out, PASS_SPOT, LIGHT_SPOT);
}

/* msaa > 1: EDGE_BIT on every sample of the pixels whose samples differ. */
void deferred_edges_pass(deferred *r, frame_stats *out)
{
    gl_state *st = r->d.b.st;
    deferred_pass_begin(&r->d, out, PASS_EDGES);
    gl_state_framebuffer(st, r->d.fb_light.fbo);
    gl_state_color_mask(st, GLS_COLOR_MASK_NONE);
    gl_state_blend(st, NULL);
    gl_state_depth(st, NULL);
    gl_state_cull(st, GLS_CULL_NONE);
    gl_state_stencil(st, &(gls_stencil){
                             .enabled = true,
                             .front = {.compare = GLS_COMPARE_ALWAYS,
                                       .pass = GLS_STENCIL_OP_REPLACE},
                             .ref = EDGE_BIT,
                             .write_mask = EDGE_BIT,
                         });
    deferred_bind_gbuffer_textures(&r->d);
    gl_state_program(st, r->edge_program);
    deferred_fullscreen(&r->d);   /* samples: N per edge pixel (the others are discarded) */
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    deferred_pass_end(&r->d, out);
    r->edges_pass = out->npasses;
}

/* One full-screen draw per class with the pixel and sample programs (ambient, compose). */
void deferred_fullscreen_classes(deferred *r, GLuint pixel, GLuint sample)
{
    for (int i = 0; i < nclasses(r); i++) {
        gls_stencil sbuf;
        draw_class c = class_begin(r, i);
        gl_state_stencil(r->d.b.st, class_stencil(r, c, true, &sbuf));
        gl_state_program(r->d.b.st, class_program(c, pixel, sample));
        deferred_fullscreen(&r->d);
    }
}

void deferred_collect(void *self, frame_stats *out)
{
    deferred *r = self;
    renderer_base_collect(&r->d.b, out);
    /* the edge pass passes N samples per edge pixel and discards every other pixel */
    if (r->edges_pass && r->edges_pass <= out->npasses)
        out->edge_fraction = out->pass[r->edges_pass - 1].samples / r->d.b.samples /
                             ((double)r->d.b.width * r->d.b.height);
}
