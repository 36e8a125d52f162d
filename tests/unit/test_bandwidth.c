/* Seed 002's bandwidth model (results/bandwidth.h, equations 4-7 of its section "MRT
 * Configuration and Bandwidth") and the per-frame G-buffer traffic built on it
 * (renderers/deferred/deferred.h, deferred_gbuffer_traffic; the visibility ids' terms,
 * visibility_id_traffic). No GL context: the layout code and
 * the traffic are arithmetic. Every expected number is worked out by hand beside it. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/unit/assert_near.h"

#include <math.h>
#include <string.h>

#include "renderers/deferred/deferred.h"
#include "renderers/visibility/visibility.h"
#include "results/bandwidth.h"


/* Table 1's practical values as the worked example enters them (bytes): 1024 x 768,
 * depth term 8 (the example writes 8 x (3 + 1.5)), back buffer 4, overdraw 3, sorting
 * 1.5, textures 3 bytes with 2 lookups building and 4 shading, 8 shading passes,
 * C_Geometry 16 x 10^6 bytes; n_MRT and MRT_BPP as given. */
static s002_vars practical(double n_mrt, double mrt_bytes)
{
    return (s002_vars){.w = 1024, .h = 768, .z_bytes = 8, .bb_bytes = 4, .overdraw = 3,
                       .sorting = 1.5, .t_bytes = 3, .t_building = 2, .t_shading = 4, .n = 8,
                       .n_mrt = n_mrt, .mrt_bytes = mrt_bytes, .c_geometry = 16e6};
}

/* >>equations 4, 5 and 6 */

static void test_equations_4_5_practical_example(void **state)
{
    (void)state;
    s002_vars v = practical(3, 8);   /* three 64-bit targets */
    /* eq. 4: 786432 x [8 x 4.5 + 3 x 2 x 1.5 + 3 x 8 x 1.5] + 16e6
     *      = 786432 x (36 + 9 + 36) + 16e6 = 63,700,992 + 16,000,000 */
    assert_near(s002_building_bytes(&v), 79700992.0, 1e-6);
    /* eq. 5: 786432 x 8 x [2 x 4 + 4 x 3 + 3 x 8] = 786432 x 8 x 44 */
    assert_near(s002_shading_bytes(&v), 276824064.0, 1e-6);
    /* eq. 6 at 60 fps: (79,700,992 + 276,824,064) x 60 = 356,525,056 x 60 */
    assert_near(s002_bandwidth(&v, 60), 21391503360.0, 1e-3);
}

/* The paper regroups eq. 6 as W H [MRT n_MRT (1.5 + 8) + 205] + C: the constant part of
 * the bracket is 8 x 4.5 + 3 x 2 x 1.5 + 8 x (2 x 4 + 4 x 3) = 36 + 9 + 160 = 205. */
static void test_equation_6_regrouped(void **state)
{
    (void)state;
    for (int n_mrt = 1; n_mrt <= 4; n_mrt++)
        for (double mrt = 4; mrt <= 16; mrt *= 2) {
            s002_vars v = practical(n_mrt, mrt);
            double wh = 1024.0 * 768.0;
            double bracket = (s002_bandwidth(&v, 1) - v.c_geometry) / wh;
            assert_near(bracket, mrt * n_mrt * 9.5 + 205.0, 1e-9);
        }
}

/* >>equation 7 and Table 2 */

static void test_table_2_is_equation_7(void **state)
{
    (void)state;
    /* Table 2, GB/s: rows n_MRT = 2, 3, 4; columns MRT_BPP = 32, 64, 128 bpp (4, 8, 16 B) */
    static const double table2[3][3] = {{14, 18, 26}, {16, 22, 34}, {18, 26, 42}};
    static const double bytes[3] = {4, 8, 16};
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            assert_near(s002_bandwidth_approx_gbps(r + 2, bytes[c]), table2[r][c], 1e-12);
}

/* "A gross approximation": equation 6 exactly, in 10^9 bytes/s, against Table 2.
 * Hand-worked extremes: n_MRT = 2, 4 B: (786432 x 281 + 16e6) x 60 = 14.219 GB/s (+1.6%);
 * n_MRT = 4, 16 B: (786432 x 813 + 16e6) x 60 = 39.322 GB/s (-6.4%). All nine within 7%. */
