/* "glass": translucent panes and particles over a lit, textured floor (our own scene for
 * the translucent pass, renderers/frame/translucent.h).
 *
 * Floor, pillar, panes, particles, lights and camera: the comment above the counts below. */
#include "scenes/scene_build.h"

#include <math.h>

/*   floor      a 24 x 24 box, its top at y = 0, checker diffuse + gloss maps (opaque)
 *   pillar     one opaque pillar behind the panes, so panes are seen over geometry as
 *              well as over the floor and the sky
 *   panes      GLASS_PANES thin boxes (0.1 x 3 x 4, facing +-x) standing on the floor,
 *              each of its own colour and opacity, staggered in x and z so that the
 *              default camera (at t = 0 on +x, looking along -x) sees each overlap its
 *              neighbours; none intersects another, so sorting their centres by view
 *              depth orders them
 *   particles  GLASS_PARTICLES small icospheres (radius 0.25) on a helix through the
 *              panes' space, translucent, faintly emissive, one of them with the
 *              floor's diffuse map (the DIFFUSE_MAP variant of the translucent pass)
 *   lights     GLASS_LIGHTS authored point lights (linear range 6) on a ring above the
 *              floor, for `lights.placement: scene`; random and grid lights go in the
 *              box [-10, 10] x [0.5, 5] x [-10, 10]
 *
 * Camera: an orbit of radius 14 at height 5 about (0, 1.5, 0), 30 s a turn; ambient
 * 0.05, a sky. Units are metres (the panes are door-sized). Everything is static but
 * the camera, so a frame depends on t only through it (clock: fixed is deterministic). */
enum { GLASS_PANES = 4, GLASS_PARTICLES = 24, GLASS_LIGHTS = 12 };

bool scene_build_glass(scene_builder *b, const void *arg)
{
    (void)arg;
    scene *s = b->s;
    if (!sb_begin(b, 2 + GLASS_PANES + GLASS_PARTICLES))
        return false;
    texture_desc checker = {.width = 256, .height = 256, .pattern = TEXTURE_CHECKER, .cells = 8,
                            .color_a = {0.85f, 0.85f, 0.8f}, .color_b = {0.3f, 0.3f, 0.32f}};
    int t_floor = sb_texture(b, texture_diffuse, &checker);
    int t_floor_gloss = sb_texture(b, texture_gloss, &checker);
    if (b->failed)
        return false;

    sb_map_set floor_maps = {t_floor, t_floor_gloss, -1, -1};
    uint32_t floor = sb_material_maps(b, &floor_maps, 0.4f, 32, 0.0f);
    uint32_t stone = sb_material(b, 0.6f, 0.55f, 0.5f, 0.2f, 16);
    static const float pane_color[GLASS_PANES][4] = {
        {0.9f, 0.15f, 0.1f, 0.5f},    /* red, half covering */
        {0.1f, 0.8f, 0.2f, 0.4f},     /* green */
        {0.15f, 0.3f, 0.95f, 0.6f},   /* blue */
        {0.95f, 0.7f, 0.1f, 0.35f},   /* amber */
    };
    uint32_t pane_mat[GLASS_PANES];
    for (int i = 0; i < GLASS_PANES; i++) {
        pane_mat[i] = sb_material(b, pane_color[i][0], pane_color[i][1], pane_color[i][2],
                                  0.8f, 64);
        if (b->failed)
            return false;
        s->materials[pane_mat[i]].alpha = MATERIAL_BLEND;
        s->materials[pane_mat[i]].opacity = pane_color[i][3];
    }
    uint32_t mote = sb_material(b, 0.7f, 0.9f, 1.0f, 0.5f, 32);
    uint32_t mote_mapped = sb_material(b, 1, 1, 1, 0.5f, 32);
    if (b->failed)
        return false;
    s->materials[mote].alpha = MATERIAL_BLEND;
    s->materials[mote].opacity = 0.3f;
    sm_vec3_make(0.05f, 0.08f, 0.1f, s->materials[mote].emissive);
    s->materials[mote_mapped].alpha = MATERIAL_BLEND;
    s->materials[mote_mapped].opacity = 0.45f;
    s->materials[mote_mapped].diffuse_map = t_floor;

    int floor_mesh = sb_box(b, 12.0f, 0.5f, 12.0f);
    int pillar_mesh = sb_pillar(b, 0.6f, 4.0f, 16);
    int pane_mesh = sb_box(b, 0.05f, 1.5f, 2.0f);   /* facing +-x */
    int mote_mesh = sb_icosphere(b, 0.25f, 1);
    if (b->failed)
        return false;

    sm_vec3_make(0.05f, 0.05f, 0.05f, s->ambient);
    sb_set_sky(b, 0.4f, 0.55f, 0.75f);
    sb_object(b, floor_mesh, floor, 0.0f, -0.5f, 0.0f, 1.0f);
    sb_object(b, pillar_mesh, stone, -1.0f, 0.0f, -5.0f, 1.0f);
    /* staggered: each pane 1.5 further from the camera at t = 0 (on +x) and 1.8 to the
     * side of the one before, so neighbours overlap by 2.2 of their 4 */
    for (int i = 0; i < GLASS_PANES; i++)
        sb_object(b, pane_mesh, pane_mat[i], 2.25f - 1.5f * (float)i, 1.5f,
                  -2.7f + 1.8f * (float)i, 1.0f);
    for (int i = 0; i < GLASS_PARTICLES; i++) {
        float a = 0.7f * (float)i, r = 3.5f + 0.1f * (float)i;
        sb_object(b, mote_mesh, i == 5 ? mote_mapped : mote, r * cosf(a),
                  0.6f + 0.12f * (float)i, r * sinf(a), 1.0f);
    }
    for (int i = 0; i < GLASS_LIGHTS; i++) {
        float a = 2.0f * SM_PI * (float)i / (float)GLASS_LIGHTS;
        float c = (float)(i % 3);
        sb_point(b, 6.0f * cosf(a), 1.0f + 0.5f * (float)(i % 4), 6.0f * sinf(a), 6.0f,
                 c == 0 ? 1.0f : 0.4f, c == 1 ? 1.0f : 0.4f, c == 2 ? 1.0f : 0.4f);
    }
    sb_set_bounds(b, -10.0f, 0.5f, -10.0f, 10.0f, 5.0f, 10.0f);
    sb_set_orbit(b, 0.0f, 1.5f, 0.0f, 14.0f, 5.0f, 30.0f);
    sb_set_projection(b, 60.0f, 0.1f, 100.0f);
    return !b->failed;
}
