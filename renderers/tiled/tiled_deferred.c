/* tiled-deferred (Andersson 2009, Lauritzen 2010), and clustered with clustered.shading:
 * deferred (Olsson et al. 2012): deferred's G-buffer (every preset and override;
 * renderers/deferred_core.h), then instead of deferred's ambient and light passes ONE
 * compute dispatch (tiled_deferred.comp) over the light grid (grid.h): per tile (or
 * cluster) the lights that reach it culled, then ambient, emissive and those lights
 * shaded from the G-buffer and stored into the "light" target by image store (the run's
 * HDR format: renderer_base_hdr_define, renderer_base_hdr_image_format). The passes:
 *
 *   shadows, gbuffer   as deferred (deferred.c's header)
 *   tiled              the frame's visible lights into the grid's light buffer, then the
 *                      dispatch; "translucent-lists" (not a pass) says whether it builds
 *                      the tiles' translucent lists after the opaque ones (TLISTS, when
 *                      the scene has translucent objects and point or spot lights)
 *   fog, sky, translucent, [msaa-resolve], edge-aa, resolve   as deferred
 *
 * The dispatch samples the depth target, so the output framebuffer (no texture attached)
 * is bound for it, as forward-plus does for its cull, and no "depth.sampled" copy is
 * made. With no point or spot light nothing is culled (NO_GRID): every light is looped.
 *
 * MSAA (msaa > 1): no edges pass and no stencil; the dispatch classifies the pixels by
 * deferred's rule (edge_rule.inc), shades sample 0 of every pixel into all its samples
 * off the edges and, from a per-tile edge list in shared memory, the other samples of
 * the edge pixels; the edge pixels are counted into a small storage buffer
 * (BIND_SSBO_EDGES), which collect reads back (edge_fraction, the pass's samples).
 *
 * Refused at create: deferred.sky_stencil (no stencil test masks a dispatch; it skips
 * pixels without a surface itself) and deferred.separate_specular (one target). */
#include "renderers/deferred_core.h"
#include "renderers/shadow.h"
#include "renderers/tiled/grid.h"
#include "renderers/tiled/tiled.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct tiled_deferred {
    deferred_renderer d;             /* first: deferred_describe and the accessors read it */
    light_grid g;                    /* tiles, or clusters (g.slices_y) */
    GLuint program;                  /* tiled_deferred.comp */
    GLuint edges;                    /* msaa > 1: the dispatch's edge-pixel count */
    uint32_t edge_pixels;            /* msaa > 1: the last frame's, after collect */
    char msaa_define[24];
    size_t tiled_index;              /* msaa > 1: 1 + the tiled pass's index; 0: none */
} tiled_deferred;
_Static_assert(offsetof(tiled_deferred, d) == 0, "destroy: the object begins with d");

static void *create(const char *name, bool clustered, const renderer_options *opts, char *err,
                    size_t errlen)
{
    light_grid g = {0};
    if (clustered && !light_grid_slices_option(&g, name, opts, err, errlen))
        return NULL;
    if (opts->sky_stencil) {
        snprintf(err, errlen, "%s: deferred.sky_stencil: the shading is one compute dispatch, "
                 "which no stencil test masks (it skips pixels without a surface itself)",
                 name);
        return NULL;
    }
    if (opts->separate_specular) {
        snprintf(err, errlen, "%s: deferred.separate_specular: the one light pass adds diffuse "
                 "and specular light together; there is no second target", name);
        return NULL;
    }
    if (!light_grid_tile_option(&g, name, opts, err, errlen))
        return NULL;
    tiled_deferred *r =
        (tiled_deferred *)deferred_core_create(name, sizeof *r, true, false, opts, err, errlen);
    if (r)
        r->g = g;
    return r;
}

static void *tiled_deferred_create(const renderer_options *opts, char *err, size_t errlen)
{
    return create("tiled-deferred", false, opts, err, errlen);
}

