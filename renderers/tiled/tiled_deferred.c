/* tiled-deferred (Andersson 2009, Lauritzen 2010), and clustered with clustered.shading:
 * deferred (Olsson et al. 2012): deferred's G-buffer (every preset and override;
 * renderers/deferred/deferred_core.h), then instead of deferred's ambient and light passes ONE
 * compute dispatch (tiled_deferred.comp) over the light grid (grid.h): per tile (or
 * cluster) the lights that reach it culled, then ambient, emissive and those lights
 * shaded from the G-buffer and stored into the "light" target by image store (the run's
 * HDR format: renderer_base_hdr_define, renderer_base_hdr_image_format).
 *
 * The passes, the dispatch's depth binding, MSAA and what create refuses: the comment
 * above create(). The pass itself (its plan, the grid's buffers, the program, the
 * dispatch, its counters) is tiled_pass.c's, which deferred-lighting's tiled light
 * accumulation shares. */
#include "renderers/deferred/deferred_core.h"
#include "renderers/tiled/tiled.h"
#include "renderers/tiled/tiled_pass.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct tiled_deferred {
    deferred_renderer d;             /* first: deferred_describe and the accessors read it */
    tiled_pass t;                    /* the grid (tiles, or clusters) and the dispatch */
} tiled_deferred;
_Static_assert(offsetof(tiled_deferred, d) == 0, "destroy: the object begins with d");

/* The passes:
 *
 *   shadows, gbuffer   as deferred (docs/notes/deferred.md)
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
 * pixels without a surface itself) and deferred.separate_specular (one target).
 */
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
    if (r) {
        r->t.g = g;
        light_grid_culling_option(&r->t.g, &r->d.b, opts);
    }
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

void *tiled_deferred_zbin_create(const renderer_options *opts, char *err, size_t errlen)
{
    tiled_deferred *r = create("zbin", false, opts, err, errlen);
    if (r && !light_grid_zbin_option(&r->t.g, opts, err, errlen)) {
        deferred_core_destroy(&r->d);
        return NULL;
    }
    return r;
}

static void release(tiled_deferred *r)
{
    deferred_core_release(&r->d);
    tiled_pass_release(&r->t);
}

static bool tiled_deferred_prepare(void *self, const scene *s, char *err, size_t errlen)
{
    tiled_deferred *r = self;
    deferred_renderer *d = &r->d;
    release(r);
    if (!deferred_prepare_scene(d, s, err, errlen) || !tiled_pass_plan(&r->t, d, s, err, errlen))
        goto fail;
    /* the grid's buffers before the targets, as it always was */
    if (!tiled_pass_buffers(&r->t, d, err, errlen) || !deferred_make_targets(d, err, errlen) ||
        !deferred_compile_gbuffer(d, err, errlen) || !tiled_pass_compile(&r->t, d, err, errlen) ||
        !deferred_compile_fog(d, err, errlen) ||
        !translucent_prepare(&d->translucent, &d->b, s, &d->b.shadows, true, err, errlen) ||
        !deferred_prepare_edge_aa(d, err, errlen))
        goto fail;
    const translucent_grid tg = light_grid_translucent(&r->t.g);
    if (!translucent_compile(&d->translucent, &d->b, &d->b.shadows, r->t.g.ntlists ? &tg : NULL,
                             err, errlen))
        goto fail;
    deferred_prepare_end(d);
    return true;
fail:
    release(r);
    return false;
}

static void tiled_deferred_draw(void *self, const scene *s, frame_stats *out)
{
    tiled_deferred *r = self;
    r->t.index = 0;
    if (!deferred_frame_begin(&r->d, s, out))
        return;
    tiled_pass_run(&r->t, &r->d, s, out);
    deferred_frame_end(&r->d, s, out, r->d.fb_light.fbo);
}

static void tiled_deferred_collect(void *self, frame_stats *out)
{
    tiled_deferred *r = self;
    tiled_pass_collect(&r->t, &r->d, out);
}

static const uint32_t *tiled_deferred_light_grid(const void *self, size_t *n)
{
    const tiled_deferred *r = self;
    return light_grid_counts(&r->t.g, n);
}

RENDERER_DESTROY(tiled_deferred, release, deferred_core_destroy)

/* The plan is deferred's: the same G-buffer, with the cull-and-shade pass among its passes. */
static void tiled_deferred_describe(const void *self, pass_plan *out)
{
    deferred_describe(self, out);
}

const renderer_impl renderer_tiled_deferred_impl = RENDERER_IMPL(
    tiled_deferred, "tiled-deferred",
    "gbuffer tiles lights.culling lights.culling_error hdr msaa fog aa",
    "G-buffer pass (every preset and override of deferred), then one compute "
    "pass that culls lights per screen tile and shades ambient, directional "
    "and local lights into the HDR target by image store; sky last",
    .collect = tiled_deferred_collect, .read_hdr = deferred_read_hdr,
    .light_grid = tiled_deferred_light_grid, .traffic = deferred_traffic,
    .own_bytes = deferred_gbuffer_own_bytes);
