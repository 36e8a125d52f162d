/* clustered (Olsson, Billeter and Assarsson, "Clustered Deferred and Forward Shading",
 * HPG 2012): the light grid (grid.h) with its tiles cut into clustered.slices exponential
 * depth slices. Forward (the default): forward_plus.c's passes over the clusters (depth
 * pre-pass, one cull dispatch, shade). With clustered.shading: deferred: tiled_deferred.c's
 * G-buffer and one clustered compute pass, the same cluster lists.
 *
 * The object create makes is the one of those two renderers, nothing around it: each
 * entry below calls that renderer's own, chosen by the options the object was made with
 * (renderer_base.opts.clustered_deferred; both objects start with their base). */
#include "renderers/base.h"
#include "renderers/deferred_core.h"
#include "renderers/forward_common.h"
#include "renderers/tiled/tiled.h"

#include <stddef.h>

_Static_assert(offsetof(forward_common, b) == 0, "a forward object starts with its base");
_Static_assert(offsetof(deferred_renderer, b) == 0, "a deferred object starts with its base");

/* Whether self (either renderer's object) shades deferred. */
static bool deferred_shading(const void *self)
{
    return ((const renderer_base *)self)->opts.clustered_deferred;
}

static void *cl_create(const renderer_options *opts, char *err, size_t errlen)
{
    return opts->clustered_deferred ? tiled_deferred_clustered_create(opts, err, errlen)
                                    : forward_tiled_create("clustered", true, opts, err, errlen);
}

static bool cl_prepare(void *self, const struct scene *s, char *err, size_t errlen)
{
    return deferred_shading(self) ? tiled_deferred_prepare(self, s, err, errlen)
                                  : forward_tiled_prepare(self, s, err, errlen);
}

static void cl_draw(void *self, const struct scene *s, frame_stats *out)
{
    if (deferred_shading(self))
        tiled_deferred_draw(self, s, out);
    else
        forward_tiled_draw(self, s, out);
}

static void cl_collect(void *self, frame_stats *out)
{
    if (deferred_shading(self))
        tiled_deferred_collect(self, out);
    else
        forward_tiled_collect(self, out);
}

static void cl_describe(const void *self, pass_plan *out)
{
    if (deferred_shading(self))
        deferred_describe(self, out);
    else
        forward_tiled_describe(self, out);
}

static void cl_destroy(void *self)
{
    if (!self)
        return;
    if (deferred_shading(self))
        tiled_deferred_destroy(self);
    else
        forward_tiled_destroy(self);
}

static bool cl_read_hdr(void *self, float *rgba, int width, int height)
{
    return deferred_shading(self) ? deferred_read_hdr(self, rgba, width, height)
                                  : forward_read_hdr(self, rgba, width, height);
}

static const uint32_t *cl_light_grid(const void *self, size_t *n)
{
    return deferred_shading(self) ? tiled_deferred_light_grid(self, n)
                                  : forward_tiled_light_grid(self, n);
}

const renderer_impl renderer_clustered_impl = {
    .name = "clustered",
    .description = "clustered (Olsson et al. 2012): lights culled per cluster (screen tile x "
                   "exponential depth slice) by a compute pass; forward: depth pre-pass, each "
                   "pixel shaded with its cluster's lights; deferred: from the G-buffer",
    .reads = "gbuffer tiles clustered hdr msaa fog aa",
    .create = cl_create,
    .prepare = cl_prepare,
    .draw = cl_draw,
    .collect = cl_collect,
    .describe = cl_describe,
    .destroy = cl_destroy,
    .read_hdr = cl_read_hdr,
    .light_grid = cl_light_grid,
};
