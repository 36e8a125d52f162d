/* The deferred renderer (seed 000 section 4.5; seeds 001-004 for the G-buffer
 * layouts and the light volumes).
 *
 * Every frame, in passes named as passes.csv names them (a pass the plan skips is
 * not run, and renderer_describe says why):
 *
 *   shadows      (some spot or directional light casts shadows, shadows not off;
 *                renderers/shadow.h) per visible shadow-casting light, its shadow map:
 *                one depth-only draw per object of its shadow-casting set (frontend.h)
 *   gbuffer      the G-buffer framebuffer (the layout's attachments + the shared
 *                depth-stencil target) cleared (colour 0, depth 1, stencil 0 or, for
 *                stencil-two-pass, 1), then one draw per visible object (frontend order:
 *                state buckets), mesh.vert + gbuffer.frag in the material's map variant,
 *                depth LESS with writes, back faces culled (as the forward renderers)
 *   ambient      full screen: ambient x diffuse + emissive written over the light target
 *                (no blend; it starts the accumulation)
 *   directional  full screen per visible directional light, blend ONE + ONE; a light
 *                with a shadow map is shaded by the SHADOWS variant (seed 000 4.5.6:
 *                the G-buffer position to the light's map, lighting.inc + shadow.inc),
 *                and so are spots; the variant is built only for a light type some
 *                light of which casts shadows
 *   point, spot  per visible light of that type, by renderer_options.light_volumes:
 *     fullscreen        a full-screen pass (the light's range and cone do the culling)
 *     volume            the volume's back faces (cull FRONT), depth test GREATER, no
 *                       writes: the pixels whose surface is in front of the volume's back
 *     stencil           (seed 003) mark: one draw, both faces (cull NONE), colour writes
 *                       off, depth LEQUAL without writes, two-sided stencil: back faces
 *                       increment (wrap) and front faces decrement on depth fail; shade:
 *                       back faces, depth test off, stencil NOTEQUAL 0, ZERO on pass (which
 *                       resets the stencil for the next light)
 *     stencil-two-pass  (seed 000) the stencil cleared to 1 with the G-buffer; mark front
 *                       faces (increment on depth fail), then back faces (decrement on
 *                       depth fail); shade back faces where the stencil is 0, INCR on pass
 *                       (which resets it to 1)
 *     hull              (seed 000 4.5.8's unoptimised baseline) the volume's back faces (cull
 *                       FRONT), no depth test, no stencil: every pixel the hull covers is
 *                       shaded, whatever surface lies there
 *     scissor           a full-screen pass with the scissor test on, the rectangle
 *                       deferred_scissor_rect (the projection of the box around the light's
 *                       volume; Policarpo & Fonseca as seed 000 4.5.8 cites them); passes.csv's
 *                       scissor_pixels is the sum of the pass's rectangles. GL_SCISSOR_TEST is
 *                       not state the cache keeps: it is switched off again after the pass
 *   compose      (separate_specular only, seed 001) the specular target added into the
 *                diffuse one, full screen
 *   fog          (fog.density > 0; seed 000 4.5.12) full screen into the light target
 *                alone (no depth attachment): each pixel's depth unprojected to view z,
 *                and deferred_fog.frag blends exp(-density z) of the light with the fog
 *                colour; pixels at depth 1 unchanged. Skipped (no program) when off
 *   sky          (the scene has a sky) scene_gpu_draw_sky into the light target's
 *                untouched depth (z = w, depth LEQUAL): last, as seed 000 4.5.11
 *   translucent  (the scene has MATERIAL_BLEND objects; seed 001 19.8.1: translucent
 *                geometry drawn by a forward renderer after the deferred one) the
 *                frontend's translucent objects, back to front, shaded by the forward
 *                single-pass program with every visible light and blended over the light
 *                target, testing (not writing) the G-buffer pass's depth
 *                (renderers/translucent.h); one draw each. Skipped, no program, otherwise
 *                (tiled-deferred: its tiles' translucent lists, tiled/tiled_deferred.c)
 *   edge-aa      (aa: edge; renderers/edge_aa.h) seed 001 19.5.2's edge blur of the light
 *                target into "hdr.aa", its normals from the G-buffer (gbuffer.inc)
 *   resolve      scene_gpu_resolve: the light target (or "hdr.aa") clamped into the output
 *
 * MSAA (msaa > 1; docs/architecture.md): every G-buffer attachment, the light targets and
 * depth are multisampled. After the G-buffer pass, `edges` (edge_mark.frag, full screen,
 * per pixel) sets stencil EDGE_BIT (0x40) on every sample of a pixel whose samples differ
 * from sample 0 (surface / none, off its tangent plane by > 1 % of the view depth, normal
 * > acos(0.98)); the stencil
 * modes then count in bits 0-5. Every shading draw of ambient, the light passes (every
 * light-volume mode) and compose runs twice, edges first: the per-sample variant
 * (GB_SAMPLE gl_SampleID) where EDGE_BIT is set, the per-pixel one (sample 0) where it is
 * clear (class_begin, class_stencil; the draw counts above double for those passes). Fog
 * runs per sample everywhere. `msaa-resolve` (renderers/base.h) averages the light
 * before resolve. (tiled-deferred classifies the pixels by the same rule in its dispatch:
 * tiled/tiled_deferred.c.)
 *
 * Sky mask (renderer_options.sky_stencil, deferred.sky_stencil; seed 001 section 19.7.2,
 * "Stencil Masking": the opaque geometry marks, at no extra draw, the pixels that deferred
 * shading will light, and the lighting passes skip the others by the stencil test): the
 * G-buffer draws set stencil bit 7 (SURFACE_BIT) where they pass the depth test (ALWAYS,
 * REPLACE on pass, write mask 0x80), so the pixels no geometry covers, the sky, keep it
 * clear; the full-screen passes (ambient, directional, point and spot in the fullscreen
 * and scissor modes, compose) test EQUAL 0x80 under read mask 0x80 and write nothing,
 * so each of their draws shades exactly the sky's pixel count fewer samples. The
 * stencil and stencil-two-pass modes then count in bits 0-6 (read and write masks
 * 0x7f: increment and decrement wrap within the seven bits, and reset them only), so
 * the mark survives every light. The volume, stencil and stencil-two-pass modes
 * already reject the sky by depth (nothing lies in front of a volume's back face
 * there); hull, seed 000's unoptimised baseline, is left as it is, and so is fog (its
 * framebuffer has no stencil; it leaves depth-1 pixels alone anyway). The ambient pass
 * no longer writes the sky's pixels, so with no sky pass to draw them the light
 * target is cleared to (0, 0, 0, 1) first (the ambient pass's value there); with one,
 * the sky covers exactly the unmarked pixels (depth 1). Not in tiled-deferred (its
 * create refuses the option: no stencil test masks a dispatch).
 *
 * Draw calls per frame (V visible objects, D / P / S visible directional / point / spot
 * lights this frame, frontend_build; [x] = 1 when the pass runs, else 0; C(l) the
 * shadow-casting set of a visible light l that casts shadows, Sh = sum of |C(l)| over
 * them, 0 when the shadows pass does not run):
 *
 *   fullscreen, scissor, volume, hull:
 *                      Sh + V + 1 + D + P + S            + [compose] + [fog] + [sky] + [aa] + 1
 *   stencil:           Sh + V + 1 + D + 2 (P + S)        + [compose] + [fog] + [sky] + [aa] + 1
 *   stencil-two-pass:  Sh + V + 1 + D + 3 (P + S)        + [compose] + [fog] + [sky] + [aa] + 1
 *
 * (shadows Sh, gbuffer V, ambient 1, directional D, point/spot 1 per light (shade), 2
 * (mark + shade) or 3 (front mark + back mark + shade), compose 1, fog 1, sky 1, edge-aa 1,
 * resolve 1; clears are not draws; V counts opaque objects, and the translucent pass adds
 * one draw per visible translucent object.) Without Sh they do not depend on where the camera is; the
 * shadow-casting sets do (frontend.h).
 *
 * Camera inside a volume, near and far planes. The volume passes run with GL_DEPTH_CLAMP
 * on (and it is switched off again after them; it is not state the cache keeps): the
 * near and far planes then clip nothing, and a volume's faces beyond the far plane are
 * drawn at depth 1. Every mode decides on depth FAIL only (the volume's face behind the
 * surface), which makes it exact whatever cuts the volume in front: a front face lost
 * behind the eye, or between the eye and the near plane (there at depth 0), would have
 * passed the test and counted nothing. So the same passes are correct with the camera
 * inside a point or spot volume, with the near plane cutting it (the frontend's
 * eye_inside is not needed: no per-light switch, and draw counts stay as above) and with
 * the far plane cutting it (depth clamp). Pixels that no surface covers keep depth 1,
 * where a clamped back face passes LEQUAL (fails GREATER): they are never lit, and the
 * shaders light nothing where the G-buffer holds no surface anyway (zero normal).
 *
 * G-buffer presets (deferred.h has the slots; an attachment no needed slot uses is not
 * allocated; gloss and shininess are needed when some object's material has specular >
 * 0, emissive when some object's material has an emissive colour > 0):
 *
 *   fat        (seed 000) RGBA16F position.xyz + shininess | RGBA16F normal.xyz +
 *              emissive intensity e (emissive = e x diffuse, as seed 000 modulates the
 *              diffuse colour) | RGBA16F diffuse + gloss
 *   curtis     (seed 003) RGBA16F normal.xyz + linear depth | RGBA16F diffuse + gloss
 *              ("specular") | RGBA16F shininess (the "specular colour" target: specular
 *              here is colourless, its exponent takes the place) | RGBA16F emissive (the
 *              unused fourth, written only by emissive scenes); position = view ray x
 *              depth
 *   compact    (seed 002's 96 bits) RG16F position.xy | R16F position.z | RGBA8 diffuse
 *              + normal.z | RG8 normal.xy (unorm), and beyond seed 002 (which stores no
 *              specular or emissive), when the scene needs them: RG8 gloss + shininess/255,
 *              RGBA8 emissive
 *   spheremap  (seed 004) RG8 normal (Lambert azimuthal) | RGBA16F linear depth + gloss +
 *              shininess | RGBA8 diffuse | RGBA8 emissive (when needed); position = the
 *              pixel's frustum-corner ray x depth
 *   reference  RGBA32F position.xyz + shininess | RGBA32F normal.xyz + gloss | RGBA32F
 *              diffuse | RGBA32F emissive
 *
 * Position from the depth buffer (gbuffer position: depth): the light passes test against
 * the shared depth-stencil target, which is attached to the light framebuffer, so they
 * cannot sample it too: texturing from an image attached to the bound draw framebuffer
 * is undefined in GL 4.5 (section 9.3), write masks off or not (llvmpipe gives the
 * expected texels, a GPU need not). So the G-buffer pass ends, after its draws, with one
 * glCopyImageSubData of the depth-stencil target into "depth.sampled" (the same format;
 * no draw, counted in the G-buffer pass's GPU time), and the light passes sample that.
 * tiled-deferred needs no copy (tiled/tiled_deferred.c).
 * Shadow maps do not touch it (they have their own depth targets). The state cache's
 * feedback-loop check (state.h) fails any draw or dispatch that samples an attached
 * texture in debug contexts (every test).
 *
 * The light-volume modes are one table (MODES below) of what differs per mode: full
 * screen or the volume's mesh, the scissor rectangle, the marking draws, the shading
 * draw's cull, depth test and stencil test; the code that draws a light reads it.
 * What deferred shares with tiled-deferred (the G-buffer pass, targets, fog, sky,
 * translucent, edge-aa, resolve, describe) is renderers/deferred_core.c.
 *
 * Targets: the G-buffer attachments ("gbuffer.<slots>"), "light" (the run's HDR format,
 * RGBA16F or RGBA32F, renderers/base.h; with
 * separate_specular "light.diffuse" + "light.specular") and "depth" (depth24-stencil8,
 * shared by the G-buffer and light framebuffers so that volumes test against the scene's
 * depth), and with position from depth (deferred only) "depth.sampled", its copy.
 * gbuffer_bytes counts the G-buffer's colour attachments. */