static void test_equation_7_approximates_6(void **state)
{
    (void)state;
    s002_vars v = practical(2, 4);
    assert_near(s002_bandwidth(&v, 60) / 1e9, 14.21924352, 1e-9);
    v = practical(4, 16);
    assert_near(s002_bandwidth(&v, 60) / 1e9, 39.32215296, 1e-9);
    for (int n_mrt = 2; n_mrt <= 4; n_mrt++)
        for (double mrt = 4; mrt <= 16; mrt *= 2) {
            v = practical(n_mrt, mrt);
            double exact = s002_bandwidth(&v, 60) / 1e9;
            double approx = s002_bandwidth_approx_gbps(n_mrt, mrt);
            assert_true(fabs(exact - approx) / approx < 0.07);
        }
}

/* >>the MRT terms the project measures */

static void test_mrt_terms_are_those_of_4_and_5(void **state)
{
    (void)state;
    s002_vars v = practical(3, 8), none = v;
    none.n_mrt = 0;
    /* eq. 4's MRT term: 3 x 8 x 786432 x 1.5 = 28,311,552 */
    double w = s002_mrt_write_bytes(v.n_mrt * v.mrt_bytes, v.w * v.h * v.sorting);
    assert_near(w, 28311552.0, 1e-6);
    assert_near(w, s002_building_bytes(&v) - s002_building_bytes(&none), 1e-6);
    /* eq. 5's MRT term: 3 x 8 x 786432 x 8 = 150,994,944 */
    double r = s002_mrt_read_bytes(v.n_mrt * v.mrt_bytes, v.w * v.h * v.n);
    assert_near(r, 150994944.0, 1e-6);
    assert_near(r, s002_shading_bytes(&v) - s002_shading_bytes(&none), 1e-6);
}

/* >>the layouts' bytes per pixel (renderers/deferred/gbuffer_layout.c) */

static unsigned bpp(const char *kind, gbuffer_preset p, gbuffer_position pos, bool cd)
{
    renderer_options o;
    memset(&o, 0, sizeof o);
    o.gbuffer = p;
    o.gbuffer_position = pos;
    o.clustered_deferred = cd;
    /* no scene: nothing needs gloss or emissive */
    if (!renderer_uses_gbuffer(kind, &o))
        return 0;
    return deferred_gbuffer_bytes_per_pixel(&o, deferred_needs_of(NULL));
}

static void test_layout_bytes_per_pixel(void **state)
{
    (void)state;
    /* compact is seed 002's optimised 96 bits: RG16F 4 + R16F 2 + RGBA8 4 + RG8 2 = 12 */
    assert_int_equal(bpp("deferred", GBUFFER_COMPACT, GBUFFER_POSITION_PRESET, false), 12);
    /* compact with the position rebuilt from depth: RGBA8 4 + RG8 2 = 6 */
    assert_int_equal(bpp("deferred", GBUFFER_COMPACT, GBUFFER_POSITION_DEPTH, false), 6);
    /* fat (seed 000): three RGBA16F = 24; curtis without gloss or emissive: two = 16 */
    assert_int_equal(bpp("tiled-deferred", GBUFFER_FAT, GBUFFER_POSITION_PRESET, false), 24);
    assert_int_equal(bpp("deferred", GBUFFER_CURTIS, GBUFFER_POSITION_PRESET, false), 16);
    /* reference: position+shininess, normal+gloss, diffuse in RGBA32F = 48 */
    assert_int_equal(bpp("clustered", GBUFFER_REFERENCE, GBUFFER_POSITION_PRESET, true), 48);
    /* no G-buffer: forward renderers, clustered shading forward */
    assert_int_equal(bpp("clustered", GBUFFER_REFERENCE, GBUFFER_POSITION_PRESET, false), 0);
    assert_int_equal(bpp("forward-spml", GBUFFER_FAT, GBUFFER_POSITION_PRESET, false), 0);
    assert_int_equal(bpp("null", GBUFFER_FAT, GBUFFER_POSITION_PRESET, false), 0);
}

/* >>one frame's traffic */

static void add_pass(frame_stats *fs, const char *name, double samples)
{
    pass_stats *p = &fs->pass[fs->npasses++];
    memset(p, 0, sizeof *p);
    p->name = name;
    p->samples = samples;
}

