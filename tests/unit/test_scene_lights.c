/* Light placement (scenes/lights.h, scenes/scene_place.c): recorded random lights, the overlap
 * radius (formula and a Monte-Carlo check), grid placement, and the scenes' authored
 * lights (placement scene). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scenes/scene.h"

static light_params params(light_placement p, rng_kind k, uint32_t n)
{
    light_params lp = {
        .placement = p,
        .seed = 1337,
        .rng = k,
        .count = {.growth = false, .start = n, .max = n},
        .radius = 1.0f,
        .color_max = 0.3f,
    };
    return lp;
}

// >>recorded random lights

/* The first five lights of "empty" (light bounds x, z in [-50, 50], y in [0, 20];
 * color_max 0.3) for seed 1337, recorded by an independent Python script (not this
 * code): MSVC rand as state = state * 214013 + 2531011 mod 2^32, output (state >> 16) &
 * 0x7fff (checked against srand(1): 41, 18467, 6334); MT19937 with init_genrand
 * (mt[i] = 1812433253 (mt[i-1] ^ mt[i-1] >> 30) + i) and the standard tempering (checked
 * against std::mt19937's 10000th output for seed 5489, 4123659995). Per light: x, y, z,
 * then r, g, b, each u = float(next / max) (max 32767 or 2^32 - 1) as scenes/rng.c
 * converts, position = float(lo + float(u * float(hi - lo))) and colour = float(u *
 * float(0.3)), every step rounded to float32 (struct.pack('f')), printed with 9 digits. */
static const float recorded_msvc[5][2][3] = {
    {{-36.5596466f, 15.8415489f, 4.2100296f}, {0.271727681f, 0.0376567915f, 0.173543513f}},
    {{-25.0480671f, 10.9323406f, -47.5157928f}, {0.0242164396f, 0.0431318097f, 0.196432397f}},
    {{-15.4683037f, 2.63618898f, -38.8607445f}, {0.274410248f, 0.150233462f, 0.176454976f}},
    {{28.8476257f, 6.0328989f, -8.43989182f}, {0.187954351f, 0.088763088f, 6.40888757e-05f}},
    {{-10.612812f, 5.21561337f, -18.7215805f}, {0.0927823782f, 0.00889919791f, 0.220960125f}},
};
static const float recorded_mt[5][2][3] = {
    {{-23.797533f, 11.2105951f, -34.1316032f}, {0.0637762994f, 0.0834379569f, 0.162924215f}},
    {{-4.0683136f, 0.679427862f, -17.8999443f}, {0.0706166327f, 0.155517846f, 0.177633911f}},
    {{-23.8057079f, 6.70053673f, 47.6085281f}, {0.0811445788f, 0.219844371f, 0.0922358483f}},
    {{-38.47258f, 16.0473862f, -11.3724899f}, {0.0285443384f, 0.188550368f, 0.108942062f}},
    {{-37.4942093f, 14.8231106f, 48.3548584f}, {0.0479845926f, 0.132967472f, 0.258794278f}},
};

static void expect_recorded(rng_kind k, const float want[5][2][3])
{
    char err[256];
    light_params lp = params(PLACEMENT_RANDOM, k, 5);
    scene *s = scene_build("empty", &lp, 64, 64, err, sizeof err);
    assert_non_null(s);
    assert_int_equal(s->nlights_total, 5);
    for (int i = 0; i < 5; i++) {
        for (int c = 0; c < 3; c++) {
            if (s->lights[i].position[c] != want[i][0][c] || s->lights[i].color[c] != want[i][1][c])
                fail_msg("%s light %d channel %d: position %.9g (recorded %.9g), colour %.9g "
                         "(recorded %.9g)", rng_kind_name(k), i, c,
                         (double)s->lights[i].position[c], (double)want[i][0][c],
                         (double)s->lights[i].color[c], (double)want[i][1][c]);
        }
        assert_int_equal(s->lights[i].type, LIGHT_POINT);
    }
    scene_destroy(s);
}