#include "renderers/deferred_core.h"

#include "renderers/frontend.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/state.h"
#include "renderers/scene_gpu.h"
#include "renderers/shading.h"
#include "renderers/shadow.h"
#include "scenes/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(sizeof(gpu_light) == 80, "gpu_light is 5 vec4s, as lighting.inc's Light");

typedef struct deferred {
    deferred_renderer d;             /* first: deferred_describe and the accessors read it */
    GLuint ambient_program, compose_program, mark_program;
    GLuint light_program[DEFERRED_LIGHT_TYPES];
    /* msaa > 1: the per-sample variants (edge pixels) and the edge-mark program */
    GLuint ambient_sample_program, compose_sample_program, edge_program;
    GLuint light_sample_program[DEFERRED_LIGHT_TYPES];
    /* deferred-lighting: the material pass's programs, per map variant */
    GLuint material_program[DEFERRED_VARIANTS];
    bool lbuf_cleared;               /* deferred-lighting: the light buffer cleared this frame */

    /* >>the last frame, for tests */
    uint64_t mark_draws[DEFERRED_LIGHT_TYPES], shade_draws[DEFERRED_LIGHT_TYPES];
    int64_t scissor_area;            /* light_volumes scissor: this pass's rectangles */
    size_t edges_pass;               /* msaa > 1: 1 + the edge pass's index; 0: none */
} deferred;

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


