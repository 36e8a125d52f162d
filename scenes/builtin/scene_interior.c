/* interior: seed 000's interior scene (section 4.8.2): "a smaller, darker interior area"
 * with "a shorter draw distance (2048 units)", "an ambient light source", "a
 * shadow-casting directional light source (the moon)", "5 non shadow casting
 * omni-directional lights", "3 shadow casting spotlights" and "72 instances of various
 * meshes, each with their own associated diffuse, specular and normal maps. A handful of
 * meshes have an emissive channel." "The majority of the lights do not overlap, but in a
 * handful of places (such as between the two generators) there is some overlapping."
 *
 * Units, the hall and corridor, the 72 instances, the authored lights, the camera and
 * the random lights' bounds: the comment above scene_build_interior. */
#include "scenes/scene_build.h"

#include <math.h>

enum { INTERIOR_OBJECTS = 72 };

/* Units: 1 world unit = 1 inch (the convention of the id Tech games the section names;
 * 2048 units is then 52 m). A generator hall 1152 x 288 x 896 (x, y, z; floor at y = 0,
 * x in [-576, 576], z in [-448, 448]) with a doorway (128 x 176) in its north wall (z =
 * -448) into a corridor 128 wide, 176 high and 512 long, closed at z = -960.
 *
 * The 72 instances (every one with diffuse, gloss and normal maps; the 7 lamps and
 * generator caps also emissive):
 *   10 shell: floor, ceiling, south, east and west walls, the north wall's two halves
 *      and the lintel over the doorway, the corridor, the corridor's end wall
 *   12 pillars in two rows (z = +-360, x = +-84, +-252, +-420)
 *    6 two generators at x = +-140: base, body, glowing cap
 *   20 crates, five in each corner (four on the floor, one stacked)
 *   12 barrels, six along each of the east and west walls
 *    5 wall lamps (emissive), one at each omni light
 *    4 pipes along the north and south walls under the ceiling
 *    3 spot-light housings, one over each spot
 *
 * Authored lights (lights.placement: scene), in this order:
 *   0    the moon: directional, dim blue, shadows
 *   1-4  omni lights at the wall lamps (+-530, 200, +-300), range 200
 *   5    omni light at the south wall's lamp (0, 200, 410), range 200
 *        (the five spheres are at least 540 apart: none overlap)
 *   6-7  spots over the generators at (+-140, 255, 0), straight down, 35 degrees,
 *        range 330, shadows: their footprints (radius 179 on the floor) overlap for
 *        |x| < 39, between the generators
 *   8    spot in the corridor at (0, 150, -500), aimed down the corridor, 25 degrees,
 *        range 480, shadows
 * All with linear-range attenuation (the renderers' max(0, 1 - d / range)).
 *
 * The camera orbits the generators at radius 270, eye 190 above the floor, looking at
 * (0, 80, 0), once in 60 s: clear of the pillars (370 from the centre at least), the
 * generators (212) and the ceiling (288). Random lights: x in [-540, 540], y in [20, 270],
 * z in [-420, 420]; for them, linear-range attenuation and a radius of 100 to 200 suit
 * the scale (1/d^2 with colour 0.3 fades out within 9 units). */
