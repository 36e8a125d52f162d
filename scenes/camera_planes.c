/* A file camera's near and far planes fitted to the scene in front of it, and the depth
 * slices a pair of planes makes for clustered shading (scene.h; docs/notes/file-scenes.md,
 * "A file camera's planes"). Pure functions: no scene, no GL. */
#include "scenes/scene.h"

#include <math.h>

uint32_t scene_depth_slices(double proj11, double znear, double zfar, int slices_y,
                            double *ratio)
{
    double r = 1.0 + 2.0 / (proj11 * (slices_y > 0 ? slices_y : 1));
    if (ratio)
        *ratio = r;
    if (!(r > 1.0) || !(znear > 0.0) || !(zfar > znear))
        return 1;
    double k = ceil(log(zfar / znear) / log(r));
    return k < 1.0 ? 1u : k > 1e6 ? 1000000u : (uint32_t)k;
}

void scene_fit_planes(float file_near, float file_far, float depth_near, float depth_far,
                      float proj11, float size, float out[2])
{
    /* what the file leaves out (glTF's infinite projection has no zfar) bounds nothing */
    bool has_near = isfinite(file_near) && file_near > 0.0f;
    bool has_far = isfinite(file_far) && file_far > (has_near ? file_near : 0.0f);
    float n, f;
    if (!(depth_far > 0.0f) || !isfinite(depth_far) || isnan(depth_near)) {
        /* nothing in front (or depths past float's range, from coordinates near it):
         * nothing to fit; the file's planes, else the orbit's */
        n = has_near ? file_near : size * 1e-3f;
        f = has_far && file_far > n ? file_far : fmaxf(size * 10.0f, n * 2.0f);
    } else {
        float fit_far = depth_far * SCENE_PLANES_MARGIN;
        float fit_near = depth_near > 0.0f ? depth_near / SCENE_PLANES_MARGIN : 0.0f;
        n = has_near ? fmaxf(file_near, fit_near) : fit_near;
        f = has_far ? fminf(file_far, fit_far) : fit_far;
        if (!(f > n)) {
            /* the file's planes hold none of the scene: an empty frame measures nothing */
            n = fit_near;
            f = fit_far;
        }
    }
    /* 24-bit depth and clustered's slices: near no closer than far / ratio, the ratio
     * no more than clustered.slices' default cuts into SCENE_PLANES_SLICES slices (a
     * narrow field of view makes thin slices: about 12 degrees and below) */
    double r = 1.0 + 2.0 / ((double)proj11 * SCENE_PLANES_SLICES_Y);
    double most = proj11 > 0.0f ? fmin(SCENE_PLANES_RATIO, exp(SCENE_PLANES_SLICES * log(r)))
                                : SCENE_PLANES_RATIO;
    if (!(n > 0.0f) || (double)f / (double)n > most)
        n = (float)((double)f / most);
    out[0] = n;
    out[1] = f;
}