void *tiled_deferred_clustered_create(const renderer_options *opts, char *err, size_t errlen)
{
    return create("clustered", true, opts, err, errlen);
}

static void release(tiled_deferred *r)
{
    deferred_core_release(&r->d);
    light_grid_release(&r->g);
    if (r->edges)
        gl.DeleteBuffers(1, &r->edges);
    r->edges = 0;
    r->program = 0;
}

/* The pass plan's entries of the tiled pass (deferred_prepare_scene has the others). */
static void plan_tiled(tiled_deferred *r)
{
    deferred_renderer *d = &r->d;
    const light_grid *g = &r->g;
    const char *kind = g->slices ? "clustered" : "tiled";
    if (g->ntlists)
        deferred_plan(d, PASS_TLISTS, true, "in the %s dispatch: per tile, near plane to its "
                      "max depth", kind);
    else
        deferred_plan(d, PASS_TLISTS, false, "%s", !d->translucency
                                                       ? "skipped: no translucent materials"
                                                       : "skipped: no culling, every light");
    if (g->slices)
        deferred_plan(d, PASS_TILED, true, "one dispatch: %ux%ux%u clusters (%d px), %s",
                      g->tiles_x, g->tiles_y, g->slices, g->tile,
                      g->cull ? "lights culled per cluster, ambient and lights shaded"
                              : "no point or spot light: no culling, ambient and lights shaded");
    else
        deferred_plan(d, PASS_TILED, true, "one dispatch: %ux%u tiles of %d px, %s", g->tiles_x,
                      g->tiles_y, g->tile,
                      g->cull ? "lights culled per tile, ambient and lights shaded"
                              : "no point or spot light: no culling, ambient and lights shaded");
    const char *in = g->slices ? "in the clustered pass" : "in the tiled pass";
    deferred_plan(d, PASS_AMBIENT, false, "%s", in);
    deferred_plan(d, PASS_DIRECTIONAL, false, "%s", in);
    deferred_plan(d, PASS_POINT, false, "%s", in);
    deferred_plan(d, PASS_SPOT, false, "%s", in);
    deferred_plan(d, PASS_EDGES, false, "msaa %d: in the %s pass: pixels whose samples differ "
                  "(the same rule) listed per tile; per sample there, per pixel elsewhere",
                  d->b.samples, g->slices_y ? "clustered" : "tiled");
}

/* The grid's buffers (before the targets, as it always was), and the edge counter. */
static bool make_buffers(tiled_deferred *r, const scene *s, char *err, size_t errlen)
{
    light_grid *g = &r->g;
    int max_block = light_grid_max_block();
    if (!light_grid_lights_fit(g, s->nlights_total, max_block, err, errlen))
        return false;
    light_grid_capacity(g, r->d.b.opts.max_lights_per_tile, max_block);
    light_grid_defines(g);
    if (!light_grid_heads_fit(g, "cells", max_block, err, errlen))
        return false;
    if (!light_grid_alloc(g)) {
        snprintf(err, errlen, "%s: out of memory for %u lights and %u tiles", r->d.b.name,
                 s->nlights_total, g->ntiles);
        return false;
    }
    if (r->d.b.samples > 1) {
        gl.CreateBuffers(1, &r->edges);
        gl.NamedBufferStorage(r->edges, sizeof(uint32_t), NULL, GL_DYNAMIC_STORAGE_BIT);
    }
    return true;
}

/* tiled_deferred.comp with the grid's, the samples', the HDR image's, the shadows' and
 * the layout's defines. */
