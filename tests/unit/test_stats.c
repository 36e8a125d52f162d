/* Statistics on frame times: summaries, Student's t, batch-means CI, per-second bins.
 * Every expected value below is worked out by hand in the comment next to it. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/unit/assert_near.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "results/stats.h"

#define EPS 1e-9


/* >>summaries */

static void test_summary_known(void **state)
{
    (void)state;
    const double x[] = {4, 1, 3, 2, 5};
    double copy[5];
    memcpy(copy, x, sizeof x);
    sample_summary s;
    stats_summarize(copy, 5, &s);
    assert_memory_equal(copy, x, sizeof x); /* input untouched */
    assert_int_equal(s.n, 5);
    assert_near(s.mean, 3.0, EPS);
    /* squared deviations 1+4+0+1+4 = 10, / (5-1) */
    assert_near(s.sd, sqrt(10.0 / 4.0), EPS);
    /* nearest rank: p50 -> ceil(2.5) = 3rd = 3; p99 -> ceil(4.95) = 5th = 5 */
    assert_near(s.p50, 3.0, 0);
    assert_near(s.p99, 5.0, 0);
    assert_near(s.min, 1.0, 0);
    assert_near(s.max, 5.0, 0);
}

static void test_summary_1_to_100(void **state)
{
    (void)state;
    double x[100];
    for (int i = 0; i < 100; i++)
        x[i] = (double)(100 - i); /* descending: sorting matters */
    sample_summary s;
    stats_summarize(x, 100, &s);
    assert_near(s.mean, 50.5, EPS);
    /* variance of 1..n with n-1: n(n+1)/12 */
    assert_near(s.sd, sqrt(100.0 * 101.0 / 12.0), 1e-12);
    assert_near(s.p50, 50.0, 0); /* rank ceil(50) = 50 */
    assert_near(s.p99, 99.0, 0); /* rank ceil(99) = 99 */
    assert_near(s.min, 1.0, 0);
    assert_near(s.max, 100.0, 0);

    /* ten values: p99 -> rank ceil(9.9) = 10 */
    double y[10];
    for (int i = 0; i < 10; i++)
        y[i] = 10.0 * (i + 1);
    stats_summarize(y, 10, &s);
    assert_near(s.p50, 50.0, 0);
    assert_near(s.p99, 100.0, 0);
}

static void test_summary_empty_and_single(void **state)
{
    (void)state;
    sample_summary s;
    stats_summarize(NULL, 0, &s);
    assert_int_equal(s.n, 0);
    assert_true(isnan(s.mean) && isnan(s.sd) && isnan(s.p50) && isnan(s.p99));
    assert_true(isnan(s.min) && isnan(s.max));

    const double one = 16.7;
    stats_summarize(&one, 1, &s);
    assert_int_equal(s.n, 1);
    assert_near(s.mean, 16.7, 0);
    assert_true(isnan(s.sd));
    assert_near(s.p50, 16.7, 0);
    assert_near(s.p99, 16.7, 0);
    assert_near(s.min, 16.7, 0);
    assert_near(s.max, 16.7, 0);
}

static void test_percentile_edges(void **state)
{
    (void)state;
    const double x[] = {1, 2, 3, 4};
    assert_near(stats_percentile_sorted(x, 4, 25.0), 1.0, 0);  /* rank 1 exactly */
    assert_near(stats_percentile_sorted(x, 4, 25.1), 2.0, 0);  /* rank ceil(1.004) */
    assert_near(stats_percentile_sorted(x, 4, 100.0), 4.0, 0);
    assert_near(stats_percentile_sorted(x, 4, 0.001), 1.0, 0);
    assert_true(isnan(stats_percentile_sorted(x, 0, 50.0)));
    assert_true(isnan(stats_percentile_sorted(x, 4, 0.0)));
}

/* >>t */