static const gls_blend BLEND_ADD = {.enabled = true, .src = GLS_BLEND_ONE, .dst = GLS_BLEND_ONE};

/* deferred-lighting: the light buffer (bound) starts the frame at zero: the first light
 * pass that runs clears it, or the material pass when none does. */
static void clear_light_buffer(deferred *r)
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
        clear_light_buffer(r);   /* before the scissor test is on: all of it */
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    gl_state_blend(st, &BLEND_ADD);
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

// >>create and prepare

static void *deferred_create(const renderer_options *opts, char *err, size_t errlen)
{
    return deferred_core_create("deferred", sizeof(deferred), false, false, opts, err, errlen);
}

/* The lighting programs: ambient, edges (msaa), one per light type that runs (its
 * vertex shader by the mode), the stencil modes' mark program, compose. */
static bool compile_lighting(deferred *r, char *err, size_t errlen)
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
    if (d->b.samples > 1) {
        const char *extra[2] = {unclipped, NULL};
        if (!deferred_build_msaa(d, "deferred_edges", fs_vert, "edge_mark.frag", &ld, extra,
                                 &r->edge_program, NULL, err, errlen))
            return false;
    }
    if (d->b.samples > 1 && d->layout.position == DEFERRED_POSITION_DEPTH_BUFFER)
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
static void plan_lights(deferred *r)
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
static void forget_programs(deferred *r)
{
    memset(r->light_program, 0, sizeof r->light_program);
    memset(r->light_sample_program, 0, sizeof r->light_sample_program);
    memset(r->material_program, 0, sizeof r->material_program);
    r->ambient_program = r->compose_program = r->mark_program = 0;
    r->ambient_sample_program = r->compose_sample_program = r->edge_program = 0;
}