static bool compile_tiled(tiled_deferred *r, char *err, size_t errlen)
{
    deferred_renderer *d = &r->d;
    const light_grid *g = &r->g;
    deferred_layout_defs ld;
    deferred_layout_defines(&d->layout, &ld);
    const char *extra[16] = {g->tile_define, g->tiles_x_define};
    int n = 2;
    if (d->b.samples > 1) {   /* the multisampled G-buffer, per tile edge list */
        /* the count the driver gave (known once the targets exist) */
        snprintf(r->msaa_define, sizeof r->msaa_define, "MSAA_SAMPLES %d", d->b.samples);
        extra[n++] = "GB_MSAA";
        extra[n++] = r->msaa_define;
    }
    if (renderer_base_hdr_define(&d->b))   /* the image store's format qualifier */
        extra[n++] = renderer_base_hdr_define(&d->b);
    if (g->slices) {
        extra[n++] = g->tiles_y_define;
        extra[n++] = g->slices_define;
        extra[n++] = g->slices_y_define;
    }
    if (!g->cull)
        extra[n++] = "NO_GRID";
    if (g->ntlists)
        extra[n++] = g->tlists_define;
    n += (int)shadow_maps_defines(&d->b.shadows, extra + n);   /* any type: one program */
    gl_program_desc desc = {.name = g->slices ? (g->ntlists ? "clustered_deferred_translucent"
                                                            : "clustered_deferred")
                                              : (g->ntlists ? "tiled_deferred_translucent"
                                                            : "tiled_deferred"),
                            .compute = "tiled_deferred.comp"};
    unsigned k = 0;
    for (int i = 0; i < n; i++)
        desc.defines[k++] = extra[i];
    for (int i = 0; i < ld.n && k < GLP_MAX_DEFINES; i++)
        desc.defines[k++] = ld.text[i];
    if (k < (unsigned)n + (unsigned)ld.n) {
        snprintf(err, errlen, "bug: %s: too many defines for tiled_deferred", d->b.name);
        return false;
    }
    char why[4096] = "";
    if (gl_program_get(d->b.programs, &desc, &r->program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "%s: %s", d->b.name, why);
        return false;
    }
    if (d->b.samples > 1)   /* u_sample_pos, after u_light_count */
        deferred_set_sample_positions(d, d->fb_gbuffer.fbo, r->program,
                                      DEFERRED_UNIFORM_LIGHT + 1);
    return true;
}

static bool tiled_deferred_prepare(void *self, const scene *s, char *err, size_t errlen)
{
    tiled_deferred *r = self;
    deferred_renderer *d = &r->d;
    release(r);
    if (!deferred_prepare_scene(d, s, err, errlen) ||
        !light_grid_size(&r->g, s, d->b.width, d->b.height,
                         d->count[LIGHT_POINT] + d->count[LIGHT_SPOT] > 0, d->translucency, err,
                         errlen))
        goto fail;
    plan_tiled(r);
    if (!make_buffers(r, s, err, errlen) || !deferred_make_targets(d, err, errlen) ||
        !deferred_compile_gbuffer(d, err, errlen) || !compile_tiled(r, err, errlen) ||
        !deferred_compile_fog(d, err, errlen) ||
        !translucent_prepare(&d->translucent, &d->b, s, &d->b.shadows, true, err, errlen) ||
        !deferred_prepare_edge_aa(d, err, errlen))
        goto fail;
    const translucent_grid tg = light_grid_translucent(&r->g);
    if (!translucent_compile(&d->translucent, &d->b, &d->b.shadows, r->g.ntlists ? &tg : NULL,
                             err, errlen))
        goto fail;
    deferred_prepare_end(d);
    return true;
fail:
    release(r);
    return false;
}

/* The tiled pass: the frame's visible lights into the light buffer, then one dispatch
 * that culls per tile and stores ambient + lights into the "light" target. */