static void test_t975(void **state)
{
    (void)state;
    static const struct {
        size_t dof;
        double t;
    } table[] = {
        {1, 12.706},  {2, 4.303},    {3, 3.182},    {5, 2.571},  {10, 2.228},
        {20, 2.086},  {29, 2.045},   {30, 2.042},   {31, 2.040}, {40, 2.021},
        {60, 2.000},  {120, 1.980},  {1000, 1.962}, {1000000, 1.960},
        {0, 0},
    };
    for (size_t i = 0; table[i].dof != 0; i++)
        assert_near(stats_t975(table[i].dof), table[i].t, 1e-3);
    assert_near(stats_t975(100000000), 1.959964, 1e-6);
    assert_true(isnan(stats_t975(0)));
    /* decreasing everywhere, the 30 -> 31 seam included */
    for (size_t d = 1; d < 2000; d++)
        assert_true(stats_t975(d + 1) < stats_t975(d));
}

/* >>ci */

static void test_ci_constant_is_zero(void **state)
{
    (void)state;
    double x[1000];
    for (int i = 0; i < 1000; i++)
        x[i] = 16.0;
    assert_near(stats_ci95_batch_means(x, 1000), 0.0, 0);
    assert_near(stats_ci95_batch_means(x, 5), 0.0, 0); /* fallback path */
}

/* Batches alternate between mean 1 and mean 3: batch means 1,3,1,3,... have mean 2,
 * sd sqrt(10 * 1 / 9), so CI = t(9) * sqrt(10/9) / sqrt(10) = t(9) / 3. The noise
 * inside each batch (+-d around its mean) must not matter. */
static void test_ci_alternating_batches(void **state)
{
    (void)state;
    const double want = 2.2621572 / 3.0;
    double x[23];
    /* n = 20: ten batches of two values m-0.5, m+0.5 */
    for (int b = 0; b < 10; b++) {
        double m = (b % 2 == 0) ? 1.0 : 3.0;
        x[2 * b] = m - 0.5;
        x[2 * b + 1] = m + 0.5;
    }
    assert_near(stats_ci95_batch_means(x, 20), want, 1e-6);

    /* n = 23: batches of 2, the last takes the remainder (5 values, mean 3) */
    for (int i = 18; i < 23; i++)
        x[i] = 3.0 + (i % 2 == 0 ? 0.25 : -0.25) + (i == 22 ? -0.25 : 0.0);
    /* values 3.25, 2.75, 3.25, 2.75, 3.0: mean 3 */
    assert_near(stats_ci95_batch_means(x, 23), want, 1e-6);
}

static void test_ci_fallback_small(void **state)
{
    (void)state;
    /* fewer than 20 frames: t(n-1) * sd / sqrt(n) over frames.
     * {1,2,3,4}: sd = sqrt(5/3), t(3) = 3.1824463 */
    const double x[] = {1, 2, 3, 4};
    assert_near(stats_ci95_batch_means(x, 4), 3.1824463 * sqrt(5.0 / 3.0) / 2.0, 1e-6);
    assert_true(isnan(stats_ci95_batch_means(x, 1)));
    assert_true(isnan(stats_ci95_batch_means(x, 0)));
}

/* >>bins */

static frame_record rec(double t, double ft, unsigned lights, uint64_t dc)
{
    frame_record r;
    memset(&r, 0, sizeof r);
    r.t_wall_s = t;
    r.t_scene_s = t;
    r.frametime_us = ft;
    r.lights = lights;
    r.draw_calls = dc;
    r.gpu_us = NAN;
    r.fragments = NAN;
    return r;
}

static void assert_empty_bin(const second_bin *b, unsigned second)
{
    assert_int_equal(b->second, second);
    assert_int_equal(b->frames, 0);
    assert_int_equal(b->lights_min, 0);
    assert_int_equal(b->lights_max, 0);
    assert_true(isnan(b->frametime_mean_us) && isnan(b->frametime_sd_us));
    assert_true(isnan(b->frametime_p50_us) && isnan(b->frametime_p99_us));
    assert_true(isnan(b->draw_calls_mean));
}