static bool deferred_prepare(void *self, const scene *s, char *err, size_t errlen)
{
    deferred *r = self;
    deferred_renderer *d = &r->d;
    deferred_core_release(d);
    forget_programs(r);
    if (!deferred_prepare_scene(d, s, err, errlen))
        goto fail;
    deferred_plan(d, PASS_AMBIENT, true, "%s%s",
                  d->needs.emissive ? "ambient x diffuse + emissive, full screen"
                                    : "ambient x diffuse, full screen (no material is emissive)",
                  d->b.opts.sky_stencil ? "; the full-screen passes skip the sky by the stencil"
                                        : "");
    plan_lights(r);
    deferred_plan(d, PASS_TILED, false, "deferred shades with light volumes, not tiles");
    deferred_plan(d, PASS_EDGES, d->b.samples > 1,
                  "msaa %d: pixels whose samples differ (off the plane > 1%% of depth, normal > "
                  "11.5 deg) get stencil bit 0x40; per sample there, per pixel elsewhere",
                  d->b.samples);
    if (!deferred_make_targets(d, err, errlen) || !deferred_compile_gbuffer(d, err, errlen) ||
        !compile_lighting(r, err, errlen) || !deferred_compile_fog(d, err, errlen) ||
        !translucent_prepare(&d->translucent, &d->b, s, &d->b.shadows, false, err, errlen) ||
        !deferred_prepare_edge_aa(d, err, errlen))
        goto fail;
    deferred_prepare_end(d);
    return true;
fail:
    deferred_core_release(d);
    return false;
}