bool scene_build_interior(scene_builder *b, const void *arg)
{
    scene *s = b->s;
    if (!sb_begin(b, INTERIOR_OBJECTS))
        return false;

    // >>maps: six patterns, each with diffuse, gloss and normal maps
    texture_desc tiles = {.pattern = TEXTURE_CHECKER, .cells = 8, .color_a = {0.42f, 0.42f, 0.4f},
                          .color_b = {0.3f, 0.3f, 0.32f}, .gloss_a = 0.6f, .gloss_b = 0.35f};
    texture_desc bricks = {.pattern = TEXTURE_BRICKS, .cells = 8, .seed = 11,
                           .color_a = {0.45f, 0.28f, 0.22f}, .color_b = {0.35f, 0.33f, 0.3f},
                           .gloss_a = 0.25f, .gloss_b = 0.05f};
    texture_desc concrete = {.pattern = TEXTURE_NOISE, .cells = 6, .seed = 12,
                             .color_a = {0.3f, 0.3f, 0.3f}, .color_b = {0.5f, 0.49f, 0.46f},
                             .noise = 0.5f, .gloss_a = 0.2f, .gloss_b = 0.05f};
    texture_desc metal = {.pattern = TEXTURE_CHECKER, .cells = 16, .color_a = {0.5f, 0.52f, 0.55f},
                          .color_b = {0.38f, 0.4f, 0.42f}, .gloss_a = 1.0f, .gloss_b = 0.7f,
                          .bump = 1.5f};
    texture_desc wood = {.pattern = TEXTURE_BRICKS, .cells = 4, .seed = 13,
                         .color_a = {0.5f, 0.36f, 0.2f}, .color_b = {0.3f, 0.2f, 0.12f},
                         .noise = 0.3f, .gloss_a = 0.2f, .gloss_b = 0.05f};
    texture_desc glow = {.pattern = TEXTURE_CHECKER, .cells = 2, .color_a = {0.8f, 0.75f, 0.6f},
                         .color_b = {0.6f, 0.55f, 0.45f}, .emissive_fraction = 1.0f,
                         .emissive_color = {1.0f, 0.8f, 0.5f}};
    sb_map_set m_tiles = sb_maps(b, &tiles, false), m_bricks = sb_maps(b, &bricks, false),
               m_concrete = sb_maps(b, &concrete, false), m_metal = sb_maps(b, &metal, false),
               m_wood = sb_maps(b, &wood, false), m_glow = sb_maps(b, &glow, true);
    uint32_t floor_mat = sb_material_maps(b, &m_tiles, 0.5f, 32.0f, 0.0f);
    uint32_t wall_mat = sb_material_maps(b, &m_bricks, 0.15f, 8.0f, 0.0f);
    uint32_t concrete_mat = sb_material_maps(b, &m_concrete, 0.1f, 8.0f, 0.0f);
    uint32_t metal_mat = sb_material_maps(b, &m_metal, 0.9f, 64.0f, 0.0f);
    uint32_t wood_mat = sb_material_maps(b, &m_wood, 0.1f, 8.0f, 0.0f);
    uint32_t glow_mat = sb_material_maps(b, &m_glow, 0.3f, 16.0f, 1.0f);

    // >>meshes (texture repeats: every 128 units on the shell)
    const float tile = 128.0f;
    sm_vec3 slab = {576, 8, 448}, wall_x = {576, 144, 8}, wall_z = {8, 144, 448},
            wall_part = {256, 144, 8}, lintel = {64, 56, 8}, end_wall = {64, 88, 8};
    int m_slab = sb_box(b, slab[0], slab[1], slab[2]);
    sb_box_uv_tile(b, m_slab, slab, tile);
    int m_wall_x = sb_box(b, wall_x[0], wall_x[1], wall_x[2]);
    sb_box_uv_tile(b, m_wall_x, wall_x, tile);
    int m_wall_z = sb_box(b, wall_z[0], wall_z[1], wall_z[2]);
    sb_box_uv_tile(b, m_wall_z, wall_z, tile);
    int m_wall_part = sb_box(b, wall_part[0], wall_part[1], wall_part[2]);
    sb_box_uv_tile(b, m_wall_part, wall_part, tile);
    int m_lintel = sb_box(b, lintel[0], lintel[1], lintel[2]);
    sb_box_uv_tile(b, m_lintel, lintel, tile);
    int m_corridor = sb_corridor(b, 128.0f, 176.0f, 512.0f, 1.0f / tile);
    int m_end = sb_box(b, end_wall[0], end_wall[1], end_wall[2]);
    sb_box_uv_tile(b, m_end, end_wall, tile);
    int m_pillar = sb_pillar(b, 18.0f, 288.0f, 16);
    int m_gen_base = sb_box(b, 72.0f, 12.0f, 72.0f);
    int m_gen_body = sb_cylinder(b, 52.0f, 120.0f, 32);
    int m_gen_cap = sb_cylinder(b, 40.0f, 14.0f, 32);
    int m_crate = sb_box(b, 24.0f, 24.0f, 24.0f);
    int m_barrel = sb_cylinder(b, 16.0f, 44.0f, 20);
    int m_lamp = sb_box(b, 8.0f, 12.0f, 8.0f);
    int m_pipe = sb_cylinder(b, 6.0f, 1100.0f, 12);
    int m_housing = sb_cone(b, 14.0f, 24.0f, 20, true);
    sm_mat4 rot;
    sm_vec3 zaxis = {0, 0, 1}, xaxis = {1, 0, 0};
    sm_mat4_rotate_make((float)SM_PI_2, zaxis, rot);     /* pipes: Y -> along X */
    sb_mesh_transform(b, m_pipe, rot);
    sm_mat4_rotate_make(-(float)SM_PI_2, xaxis, rot);    /* housings: open -Z -> -Y */
    sb_mesh_transform(b, m_housing, rot);
    if (b->failed)
        return false;

    // >>objects
    /* shell (10) */
    sb_object(b, m_slab, floor_mat, 0, -8, 0, 1);
    sb_object(b, m_slab, concrete_mat, 0, 296, 0, 1);
    sb_object(b, m_wall_x, wall_mat, 0, 144, 456, 1);
    sb_object(b, m_wall_z, wall_mat, 584, 144, 0, 1);
    sb_object(b, m_wall_z, wall_mat, -584, 144, 0, 1);
    sb_object(b, m_wall_part, wall_mat, -320, 144, -456, 1);
    sb_object(b, m_wall_part, wall_mat, 320, 144, -456, 1);
    sb_object(b, m_lintel, wall_mat, 0, 232, -456, 1);
    sb_object(b, m_corridor, wall_mat, 0, 88, -704, 1);
    sb_object(b, m_end, wall_mat, 0, 88, -968, 1);
    /* pillars (12) */
    for (int k = 0; k < 12; k++)
        sb_object(b, m_pillar, concrete_mat, -420.0f + 168.0f * (float)(k % 6), 144,
                  k < 6 ? -360.0f : 360.0f, 1);
    /* generators (6) */
    for (int g = 0; g < 2; g++) {
        float x = g ? 140.0f : -140.0f;
        sb_object(b, m_gen_base, metal_mat, x, 12, 0, 1);
        sb_object(b, m_gen_body, metal_mat, x, 84, 0, 1);
        sb_object(b, m_gen_cap, glow_mat, x, 151, 0, 1);
    }
    /* crates (20): per corner, four on the floor and one on top of the first two */
    static const float crate[5][3] = {{0, 24, 0}, {-48, 24, 0}, {0, 24, -48}, {-48, 24, -48},
                                      {-24, 72, 0}};
    for (int c = 0; c < 4; c++) {
        float sx = c % 2 ? 1.0f : -1.0f, sz = c / 2 ? 1.0f : -1.0f;
        for (int k = 0; k < 5; k++)
            sb_object(b, m_crate, wood_mat, sx * (548.0f + crate[k][0]), crate[k][1],
                      sz * (420.0f + crate[k][2]), 1);
    }
    /* barrels (12) */
    static const float barrel_z[6] = {-150, -110, -70, 70, 110, 150};
    for (int k = 0; k < 12; k++)
        sb_object(b, m_barrel, metal_mat, k < 6 ? -550.0f : 550.0f, 22, barrel_z[k % 6], 1);
    /* wall lamps (5) */
    for (int k = 0; k < 4; k++)
        sb_object(b, m_lamp, glow_mat, k % 2 ? 570.0f : -570.0f, 200, k / 2 ? 300.0f : -300.0f, 1);
    sb_object(b, m_lamp, glow_mat, 0, 200, 442, 1);
    /* pipes (4) */
    sb_object(b, m_pipe, metal_mat, 0, 250, 436, 1);
    sb_object(b, m_pipe, metal_mat, 0, 266, 436, 1);
    sb_object(b, m_pipe, metal_mat, 0, 250, -436, 1);
    sb_object(b, m_pipe, metal_mat, 0, 266, -436, 1);
    /* spot housings (3): apex up, the light just below the rim */
    sb_object(b, m_housing, metal_mat, -140, 282, 0, 1);
    sb_object(b, m_housing, metal_mat, 140, 282, 0, 1);
    sb_object(b, m_housing, metal_mat, 0, 176, -500, 1);

    // >>authored lights
    sm_vec3 moon_dir = {0.3f, -0.8f, 0.5f}, moon = {0.1f, 0.12f, 0.2f};
    sb_directional(b, moon_dir, moon, true);
    for (int k = 0; k < 4; k++)
        sb_point(b, k % 2 ? 530.0f : -530.0f, 200, k / 2 ? 300.0f : -300.0f, 200.0f, 1.0f,
                 0.75f, 0.5f);
    sb_point(b, 0, 200, 410, 200.0f, 1.0f, 0.75f, 0.5f);
    sm_vec3 spot_color = {1.2f, 1.15f, 1.0f};
    for (int g = 0; g < 2; g++) {
        float x = g ? 140.0f : -140.0f;
        sm_vec3 pos = {x, 255, 0}, at = {x, 0, 0};
        sb_spot(b, pos, at, 35.0f, 4.0f, 330.0f, spot_color, true);
    }
    sm_vec3 cpos = {0, 150, -500}, cat = {0, 0, -900};
    sb_spot(b, cpos, cat, 25.0f, 4.0f, 480.0f, spot_color, true);

    sm_vec3_make(0.04f, 0.04f, 0.05f, s->ambient);
    s->sky = false;
    sb_set_bounds(b, -540.0f, 20.0f, -420.0f, 540.0f, 270.0f, 420.0f);
    sb_set_orbit(b, 0.0f, 80.0f, 0.0f, 270.0f, 110.0f, 60.0f);
    sb_set_projection(b, 60.0f, 1.0f, 2048.0f);
    if (!b->failed && s->nobjects != INTERIOR_OBJECTS)
        sb_fail(b, "bug: %u objects, not %d", s->nobjects, INTERIOR_OBJECTS);
    return !b->failed;
}
