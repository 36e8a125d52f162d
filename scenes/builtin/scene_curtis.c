/* Curtis 2014 (seed 003), section 6 Methodology: "Three scenes of varying geometric
 * complexity were used. The first contained one model [...]. The second scene contained
 * two models which rotate around cardinal axes and two subdivided icosahedrons. The third
 * scene comprised of a hundred spheres and four rotating models." The camera "rotated
 * around a scene for sixty seconds"; 160 lights (experiment 1), or growing by 10 a second
 * to 590 (experiment 2), placed with srand(1337), colour channels at most 0.3, squared
 * distance attenuation.
 *
 * Units, the lights' range and bounds, no floor and no sky: the comment above C_PERIOD. */
#include "scenes/scene_build.h"

#include <math.h>

/* The paper gives no sizes. Units here: 1 world unit = 1 metre, models a few metres
 * across. Under 1/d^2 attenuation a light of colour 0.3 adds less than 1/255 beyond
 * sqrt(0.3 x 255) = 8.7 units, so the manifest's default range, lights.radius 10, cuts off
 * only what an 8-bit image cannot show: it is the radius these scenes are made for. The
 * light bounds hug the models, so that the mean light arriving at a surface point from
 * 160 lights, about n/V x 0.15 (mean colour) x pi x 10 (the integral of cos / d^2 over the
 * half-ball of radius 10), is a clearly visible 0.1 to 0.4 on top of an ambient of 0.05.
 *
 * No floor and no sky: the models float over the clear colour, as the paper's did. */
#define C_PERIOD 60.0f   /* the camera "rotated around a scene for sixty seconds" */

/* The models' and the spheres' maps: a noise "stone" for the models, bevelled checker
 * tiles for the spheres; each with diffuse, gloss and normal maps. */
static void curtis_materials(scene_builder *b, uint32_t *model, uint32_t *tiles)
{
    texture_desc stone = {.width = 256, .height = 256, .pattern = TEXTURE_NOISE, .cells = 4,
                          .seed = 2014, .color_a = {0.55f, 0.5f, 0.45f},
                          .color_b = {0.85f, 0.8f, 0.7f}, .noise = 0.6f, .bump = 3.0f};
    texture_desc checker = {.width = 256, .height = 256, .pattern = TEXTURE_CHECKER, .cells = 8,
                            .color_a = {0.85f, 0.85f, 0.85f}, .color_b = {0.45f, 0.45f, 0.5f},
                            .gloss_a = 0.9f, .gloss_b = 0.4f};
    sb_map_set m = sb_maps(b, &stone, false);
    *model = sb_material_maps(b, &m, 0.6f, 32.0f, 0.0f);
    if (tiles) {
        sb_map_set t = sb_maps(b, &checker, false);
        *tiles = sb_material_maps(b, &t, 0.8f, 48.0f, 0.0f);
    }
}

/* What every Curtis scene ends with: ambient 0.05 and no sky, the light bounds lo..hi,
 * the camera orbiting (0, target_y, 0) at `radius`, `height` above it, once in 60 s, with
 * a 60-degree fovy from 0.1 to zfar. */
