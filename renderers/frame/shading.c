/* CPU side of the shared shading code: lights and per-frame values packed the way
 * renderers/shaders/lighting.inc.glsl and frame.inc.glsl read them (shading.h). */
#include "renderers/frame/shading.h"

#include "renderers/frame/environment.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void shading_pack_light(const scene_light *l, const sm_mat4 view, gpu_light *out)
{
    sm_vec3 p, d;

    memset(out, 0, sizeof *out);
    /* [0] view-space position (a point), range */
    sm_mat4_mulv3(view, l->position, 1.0f, p);
    out->v[0][0] = p[0];
    out->v[0][1] = p[1];
    out->v[0][2] = p[2];
    out->v[0][3] = l->radius;
    /* [1] colour, type */
    out->v[1][0] = l->color[0];
    out->v[1][1] = l->color[1];
    out->v[1][2] = l->color[2];
    out->v[1][3] = (float)l->type;
    /* [2] view-space direction (a vector, made unit), cos of the spot's cut-off.
     * Only spots have a cone; the others get cos = -1 (a cone that holds everything). */
    sm_mat4_mulv3(view, l->direction, 0.0f, d);
    sm_vec3_normalize(d);
    out->v[2][0] = d[0];
    out->v[2][1] = d[1];
    out->v[2][2] = d[2];
    out->v[2][3] = l->type == LIGHT_SPOT ? cosf(l->spot_angle) : -1.0f;
    /* [3] spot exponent, attenuation kind */
    out->v[3][0] = l->type == LIGHT_SPOT ? l->spot_exponent : 0.0f;
    out->v[3][1] = (float)l->attenuation;
    /* [4] quadratic a, b, c */
    out->v[4][0] = l->att_a;
    out->v[4][1] = l->att_b;
    out->v[4][2] = l->att_c;
}

void shading_set_shadow_layer(gpu_light *l, uint32_t layer)
{
    l->v[3][2] = layer == UINT32_MAX ? 0.0f : (float)layer + 1.0f;
}

void shading_pack_frame(const scene *s, gpu_frame *out)
{
    sm_mat4 inv;

    memset(out, 0, sizeof *out);
    memcpy(out->proj, s->proj, sizeof out->proj);
    sm_mat4_inv(s->proj, inv);
    memcpy(out->inv_proj, inv, sizeof out->inv_proj);
    out->ambient[0] = s->ambient[0];
    out->ambient[1] = s->ambient[1];
    out->ambient[2] = s->ambient[2];
    out->viewport[0] = (float)s->width;
    out->viewport[1] = (float)s->height;
    out->viewport[2] = s->width > 0 ? 1.0f / (float)s->width : 0.0f;
    out->viewport[3] = s->height > 0 ? 1.0f / (float)s->height : 0.0f;
    out->sky[0] = s->sky_color[0];
    out->sky[1] = s->sky_color[1];
    out->sky[2] = s->sky_color[2];
    out->sky[3] = s->sky ? 1.0f : 0.0f;
    out->clip[0] = s->cam.znear;
    out->clip[1] = s->cam.zfar;
    sm_mat4_inv(s->view, inv);
    memcpy(out->view_to_world, inv, sizeof out->view_to_world);
    const environment_maps *env = s->environment != ENVIRONMENT_NONE ? environment_get() : NULL;
    if (env) {   /* without the maps (out of memory) scene_gpu_create has failed already */
        out->environment[0] = s->environment_intensity;
        out->environment[1] = (float)(ENVIRONMENT_LEVELS - 1);
        for (int i = 0; i < 9; i++)
            for (int c = 0; c < 3; c++)
                out->environment_sh[i][c] = env->sh[i][c] * s->environment_intensity;
    }
}

size_t shading_frame_bytes(const scene *s)
{
    return s->environment != ENVIRONMENT_NONE ? sizeof(gpu_frame)
                                              : offsetof(gpu_frame, view_to_world);
}

unsigned shading_material_defines(const scene_material *m,
                                  const char *defines[SHADING_MATERIAL_DEFINES])
{
    unsigned n = 0;
    if (m->diffuse_map >= 0)
        defines[n++] = "DIFFUSE_MAP";
    if (m->gloss_map >= 0)
        defines[n++] = "GLOSS_MAP";
    if (m->normal_map >= 0)
        defines[n++] = "NORMAL_MAP";
    if (m->emissive_map >= 0)
        defines[n++] = "EMISSIVE_MAP";
    if (m->alpha == MATERIAL_MASK)
        defines[n++] = "ALPHA_TEST";
    return n;
}

uint32_t shading_cluster_slices(const scene *s, int slices_y, double *ratio)
{
    return scene_depth_slices(s->proj[1][1], s->cam.znear, s->cam.zfar, slices_y, ratio);
}

bool shading_cluster_slices_ok(const char *name, double proj11, double znear, double zfar,
                               int slices_y, uint32_t *slices, double *ratio, char *err,
                               size_t errlen)
{
    double r;
    uint32_t k = scene_depth_slices(proj11, znear, zfar, slices_y, &r);
    if (slices)
        *slices = k;
    if (ratio)
        *ratio = r;
    if (k <= SCENE_DEPTH_SLICES_MAX)
        return true;
    snprintf(err, errlen,
             "%s: %u depth slices from near %g to far %g (each %.4g times deeper, "
             "clustered.slices %d): at most %u; raise near or lower clustered.slices",
             name, k, znear, zfar, r, slices_y, SCENE_DEPTH_SLICES_MAX);
    return false;
}
