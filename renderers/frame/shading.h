#pragma once
/* CPU side of the shared shading code (renderers/shaders/lighting.inc.glsl and
 * frame.inc.glsl): lights and per-frame values packed as the shaders read them.
 * All shading is in view space. */
#include <stddef.h>
#include <stdint.h>
#include "scenes/scene.h"

/* One light: 5 vec4s, the layout of lighting.inc.glsl's Light. */
typedef struct gpu_light {
    float v[5][4];
} gpu_light;

/* The Frame uniform block (std140). */
typedef struct gpu_frame {
    float proj[16];
    float inv_proj[16];
    float ambient[4];
    float viewport[4];
    float sky[4];
    float clip[4];
    /* the environment light (environment.h): in the block only with the ENVIRONMENT
     * define, a scene with one (shading_frame_bytes) */
    float view_to_world[16];   /* the view matrix's inverse */
    float environment[4];      /* x intensity, y the cube map's last lod, zw 0 */
    float environment_sh[9][4];   /* rgb: environment_maps.sh x intensity, w 0 */
} gpu_frame;

/* Light l in the view space of `view`: [0] position transformed as a point, w range;
 * [1] colour, w type (light_type as a float); [2] direction transformed as a vector and
 * normalized, w cos(spot_angle) for a spot (-1 for the others: no cone); [3] x spot
 * exponent (0 unless a spot), y attenuation kind (attenuation_kind as a float), z 0
 * (no shadow map: shading_set_shadow_layer sets it), w 0; [4] att_a, att_b, att_c, 0. */
void shading_pack_light(const scene_light *l, const sm_mat4 view, gpu_light *out);
/* The light's shadow-map layer into a packed light: [3].z = layer + 1 (shadow.inc
 * reads params.z - 1), or 0 for FRONTEND_NO_SHADOW (UINT32_MAX): no shadow map. */
void shading_set_shadow_layer(gpu_light *l, uint32_t layer);
/* proj = s->proj, inv_proj = its inverse (sm_mat4_inv), ambient = (s->ambient, 0),
 * viewport = (width, height, 1/width, 1/height) of s, sky = (s->sky_color, 1 when
 * s->sky else 0), clip = (s->cam.znear, s->cam.zfar, 0, 0), view_to_world = s->view's
 * inverse; with an environment (s->environment), environment = (intensity, levels - 1,
 * 0, 0) and environment_sh its irradiance times the intensity (zero otherwise; the maps
 * are built at the first such call: environment_get). */
void shading_pack_frame(const scene *s, gpu_frame *out);
/* The bytes of gpu_frame that frame.inc's block has for s: all of them with an
 * environment, else up to view_to_world (the block without ENVIRONMENT). */
size_t shading_frame_bytes(const scene *s);

/* clustered: the depth slices that reach from s's near to its far plane with Olsson
 * et al.'s spacing, each slice's far/near ratio being 1 + 2 tan(fovy/2) / slices_y
 * (tan(fovy/2) = 1 / proj[1][1], as tile_cull.inc computes it), at least 1; *ratio (may
 * be NULL) gets that ratio. */
uint32_t shading_cluster_slices(const scene *s, int slices_y, double *ratio);
/* Whether clustered.slices slices_y cuts the planes (proj11 the projection's y scale)
 * into at most SCENE_DEPTH_SLICES_MAX slices; false with the message that names `name`
 * ("clustered: 1282 depth slices from near ... at most 1024; raise near or lower
 * clustered.slices"). The renderers' grid and the plan check (validate, before GL) give
 * the same one. *slices and *ratio (may be NULL) get the count and the ratio. */
bool shading_cluster_slices_ok(const char *name, double proj11, double znear, double zfar,
                               int slices_y, uint32_t *slices, double *ratio, char *err,
                               size_t errlen);

/* The shader defines a material needs ("DIFFUSE_MAP", "GLOSS_MAP", "NORMAL_MAP",
 * "EMISSIVE_MAP", "ALPHA_TEST" for a MATERIAL_MASK material), in that order; returns
 * how many (<= SHADING_MATERIAL_DEFINES). */
#define SHADING_MATERIAL_DEFINES 5
unsigned shading_material_defines(const scene_material *m,
                                  const char *defines[SHADING_MATERIAL_DEFINES]);