static void check_long_frame_bins(const second_bin *b, size_t nb)
{
    assert_int_equal(nb, 4);
    /* second 0: frames at 0.1 and 0.5 */
    assert_int_equal(b[0].second, 0);
    assert_int_equal(b[0].frames, 2);
    assert_true(b[0].complete);
    assert_int_equal(b[0].lights_min, 1);
    assert_int_equal(b[0].lights_max, 3);
    assert_near(b[0].frametime_mean_us, 150.0, EPS);
    assert_near(b[0].frametime_sd_us, sqrt(2 * 50.0 * 50.0), EPS);
    assert_near(b[0].frametime_p50_us, 100.0, 0);
    assert_near(b[0].frametime_p99_us, 200.0, 0);
    assert_near(b[0].draw_calls_mean, 15.0, EPS);
    /* second 1: the frame ending exactly at 1.0 belongs here */
    assert_int_equal(b[1].frames, 1);
    assert_true(b[1].complete);
    assert_int_equal(b[1].lights_min, 5);
    assert_int_equal(b[1].lights_max, 5);
    assert_near(b[1].frametime_mean_us, 300.0, 0);
    assert_true(isnan(b[1].frametime_sd_us));
    assert_near(b[1].frametime_p50_us, 300.0, 0);
    assert_near(b[1].frametime_p99_us, 300.0, 0);
    assert_near(b[1].draw_calls_mean, 30.0, 0);
    /* second 2: nothing ended in it (a 2.5 s frame was running), still present */
    assert_empty_bin(&b[2], 2);
    assert_true(b[2].complete);
    /* second 3: the long frame (ended at 3.5) and one more */
    assert_int_equal(b[3].frames, 2);
    assert_true(b[3].complete); /* 3 + 1 <= t_end = 4.0 */
    assert_int_equal(b[3].lights_min, 6);
    assert_int_equal(b[3].lights_max, 7);
    assert_near(b[3].frametime_mean_us, (2.5e6 + 400.0) / 2.0, EPS);
    assert_near(b[3].frametime_p50_us, 400.0, 0);
    assert_near(b[3].frametime_p99_us, 2.5e6, 0);
    assert_near(b[3].draw_calls_mean, 45.0, EPS);
}

static void test_bins_long_frame(void **state)
{
    (void)state;
    frame_record f[5] = {
        rec(0.1, 100.0, 1, 10),  rec(0.5, 200.0, 3, 20), rec(1.0, 300.0, 5, 30),
        rec(3.5, 2.5e6, 7, 40),  rec(3.9, 400.0, 6, 50),
    };
    second_bin *b = NULL;
    size_t nb = 0;
    assert_true(stats_bin_seconds(f, 5, 4.0, &b, &nb));
    check_long_frame_bins(b, nb);
    free(b);

    /* the same frames in another order give the same bins */
    frame_record r[5] = {f[4], f[2], f[0], f[3], f[1]};
    assert_true(stats_bin_seconds(r, 5, 4.0, &b, &nb));
    check_long_frame_bins(b, nb);
    free(b);
}

static void test_bins_complete_flag(void **state)
{
    (void)state;
    frame_record f[3] = {rec(0.5, 1, 1, 1), rec(1.5, 1, 1, 1), rec(2.5, 1, 1, 1)};
    second_bin *b = NULL;
    size_t nb = 0;

    /* t_end = 3.0: seconds 0..2, all complete (2 + 1 <= 3) */
    assert_true(stats_bin_seconds(f, 3, 3.0, &b, &nb));
    assert_int_equal(nb, 3);
    for (size_t i = 0; i < nb; i++) {
        assert_int_equal(b[i].second, i);
        assert_int_equal(b[i].frames, 1);
        assert_true(b[i].complete);
    }
    free(b);

    /* t_end = 3.4: seconds 0..3; second 3 was measured for 0.4 s, had no frame */
    assert_true(stats_bin_seconds(f, 3, 3.4, &b, &nb));
    assert_int_equal(nb, 4);
    for (size_t i = 0; i < 3; i++)
        assert_true(b[i].complete);
    assert_false(b[3].complete);
    assert_empty_bin(&b[3], 3);
    free(b);

    /* t_end = 2.7: the last second is partial and has a frame */
    assert_true(stats_bin_seconds(f, 3, 2.7, &b, &nb));
    assert_int_equal(nb, 3);
    assert_true(b[1].complete);
    assert_false(b[2].complete);
    assert_int_equal(b[2].frames, 1);
    free(b);
}

