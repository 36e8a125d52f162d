/* deferred-lighting, the light pre-pass (Engel 2008; one of the six schemes of
 * Lauritzen 2010): deferred's light passes (renderers/deferred/deferred_lights.c), or the tiled
 * light lists (renderers/tiled/tiled_pass.c), into a light buffer, then the scene's
 * materials in a second geometry pass. */
#include "renderers/deferred/deferred_lights.h"
#include "renderers/tiled/tiled_pass.h"

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

/* deferred-lighting (Engel 2008, Lauritzen 2010): deferred's light passes over a minimal
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
 *   tiled              (deferred_lighting.lights: tiled, instead of the three above)
 *                      tiled-deferred's dispatch (tiled_pass.h, tiles.size) with
 *                      LIGHT_PREPASS: each tile's lights culled, the same two sums
 *                      stored into the light buffer's two images (every pixel written:
 *                      no clear); no depth.sampled copy (the dispatch samples depth)
 *   material           the visible opaque objects again (frontend order, one draw each),
 *                      mesh.vert + deferred_lighting_material.frag in the material's map
 *                      variant, depth EQUAL without writes, back faces culled, into the
 *                      light target cleared to (0, 0, 0, 1): ambient x diffuse + emissive
 *                      + diffuse x L_diffuse + gloss x L_specular
 *   fog, sky, translucent, edge-aa, resolve
 *                      deferred_frame_end, as deferred
 *
 * Draw calls: Sh + 2 V + (the light draws as deferred's, same mode; tiled: none, one
 * dispatch) + [fog] + [sky] + [translucent objects] + [aa] + 1. deferred.separate_specular
 * and deferred.sky_stencil are not read (its light buffer is always split; no full-screen
 * ambient pass to mask), nor gbuffer.* (the layout is fixed), nor tiles.* (volumes) or
 * deferred.light_volumes (tiled).
 *
 * MSAA (msaa > 1): the G-buffer, light buffer, light target and depth multisampled;
 * deferred's `edges` pass after the G-buffer, and its two classes in every light pass
 * (per sample on edge pixels, per pixel elsewhere: the light draws double as deferred's);
 * the material pass runs per sample everywhere (it reads the light buffer at gl_SampleID,
 * so that each sample takes the light of the surface it holds), then `msaa-resolve`.
 * Tiled: no edges pass; the dispatch finds the edge pixels by the same rule and
 * accumulates their other samples' light per sample (tiled_deferred.c's header). */

typedef struct deferred_lighting {
    deferred r;                      /* first: deferred's light passes and accessors read it */
    tiled_pass t;                    /* deferred_lighting.lights: tiled (r.d.tiled) */
} deferred_lighting;
_Static_assert(offsetof(deferred_lighting, r) == 0, "the object begins with deferred's");

static void deferred_lighting_describe(const void *self, pass_plan *out)
{
    deferred_describe(self, out);
}

static void deferred_lighting_destroy(void *self)
{
    deferred_lighting *l = self;
    if (l)
        tiled_pass_release(&l->t);
    deferred_core_destroy(self);
}