static void test_recorded_lights(void **state)
{
    (void)state;
    expect_recorded(RNG_MSVC, recorded_msvc);
    expect_recorded(RNG_MT19937, recorded_mt);
}

// >>overlap radius

static void test_overlap_radius_formula(void **state)
{
    (void)state;
    const double pi = 3.14159265358979323846;
    float lo[3] = {0, 0, 0}, cube[3] = {10, 10, 10}, flat[3] = {10, 0, 20}, line[3] = {0, 0, 10};
    /* 1000 lights in 1000 cubic units, k = 1: each reaches a ball of 1 unit^3 */
    assert_float_equal(lights_overlap_radius(1000, 1.0f, lo, cube), cbrt(3.0 / (4.0 * pi)), 1e-6);
    assert_float_equal(lights_overlap_radius(160, 2.5f, lo, cube),
                       cbrt(3.0 * 2.5 * 1000.0 / (4.0 * pi * 160.0)), 1e-5);
    /* flat: n pi r^2 / A = k */
    assert_float_equal(lights_overlap_radius(100, 2.0f, lo, flat), sqrt(2.0 * 200.0 / (pi * 100.0)),
                       1e-6);
    /* a segment: n 2 r / L = k */
    assert_float_equal(lights_overlap_radius(5, 1.0f, lo, line), 1.0, 1e-6);
    /* nothing to place, no overlap asked, or no box */
    assert_true(lights_overlap_radius(0, 1.0f, lo, cube) == 0.0f);
    assert_true(lights_overlap_radius(10, 0.0f, lo, cube) == 0.0f);
    assert_true(lights_overlap_radius(10, NAN, lo, cube) == 0.0f);
    assert_true(lights_overlap_radius(10, 1.0f, cube, lo) == 0.0f);   /* min > max */
    assert_true(lights_overlap_radius(10, 1.0f, lo, lo) == 0.0f);     /* a point */
}

/* 2000 random lights in "empty"'s 100 x 20 x 100 bounds with overlap 1.5 (radius 3.30):
 * the mean number of lights within the radius of 20000 uniform points at least a radius
 * inside the bounds (where no ball is cut by a face, so the expectation is exactly k)
 * is within 5% of 1.5. The statistical spread of that mean is about 2% (Poisson counts
 * over the points, plus the lights' own placement), and the seeds are fixed. */
static void test_overlap_monte_carlo(void **state)
{
    (void)state;
    char err[256];
    light_params lp = params(PLACEMENT_RANDOM, RNG_PCG32, 2000);
    lp.overlap = 1.5f;
    lp.radius = 99.0f;   /* not used when overlap > 0 */
    scene *s = scene_build("empty", &lp, 64, 64, err, sizeof err);
    assert_non_null(s);
    float r = s->lights[0].radius;
    assert_float_equal(r, lights_overlap_radius(2000, 1.5f, s->light_bounds_min,
                                                s->light_bounds_max), 0.0);
    assert_float_equal(r, cbrt(3.0 * 1.5 * 200000.0 / (4.0 * 3.14159265358979 * 2000.0)), 1e-4);
    rng g;
    rng_seed(&g, RNG_PCG32, 99);
    const int npoints = 20000;
    uint64_t hits = 0;
    for (int p = 0; p < npoints; p++) {
        float q[3];
        for (int c = 0; c < 3; c++) {
            float lo = s->light_bounds_min[c] + r, hi = s->light_bounds_max[c] - r;
            q[c] = lo + rng_unit(&g) * (hi - lo);
        }
        for (uint32_t i = 0; i < s->nlights_total; i++)
            hits += sm_vec3_distance2(q, s->lights[i].position) <= r * r;
    }
    for (uint32_t i = 0; i < s->nlights_total; i++)
        assert_true(s->lights[i].radius == r);
    double mean = (double)hits / npoints;
    if (fabs(mean - 1.5) > 0.05 * 1.5)
        fail_msg("mean lights within r = %.4f, expected 1.5 within 5%%", mean);
    scene_destroy(s);
}