static void test_frame_traffic_deferred(void **state)
{
    (void)state;
    frame_stats fs;
    memset(&fs, 0, sizeof fs);
    add_pass(&fs, "shadows", 0);
    add_pass(&fs, "gbuffer", 1000);     /* W H Sorting */
    add_pass(&fs, "ambient", 640);      /* full screen at 32 x 20 */
    add_pass(&fs, "directional", 640);
    add_pass(&fs, "point", 300);
    add_pass(&fs, "spot", 200);
    add_pass(&fs, "compose", 640);      /* the specular target, not the G-buffer */
    add_pass(&fs, "sky", 50);
    add_pass(&fs, "resolve", 640);
    gbuffer_traffic t = deferred_gbuffer_traffic(12, 32, 20, &fs);
    assert_near(t.write_bytes, 12.0 * 1000, 0);
    assert_near(t.read_bytes, 12.0 * (640 + 640 + 300 + 200), 0);   /* 21,360 */
    /* a light pass without a count: the reads are unknown, the writes are not */
    fs.pass[4].samples = NAN;
    t = deferred_gbuffer_traffic(12, 32, 20, &fs);
    assert_near(t.write_bytes, 12000.0, 0);
    assert_true(isnan(t.read_bytes));
    /* no G-buffer: neither */
    t = deferred_gbuffer_traffic(0, 32, 20, &fs);
    assert_true(isnan(t.write_bytes) && isnan(t.read_bytes));
}

static void test_frame_traffic_tiled(void **state)
{
    (void)state;
    frame_stats fs;
    memset(&fs, 0, sizeof fs);
    add_pass(&fs, "gbuffer", 1000);
    add_pass(&fs, "tiled", 0);          /* a compute dispatch: no samples */
    add_pass(&fs, "sky", 50);
    add_pass(&fs, "resolve", 640);
    gbuffer_traffic t = deferred_gbuffer_traffic(24, 32, 20, &fs);
    assert_near(t.write_bytes, 24.0 * 1000, 0);
    assert_near(t.read_bytes, 24.0 * 32 * 20, 0);   /* one load per pixel: 15,360 */
}

/* The visibility target's terms (visibility_id_traffic): 4 bytes a written sample, and
 * every sample of the screen read by each shading dispatch. */
static void test_frame_traffic_visibility(void **state)
{
    (void)state;
    frame_stats fs;
    memset(&fs, 0, sizeof fs);
    add_pass(&fs, "visibility", 1000);  /* samples passed, overdraw included */
    add_pass(&fs, "cull", 0);
    add_pass(&fs, "shade", 0);
    fs.pass[2].dispatches = 3;          /* three runs of equal maps */
    add_pass(&fs, "sky", 50);
    gbuffer_traffic t = visibility_id_traffic(32, 20, 1, &fs);
    assert_near(t.write_bytes, 4.0 * 1000, 0);
    assert_near(t.read_bytes, 4.0 * 32 * 20 * 3, 0);   /* 7,680 */
    t = visibility_id_traffic(32, 20, 4, &fs);         /* msaa 4: every sample's id */
    assert_near(t.read_bytes, 4.0 * 32 * 20 * 4 * 3, 0);
    fs.pass[0].samples = NAN;                          /* no count: unknown writes */
    t = visibility_id_traffic(32, 20, 4, &fs);
    assert_true(isnan(t.write_bytes) && !isnan(t.read_bytes));
    fs.npasses = 0;                                    /* no such passes: neither */
    t = visibility_id_traffic(32, 20, 4, &fs);
    assert_true(isnan(t.write_bytes) && isnan(t.read_bytes));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_equations_4_5_practical_example),
        cmocka_unit_test(test_equation_6_regrouped),
        cmocka_unit_test(test_table_2_is_equation_7),
        cmocka_unit_test(test_equation_7_approximates_6),
        cmocka_unit_test(test_mrt_terms_are_those_of_4_and_5),
        cmocka_unit_test(test_layout_bytes_per_pixel),
        cmocka_unit_test(test_frame_traffic_deferred),
        cmocka_unit_test(test_frame_traffic_visibility),
        cmocka_unit_test(test_frame_traffic_tiled),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