static void *deferred_lighting_create(const renderer_options *opts, char *err, size_t errlen)
{
    if ((unsigned)opts->lpp_light_buffer > (unsigned)LPP_LIGHT_BUFFER_RGBA8) {
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
    light_grid g = {0};
    if (o.lpp_tiled)
        o.light_volumes = LIGHT_VOLUMES_STENCIL;   /* not read: no light volume drawn */
    else {
        o.tile_size = 16;   /* not read: no grid */
        o.depth_mask = false;
        o.prune_samples = false;
        o.culling_error = 0;
    }
    if (o.lpp_tiled && !light_grid_tile_option(&g, "deferred-lighting", &o, err, errlen))
        return NULL;
    deferred_lighting *l = (deferred_lighting *)deferred_core_create(
        "deferred-lighting", sizeof(deferred_lighting), o.lpp_tiled, true, &o, err, errlen);
    if (l) {
        l->t.g = g;
        light_grid_culling_option(&l->t.g, &l->r.d.b, &o);
    }
    return l;
}

/* The material pass's programs: mesh.vert + deferred_lighting_material.frag in every map
 * variant a visible opaque object may have; tiled: the grid's buffers and the dispatch
 * first. */
static bool compile_material(deferred *r, char *err, size_t errlen)
{
    deferred_lighting *l = (deferred_lighting *)r;
    if (r->d.tiled && (!tiled_pass_buffers(&l->t, &r->d, err, errlen) ||
                       !tiled_pass_compile(&l->t, &r->d, err, errlen)))
        return false;
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

/* tiled: the translucent pass over the grid's translucent lists when it builds them. */
static bool compile_translucent(deferred *r, char *err, size_t errlen)
{
    deferred_lighting *l = (deferred_lighting *)r;
    const translucent_grid tg = light_grid_translucent(&l->t.g);
    return translucent_compile(&r->d.translucent, &r->d.b, &r->d.b.shadows,
                               r->d.tiled && l->t.g.ntlists ? &tg : NULL, err, errlen);
}

static bool deferred_lighting_prepare(void *self, const scene *s, char *err, size_t errlen)
{
    deferred_lighting *l = self;
    deferred *r = &l->r;
    deferred_renderer *d = &r->d;
    tiled_pass_release(&l->t);
    if (!deferred_lights_prepare_begin(r, s, err, errlen))
        return false;
    if (d->tiled) {
        if (!tiled_pass_plan(&l->t, d, s, err, errlen)) {
            deferred_core_release(d);
            return false;
        }
    } else {
        deferred_plan(d, PASS_EDGES, d->b.samples > 1,
                      "msaa %d: as deferred's, for the light passes; the material pass shades "
                      "per sample", d->b.samples);
        deferred_plan_lights(r);
    }
    deferred_plan(d, PASS_AMBIENT, false, "ambient and emissive are the material pass's");
    deferred_plan(d, PASS_COMPOSE, false, "the material pass combines the light buffer's "
                  "diffuse and specular light");
    deferred_plan(d, PASS_MATERIAL, true, "%u objects again, depth EQUAL, their materials "
                  "over the light buffer (%s)", s->nobjects,
                  d->b.opts.lpp_light_buffer == LPP_LIGHT_BUFFER_RGBA8 ? "rgba8" : "rgba16f");
    if (deferred_lights_prepare_end(r, s, compile_material, compile_translucent, err, errlen))
        return true;
    tiled_pass_release(&l->t);
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
        deferred_clear_light_buffer(r);
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
    deferred_lighting *l = self;
    deferred *r = &l->r;
    deferred_renderer *d = &r->d;
    r->lbuf_cleared = false;
    l->t.index = 0;
    if (!deferred_lights_frame_begin(r, s, out))
        return;
    deferred_bind_gbuffer_textures(d);   /* the normal, shininess and depth (.sampled) */
    if (d->tiled) {
        tiled_pass_run(&l->t, d, s, out);
        r->lbuf_cleared = true;   /* the dispatch wrote every pixel of both */
    } else {
        deferred_light_passes(r, s, out);
    }
    material_pass(r, s, out);
    deferred_frame_end(d, s, out, d->fb_light.fbo);
}

static void deferred_lighting_collect(void *self, frame_stats *out)
{
    deferred_lighting *l = self;
    if (l->r.d.tiled)
        tiled_pass_collect(&l->t, &l->r.d, out);
    else
        deferred_collect(self, out);
}

static const uint32_t *deferred_lighting_light_grid(const void *self, size_t *n)
{
    const deferred_lighting *l = self;
    return light_grid_counts(&l->t.g, n);
}

/* Its fixed G-buffer (normal + shininess, RGBA16F; under pbr F0 beside it, RGBA16F), depth.sampled (volumes) and the light buffer's two targets
 * (deferred_lighting.light_buffer), every one per sample; the tiled lists are the memory
 * estimate's own (runner/plan/memory.c, by the design's reads). */
static uint64_t deferred_lighting_own_bytes(const renderer_estimate *e)
{
    uint64_t light = e->opts->lpp_light_buffer == LPP_LIGHT_BUFFER_RGBA8 ? 4 : 8;
    uint64_t depth = e->opts->lpp_tiled ? 0 : 4;
    uint64_t f0 = e->scene && e->needs.pbr ? 8 : 0;
    return (8 + f0 + depth + 2 * light) * e->samples * e->pixels;
}

/* The two designs differ in what they read (deferred.light_volumes, or tiles.*) and in
 * whether they have light lists (light_grid: lightgrid.csv): the registry's entry reads
 * both and has both, and `variant` names the design of a run's options, whose reads the
 * memory estimate asks. Every other entry point is the same. */
#define DEFERRED_LIGHTING_DESIGN(READS, ...)                                                   \
    RENDERER_IMPL(deferred_lighting, "deferred-lighting", READS,                               \
                  "light pre-pass (Engel 2008): normal + shininess G-buffer, diffuse and "     \
                  "specular light into a light buffer by deferred's light volumes or the "    \
                  "tiled light lists, then the objects again with their materials (depth "    \
                  "EQUAL)",                                                                    \
                  .collect = deferred_lighting_collect, .read_hdr = deferred_read_hdr,         \
                  .traffic = deferred_traffic, .own_bytes = deferred_lighting_own_bytes,       \
                  .draws_per_light = deferred_draws_per_light,                                 \
                  .gbuffer_layout = "light-prepass",                                           \
                  __VA_ARGS__)

static const renderer_impl volumes_design = DEFERRED_LIGHTING_DESIGN(
    "deferred.light_volumes deferred_lighting hdr msaa fog aa", .variant = NULL);
static const renderer_impl tiled_design = DEFERRED_LIGHTING_DESIGN(
    "deferred_lighting tiles lights.culling lights.culling_error hdr msaa fog aa",
    .light_grid = deferred_lighting_light_grid);

static const renderer_impl *deferred_lighting_variant(const renderer_options *opts)
{
    return opts->lpp_tiled ? &tiled_design : &volumes_design;
}

const renderer_impl renderer_deferred_lighting_impl = DEFERRED_LIGHTING_DESIGN(
    "deferred.light_volumes deferred_lighting tiles lights.culling lights.culling_error hdr msaa "
    "fog aa",
    .light_grid = deferred_lighting_light_grid, .variant = deferred_lighting_variant);
