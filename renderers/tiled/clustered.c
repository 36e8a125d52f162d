/* clustered (Olsson, Billeter and Assarsson, "Clustered Deferred and Forward Shading",
 * HPG 2012): the light grid (grid.h) with its tiles cut into clustered.slices exponential
 * depth slices. Forward (the default): forward_plus.c's passes over the clusters (depth
 * pre-pass, one cull dispatch, shade). With clustered.shading: deferred: tiled_deferred.c's
 * G-buffer and one clustered compute pass, the same cluster lists.
 *
 * The registry's entry makes the object of either design with its clusters; `variant`
 * names the design whose functions renderer_create then calls for everything else. */
#include "renderers/tiled/tiled.h"


static void *clustered_create(const renderer_options *opts, char *err, size_t errlen)
{
    return opts->clustered_deferred ? tiled_deferred_clustered_create(opts, err, errlen)
                                    : forward_tiled_new("clustered", true, opts, err, errlen);
}

static const renderer_impl *clustered_variant(const renderer_options *opts)
{
    return opts->clustered_deferred ? &renderer_tiled_deferred_impl : &renderer_forward_plus_impl;
}

const renderer_impl renderer_clustered_impl = {
    .name = "clustered",
    .description = "clustered (Olsson et al. 2012): lights culled per cluster (screen tile x "
                   "exponential depth slice) by a compute pass; forward: depth pre-pass, each "
                   "pixel shaded with its cluster's lights; deferred: from the G-buffer",
    .reads = "gbuffer tiles clustered lights.culling lights.culling_error hdr msaa fog aa",
    .create = clustered_create,
    .variant = clustered_variant,
};