// >>per frame

/* msaa > 1: EDGE_BIT on every sample of the pixels whose samples differ. */
static void edges_pass(deferred *r, frame_stats *out)
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
static void fullscreen_classes(deferred *r, GLuint pixel, GLuint sample)
{
    for (int i = 0; i < nclasses(r); i++) {
        gls_stencil sbuf;
        draw_class c = class_begin(r, i);
        gl_state_stencil(r->d.b.st, class_stencil(r, c, true, &sbuf));
        gl_state_program(r->d.b.st, class_program(c, pixel, sample));
        deferred_fullscreen(&r->d);
    }
}

static void deferred_draw(void *self, const scene *s, frame_stats *out)
{
    deferred *r = self;
    deferred_renderer *d = &r->d;
    gl_state *st = d->b.st;
    memset(r->mark_draws, 0, sizeof r->mark_draws);
    r->edges_pass = 0;
    memset(r->shade_draws, 0, sizeof r->shade_draws);
    if (!deferred_frame_begin(d, s, out))
        return;
    if (d->run[PASS_EDGES])
        edges_pass(r, out);

    /* >>ambient + emissive */
    deferred_pass_begin(d, out, PASS_AMBIENT);
    gl_state_framebuffer(st, d->fb_light.fbo);
    if (d->b.opts.sky_stencil && !d->run[PASS_SKY]) {
        /* the sky's pixels: what the ambient pass writes there, as nothing else will */
        static const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
        gl_state_clear(st, GL_COLOR_BUFFER_BIT, black, 1.0, 0);
    }
    gl_state_blend(st, NULL);
    gl_state_depth(st, NULL);
    gl_state_cull(st, GLS_CULL_NONE);
    deferred_bind_gbuffer_textures(d);
    fullscreen_classes(r, r->ambient_program, r->ambient_sample_program);
    deferred_pass_end(d, out);

    /* >>lights */
    if (d->run[PASS_DIRECTIONAL])
        light_pass(r, s, out, PASS_DIRECTIONAL, LIGHT_DIRECTIONAL);
    if (d->run[PASS_POINT])
        light_pass(r, s, out, PASS_POINT, LIGHT_POINT);
    if (d->run[PASS_SPOT])
        light_pass(r, s, out, PASS_SPOT, LIGHT_SPOT);

    GLuint hdr_fbo = d->fb_light.fbo;   /* where the sky goes */
    if (d->run[PASS_COMPOSE]) {
        deferred_pass_begin(d, out, PASS_COMPOSE);
        gl_state_framebuffer(st, d->fb_compose.fbo);
        gl_state_blend(st, &BLEND_ADD);
        gl_state_depth(st, NULL);
        gl_state_cull(st, GLS_CULL_NONE);
        gl_state_texture(st, DEFERRED_SPECULAR_UNIT, d->specular.texture);
        fullscreen_classes(r, r->compose_program, r->compose_sample_program);
        deferred_pass_end(d, out);
        hdr_fbo = d->fb_compose.fbo;
    }
    deferred_frame_end(d, s, out, hdr_fbo);
}

