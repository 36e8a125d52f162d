/* The streaming statistics (results/stream_stats.h) against the exact, array-based
 * ones (results/stats.h): equal where the header says exact, within the stated bound
 * where it says approximate. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "results/stats.h"
#include "results/stream_stats.h"

static void check_rel(double got, double want, double rel, const char *what, const char *file,
                      int line)
{
    if (got == want || (isnan(got) && isnan(want)) || fabs(got - want) <= rel * fabs(want))
        return;
    print_error("%s: %.17g, expected %.17g (relative tolerance %g)\n", what, got, want, rel);
    _fail(file, line);
}
#define assert_rel(got, want, rel) check_rel((got), (want), (rel), #got, __FILE__, __LINE__)

static uint64_t rng_state;
static double uniform01(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

/* Frame times of several shapes: 0 uniform, 1 log-uniform over six decades, 2 heavy
 * tail (Pareto, alpha 1.5), 3 constant, 4 two spikes (mostly 1000, 2% at 50000). */
static double draw(int shape)
{
    switch (shape) {
    case 0: return 900.0 + 200.0 * uniform01();
    case 1: return exp(log(0.01) + uniform01() * log(1e6));
    case 2: return 500.0 / pow(1.0 - uniform01(), 1.0 / 1.5);
    case 3: return 16666.0;
    default: return uniform01() < 0.02 ? 50000.0 : 1000.0;
    }
}

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

static const double percents[] = {0.1, 1, 10, 25, 50, 75, 90, 99, 99.9, 100};
#define NPERCENTS (sizeof percents / sizeof percents[0])

/* Up to QS_EXACT values the sketch is exact; past it every percentile is within
 * QS_ALPHA of the exact nearest-rank value (the 1e-12 is the rounding of log()). */
static void test_sketch_against_exact(void **state)
{
    (void)state;
    quantile_sketch *q = malloc(sizeof *q);
    const size_t sizes[] = {1, 2, 7, QS_EXACT, QS_EXACT + 1, 5000, 100000};
    for (int shape = 0; shape < 5; shape++)
        for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
            size_t n = sizes[si];
            rng_state = 99 + (uint64_t)shape * 1000 + n;
            double *x = malloc(n * sizeof *x);
            qs_reset(q);
            for (size_t i = 0; i < n; i++) {
                x[i] = draw(shape);
                qs_add(q, x[i]);
            }
            qsort(x, n, sizeof *x, cmp_double);
            assert_true(q->min == x[0] && q->max == x[n - 1]);
            for (size_t k = 0; k < NPERCENTS; k++) {
                double want = stats_percentile_sorted(x, n, percents[k]);
                double got = qs_percentile(q, percents[k]);
                if (n <= QS_EXACT)
                    assert_true(got == want);
                else
                    assert_rel(got, want, QS_ALPHA * (1 + 1e-12));
                assert_true(got >= x[0] && got <= x[n - 1]);
            }
            free(x);
        }
    qs_reset(q);
    assert_true(isnan(qs_percentile(q, 50)));
    free(q);
}

/* Values outside [QS_LO, QS_HI] land in the end buckets, which report the extremes. */
static void test_sketch_out_of_range(void **state)
{
    (void)state;
    quantile_sketch *q = malloc(sizeof *q);
    qs_reset(q);
    for (int i = 0; i < 3000; i++)
        qs_add(q, i < 1000 ? 0.0 : i < 2000 ? 100.0 : 1e12);
    assert_true(qs_percentile(q, 10) == 0.0);
    assert_rel(qs_percentile(q, 50), 100.0, QS_ALPHA);
    assert_true(qs_percentile(q, 90) == 1e12);
    free(q);
}

/* Batch means: identical (to rounding) to stats_ci95_batch_means up to BM_BLOCKS
 * frames, the per-frame fallback under 20 included; past it, on a smooth stream (where
 * moving a boundary by half a block changes little), within 0.1%, and on independent
 * frames within 10% (the boundaries move by at most 10 / BM_BLOCKS of a batch). */
static void test_batch_means(void **state)
{
    (void)state;
    batch_prefix *b = malloc(sizeof *b);
    const size_t sizes[] = {0, 1, 2, 19, 20, 21, 1234, BM_BLOCKS, BM_BLOCKS + 1, 3 * BM_BLOCKS + 7};
    for (int smooth = 0; smooth < 2; smooth++)
        for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
            size_t n = sizes[si];
            double *x = malloc((n ? n : 1) * sizeof *x);
            moments m = {0};
            bp_reset(b);
            rng_state = 5 + n;
            for (size_t i = 0; i < n; i++) {
                x[i] = smooth ? 1000.0 + 300.0 * sin(6.0 * (double)i / (double)n) : draw(0);
                bp_add(b, x[i]);
                moments_add(&m, x[i]);
            }
            double want = stats_ci95_batch_means(x, n), got = bp_ci95(b, &m);
            if (n < 2)
                assert_true(isnan(got) && isnan(want));
            else if (n <= BM_BLOCKS)
                assert_rel(got, want, 1e-9);
            else
                assert_rel(got, want, smooth ? 1e-3 : 0.1);
            assert_int_equal(b->n, n);
            free(x);
        }
    free(b);
}