static void test_bins_zero_frames(void **state)
{
    (void)state;
    second_bin *b = (second_bin *)&b; /* must be reset */
    size_t nb = 99;
    assert_true(stats_bin_seconds(NULL, 0, 0.0, &b, &nb));
    assert_int_equal(nb, 0);
    assert_null(b);

    assert_true(stats_bin_seconds(NULL, 0, 2.5, &b, &nb));
    assert_int_equal(nb, 3);
    for (unsigned i = 0; i < 3; i++)
        assert_empty_bin(&b[i], i);
    assert_true(b[0].complete);
    assert_true(b[1].complete);
    assert_false(b[2].complete);
    free(b);
}

/* >>convergence */

static uint64_t conv_state;
static double conv_uniform(void)   /* splitmix64 -> [0, 1) */
{
    uint64_t z = (conv_state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    z ^= z >> 31;
    return (double)(z >> 11) / 9007199254740992.0;
}

/* n frames of 1000 +- 100 us (uniform: sd 200/sqrt(12)), one ending every 1 ms. */
static frame_record *uniform_stream(size_t n, uint64_t seed)
{
    frame_record *f = calloc(n, sizeof *f);
    conv_state = seed;
    for (size_t i = 0; i < n; i++) {
        f[i].frame = (uint32_t)i;
        f[i].t_wall_s = (double)(i + 1) * 0.001;
        f[i].frametime_us = 900.0 + 200.0 * conv_uniform();
    }
    return f;
}

/* The points: one per whole second and the end; each equals the direct estimator
 * on the frames that ended by then. */
static void test_convergence_points_match_direct(void **state)
{
    (void)state;
    size_t n = 3400;
    frame_record *f = uniform_stream(n, 7);
    convergence_point *p;
    size_t np;
    assert_true(stats_convergence(f, n, 3.4, &p, &np));
    assert_int_equal(np, 4);
    double want_at[4] = {1.0, 2.0, 3.0, 3.4};
    size_t want_frames[4] = {1000, 2000, 3000, 3400};
    double *x = malloc(n * sizeof *x);
    for (size_t i = 0; i < n; i++)
        x[i] = f[i].frametime_us;
    for (size_t i = 0; i < np; i++) {
        assert_true(p[i].elapsed_s == want_at[i]);
        assert_int_equal(p[i].frames, want_frames[i]);
        double direct = stats_ci95_batch_means(x, p[i].frames);
        assert_true(fabs(p[i].ci95_us - direct) <= 1e-9 * direct);
        sample_summary sm;
        stats_summarize(x, p[i].frames, &sm);
        assert_true(fabs(p[i].mean_us - sm.mean) <= 1e-9 * sm.mean);
    }
    free(p);
    /* a measurement ending on a whole second has no extra point */
    assert_true(stats_convergence(f, 3000, 3.0, &p, &np));
    assert_int_equal(np, 3);
    free(p);
    /* under one second: one point, at the end */
    assert_true(stats_convergence(f, 500, 0.5, &p, &np));
    assert_int_equal(np, 1);
    assert_int_equal(p[0].frames, 500);
    free(p);
    assert_true(stats_convergence(f, 0, 0.0, &p, &np));
    assert_int_equal(np, 0);
    assert_null(p);
    free(x);
    free(f);
}

/* Known variance: for independent frames of sd sigma, the batch-means half-width
 * at n frames is t(0.975, 9) x s_b / sqrt(10) with s_b the sd of 10 batch means of
 * sd sigma / sqrt(n / 10): on average t x c4(10) x sigma / sqrt(n), c4(10) = 0.9727
 * (exact for normal batch means, which means of 100+ uniform frames are to within
 * the tolerance). Averaged over 200 streams (sd of the average ~0.035) it must be
 * within 0.15 of t x c4 = 2.2003 at every point, i.e. shrink as 1 / sqrt(n). */
static void test_convergence_known_variance(void **state)
{
    (void)state;
    const double sigma = 200.0 / sqrt(12.0);
    const size_t n = 10000;   /* 10 s at 1000 frames a second */
    double sum[10] = {0};
    const int streams = 200;
    for (int k = 0; k < streams; k++) {
        frame_record *f = uniform_stream(n, 1000 + (uint64_t)k);
        convergence_point *p;
        size_t np;
        assert_true(stats_convergence(f, n, 10.0, &p, &np));
        assert_int_equal(np, 10);
        for (size_t i = 0; i < np; i++)
            sum[i] += p[i].ci95_us * sqrt((double)p[i].frames) / sigma;
        free(p);
        free(f);
    }
    const double expected = 2.262157 * 0.972659;
    for (int i = 0; i < 10; i++) {
        double avg = sum[i] / streams;
        if (fabs(avg - expected) >= 0.15)
            print_error("point %d: ci95 x sqrt(n) / sigma = %.4f, expected %.4f\n", i, avg,
                        expected);
        assert_true(fabs(avg - expected) < 0.15);
    }
}

/* "Stayed within 1%": the first point from which every later point is within it,
 * checked against a brute-force scan; a constant stream converges at once; a stream
 * whose frame time keeps doubling never does. */
static void test_converged_after(void **state)
{
    (void)state;
    size_t n = 10000;
    frame_record *f = uniform_stream(n, 99);
    convergence_point *p;
    size_t np;
    assert_true(stats_convergence(f, n, 10.0, &p, &np));
    for (double rel = 0.0005; rel < 0.01; rel += 0.0005) {
        double want = NAN;
        for (size_t i = np; i-- > 0;) {
            if (p[i].ci95_us > rel * p[i].mean_us)
                break;
            want = p[i].elapsed_s;
        }
        double got = stats_converged_after(p, np, rel);
        assert_true((isnan(want) && isnan(got)) || want == got);
    }
    /* the uniform stream's CI is ~0.13% of the mean after 10 s: within 1% from 1 s */
    assert_true(stats_converged_after(p, np, 0.01) == 1.0);
    free(p);

    for (size_t i = 0; i < n; i++)
        f[i].frametime_us = 1000.0;
    assert_true(stats_convergence(f, n, 10.0, &p, &np));
    assert_true(stats_converged_after(p, np, 0.01) == 1.0);
    assert_true(p[np - 1].ci95_us == 0.0);
    free(p);

    for (size_t i = 0; i < n; i++)
        f[i].frametime_us = 1000.0 * pow(2.0, (double)(i / 1000));   /* doubles each second */
    assert_true(stats_convergence(f, n, 10.0, &p, &np));
    assert_true(isnan(stats_converged_after(p, np, 0.01)));
    free(p);
    free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_convergence_points_match_direct),
        cmocka_unit_test(test_convergence_known_variance),
        cmocka_unit_test(test_converged_after),
        cmocka_unit_test(test_summary_known),
        cmocka_unit_test(test_summary_1_to_100),
        cmocka_unit_test(test_summary_empty_and_single),
        cmocka_unit_test(test_percentile_edges),
        cmocka_unit_test(test_t975),
        cmocka_unit_test(test_ci_constant_is_zero),
        cmocka_unit_test(test_ci_alternating_batches),
        cmocka_unit_test(test_ci_fallback_small),
        cmocka_unit_test(test_bins_long_frame),
        cmocka_unit_test(test_bins_complete_flag),
        cmocka_unit_test(test_bins_zero_frames),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