static void deferred_collect(void *self, frame_stats *out)
{
    deferred *r = self;
    renderer_base_collect(&r->d.b, out);
    /* the edge pass passes N samples per edge pixel and discards every other pixel */
    if (r->edges_pass && r->edges_pass <= out->npasses)
        out->edge_fraction = out->pass[r->edges_pass - 1].samples / r->d.b.samples /
                             ((double)r->d.b.width * r->d.b.height);
}

static void deferred_destroy(void *self)
{
    deferred_core_destroy(self);
}

// >>deferred-lighting (the light pre-pass)

/* deferred-lighting (Engel 2008, Lauritzen 2010): this file's light passes over a minimal
 * G-buffer (gbuffer_layout.c's deferred_layout_light_prepass) into a light buffer, then
 * a second geometry pass that applies the materials. docs/architecture.md has the design.
 *
 *   shadows, gbuffer   deferred_frame_begin, the G-buffer holding the normal and the
 *                      shininess only
 *   directional, point, spot
 *                      as deferred's, every light_volumes mode, blend ONE + ONE into the
 *                      light buffer (lightbuffer.diffuse: incoming x max(N.L, 0),
 *                      lightbuffer.specular: incoming x spec; deferred_light.frag with
 *                      LIGHT_PREPASS); the first that runs clears the light buffer
 *   material           the visible opaque objects again (frontend order, one draw each),
 *                      mesh.vert + deferred_lighting_material.frag in the material's map
 *                      variant, depth EQUAL without writes, back faces culled, into the
 *                      light target cleared to (0, 0, 0, 1): ambient x diffuse + emissive
 *                      + diffuse x L_diffuse + gloss x L_specular
 *   fog, sky, translucent, edge-aa, resolve
 *                      deferred_frame_end, as deferred
 *
 * Draw calls: Sh + 2 V + (the light draws as deferred's, same mode) + [fog] + [sky] +
 * [translucent objects] + [aa] + 1. deferred.separate_specular and deferred.sky_stencil
 * are not read (its light buffer is always split; no full-screen ambient pass to mask),
 * nor gbuffer.* (the layout is fixed).
 *
 * MSAA (msaa > 1): the G-buffer, light buffer, light target and depth multisampled;
 * deferred's `edges` pass after the G-buffer, and its two classes in every light pass
 * (per sample on edge pixels, per pixel elsewhere: the light draws double as deferred's);
 * the material pass runs per sample everywhere (it reads the light buffer at gl_SampleID,
 * so that each sample takes the light of the surface it holds), then `msaa-resolve`. */

static void deferred_lighting_describe(const void *self, pass_plan *out)
{
    deferred_describe(self, out);
}

static void deferred_lighting_destroy(void *self)
{
    deferred_core_destroy(self);
}

static void *deferred_lighting_create(const renderer_options *opts, char *err, size_t errlen)
{
    if ((unsigned)opts->lpp_light_buffer - 1u > 1u) {
        snprintf(err, errlen, "deferred-lighting: unknown light buffer format %d",
                 (int)opts->lpp_light_buffer);
        return NULL;
    }
    /* What the renderer does not read (its reads) must not change what it draws: the
     * runner folds runs that differ only there. */
    renderer_options o = *opts;
    o.separate_specular = false;
    o.sky_stencil = false;
    o.gbuffer = GBUFFER_CURTIS;
    o.gbuffer_position = GBUFFER_POSITION_PRESET;
    o.gbuffer_normal = GBUFFER_NORMAL_PRESET;
    return deferred_core_create("deferred-lighting", sizeof(deferred), false, true, &o, err,
                                errlen);
}

