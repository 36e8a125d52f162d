/* The spot-light tests of seed 000 (sections 5.4 and 5.5), each a floor with a few
 * objects, its authored spot light(s) and a scripted camera path (CAMERA_SCRIPTED) whose
 * two ends are the paper's two configurations: a manifest holds the camera at either end
 * with camera.hold 0 or 1, or lets it travel over camera.period seconds (default 20).
 * Each records the screen coverage of its spots (ncoverage_lights = all of them, with
 * lights.placement: scene).
 *
 * Units: 1 world unit = 1 metre. Spots use linear-range attenuation and ranges long
 * enough that the lit footprint on the floor is the cone's whole footprint (range >=
 * height / cos(angle)), and not much longer, so that the volume stays close to what it
 * lights. Coverage is that of the volume renderers draw: the cone capped by the plane at
 * the range (scene.h: scene_light_coverage), which pokes a little under the floor.
 * Dark surroundings: ambient 0.05, no sky. The coverages quoted are
 * scene_light_coverage's (tests/unit/test_scene_catalog.c checks the 4:3 ones). */
#include "scenes/scene_build.h"

#define SPOT_PATH_SECONDS 20.0f

/* The shared room: a 30 x 30 floor (top at y = 0) with a crate, a ball and a column
 * away from the spots; `wall` adds a back wall 30 wide and 10 high at z = -20. */
static void spot_room(scene_builder *b, bool wall)
{
    texture_desc tiles = {.pattern = TEXTURE_CHECKER, .cells = 8, .color_a = {0.7f, 0.7f, 0.68f},
                          .color_b = {0.45f, 0.45f, 0.47f}, .gloss_a = 0.6f, .gloss_b = 0.3f};
    texture_desc bricks = {.pattern = TEXTURE_BRICKS, .cells = 8, .seed = 5,
                           .color_a = {0.6f, 0.35f, 0.25f}, .color_b = {0.6f, 0.58f, 0.55f}};
    sb_map_set mt = sb_maps(b, &tiles, false), mb = sb_maps(b, &bricks, false);
    uint32_t floor_mat = sb_material_maps(b, &mt, 0.5f, 32.0f, 0.0f);
    uint32_t brick_mat = sb_material_maps(b, &mb, 0.2f, 16.0f, 0.0f);
    uint32_t plain = sb_material(b, 0.7f, 0.7f, 0.75f, 0.6f, 32.0f);
    sm_vec3 floor_half = {15.0f, 0.1f, 15.0f};
    int floor_mesh = sb_box(b, floor_half[0], floor_half[1], floor_half[2]);
    sb_box_uv_tile(b, floor_mesh, floor_half, 2.0f);
    int crate = sb_box(b, 0.5f, 0.5f, 0.5f);
    int ball = sb_sphere(b, 0.8f, 24, 12);
    int column = sb_pillar(b, 0.3f, 4.0f, 16);
    sb_object(b, floor_mesh, floor_mat, 0.0f, -0.1f, 0.0f, 1.0f);
    sb_object(b, crate, brick_mat, -6.0f, 0.5f, -5.0f, 1.0f);
    sb_object(b, ball, plain, 6.0f, 0.8f, -6.0f, 1.0f);
    sb_object(b, column, brick_mat, -7.0f, 2.0f, 4.0f, 1.0f);
    if (wall) {
        sm_vec3 wall_half = {15.0f, 5.0f, 0.2f};
        int w = sb_box(b, wall_half[0], wall_half[1], wall_half[2]);
        sb_box_uv_tile(b, w, wall_half, 2.0f);
        sb_object(b, w, brick_mat, 0.0f, 5.0f, -20.0f, 1.0f);
    }
    sm_vec3_make(0.05f, 0.05f, 0.05f, b->s->ambient);
    b->s->sky = false;
    sb_set_projection(b, 60.0f, 0.05f, 100.0f);
}

/* One spot test: its room, its spots (all of one angle, range and colour; exponent 4, no
 * shadows), and the scripted camera's two key poses, from hold 0 to hold 1. */
typedef struct spot_test {
    bool wall;
    uint32_t nspots;
    float pos[2][3], at[2][3];
    float half_angle_deg, range;
    float color[3];
    float eyes[2][3], targets[2][3];
} spot_test;

static bool spot_build(scene_builder *b, const spot_test *t)
{
    if (!sb_begin(b, t->wall ? 5 : 4))
        return false;
    spot_room(b, t->wall);
    for (uint32_t k = 0; k < t->nspots; k++)
        sb_spot(b, t->pos[k], t->at[k], t->half_angle_deg, 4.0f, t->range, t->color, false);
    b->ncoverage = t->nspots;
    sb_set_keys(b, 2, t->eyes, t->targets, SPOT_PATH_SECONDS);
    sb_set_bounds(b, -10.0f, 0.5f, -10.0f, 10.0f, 6.0f, 10.0f);
    return !b->failed;
}