// >>grid

/* Smallest distance between two lights, and whether all lie in the light bounds. */
static double min_pair_distance(const scene *s, bool *inside)
{
    double best = INFINITY;
    *inside = true;
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        for (int c = 0; c < 3; c++)
            *inside = *inside && s->lights[i].position[c] >= s->light_bounds_min[c] &&
                      s->lights[i].position[c] <= s->light_bounds_max[c];
        for (uint32_t j = 0; j < i; j++)
            best = fmin(best, sm_vec3_distance(s->lights[i].position, s->lights[j].position));
    }
    return best;
}

/* 100 lights in "empty" (100 x 20 x 100): a 10 x 10 grid 10 apart in one layer at
 * mid-height (two layers 10 apart would not space them further), cell centres from
 * (-45, 10, -45), row by row; radius 5 (half the spacing) is the largest allowed, and
 * no two spheres overlap. */
static void test_grid_single_layer(void **state)
{
    (void)state;
    char err[512];
    light_params lp = params(PLACEMENT_GRID, RNG_MSVC, 100);
    lp.radius = 5.0f;
    scene *s = scene_build("empty", &lp, 64, 64, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    assert_int_equal(s->nlights_total, 100);
    for (uint32_t i = 0; i < 100; i++) {
        assert_float_equal(s->lights[i].position[0], -45.0f + 10.0f * (float)(i % 10), 1e-4);
        assert_float_equal(s->lights[i].position[1], 10.0f, 1e-4);
        assert_float_equal(s->lights[i].position[2], -45.0f + 10.0f * (float)(i / 10), 1e-4);
        assert_true(s->lights[i].radius == 5.0f);
        assert_int_equal(s->lights[i].type, LIGHT_POINT);
        for (int c = 0; c < 3; c++)
            assert_true(s->lights[i].color[c] >= 0.0f && s->lights[i].color[c] <= 0.3f);
    }
    bool inside;
    double d = min_pair_distance(s, &inside);
    assert_true(inside);
    assert_true(d >= 2.0 * 5.0 - 1e-4);
    /* colours come from the seeded generator: the first is msvc/1337's 1st, 2nd, 3rd */
    rng g;
    rng_seed(&g, RNG_MSVC, 1337);
    for (int c = 0; c < 3; c++)
        assert_true(s->lights[0].color[c] == rng_unit(&g) * 0.3f);
    scene_destroy(s);

    lp.radius = 5.01f;
    assert_null(scene_build("empty", &lp, 64, 64, err, sizeof err));
    assert_string_equal(err, "scene 'empty': grid placement of 100 lights in 10 x 1 x 10 cells "
                             "(x, y, z) of the light bounds puts neighbours 10 apart: radius "
                             "5.01 makes them overlap; the largest radius allowed is 5");
}

/* 1000 lights in the same bounds: more layers space them further apart: 3 layers (6.7
 * apart) of 18 x 19 cells (5.6 x 5.3) beat 1 layer (3.2 apart), 2 (4.3) and 4 (5.0); no
 * two lights closer than the spacing, all in the bounds. */
static void test_grid_layers(void **state)
{
    (void)state;
    char err[512];
    light_params lp = params(PLACEMENT_GRID, RNG_PCG32, 1000);
    lp.radius = 1000.0f;
    assert_null(scene_build("empty", &lp, 64, 64, err, sizeof err));
    double spacing = 0.0;
    assert_non_null(strstr(err, "in 18 x 3 x 19 cells"));
    assert_int_equal(sscanf(strstr(err, "the largest radius allowed is "),
                            "the largest radius allowed is %lf", &spacing), 1);
    assert_float_equal(spacing, 100.0 / 19.0 / 2.0, 1e-5);
    lp.radius = (float)(spacing * 0.9999);   /* the message rounds to 6 digits */
    scene *s = scene_build("empty", &lp, 64, 64, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    bool inside;
    double d = min_pair_distance(s, &inside);
    assert_true(inside);
    assert_true(d >= 2.0 * spacing * (1.0 - 1e-5));
    unsigned layers = 0;
    float seen[8];
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        bool known = false;
        for (unsigned k = 0; k < layers; k++)
            known = known || seen[k] == s->lights[i].position[1];
        if (!known && layers < 8)
            seen[layers++] = s->lights[i].position[1];
    }
    assert_int_equal(layers, 3);
    scene_destroy(s);
}

/* The layout is planned for the schedule's largest count: a growth schedule to 100 has
 * exactly the fixed-100 layout, lights turn on in that order and never move. */
static void test_grid_growth(void **state)
{
    (void)state;
    char err[512];
    light_params fixed = params(PLACEMENT_GRID, RNG_MT19937, 100);
    fixed.radius = 2.0f;
    light_params grow = fixed;
    grow.count = (light_count){.growth = true, .start = 10, .step = 10, .every = 1.0, .max = 100};
    scene *a = scene_build("empty", &fixed, 64, 64, err, sizeof err);
    scene *b = scene_build("empty", &grow, 64, 64, err, sizeof err);
    assert_non_null(a);
    assert_non_null(b);
    assert_memory_equal(a->lights, b->lights, 100 * sizeof *a->lights);
    scene_light before[10];
    memcpy(before, b->lights, sizeof before);
    scene_update(b, 0.0);
    assert_int_equal(b->nlights_active, 10);
    scene_update(b, 5.5);
    assert_int_equal(b->nlights_active, 60);
    assert_memory_equal(before, b->lights, sizeof before);
    scene_destroy(a);
    scene_destroy(b);

    /* overlap with grid: the radius from lights_overlap_radius, then the same check */
    light_params ov = params(PLACEMENT_GRID, RNG_MSVC, 100);
    ov.overlap = 0.05f;
    scene *c = scene_build("empty", &ov, 64, 64, err, sizeof err);
    if (!c)
        fail_msg("%s", err);
    assert_true(c->lights[0].radius ==
                lights_overlap_radius(100, 0.05f, c->light_bounds_min, c->light_bounds_max));
    scene_destroy(c);
    ov.overlap = 1.0f;   /* r = 7.8 > 5: neighbours would overlap */
    assert_null(scene_build("empty", &ov, 64, 64, err, sizeof err));
    assert_non_null(strstr(err, "the largest radius allowed is 5"));
}

// >>authored lights

/* interior: the moon (directional, shadows), 5 omni lights (no shadows), 3 spots
 * (shadows); the count caps them in this order; the run's rng, seed and radius do not
 * change them. */
// >>sizing (lights.sizing)

/* range-from-intensity: each light's range is sqrt(max channel x exposure / cutoff), its
 * colour untouched; intensity-from-range: the range stays, every colour is scaled by
 * cutoff r^2 / (exposure color_max); radius and placement scene change nothing. The
 * expected values are computed here from the lights' own colours, in double. */
static void test_sizing(void **state)
{
    (void)state;
    char err[256];
    light_params lp = params(PLACEMENT_RANDOM, RNG_MSVC, 8);
    lp.radius = 3.0f;
    lp.cutoff = 0.005f;
    scene *a = scene_build("empty", &lp, 64, 64, err, sizeof err);
    scene *b = scene_build("empty", &lp, 64, 64, err, sizeof err);
    assert_non_null(a);
    assert_non_null(b);
    scene_light before[8];
    memcpy(before, a->lights, sizeof before);
    lp.sizing = LIGHT_SIZING_RADIUS;
    assert_true(scene_size_lights(a, &lp, 2.0f, err, sizeof err));
    assert_memory_equal(a->lights, before, sizeof before);
    lp.sizing = LIGHT_SIZING_RANGE_FROM_INTENSITY;
    assert_true(scene_size_lights(a, &lp, 2.0f, err, sizeof err));
    lp.sizing = LIGHT_SIZING_INTENSITY_FROM_RANGE;
    assert_true(scene_size_lights(b, &lp, 2.0f, err, sizeof err));
    for (int i = 0; i < 8; i++) {
        const float *c = before[i].color;
        double m = fmax(c[0], fmax(c[1], c[2]));
        assert_float_equal(a->lights[i].radius, sqrt(m * 2.0 / 0.005), 1e-5 * a->lights[i].radius);
        assert_memory_equal(a->lights[i].color, c, sizeof(sm_vec3));
        assert_float_equal(b->lights[i].radius, 3.0f, 0.0f);
        for (int k = 0; k < 3; k++)
            assert_float_equal(b->lights[i].color[k], c[k] * 0.005 * 9.0 / (2.0 * 0.3),
                               1e-6 * (1.0 + c[k]));
    }
    /* a light at the brightest colour (0.3) meets the cutoff at the range: 0.3 x k x
     * exposure / r^2 = cutoff */
    assert_float_equal(0.3 * (0.005 * 9.0 / (2.0 * 0.3)) * 2.0 / 9.0, 0.005, 1e-12);
    assert_false(scene_size_lights(b, &lp, NAN, err, sizeof err));
    assert_non_null(strstr(err, "lights.sizing"));
    scene_destroy(a);
    scene_destroy(b);

    light_params own = params(PLACEMENT_SCENE, RNG_MSVC, LIGHT_COUNT_ALL);
    own.sizing = LIGHT_SIZING_RANGE_FROM_INTENSITY;
    own.cutoff = 0.005f;
    scene *c = scene_build("interior", &own, 64, 64, err, sizeof err);
    assert_non_null(c);
    float r0 = c->lights[0].radius;
    assert_true(scene_size_lights(c, &own, 2.0f, err, sizeof err));
    assert_float_equal(c->lights[0].radius, r0, 0.0f);
    scene_destroy(c);
}

static void test_scene_placement_interior(void **state)
{
    (void)state;
    char err[256];
    light_params lp = params(PLACEMENT_SCENE, RNG_MSVC, 9);
    scene *s = scene_build("interior", &lp, 64, 64, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    assert_int_equal(s->nlights_total, 9);
    assert_int_equal(s->ncoverage_lights, 0);
    static const light_type types[9] = {LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_POINT, LIGHT_POINT,
                                        LIGHT_POINT, LIGHT_POINT, LIGHT_SPOT, LIGHT_SPOT,
                                        LIGHT_SPOT};
    static const bool shadows[9] = {true, false, false, false, false, false, true, true, true};
    for (int i = 0; i < 9; i++) {
        assert_int_equal(s->lights[i].type, types[i]);
        assert_int_equal(s->lights[i].shadows, shadows[i]);
        assert_float_equal(sm_vec3_norm(s->lights[i].direction), 1.0, 1e-5);
        if (types[i] != LIGHT_DIRECTIONAL)
            assert_true(s->lights[i].radius > 0.0f);
    }
    /* the five omni lights never overlap one another */
    for (int i = 1; i <= 5; i++)
        for (int j = 1; j < i; j++)
            assert_true(sm_vec3_distance(s->lights[i].position, s->lights[j].position) >
                        s->lights[i].radius + s->lights[j].radius);
    /* the two generator spots' floor footprints overlap between the generators */
    const scene_light *a = &s->lights[6], *b = &s->lights[7];
    float foot = a->position[1] * tanf(a->spot_angle);
    assert_true(sm_vec3_distance(a->position, b->position) < 2.0f * foot);

    /* other placement parameters do not apply */
    light_params other = lp;
    other.rng = RNG_PCG32;
    other.seed = 7;
    other.radius = 123.0f;
    other.color_max = 9.0f;
    other.overlap = 2.0f;
    scene *t = scene_build("interior", &other, 64, 64, err, sizeof err);
    assert_non_null(t);
    assert_memory_equal(s->lights, t->lights, 9 * sizeof *s->lights);
    scene_destroy(t);

    /* the count caps them in order; a larger count gives them all */
    light_params four = params(PLACEMENT_SCENE, RNG_MSVC, 4);
    t = scene_build("interior", &four, 64, 64, err, sizeof err);
    assert_non_null(t);
    assert_int_equal(t->nlights_total, 4);
    assert_memory_equal(s->lights, t->lights, 4 * sizeof *s->lights);
    scene_destroy(t);
    light_params grow = params(PLACEMENT_SCENE, RNG_MSVC, 0);
    grow.count = (light_count){.growth = true, .start = 1, .step = 2, .every = 1.0, .max = 500};
    t = scene_build("interior", &grow, 64, 64, err, sizeof err);
    assert_non_null(t);
    assert_int_equal(t->nlights_total, 9);
    assert_int_equal(t->nlights_active, 1);
    scene_update(t, 2.0);
    assert_int_equal(t->nlights_active, 5);
    scene_update(t, 100.0);
    assert_int_equal(t->nlights_active, 9);
    scene_destroy(t);
    scene_destroy(s);
}

static void test_scene_placement_others(void **state)
{
    (void)state;
    char err[256];
    light_params lp = params(PLACEMENT_SCENE, RNG_MSVC, 10);
    /* canyon: the sun, directional, no shadows */
    scene *s = scene_build("canyon", &lp, 64, 64, err, sizeof err);
    assert_non_null(s);
    assert_int_equal(s->nlights_total, 1);
    assert_int_equal(s->lights[0].type, LIGHT_DIRECTIONAL);
    assert_false(s->lights[0].shadows);
    scene_destroy(s);
    /* the coverage scenes record their spots */
    static const struct {
        const char *name;
        uint32_t n;
    } cov[] = {{"spot-coverage", 1}, {"two-spots-overlap", 2}, {"floating-spot", 1}};
    for (size_t i = 0; i < sizeof cov / sizeof cov[0]; i++) {
        s = scene_build(cov[i].name, &lp, 64, 64, err, sizeof err);
        assert_non_null(s);
        assert_int_equal(s->nlights_total, cov[i].n);
        assert_int_equal(s->ncoverage_lights, cov[i].n);
        for (uint32_t k = 0; k < cov[i].n; k++)
            assert_int_equal(s->lights[k].type, LIGHT_SPOT);
        scene_destroy(s);
        /* with random lights nothing is recorded */
        light_params rnd = params(PLACEMENT_RANDOM, RNG_MSVC, 3);
        s = scene_build(cov[i].name, &rnd, 64, 64, err, sizeof err);
        assert_non_null(s);
        assert_int_equal(s->ncoverage_lights, 0);
        scene_destroy(s);
    }
    /* scenes without authored lights */
    static const char *const none[] = {"empty", "shapes", "curtis-scene1", "curtis-scene2",
                                       "curtis-scene3"};
    for (size_t i = 0; i < sizeof none / sizeof none[0]; i++) {
        assert_null(scene_build(none[i], &lp, 64, 64, err, sizeof err));
        char want[128];
        snprintf(want, sizeof want, "scene '%s' has no authored lights", none[i]);
        assert_string_equal(err, want);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_recorded_lights),
        cmocka_unit_test(test_overlap_radius_formula),
        cmocka_unit_test(test_overlap_monte_carlo),
        cmocka_unit_test(test_grid_single_layer),
        cmocka_unit_test(test_grid_layers),
        cmocka_unit_test(test_grid_growth),
        cmocka_unit_test(test_sizing),
        cmocka_unit_test(test_scene_placement_interior),
        cmocka_unit_test(test_scene_placement_others),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