/* The material pass's programs: mesh.vert + deferred_lighting_material.frag in every map
 * variant a visible opaque object may have. */
static bool compile_material(deferred *r, char *err, size_t errlen)
{
    for (unsigned v = 0; v < DEFERRED_VARIANTS; v++) {
        if (!(r->d.variants & (1u << v)))
            continue;
        scene_material m = {.diffuse_map = (v & 1u) ? 0 : -1, .gloss_map = (v & 2u) ? 0 : -1,
                            .normal_map = (v & 4u) ? 0 : -1, .emissive_map = (v & 8u) ? 0 : -1,
                            .alpha = (v & 16u) ? MATERIAL_MASK : MATERIAL_OPAQUE};
        const char *defs[SHADING_MATERIAL_DEFINES + 3] = {NULL};
        unsigned n = shading_material_defines(&m, defs);
        if (r->d.b.samples > 1) {
            /* msaa: the light buffer per sample, and so every fragment per sample: where
             * two surfaces share a pixel each sample takes its own surface's light */
            defs[n++] = "GB_MSAA";
            defs[n++] = "GB_SAMPLE gl_SampleID";
        }
        if (!deferred_build_program(&r->d, "deferred_lighting_material", "mesh.vert",
                                    "deferred_lighting_material.frag", NULL, defs,
                                    &r->material_program[v], err, errlen))
            return false;
    }
    return true;
}

static bool deferred_lighting_prepare(void *self, const scene *s, char *err, size_t errlen)
{
    deferred *r = self;
    deferred_renderer *d = &r->d;
    deferred_core_release(d);
    forget_programs(r);
    if (!deferred_prepare_scene(d, s, err, errlen))
        goto fail;
    deferred_plan(d, PASS_EDGES, d->b.samples > 1,
                  "msaa %d: as deferred's, for the light passes; the material pass shades "
                  "per sample", d->b.samples);
    deferred_plan(d, PASS_AMBIENT, false, "ambient and emissive are the material pass's");
    plan_lights(r);
    deferred_plan(d, PASS_COMPOSE, false, "the material pass combines the light buffer's "
                  "diffuse and specular light");
    deferred_plan(d, PASS_MATERIAL, true, "%u objects again, depth EQUAL, their materials "
                  "over the light buffer (%s)", s->nobjects,
                  d->b.opts.lpp_light_buffer == LPP_LIGHT_BUFFER_RGBA8 ? "rgba8" : "rgba16f");
    if (!deferred_make_targets(d, err, errlen) || !deferred_compile_gbuffer(d, err, errlen) ||
        !compile_lighting(r, err, errlen) || !compile_material(r, err, errlen) ||
        !deferred_compile_fog(d, err, errlen) ||
        !translucent_prepare(&d->translucent, &d->b, s, &d->b.shadows, false, err, errlen) ||
        !deferred_prepare_edge_aa(d, err, errlen))
        goto fail;
    deferred_prepare_end(d);
    return true;
fail:
    deferred_core_release(d);
    return false;
}