/* A trial streamed frame by frame gives what the array-based functions give on the
 * same frames: every bin (count, completeness, lights, mean, sd, draw calls exactly;
 * percentiles exactly while a second holds at most QS_EXACT frames), every
 * convergence point, and the totals. */
typedef struct collected {
    second_bin bins[64];
    size_t nbins;
    convergence_point pts[64];
    size_t npts;
} collected;

static void on_bin(void *ctx, const second_bin *b)
{
    collected *c = ctx;
    assert_true(c->nbins < 64);
    c->bins[c->nbins++] = *b;
}

static void on_point(void *ctx, const convergence_point *p)
{
    collected *c = ctx;
    assert_true(c->npts < 64);
    c->pts[c->npts++] = *p;
}

static void check_trial(const frame_record *f, size_t n, double t_end)
{
    trial_stream *ts = trial_stream_new();
    assert_non_null(ts);
    collected *c = calloc(1, sizeof *c);
    trial_stream_begin(ts, 0.01, on_bin, on_point, c);
    for (size_t i = 0; i < n; i++)
        trial_stream_add(ts, &f[i]);
    trial_totals tt;
    trial_stream_end(ts, t_end, &tt);

    second_bin *bins;
    size_t nbins;
    assert_true(stats_bin_seconds(f, n, t_end, &bins, &nbins));
    assert_int_equal(c->nbins, nbins);
    for (size_t i = 0; i < nbins; i++) {
        const second_bin *a = &c->bins[i], *e = &bins[i];
        assert_int_equal(a->second, e->second);
        assert_int_equal(a->frames, e->frames);
        assert_int_equal(a->complete, e->complete);
        assert_int_equal(a->lights_min, e->lights_min);
        assert_int_equal(a->lights_max, e->lights_max);
        assert_rel(a->frametime_mean_us, e->frametime_mean_us, 1e-12);
        assert_rel(a->frametime_sd_us, e->frametime_sd_us, 1e-9);
        assert_rel(a->draw_calls_mean, e->draw_calls_mean, 1e-12);
        double rel = e->frames <= QS_EXACT ? 0 : QS_ALPHA * (1 + 1e-12);
        assert_rel(a->frametime_p50_us, e->frametime_p50_us, rel);
        assert_rel(a->frametime_p99_us, e->frametime_p99_us, rel);
    }
    free(bins);

    convergence_point *pts;
    size_t npts;
    assert_true(stats_convergence(f, n, t_end, &pts, &npts));
    assert_int_equal(c->npts, npts);
    for (size_t i = 0; i < npts; i++) {
        assert_true(c->pts[i].elapsed_s == pts[i].elapsed_s);
        assert_int_equal(c->pts[i].frames, pts[i].frames);
        assert_rel(c->pts[i].mean_us, pts[i].mean_us, 1e-12);
        assert_rel(c->pts[i].ci95_us, pts[i].ci95_us, 1e-9);
    }
    double after = stats_converged_after(pts, npts, 0.01);
    assert_true(after == tt.ci_converged_after_s || (isnan(after) && isnan(tt.ci_converged_after_s)));
    free(pts);

    double *x = malloc((n ? n : 1) * sizeof *x);
    for (size_t i = 0; i < n; i++)
        x[i] = f[i].frametime_us;
    sample_summary s;
    stats_summarize(x, n, &s);
    assert_int_equal(tt.ft.n, n);
    assert_rel(tt.ft.mean, s.mean, 1e-12);
    assert_rel(tt.ft.sd, s.sd, 1e-9);
    assert_true(tt.ft.min == s.min || (isnan(s.min) && isnan(tt.ft.min)));
    assert_true(tt.ft.max == s.max || (isnan(s.max) && isnan(tt.ft.max)));
    double rel = n <= QS_EXACT ? 0 : QS_ALPHA * (1 + 1e-12);
    assert_rel(tt.ft.p50, s.p50, rel);
    assert_rel(tt.ft.p99, s.p99, rel);
    assert_rel(tt.ft_ci95, stats_ci95_batch_means(x, n), 1e-9);
    free(x);
    free(c);
    trial_stream_free(ts);
}

