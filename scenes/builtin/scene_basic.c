/* The harness's own scenes: "empty" (and the test scenes, which build as it) and "shapes". */
#include "scenes/scene_build.h"

/* "empty": no geometry, an orbiting camera and the run's lights; no authored lights. */
bool scene_build_empty(scene_builder *b, const void *arg)
{
    if (!sb_begin(b, 0))
        return false;
    sb_set_bounds(b, -50.0f, 0.0f, -50.0f, 50.0f, 20.0f, 50.0f);
    sm_vec3_make(0.1f, 0.1f, 0.1f, b->s->ambient);
    sb_set_orbit(b, 0.0f, 0.0f, 0.0f, 80.0f, 30.0f, 60.0f);
    sb_set_projection(b, 60.0f, 0.1f, 1000.0f);
    return !b->failed;
}

/* "shapes": a floor and a 3 x 3 grid of objects (sphere, torus knot, box, icosphere,
 * cone, pillar...) under an orbiting camera; materials without maps, with diffuse
 * and gloss maps, and with diffuse, normal and emissive maps, so every shader
 * variant has work. Lights are placed above the floor; no authored lights. */
bool scene_build_shapes(scene_builder *b, const void *arg)
{
    scene *s = b->s;
    if (!sb_begin(b, 10))
        return false;
    texture_desc checker = {.width = 256, .height = 256, .pattern = TEXTURE_CHECKER, .cells = 8,
                            .color_a = {0.9f, 0.85f, 0.7f}, .color_b = {0.35f, 0.3f, 0.25f}};
    texture_desc bricks = {.width = 256, .height = 256, .pattern = TEXTURE_BRICKS, .cells = 8,
                           .seed = 7, .color_a = {0.7f, 0.3f, 0.2f}, .color_b = {0.8f, 0.8f, 0.75f},
                           .emissive_fraction = 0.1f, .emissive_color = {1.0f, 0.6f, 0.2f}};
    texture_desc ground = {.width = 256, .height = 256, .pattern = TEXTURE_NOISE, .cells = 4,
                           .seed = 3, .color_a = {0.25f, 0.3f, 0.2f}, .color_b = {0.5f, 0.5f, 0.4f},
                           .noise = 0.5f};
    int t_checker = sb_texture(b, texture_diffuse, &checker);
    int t_checker_gloss = sb_texture(b, texture_gloss, &checker);
    int t_bricks = sb_texture(b, texture_diffuse, &bricks);
    int t_bricks_normal = sb_texture(b, texture_normal_map, &bricks);
    int t_bricks_emissive = sb_texture(b, texture_emissive, &bricks);
    int t_ground = sb_texture(b, texture_diffuse, &ground);
    if (b->failed)
        return false;

    /* maps: diffuse, gloss, normal, emissive */
    sb_map_set ground_maps = {t_ground, -1, -1, -1};
    sb_map_set checker_maps = {t_checker, t_checker_gloss, -1, -1};
    sb_map_set brick_maps = {t_bricks, -1, t_bricks_normal, t_bricks_emissive};
    uint32_t floor = sb_material_maps(b, &ground_maps, 0.2f, 16, 0.0f);
    sb_material(b, 0.8f, 0.8f, 0.85f, 0.6f, 32);                    /* 1: plain */
    sb_material_maps(b, &checker_maps, 1.0f, 64, 0.0f);             /* 2: checker + gloss */
    sb_material_maps(b, &brick_maps, 0.3f, 24, 1.0f);               /* 3: bricks */

    int floor_mesh = sb_box(b, 40.0f, 0.5f, 40.0f);
    sb_sphere(b, 2.0f, 32, 16);
    sb_torus_knot(b, 2, 3, 1.6f, 0.5f, 128, 12);
    sb_box(b, 1.5f, 1.5f, 1.5f);
    sb_icosphere(b, 2.0f, 2);
    sb_cone(b, 1.8f, 3.5f, 24, true);
    sb_pillar(b, 1.0f, 5.0f, 16);
    if (b->failed)
        return false;

    sb_object(b, floor_mesh, floor, 0.0f, -0.5f, 0.0f, 1.0f);
    /* mesh, material per grid cell, row by row */
    static const uint32_t grid[9][2] = {{1, 1}, {2, 2}, {3, 3}, {4, 2}, {2, 3},
                                        {5, 1}, {6, 3}, {1, 2}, {3, 1}};
    for (int i = 0; i < 9; i++) {
        float x = (float)(i % 3 - 1) * 10.0f, z = (float)(i / 3 - 1) * 10.0f;
        /* the pillar stands on the floor, the cone lies on its side */
        float y = grid[i][0] == 6 ? 0.0f : (grid[i][0] == 5 ? 1.8f : 2.2f);
        scene_object *o = sb_object(b, (int)grid[i][0], grid[i][1], x, y, z, 1.0f);
        if (grid[i][0] == 2 || grid[i][0] == 3)
            o->spin_rate = 0.5f;   /* the papers' rotating models */
    }
    sb_set_bounds(b, -20.0f, 0.5f, -20.0f, 20.0f, 8.0f, 20.0f);
    sm_vec3_make(0.05f, 0.05f, 0.06f, s->ambient);
    sb_set_sky(b, 0.45f, 0.6f, 0.8f);
    sb_set_orbit(b, 0.0f, 0.0f, 0.0f, 35.0f, 18.0f, 30.0f);
    sb_set_projection(b, 60.0f, 0.5f, 200.0f);
    return !b->failed;
}