/* The second geometry pass: each visible opaque object's material over its own light. */
static void material_pass(deferred *r, const scene *s, frame_stats *out)
{
    deferred_renderer *d = &r->d;
    gl_state *st = d->b.st;
    deferred_pass_begin(d, out, PASS_MATERIAL);
    if (!r->lbuf_cleared) {   /* no light pass ran: no light */
        gl_state_framebuffer(st, d->fb_lbuf.fbo);
        clear_light_buffer(r);
    }
    gl_state_framebuffer(st, d->fb_light.fbo);
    gl_state_viewport(st, 0, 0, d->b.width, d->b.height);
    /* what deferred's ambient pass leaves where no surface is (the sky draws there) */
    static const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    gl_state_clear(st, GL_COLOR_BUFFER_BIT, black, 1.0, 0);
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    gl_state_blend(st, NULL);
    gl_state_stencil(st, NULL);
    gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_EQUAL, .write = false});
    gl_state_cull(st, GLS_CULL_BACK);   /* as the G-buffer pass: the same fragments */
    gl_state_texture(st, BIND_TEX_LIGHT_DIFFUSE, d->lbuf_diffuse.texture);
    gl_state_texture(st, BIND_TEX_LIGHT_SPECULAR, d->lbuf_specular.texture);
    renderer_base_per_sample(&d->b, d->b.samples > 1);   /* msaa: per sample everywhere */
    for (uint32_t k = 0; k < d->b.fe.nvisible; k++) {
        uint32_t o = d->b.fe.visible[k];
        unsigned v = deferred_material_variant(&s->materials[s->objects[o].material]);
        gl_state_program(st, r->material_program[v]);
        scene_gpu_draw_object(d->b.gpu, st, s, o);
    }
    renderer_base_per_sample(&d->b, false);
    /* drawn into by the next frame's light passes: not bound for sampling meanwhile */
    gl_state_texture(st, BIND_TEX_LIGHT_DIFFUSE, 0);
    gl_state_texture(st, BIND_TEX_LIGHT_SPECULAR, 0);
    deferred_pass_end(d, out);
}

static void deferred_lighting_draw(void *self, const scene *s, frame_stats *out)
{
    deferred *r = self;
    deferred_renderer *d = &r->d;
    memset(r->mark_draws, 0, sizeof r->mark_draws);
    memset(r->shade_draws, 0, sizeof r->shade_draws);
    r->edges_pass = 0;
    r->lbuf_cleared = false;
    if (!deferred_frame_begin(d, s, out))
        return;
    if (d->run[PASS_EDGES])
        edges_pass(r, out);
    deferred_bind_gbuffer_textures(d);   /* the normal, shininess and depth.sampled */
    if (d->run[PASS_DIRECTIONAL])
        light_pass(r, s, out, PASS_DIRECTIONAL, LIGHT_DIRECTIONAL);
    if (d->run[PASS_POINT])
        light_pass(r, s, out, PASS_POINT, LIGHT_POINT);
    if (d->run[PASS_SPOT])
        light_pass(r, s, out, PASS_SPOT, LIGHT_SPOT);
    material_pass(r, s, out);
    deferred_frame_end(d, s, out, d->fb_light.fbo);
}

// >>for tests

uint64_t deferred_last_mark_draws(const void *self, int type)
{
    const deferred *r = self;
    return r && type >= 0 && type < DEFERRED_LIGHT_TYPES ? r->mark_draws[type] : 0;
}

uint64_t deferred_last_shade_draws(const void *self, int type)
{
    const deferred *r = self;
    return r && type >= 0 && type < DEFERRED_LIGHT_TYPES ? r->shade_draws[type] : 0;
}

const renderer_impl renderer_deferred_impl = RENDERER_IMPL(
    deferred, "deferred", "gbuffer deferred hdr msaa fog aa",
    "G-buffer pass, then ambient, directional and light-volume passes "
    "(fullscreen | volume | stencil | stencil-two-pass), sky last",
    .collect = deferred_collect, .read_hdr = deferred_read_hdr);

const renderer_impl renderer_deferred_lighting_impl = RENDERER_IMPL(
    deferred_lighting, "deferred-lighting",
    "deferred.light_volumes deferred_lighting hdr msaa fog aa",
    "light pre-pass (Engel 2008): normal + shininess G-buffer, diffuse and specular light "
    "into a light buffer by deferred's light volumes, then the objects again with their "
    "materials (depth EQUAL)",
    .collect = deferred_collect, .read_hdr = deferred_read_hdr);
