/* What the renderer interface (renderer.h) asks of the layers below the designs: the
 * base's depth probes and statistics (base.h), the shadow maps' and lights' sizes, the
 * cluster slices (shading.h) and the scene upload (scene_gpu.h). Apart from renderer.c,
 * the registry and dispatch, which includes none of them: base.h and shadow.h include
 * renderer.h for its types, so the arrows go one way, renderer_base -> base -> renderer. */
#include "renderers/renderer_internal.h"

#include "renderers/frame/base.h"
#include "renderers/frame/shading.h"
#include "renderers/frame/shadow.h"

#include <stdio.h>

double renderer_upload_s(void) { return scene_gpu_upload_s(); }

bool renderer_coverage(renderer *r, uint64_t *covered, char *err, size_t errlen)
{
    *covered = 0;
    if (r->impl->no_base || !r->prepared) {
        snprintf(err, errlen, "%s: no depth target to count coverage in%s", r->kind,
                 r->prepared ? "" : " (not prepared)");
        return false;
    }
    return renderer_base_coverage(r->self, covered, err, errlen);
}

bool renderer_lights_reaching(renderer *r, const struct scene *s, uint32_t *counts, char *err,
                              size_t errlen)
{
    if (r->impl->no_base || !r->prepared) {
        snprintf(err, errlen, "%s: no depth target to count the lights reaching in%s", r->kind,
                 r->prepared ? "" : " (not prepared)");
        return false;
    }
    return renderer_base_lights_reaching(r->self, s, counts, err, errlen);
}

void renderer_impl_collect(const renderer_impl *impl, void *self, frame_stats *out)
{
    if (impl->collect)
        impl->collect(self, out);
    else
        renderer_base_collect(self, out);   /* renderer_impl.collect: the base first */
}

uint64_t renderer_light_bytes(void) { return sizeof(gpu_light); }

uint64_t renderer_shadow_layer_bytes(void)
{
    return (uint64_t)SHADOW_DEFAULT_SIZE * SHADOW_DEFAULT_SIZE * 4;   /* 4 bytes a texel */
}

uint32_t renderer_cluster_slices(const struct scene *s, int slices_y)
{
    double ratio;
    return shading_cluster_slices(s, slices_y, &ratio);
}

bool renderer_cluster_slices_ok(const char *kind, double proj11, double znear, double zfar,
                                int slices_y, char *err, size_t errlen)
{
    return shading_cluster_slices_ok(kind, proj11, znear, zfar, slices_y, NULL, NULL, err,
                                     errlen);
}
