/* clustered (Olsson, Billeter and Assarsson, "Clustered Deferred and Forward Shading",
 * HPG 2012): the light grid (grid.h) with its tiles cut into clustered.slices exponential
 * depth slices. Forward (the default): forward_plus.c's passes over the clusters (depth
 * pre-pass, one cull dispatch, shade). With clustered.shading: deferred: tiled_deferred.c's
 * G-buffer and one clustered compute pass, the same cluster lists.
 *
 * The registry's entry only names the renderer; renderer_create asks `variant` which of
 * the two designs serves an object made with the run's options, and dispatches every
 * call to that design's own functions. */
#include "renderers/deferred_core.h"
#include "renderers/forward_common.h"
#include "renderers/tiled/tiled.h"

static void *forward_create(const renderer_options *opts, char *err, size_t errlen)
{
    return forward_tiled_create("clustered", true, opts, err, errlen);
}

/* Each design reads what it shades with: deferred_uses_gbuffer asks its `reads`. */
static const renderer_impl clustered_forward = {
    .name = "clustered",
    .reads = "tiles clustered hdr msaa fog aa",
    RENDERER_ENTRY_POINTS(forward_create, forward_tiled_prepare, forward_tiled_draw,
                          forward_tiled_collect, forward_tiled_describe, forward_tiled_destroy),
    .read_hdr = forward_read_hdr,
    .light_grid = forward_tiled_light_grid,
};

static const renderer_impl clustered_deferred = {
    .name = "clustered",
    .reads = "gbuffer tiles clustered hdr msaa fog aa",
    RENDERER_ENTRY_POINTS(tiled_deferred_clustered_create, tiled_deferred_prepare,
                          tiled_deferred_draw, tiled_deferred_collect, deferred_describe,
                          tiled_deferred_destroy),
    .read_hdr = deferred_read_hdr,
    .light_grid = tiled_deferred_light_grid,
};

static const renderer_impl *variant(const renderer_options *opts)
{
    return opts->clustered_deferred ? &clustered_deferred : &clustered_forward;
}

const renderer_impl renderer_clustered_impl = {
    .name = "clustered",
    .description = "clustered (Olsson et al. 2012): lights culled per cluster (screen tile x "
                   "exponential depth slice) by a compute pass; forward: depth pre-pass, each "
                   "pixel shaded with its cluster's lights; deferred: from the G-buffer",
    .reads = "gbuffer tiles clustered hdr msaa fog aa",
    .variant = variant,
};