static frame_record *stream_of(size_t n, double fps, uint64_t seed)
{
    frame_record *f = calloc(n ? n : 1, sizeof *f);
    rng_state = seed;
    double t = 0;
    for (size_t i = 0; i < n; i++) {
        f[i].frame = (uint32_t)i;
        f[i].frametime_us = draw(i % 97 == 0 ? 2 : 0) * 1000.0 / fps;
        t += f[i].frametime_us * 1e-6 * (0.5 + uniform01());
        f[i].t_wall_s = t;
        f[i].lights = (uint32_t)(i / 50);
        f[i].draw_calls = 3 + i % 5;
        f[i].gpu_us = i % 3 ? f[i].frametime_us / 2 : NAN;
    }
    return f;
}

static void test_trial_matches_arrays(void **state)
{
    (void)state;
    /* a few hundred frames a second over 4.x s; then 3000 a second (approximate
     * percentiles per bin); then a frame of 3 s (empty bins between) */
    frame_record *f = stream_of(1500, 300, 1);
    check_trial(f, 1500, f[1499].t_wall_s);
    check_trial(f, 1500, ceil(f[1499].t_wall_s) + 1.5);   /* empty bins at the end */
    check_trial(f, 300, 3.0);
    free(f);
    f = stream_of(12000, 3000, 2);
    check_trial(f, 12000, f[11999].t_wall_s);
    f[5000].frametime_us = 3e6;
    for (size_t i = 5000; i < 12000; i++)
        f[i].t_wall_s += 3.0;
    check_trial(f, 12000, f[11999].t_wall_s);
    free(f);
    check_trial(NULL, 0, 0.0);
    check_trial(NULL, 0, 2.5);
    frame_record one = {.t_wall_s = 0.25, .frametime_us = 250000, .lights = 4, .gpu_us = NAN};
    check_trial(&one, 1, 0.25);
    /* a frame ending on a whole second belongs to that second's bin and point */
    frame_record two[2] = {{.t_wall_s = 1.0, .frametime_us = 1e6}, {.frame = 1, .t_wall_s = 2.0, .frametime_us = 1e6}};
    check_trial(two, 2, 2.0);
}

/* The totals that are plain sums. */
static void test_trial_totals(void **state)
{
    (void)state;
    trial_stream *ts = trial_stream_new();
    trial_stream_begin(ts, 0.01, NULL, NULL, NULL);
    frame_record r[3] = {
        {.t_wall_s = 0.1, .frametime_us = 100, .gpu_us = 40, .draw_calls = 2, .state_changes = 5, .fragments = 64, .lights = 3},
        {.t_wall_s = 0.2, .frametime_us = 100, .gpu_us = NAN, .draw_calls = 4, .state_changes = 7, .fragments = 32, .lights = 9},
        {.t_wall_s = 0.3, .frametime_us = 100, .gpu_us = 60, .draw_calls = 6, .state_changes = 9, .fragments = 0, .lights = 1},
    };
    /* seed 002's G-buffer bytes: the means over the frames that have them */
    r[0].gbuffer_write_bytes = 100, r[0].gbuffer_read_bytes = 300;
    r[1].gbuffer_write_bytes = NAN, r[1].gbuffer_read_bytes = NAN;
    r[2].gbuffer_write_bytes = 200, r[2].gbuffer_read_bytes = 500;
    for (int i = 0; i < 3; i++)
        trial_stream_add(ts, &r[i]);
    trial_totals tt;
    trial_stream_end(ts, 0.3, &tt);
    assert_true(tt.m.gbuffer_write_bytes_mean == 150 && tt.m.gbuffer_read_bytes_mean == 400);
    assert_true(tt.m.gpu_mean_us == 50);   /* over the two frames that have one */
    assert_true(tt.m.draw_calls_mean == 4 && tt.m.state_changes_mean == 7 && tt.m.fragments_mean == 32);
    assert_int_equal(tt.lights_max, 9);
    assert_true(tt.ft_ci95 == 0 && tt.ci_converged_after_s == 0.3);
    /* no frame with a G-buffer: NAN (an empty column) */
    trial_stream_begin(ts, 0.01, NULL, NULL, NULL);
    frame_record f = {.t_wall_s = 0.1, .frametime_us = 100, .gpu_us = NAN,
                      .gbuffer_write_bytes = NAN, .gbuffer_read_bytes = NAN};
    trial_stream_add(ts, &f);
    trial_stream_end(ts, 0.1, &tt);
    assert_true(isnan(tt.m.gbuffer_write_bytes_mean) && isnan(tt.m.gbuffer_read_bytes_mean));
    trial_stream_free(ts);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sketch_against_exact),
        cmocka_unit_test(test_sketch_out_of_range),
        cmocka_unit_test(test_batch_means),
        cmocka_unit_test(test_trial_matches_arrays),
        cmocka_unit_test(test_trial_totals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