/* spot-coverage (seed 000 section 5.4.1: "The spotlight is framed in the camera so that it
 * is occupying roughly half of the screen. The camera is then moved forward so that it is
 * completely enclosed in the spotlight"): one spot 6 above the floor's centre, straight
 * down, 35 degrees, range 9 (footprint radius 4.2). Hold 0: the eye at (0, 3, 6.6),
 * looking at the cone's middle: the volume covers about half the screen (0.51 at 4:3,
 * 0.38 at 16:9). Hold 1: the eye at (0, 3, 0.4), inside the cone, looking down at the
 * floor: coverage 1 (from hold 0.5 on at 4:3), and every visible pixel is lit. */
bool scene_build_spot_coverage(scene_builder *b, const void *arg)
{
    static const spot_test t = {
        .nspots = 1, .pos = {{0.0f, 6.0f, 0.0f}}, .at = {{0.0f, 0.0f, 0.0f}},
        .half_angle_deg = 35.0f, .range = 9.0f, .color = {3.0f, 2.9f, 2.7f},
        .eyes = {{0.0f, 3.0f, 6.6f}, {0.0f, 3.0f, 0.4f}},
        .targets = {{0.0f, 2.5f, 0.0f}, {0.0f, 0.0f, -0.6f}},
    };
    return spot_build(b, &t);
}

/* two-spots-overlap (seed 000 section 5.4.2: "The two spotlights are viewed from above,
 * looking down. The overlap is centred in the view and initially occupies a small portion
 * of the screen. On zooming in, the overlap increases in size, occupying the entire
 * screen."): two spots 6 above the floor at z = -1.5 and +1.5, straight down, 30 degrees,
 * range 9; their footprints (radius 3.5) overlap in a lens 3.9 long in z and 6.2 wide in
 * x about the origin. The camera looks down at the origin (tilted 4 degrees, so that
 * screen x is world x and the lens lies along the screen's width). Hold 0: from 20 up,
 * each spot's volume covers a small part of the screen (0.09 at 4:3, 0.07 at 16:9).
 * Hold 1: from 2 up, both cover the whole screen (1), and every visible floor pixel is in
 * both footprints. */
bool scene_build_two_spots(scene_builder *b, const void *arg)
{
    static const spot_test t = {
        .nspots = 2, .pos = {{0.0f, 6.0f, -1.5f}, {0.0f, 6.0f, 1.5f}},
        .at = {{0.0f, 0.0f, -1.5f}, {0.0f, 0.0f, 1.5f}},
        .half_angle_deg = 30.0f, .range = 9.0f, .color = {2.4f, 2.3f, 2.1f},
        .eyes = {{0.0f, 20.0f, 1.4f}, {0.0f, 2.0f, 0.14f}},
        .targets = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}},
    };
    return spot_build(b, &t);
}

/* floating-spot (seed 000 section 5.5: "the camera was placed such that a 'floating'
 * spotlight covered the majority of the screen (i.e. the spotlight, while visible, did
 * not actually light any visible pixels)"): a spot hanging 2 above the floor, pointing
 * straight up, 40 degrees, range 2.5: its cone spans y 2 to 4.5 (radius 2.1 at the top),
 * above the floor and under nothing (no ceiling; the back wall is 20 away), so it lights
 * no surface at all. Hold 0: from 14 away, the volume covers a small part of the screen
 * (0.02). Hold 1: the eye at (0, 3.3, 1.8), 1.8 from the axis at the cone's mid-height
 * (where the cone is 1.1 wide), outside it: the volume covers most of the screen (0.75
 * at 4:3, 0.65 at 16:9) and every pixel behind it is unlit floor, wall or background:
 * deferred shading's stencil test then rejects them all. */
bool scene_build_floating_spot(scene_builder *b, const void *arg)
{
    static const spot_test t = {
        .wall = true, .nspots = 1, .pos = {{0.0f, 2.0f, 0.0f}}, .at = {{0.0f, 5.0f, 0.0f}},
        .half_angle_deg = 40.0f, .range = 2.5f, .color = {1.5f, 1.45f, 1.35f},
        .eyes = {{0.0f, 2.5f, 14.0f}, {0.0f, 3.3f, 1.8f}},
        .targets = {{0.0f, 3.0f, 0.0f}, {0.0f, 3.2f, 0.0f}},
    };
    return spot_build(b, &t);
}