static void tiled_pass(tiled_deferred *r, const scene *s, frame_stats *out)
{
    deferred_renderer *d = &r->d;
    gl_state *st = d->b.st;
    light_grid *g = &r->g;
    uint32_t n = light_grid_upload_lights(g, s, &d->b.fe);
    out->grid_pass = g->cull ? out->npasses + 1 : 0;
    deferred_pass_begin(d, out, PASS_TILED);
    light_grid_reset(g);
    if (r->edges) {
        const uint32_t zero = 0;
        gl.NamedBufferSubData(r->edges, 0, sizeof zero, &zero);
        gl_state_storage_buffer(st, BIND_SSBO_EDGES, r->edges);
    }
    gl_state_program(st, r->program);
    gl.Uniform1i(LOC_RENDERER, (GLint)n);
    deferred_bind_gbuffer_textures(d);
    gl_state_texture(st, DEFERRED_DEPTH_UNIT, d->b.depth.texture);
    shadow_maps_bind(&d->b.shadows, st);
    light_grid_bind_lights(g, st);
    light_grid_bind_lists(g, st);
    gl_state_image(st, BIND_IMAGE_HDR, d->b.hdr.texture, GL_WRITE_ONLY,
                   renderer_base_hdr_image_format(&d->b));
    /* it samples the depth target: no draw framebuffer that has it attached (header) */
    gl_state_framebuffer(st, d->b.output_fbo);
    light_grid_dispatch(g, st);
    /* the sky draws into the target, resolve samples it; the translucent pass reads
     * the translucent lists */
    gl_state_barrier(st, GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                             (g->ntlists ? GL_SHADER_STORAGE_BARRIER_BIT : 0u));
    /* the depth target is drawn with (sky) next: not bound for sampling meanwhile */
    if (d->layout.position != DEFERRED_POSITION_DEPTH_BUFFER)
        gl_state_texture(st, DEFERRED_DEPTH_UNIT, 0);
    deferred_pass_end(d, out);
    if (r->edges)
        r->tiled_index = out->npasses;   /* 1 + its index */
    out->lights_drawn = n;
}

static void tiled_deferred_draw(void *self, const scene *s, frame_stats *out)
{
    tiled_deferred *r = self;
    r->tiled_index = 0;
    if (!deferred_frame_begin(&r->d, s, out))
        return;
    tiled_pass(r, s, out);
    deferred_frame_end(&r->d, s, out, r->d.fb_light.fbo);
}

static void tiled_deferred_collect(void *self, frame_stats *out)
{
    tiled_deferred *r = self;
    if (r->d.prepared && r->g.cull)
        light_grid_collect(&r->g, out);
    renderer_base_collect(&r->d.b, out);
    if (r->tiled_index && r->tiled_index <= out->npasses) {
        /* msaa N: the dispatch shades sample 0 of every pixel and N - 1 more samples of
         * each edge pixel; as deferred counts them: N samples per pixel, the edge pixels'
         * per sample (samples_shaded = pixels + edges (N - 1), renderer_collect) */
        gl.GetNamedBufferSubData(r->edges, 0, sizeof(uint32_t), &r->edge_pixels);
        double pixels = (double)r->d.b.width * r->d.b.height, n = r->d.b.samples;
        pass_stats *p = &out->pass[r->tiled_index - 1];
        p->samples = pixels * n;
        p->per_sample_samples = (double)r->edge_pixels * n;
        out->edge_fraction = r->edge_pixels / pixels;
    }
}

static const uint32_t *tiled_deferred_light_grid(const void *self, size_t *n)
{
    const tiled_deferred *r = self;
    return light_grid_counts(&r->g, n);
}

RENDERER_DESTROY(tiled_deferred, release, deferred_core_destroy)

/* The plan is deferred's: the same G-buffer, with the cull-and-shade pass among its passes. */
static void tiled_deferred_describe(const void *self, pass_plan *out)
{
    deferred_describe(self, out);
}

const renderer_impl renderer_tiled_deferred_impl = RENDERER_IMPL(
    tiled_deferred, "tiled-deferred", "gbuffer tiles hdr msaa fog aa",
    "G-buffer pass (every preset and override of deferred), then one compute "
    "pass that culls lights per screen tile and shades ambient, directional "
    "and local lights into the HDR target by image store; sky last",
    .collect = tiled_deferred_collect, .read_hdr = deferred_read_hdr,
    .light_grid = tiled_deferred_light_grid, .traffic = deferred_traffic,
    .own_bytes = deferred_gbuffer_own_bytes);
