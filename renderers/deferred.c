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
 * The light-volume modes are one table (MODES, renderers/deferred_lights.c, which
 * deferred-lighting shares) of what differs per mode: full
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
#include "renderers/deferred_lights.h"

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

// >>create and prepare

static void *deferred_create(const renderer_options *opts, char *err, size_t errlen)
{
    return deferred_core_create("deferred", sizeof(deferred), false, false, opts, err, errlen);
}

static bool deferred_prepare(void *self, const scene *s, char *err, size_t errlen)
{
    deferred *r = self;
    deferred_renderer *d = &r->d;
    if (!deferred_lights_prepare_begin(r, s, err, errlen))
        return false;
    deferred_plan(d, PASS_AMBIENT, true, "%s%s",
                  d->needs.emissive ? "ambient x diffuse + emissive, full screen"
                                    : "ambient x diffuse, full screen (no material is emissive)",
                  d->b.opts.sky_stencil ? "; the full-screen passes skip the sky by the stencil"
                                        : "");
    deferred_plan_lights(r);
    deferred_plan(d, PASS_TILED, false, "deferred shades with light volumes, not tiles");
    deferred_plan(d, PASS_EDGES, d->b.samples > 1,
                  "msaa %d: pixels whose samples differ (off the plane > 1%% of depth, normal > "
                  "11.5 deg) get stencil bit 0x40; per sample there, per pixel elsewhere",
                  d->b.samples);
    return deferred_lights_prepare_end(r, s, NULL, NULL, err, errlen);
}

// >>per frame

static void deferred_draw(void *self, const scene *s, frame_stats *out)
{
    deferred *r = self;
    deferred_renderer *d = &r->d;
    gl_state *st = d->b.st;
    if (!deferred_lights_frame_begin(r, s, out))
        return;

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
    deferred_fullscreen_classes(r, r->ambient_program, r->ambient_sample_program);
    deferred_pass_end(d, out);

    deferred_light_passes(r, s, out);

    GLuint hdr_fbo = d->fb_light.fbo;   /* where the sky goes */
    if (d->run[PASS_COMPOSE]) {
        deferred_pass_begin(d, out, PASS_COMPOSE);
        gl_state_framebuffer(st, d->fb_compose.fbo);
        gl_state_blend(st, &DEFERRED_BLEND_ADD);
        gl_state_depth(st, NULL);
        gl_state_cull(st, GLS_CULL_NONE);
        gl_state_texture(st, DEFERRED_SPECULAR_UNIT, d->specular.texture);
        deferred_fullscreen_classes(r, r->compose_program, r->compose_sample_program);
        deferred_pass_end(d, out);
        hdr_fbo = d->fb_compose.fbo;
    }
    deferred_frame_end(d, s, out, hdr_fbo);
}

static void deferred_destroy(void *self)
{
    deferred_core_destroy(self);
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

/* The G-buffer's, and depth.sampled (when the position comes from depth). */
static uint64_t deferred_own_bytes(const renderer_estimate *e)
{
    return deferred_gbuffer_own_bytes(e) + 4u * e->samples * e->pixels;
}

const renderer_impl renderer_deferred_impl = RENDERER_IMPL(
    deferred, "deferred", "gbuffer deferred hdr msaa fog aa",
    "G-buffer pass, then ambient, directional and light-volume passes "
    "(fullscreen | volume | stencil | stencil-two-pass), sky last",
    .collect = deferred_collect, .read_hdr = deferred_read_hdr, .traffic = deferred_traffic,
    .own_bytes = deferred_own_bytes, .draws_per_light = deferred_draws_per_light);