static bool curtis_finish(scene_builder *b, const float lo[3], const float hi[3],
                          float target_y, float radius, float height, float zfar)
{
    sm_vec3_make(0.05f, 0.05f, 0.05f, b->s->ambient);
    b->s->sky = false;
    sb_set_bounds(b, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    sb_set_orbit(b, 0.0f, target_y, 0.0f, radius, height, C_PERIOD);
    sb_set_projection(b, 60.0f, 0.1f, zfar);
    return !b->failed;
}

/* curtis-scene1: one model, a (2, 3) torus knot 7 units across (8192 triangles), turning
 * about Y at 0.25 rad/s at the origin. Light bounds: the 10 x 6 x 10 box about it
 * (160 lights: 0.27 per cubic unit; every light within 7.7 of the box's centre, so at
 * radius 10 all of them reach most of the model). The camera orbits at radius 10, 4 above
 * the model's centre, once in 60 s. */
bool scene_build_curtis1(scene_builder *b, const void *arg)
{
    if (!sb_begin(b, 1))
        return false;
    uint32_t model;
    curtis_materials(b, &model, NULL);
    int knot = sb_torus_knot(b, 2, 3, 3.0f, 0.55f, 256, 16);
    scene_object *o = sb_object(b, knot, model, 0.0f, 0.0f, 0.0f, 1.0f);
    o->spin_rate = 0.25f;
    return curtis_finish(b, (const float[3]){-5.0f, -3.0f, -5.0f},
                         (const float[3]){5.0f, 3.0f, 5.0f}, 0.0f, 10.0f, 4.0f, 100.0f);
}

/* The orbit of curtis-scene2, and where its big icosahedron sits on it. */
#define C2_RADIUS 16.0f
#define C2_HEIGHT 4.0f
#define C2_BIG_AT 20.0     /* schedule time (s) at which the camera is nearest the ball */
#define C2_BIG_RADIUS 5.0f
#define C2_BIG_EYE_DISTANCE 5.6f   /* from the eye to the ball's centre at C2_BIG_AT */

/* curtis-scene2: two (3, 2) and (2, 5) torus knots 5 units across (4608 triangles each),
 * at x = -4.5 turning about X and at x = +4.5 turning about Z (0.5 rad/s), and two
 * icospheres of 3 subdivisions (1280 triangles each): a small one (radius 1.5) at
 * (0, 0, 4.5), and a big one (radius 5) that the camera passes close by.
 * Seed 003 section 8.1.2: "during the camera's rotation through Scene 2 there were a few
 * seconds of complete occlusion, as one of the icosahedrons fills the screen". The big
 * ball's centre lies on the line from the eye to the orbit's target at t = 20 s, 5.6
 * from the eye (its surface 0.6 from it; nearer than at any other time): seen from there
 * it fills a cone of asin(5 / 5.6) = 63 degrees half angle, wider than the screen's
 * corners (44 degrees at 4:3, 50 at 16:9, with the 60-degree fovy), and keeps covering
 * the corners while the camera moves on: the screen is entirely covered from 18.6 s to
 * 21.4 s at 4:3 and from 19.0 s to 21.0 s at 16:9 of each 60 s turn (scene_light_coverage
 * of the ball's sphere; tests/unit/test_scene_catalog.c checks 20 s and the ends). The
 * orbit: radius 16, height 4, once in 60 s about the origin. Light bounds 16 x 7 x 16. */
bool scene_build_curtis2(scene_builder *b, const void *arg)
{
    if (!sb_begin(b, 4))
        return false;
    uint32_t model, tiles;
    curtis_materials(b, &model, &tiles);
    int knot_a = sb_torus_knot(b, 3, 2, 2.5f, 0.4f, 192, 12);
    int knot_b = sb_torus_knot(b, 2, 5, 2.5f, 0.35f, 192, 12);
    int small = sb_icosphere(b, 1.5f, 3);
    int big = sb_icosphere(b, C2_BIG_RADIUS, 3);
    scene_object *a = sb_object(b, knot_a, model, -4.5f, 0.0f, 0.0f, 1.0f);
    sm_vec3_make(1.0f, 0.0f, 0.0f, a->spin_axis);
    a->spin_rate = 0.5f;
    scene_object *c = sb_object(b, knot_b, model, 4.5f, 0.0f, 0.0f, 1.0f);
    sm_vec3_make(0.0f, 0.0f, 1.0f, c->spin_axis);
    c->spin_rate = 0.5f;
    sb_object(b, small, tiles, 0.0f, 0.0f, 4.5f, 1.0f);
    /* the eye at C2_BIG_AT (the orbit of scene_make.c: angle 2 pi t / period from +X towards
     * +Z), and the ball's centre on its line of sight */
    double ang = 2.0 * SM_PI * C2_BIG_AT / C_PERIOD;
    double eye[3] = {C2_RADIUS * cos(ang), C2_HEIGHT, C2_RADIUS * sin(ang)};
    double dist = sqrt(eye[0] * eye[0] + eye[1] * eye[1] + eye[2] * eye[2]);
    double f = 1.0 - C2_BIG_EYE_DISTANCE / dist;
    sb_object(b, big, tiles, (float)(eye[0] * f), (float)(eye[1] * f), (float)(eye[2] * f), 1.0f);
    return curtis_finish(b, (const float[3]){-8.0f, -3.0f, -8.0f},
                         (const float[3]){8.0f, 4.0f, 8.0f}, 0.0f, C2_RADIUS, C2_HEIGHT, 100.0f);
}

/* curtis-scene3: a hundred spheres (radius 0.9, 16 x 8: 224 triangles each) on a 10 x 10
 * grid 3 units apart (x and z in [-13.5, 13.5], y = 0), and four (2, 3) torus knots 4 units
 * across (3072 triangles each) 3 units above the grid at (+-6, 3, +-6), turning about Y,
 * X, Z and Y at 0.4 rad/s. Light bounds 30 x 7.5 x 30 about the grid (160 lights: 0.024
 * per cubic unit; 590: 0.087). The orbit: radius 30, 14 above a target 1 above the grid,
 * once in 60 s. */
bool scene_build_curtis3(scene_builder *b, const void *arg)
{
    if (!sb_begin(b, 104))
        return false;
    uint32_t model, tiles;
    curtis_materials(b, &model, &tiles);
    int sphere = sb_sphere(b, 0.9f, 16, 8);
    int knot = sb_torus_knot(b, 2, 3, 2.0f, 0.35f, 128, 12);
    for (int k = 0; k < 100; k++)
        sb_object(b, sphere, tiles, -13.5f + 3.0f * (float)(k % 10), 0.0f,
                  -13.5f + 3.0f * (float)(k / 10), 1.0f);
    static const float axes[4][3] = {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}};
    for (int k = 0; k < 4; k++) {
        scene_object *o = sb_object(b, knot, model, k % 2 ? 6.0f : -6.0f, 3.0f,
                                    k / 2 ? 6.0f : -6.0f, 1.0f);
        sm_vec3_copy(axes[k], o->spin_axis);
        o->spin_rate = 0.4f;
    }
    return curtis_finish(b, (const float[3]){-15.0f, -1.5f, -15.0f},
                         (const float[3]){15.0f, 6.0f, 15.0f}, 1.0f, 30.0f, 14.0f, 200.0f);
}
