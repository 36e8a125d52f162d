/* Cameras and light coverage (scenes/scene.h): scene_set_camera's checks and overrides,
 * scripted paths and holds, deterministic posing, and scene_light_coverage against
 * closed forms and the coverage scenes' two ends. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/scene.h"

#define PI 3.14159265358979323846

static scene *build(const char *name, light_placement p, uint32_t n, int w, int h)
{
    char err[256];
    light_params lp = {.placement = p, .seed = 1337, .rng = RNG_MSVC,
                       .count = {.start = n, .max = n}, .radius = 5.0f, .color_max = 0.3f};
    scene *s = scene_build(name, &lp, w, h, err, sizeof err);
    if (!s)
        fail_msg("scene_build(%s): %s", name, err);
    return s;
}

static bool mat_finite(const sm_mat4 m)
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            if (!isfinite(m[c][r]))
                return false;
    return true;
}

// >>scene_set_camera

typedef struct bad_camera {
    const char *scene;
    camera_params cp;          /* NAN where not set: filled by the test */
    const char *want;
} bad_camera;

static void test_set_camera_errors(void **state)
{
    (void)state;
    const float N = NAN;
    /* camera_params fields: radius, height, period, target, znear, zfar, hold */
    const bad_camera cases[] = {
        {"shapes", {N, N, N, {N, N, N}, -1.0f, N, N},
         "camera.near: expected a finite number > 0, found -1"},
        {"shapes", {N, N, N, {N, N, N}, 0.0f, N, N},
         "camera.near: expected a finite number > 0, found 0"},
        {"shapes", {N, N, N, {N, N, N}, N, 0.1f, N},
         "camera.far: expected a finite number > near (0.5), found 0.1"},
        {"shapes", {N, N, N, {N, N, N}, 2.0f, 2.0f, N},
         "camera.far: expected a finite number > near (2), found 2"},
        {"shapes", {N, N, N, {N, N, N}, N, INFINITY, N},
         "camera.far: expected a finite number > near (0.5), found inf"},
        {"shapes", {N, N, N, {N, N, N}, 300.0f, N, N},
         "camera.near: 300 is not below the scene's far plane (200)"},
        {"shapes", {0.0f, N, N, {N, N, N}, N, N, N},
         "camera.radius: expected a finite number > 0, found 0"},
        {"shapes", {-3.0f, N, N, {N, N, N}, N, N, N},
         "camera.radius: expected a finite number > 0, found -3"},
        {"shapes", {N, INFINITY, N, {N, N, N}, N, N, N},
         "camera.height: expected a finite number, found inf"},
        {"shapes", {N, N, 0.0f, {N, N, N}, N, N, N},
         "camera.period: expected a finite number of seconds > 0, found 0"},
        {"shapes", {N, N, N, {1.0f, N, 0.0f}, N, N, N},
         "camera.target: expected three finite numbers, found [1, nan, 0]"},
        {"shapes", {N, N, N, {N, N, N}, N, N, 1.5f},
         "camera.hold: expected a path fraction in [0, 1], found 1.5"},
        {"shapes", {N, N, N, {N, N, N}, N, N, -0.25f},
         "camera.hold: expected a path fraction in [0, 1], found -0.25"},
        {"spot-coverage", {2.0f, N, N, {N, N, N}, N, N, N},
         "camera.radius: scene 'spot-coverage' follows a scripted path, which has no orbit "
         "radius (period, hold, near and far apply)"},
        {"floating-spot", {N, N, N, {0.0f, 0.0f, 0.0f}, N, N, N},
         "camera.target: scene 'floating-spot' follows a scripted path, which has no orbit "
         "target (period, hold, near and far apply)"},
        {"spot-coverage", {N, N, -1.0f, {N, N, N}, N, N, N},
         "camera.period: expected a finite number of seconds > 0, found -1"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        scene *s = build(cases[i].scene, PLACEMENT_NONE, 0, 64, 48);
        scene_update(s, 3.0);
        scene before = *s;
        char err[256] = "";
        assert_false(scene_set_camera(s, &cases[i].cp, err, sizeof err));
        if (strcmp(err, cases[i].want) != 0)
            fail_msg("case %zu: got \"%s\", want \"%s\"", i, err, cases[i].want);
        /* nothing changed */
        assert_memory_equal(&before.cam, &s->cam, sizeof s->cam);
        assert_memory_equal(before.viewproj, s->viewproj, sizeof s->viewproj);
        assert_true(before.orbit_radius == s->orbit_radius && before.znear == s->znear &&
                    before.zfar == s->zfar && isnan(s->hold));
        scene_destroy(s);
    }
    /* an eye that meets the target: a radius lost in the rounding of a far target */
    scene *s = build("shapes", PLACEMENT_NONE, 0, 64, 48);
    camera_params cp;
    camera_params_init(&cp);
    cp.radius = 1e-3f;
    cp.height = 0.0f;
    sm_vec3_make(1e7f, 0.0f, 0.0f, cp.target);
    char err[256];
    assert_false(scene_set_camera(s, &cp, err, sizeof err));
    assert_non_null(strstr(err, "camera: the eye"));
    assert_non_null(strstr(err, "meets the target"));
    scene_destroy(s);
}

/* Orbit overrides: radius, height, target and period move the eye as the orbit's formula
 * says (angle 2 pi t / period from +X towards +Z); hold fixes the angle for every t;
 * znear and zfar reach the camera. All NAN changes nothing. */
static void test_set_camera_orbit(void **state)
{
    (void)state;
    char err[256];
    scene *s = build("shapes", PLACEMENT_NONE, 0, 64, 48);
    scene ref = *s;
    camera_params cp;
    camera_params_init(&cp);
    assert_true(scene_set_camera(s, &cp, err, sizeof err));
    assert_memory_equal(&ref.cam, &s->cam, sizeof s->cam);
    cp.radius = 20.0f;
    cp.height = 3.0f;
    cp.period = 10.0f;
    sm_vec3_make(1.0f, 2.0f, 3.0f, cp.target);
    cp.znear = 0.25f;
    cp.zfar = 500.0f;
    assert_true(scene_set_camera(s, &cp, err, sizeof err));
    scene_update(s, 2.5);   /* a quarter turn */
    assert_float_equal(s->cam.eye[0], 1.0, 1e-4);
    assert_float_equal(s->cam.eye[1], 5.0, 1e-5);
    assert_float_equal(s->cam.eye[2], 23.0, 1e-4);
    assert_float_equal(s->cam.target[0], 1.0, 0.0);
    assert_float_equal(s->cam.znear, 0.25, 0.0);
    assert_float_equal(s->cam.zfar, 500.0, 0.0);
    cp.hold = 0.5f;
    assert_true(scene_set_camera(s, &cp, err, sizeof err));
    for (double t = 0.0; t < 30.0; t += 3.7) {
        scene_update(s, t);
        assert_float_equal(s->cam.eye[0], 1.0 - 20.0, 1e-4);
        assert_float_equal(s->cam.eye[2], 3.0, 1e-4);
    }
    scene_destroy(s);
}

/* Scripted paths: hold 0 and 1 are the first and last key poses exactly; without hold the
 * camera goes from the first (t = 0) to the last (t = period) and stays there. */
static void test_scripted_path(void **state)
{
    (void)state;
    static const char *const names[] = {"spot-coverage", "two-spots-overlap", "floating-spot"};
    char err[256];
    for (size_t i = 0; i < 3; i++) {
        scene *s = build(names[i], PLACEMENT_SCENE, 10, 320, 240);
        assert_int_equal(s->path, CAMERA_SCRIPTED);
        assert_true(s->nkeys >= 2);
        uint32_t last = s->nkeys - 1;
        float period = s->orbit_period;
        assert_true(period > 0.0f);
        /* travelling */
        scene_update(s, 0.0);
        assert_memory_equal(s->cam.eye, s->key_eye[0], sizeof(sm_vec3));
        assert_memory_equal(s->cam.target, s->key_target[0], sizeof(sm_vec3));
        scene_update(s, period);
        assert_memory_equal(s->cam.eye, s->key_eye[last], sizeof(sm_vec3));
        scene_update(s, 10.0 * period);
        assert_memory_equal(s->cam.eye, s->key_eye[last], sizeof(sm_vec3));
        assert_memory_equal(s->cam.target, s->key_target[last], sizeof(sm_vec3));
        if (s->nkeys == 2) {
            scene_update(s, period / 2.0);
            for (int c = 0; c < 3; c++)
                assert_float_equal(s->cam.eye[c], (s->key_eye[0][c] + s->key_eye[1][c]) / 2.0,
                                   1e-5);
        }
        /* held */
        camera_params cp;
        camera_params_init(&cp);
        cp.hold = 0.0f;
        assert_true(scene_set_camera(s, &cp, err, sizeof err));
        for (double t = 0.0; t < 3.0 * period; t += period / 3.0) {
            scene_update(s, t);
            assert_memory_equal(s->cam.eye, s->key_eye[0], sizeof(sm_vec3));
            assert_memory_equal(s->cam.target, s->key_target[0], sizeof(sm_vec3));
        }
        cp.hold = 1.0f;
        assert_true(scene_set_camera(s, &cp, err, sizeof err));
        assert_memory_equal(s->cam.eye, s->key_eye[last], sizeof(sm_vec3));   /* re-posed */
        scene_update(s, 0.0);
        assert_memory_equal(s->cam.eye, s->key_eye[last], sizeof(sm_vec3));
        assert_memory_equal(s->cam.target, s->key_target[last], sizeof(sm_vec3));
        /* a shorter period moves it faster */
        camera_params_init(&cp);
        cp.period = period / 4.0f;
        cp.hold = NAN;
        assert_true(scene_set_camera(s, &cp, err, sizeof err));
        assert_true(isnan(s->hold) == false);   /* hold 1 stays: NAN keeps the scene's */
        scene_destroy(s);
        s = build(names[i], PLACEMENT_SCENE, 10, 320, 240);
        assert_true(scene_set_camera(s, &cp, err, sizeof err));
        scene_update(s, period / 4.0);
        assert_memory_equal(s->cam.eye, s->key_eye[last], sizeof(sm_vec3));
        assert_true(mat_finite(s->viewproj));
        scene_destroy(s);
    }
}

/* Two scene_update(t) calls at the same t pose everything bit-identically, whatever came
 * between: the pose is a function of t alone. */
static void test_update_deterministic(void **state)
{
    (void)state;
    static const double times[] = {0.0, 0.1, 7.25, 19.95, 59.999, 1234.5};
    for (size_t i = 0; i < scene_catalog_count(); i++) {
        const char *name = scene_catalog_at(i)->name;
        scene *s = build(name, PLACEMENT_RANDOM, 8, 160, 120);
        for (size_t k = 0; k < sizeof times / sizeof times[0]; k++) {
            scene_update(s, times[k]);
            scene a = *s;
            scene_object *objs = malloc((s->nobjects ? s->nobjects : 1) * sizeof *objs);
            memcpy(objs, s->objects, s->nobjects * sizeof *objs);
            scene_update(s, times[k] + 13.7);
            scene_update(s, times[k]);
            assert_memory_equal(&a.cam, &s->cam, sizeof s->cam);
            assert_memory_equal(a.view, s->view, sizeof s->view);
            assert_memory_equal(a.proj, s->proj, sizeof s->proj);
            assert_memory_equal(a.viewproj, s->viewproj, sizeof s->viewproj);
            assert_int_equal(a.nlights_active, s->nlights_active);
            if (s->nobjects)
                assert_memory_equal(objs, s->objects, s->nobjects * sizeof *objs);
            free(objs);
        }
        scene_destroy(s);
    }
}

// >>coverage

/* "empty" with the given lights, its camera held at (d, 0, 0) looking at the origin. */
static scene *coverage_scene(int w, int h, float d, const scene_light *lights, uint32_t n)
{
    char err[256];
    scene *s = build("empty", PLACEMENT_NONE, 0, w, h);
    s->lights = calloc(n, sizeof *s->lights);
    memcpy(s->lights, lights, n * sizeof *s->lights);
    s->nlights_total = n;
    s->count = (light_count){.start = n, .max = n};
    camera_params cp;
    camera_params_init(&cp);
    cp.radius = d;
    cp.height = 0.0f;
    cp.hold = 0.0f;
    sm_vec3_zero(cp.target);
    if (!scene_set_camera(s, &cp, err, sizeof err))
        fail_msg("%s", err);
    scene_update(s, 0.0);
    return s;
}

/* The fraction of a w x h screen (vertical field of view fovy) inside a circle about its
 * centre of angular radius a (a cone of view rays about the view axis), when the circle
 * is within the screen: pi tan^2 a / (4 aspect tan^2 (fovy / 2)). */
static double disc_fraction(double a, double fovy, int w, int h)
{
    double t = tan(fovy / 2.0);
    return PI * tan(a) * tan(a) / (4.0 * ((double)w / h) * t * t);
}

static void test_coverage_point(void **state)
{
    (void)state;
    scene_light l = {.type = LIGHT_POINT, .radius = 2.0f};
    /* a ball of radius 2 at distance 5 on the view axis: a disc of asin(0.4) */
    const int sizes[3][2] = {{128, 128}, {1600, 1200}, {97, 61}};
    for (int k = 0; k < 3; k++) {
        scene *s = coverage_scene(sizes[k][0], sizes[k][1], 5.0f, &l, 1);
        double want = disc_fraction(asin(0.4), s->cam.fovy, sizes[k][0], sizes[k][1]);
        double got = scene_light_coverage(s, 0);
        /* within 2%: the pixel grid's staircase along the disc's edge (the smallest disc,
         * at 97 x 61, is 46 pixels across) */
        if (fabs(got - want) > 0.02 * want)
            fail_msg("%dx%d: coverage %.5f, disc %.5f", sizes[k][0], sizes[k][1], got, want);
        scene_destroy(s);
    }
    /* the eye inside the ball: every ray starts in it */
    scene_light big = {.type = LIGHT_POINT, .radius = 12.0f};
    scene *s = coverage_scene(64, 48, 10.0f, &big, 1);
    assert_true(scene_light_coverage(s, 0) == 1.0);
    scene_destroy(s);
    /* behind the camera (the eye at (10, 0, 0) looks towards -X) */
    scene_light behind = {.type = LIGHT_POINT, .position = {14.0f, 0.0f, 0.0f}, .radius = 3.0f};
    s = coverage_scene(64, 48, 10.0f, &behind, 1);
    assert_true(scene_light_coverage(s, 0) == 0.0);
    /* out of range, zero radius, directional */
    assert_true(scene_light_coverage(s, 1) == 0.0);
    assert_true(scene_light_coverage(NULL, 0) == 0.0);
    s->lights[0].radius = 0.0f;
    s->lights[0].position[0] = 0.0f;
    assert_true(scene_light_coverage(s, 0) == 0.0);
    s->lights[0].type = LIGHT_DIRECTIONAL;
    assert_true(scene_light_coverage(s, 0) == 1.0);
    scene_destroy(s);
}

static void test_coverage_spot(void **state)
{
    (void)state;
    /* seen from 5 behind its apex along its axis, a cone of 30 degrees and range 10 fills
     * the disc of its rim: tan a = 10 tan 30 / 15 */
    scene_light l = {.type = LIGHT_SPOT, .position = {5.0f, 0.0f, 0.0f},
                     .direction = {-1.0f, 0.0f, 0.0f}, .radius = 10.0f,
                     .spot_angle = (float)(PI / 6.0)};
    scene *s = coverage_scene(128, 128, 10.0f, &l, 1);
    double want = disc_fraction(atan(10.0 * tan(PI / 6.0) / 15.0), s->cam.fovy, 128, 128);
    double got = scene_light_coverage(s, 0);
    if (fabs(got - want) > 0.02 * want)
        fail_msg("cone from behind: coverage %.5f, disc %.5f", got, want);
    /* pointing at the eye from 15 away: its cap (radius 5.77) is 5 in front of the eye
     * and wider than the screen's corners: all of it */
    s->lights[0].position[0] = -5.0f;
    s->lights[0].direction[0] = 1.0f;
    double facing = scene_light_coverage(s, 0);
    assert_true(facing > 0.99);
    /* behind the eye, pointing away: nothing */
    s->lights[0].position[0] = 12.0f;
    s->lights[0].direction[0] = 1.0f;
    assert_true(scene_light_coverage(s, 0) == 0.0);
    /* the eye inside the cone */
    s->lights[0].position[0] = 15.0f;
    s->lights[0].direction[0] = -1.0f;
    assert_true(scene_light_coverage(s, 0) == 1.0);
    /* the plane cap, not a sphere: the eye 9.9 along the axis and 5.5 off it is inside
     * the cone capped by the plane at 10 (radius 5.77 there), though 11.3 from the apex */
    s->lights[0].position[0] = 10.0f - 9.9f;
    s->lights[0].position[2] = 5.5f;
    s->lights[0].direction[0] = 1.0f;
    assert_true(scene_light_coverage(s, 0) == 1.0);
    /* a zero direction counts as -Y, as in the renderers: a cone hanging in front of
     * the eye */
    sm_vec3_make(6.0f, 1.0f, 0.0f, s->lights[0].position);
    sm_vec3_make(0.0f, -1.0f, 0.0f, s->lights[0].direction);
    double down = scene_light_coverage(s, 0);
    assert_true(down > 0.05 && down < 0.95);
    sm_vec3_zero(s->lights[0].direction);
    assert_true(scene_light_coverage(s, 0) == down);
    scene_destroy(s);
}

/* The coverage scenes at their two ends (320 x 240): spot-coverage from about half the
 * screen to all of it; two-spots-overlap from a small part to all, both spots; the floating
 * spot covering most of the screen at hold 1. */
static void test_coverage_scenes(void **state)
{
    (void)state;
    char err[256];
    static const struct {
        const char *name;
        double lo0, hi0, lo1, hi1;   /* coverage range at hold 0 and at hold 1 */
    } cases[] = {
        {"spot-coverage", 0.35, 0.7, 1.0, 1.0},
        {"two-spots-overlap", 0.02, 0.2, 1.0, 1.0},
        {"floating-spot", 0.0, 0.1, 0.5, 0.95},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        scene *s = build(cases[i].name, PLACEMENT_SCENE, 10, 320, 240);
        assert_true(s->ncoverage_lights >= 1);
        camera_params cp;
        camera_params_init(&cp);
        for (int h = 0; h <= 1; h++) {
            cp.hold = (float)h;
            assert_true(scene_set_camera(s, &cp, err, sizeof err));
            double lo = h ? cases[i].lo1 : cases[i].lo0, hi = h ? cases[i].hi1 : cases[i].hi0;
            for (uint32_t k = 0; k < s->ncoverage_lights; k++) {
                double c = scene_light_coverage(s, k);
                if (!(c >= lo && c <= hi))
                    fail_msg("%s hold %d light %u: coverage %.4f, expected [%g, %g]",
                             cases[i].name, h, k, c, lo, hi);
            }
        }
        scene_destroy(s);
    }
}

/* A file camera's planes (scene_fit_planes): the file's where they hold the scene, the
 * bounds' depths with the margin where they do not, far / near at most 1e4 or what
 * clustered.slices' default cuts into 1000 slices. M = SCENE_PLANES_MARGIN. */
static void test_fit_planes(void **state)
{
    (void)state;
    const float M = SCENE_PLANES_MARGIN, wide = sqrtf(3.0f);   /* 60 degrees */
    float out[2];
    /* the file's 0.05 to 50 hold a scene 5 to 10 in front: fitted inside them */
    scene_fit_planes(0.05f, 50.0f, 5.0f, 10.0f, wide, 20.0f, out);
    assert_true(out[0] == 5.0f / M && out[1] == 10.0f * M);
    /* the file's 6 to 8 cut into it: kept, as the file asks */
    scene_fit_planes(6.0f, 8.0f, 5.0f, 10.0f, wide, 20.0f, out);
    assert_true(out[0] == 6.0f && out[1] == 8.0f);
    /* no planes (0), glTF's infinite far: the fitted ones */
    scene_fit_planes(0.0f, INFINITY, 5.0f, 10.0f, wide, 20.0f, out);
    assert_true(out[0] == 5.0f / M && out[1] == 10.0f * M);
    scene_fit_planes(0.0f, 0.0f, 5.0f, 10.0f, wide, 20.0f, out);
    assert_true(out[0] == 5.0f / M && out[1] == 10.0f * M);
    /* planes that hold none of the scene (all beyond it, all before it): the fitted ones */
    scene_fit_planes(100.0f, 200.0f, 5.0f, 10.0f, wide, 20.0f, out);
    assert_true(out[0] == 5.0f / M && out[1] == 10.0f * M);
    scene_fit_planes(0.01f, 2.0f, 5.0f, 10.0f, wide, 20.0f, out);
    assert_true(out[0] == 5.0f / M && out[1] == 10.0f * M);
    /* the eye among the bounds: near = far / 1e4, the file's 1e-4 raised */
    scene_fit_planes(1e-4f, 1e6f, -3.0f, 10.0f, wide, 20.0f, out);
    assert_true(out[1] == 10.0f * M && out[0] == (float)((double)(10.0f * M) / 1e4));
    /* ... a file near beyond far / 1e4 is kept */
    scene_fit_planes(0.5f, 1e6f, -3.0f, 10.0f, wide, 20.0f, out);
    assert_true(out[0] == 0.5f && out[1] == 10.0f * M);
    /* ... and at a narrow field of view (proj11 20: 5.7 degrees), where 1e4 would make
     * 2216 slices of clustered.slices 24, the ratio of 1000 of them */
    scene_fit_planes(1e-4f, 1e6f, -3.0f, 10.0f, 20.0f, 20.0f, out);
    uint32_t k = scene_depth_slices(20.0, out[0], out[1], SCENE_PLANES_SLICES_Y, NULL);
    assert_true(out[1] == 10.0f * M && k >= 999 && k <= 1001);
    assert_int_equal(scene_depth_slices(20.0, (float)(out[1] / 1e4), out[1], 24, NULL), 2216);
    /* nothing in front: the file's planes, else the orbit's 1e-3 and 10 x the size */
    scene_fit_planes(0.05f, 50.0f, -10.0f, -5.0f, wide, 20.0f, out);
    assert_true(out[0] == 0.05f && out[1] == 50.0f);
    scene_fit_planes(0.0f, 0.0f, -10.0f, -5.0f, wide, 20.0f, out);
    assert_true(out[0] == 20.0f * 1e-3f && out[1] == 200.0f);
    /* depths past float's range are no fit: the file's planes */
    scene_fit_planes(0.05f, 50.0f, 1.0f, INFINITY, wide, 20.0f, out);
    assert_true(out[0] == 0.05f && out[1] == 50.0f);
    scene_fit_planes(0.05f, 50.0f, NAN, 10.0f, wide, 20.0f, out);
    assert_true(out[0] == 0.05f && out[1] == 50.0f);
}

/* Clustered's depth slices (scene_depth_slices): 2CylinderEngine's camera (yfov 0.3143)
 * with its own planes once fit, and with the fitted ones (a run's meta.yaml); the
 * extremes manifests' near 0.01 and far 1e6 at 60 degrees. */
static void test_depth_slices(void **state)
{
    (void)state;
    double p = 1.0f / tanf(0.5f * 0.3143463730812073f), r;
    assert_int_equal(scene_depth_slices(p, 0.0011960997944697738f, 23921.998046875f, 24, &r),
                     1282);
    assert_true(fabs(r - (1.0 + 2.0 / (p * 24))) == 0.0);
    assert_int_equal(scene_depth_slices(p, 27.971445083618164f, 49.921260833740234f, 24, NULL),
                     45);
    assert_int_equal(scene_depth_slices(sqrtf(3.0f), 0.01f, 1e6f, 24, NULL), 393);
    assert_int_equal(scene_depth_slices(sqrtf(3.0f), 0.01f, 1e6f, 64, NULL), 1031);
    assert_int_equal(scene_depth_slices(sqrtf(3.0f), 1.0f, 1.0f, 24, NULL), 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_set_camera_errors),
        cmocka_unit_test(test_set_camera_orbit),
        cmocka_unit_test(test_scripted_path),
        cmocka_unit_test(test_update_deterministic),
        cmocka_unit_test(test_coverage_point),
        cmocka_unit_test(test_coverage_spot),
        cmocka_unit_test(test_coverage_scenes),
        cmocka_unit_test(test_fit_planes),
        cmocka_unit_test(test_depth_slices),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
