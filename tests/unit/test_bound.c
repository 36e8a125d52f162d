/* results/bound.h: the bound of a run on a hand-made profile and hand-made counters:
 * each resource's time exactly (bytes / bandwidth, samples / the matching fill rate,
 * evaluations x 64 flops / arithmetic rate, draws and state changes x their cost,
 * dispatches x theirs), the largest named the limiter, the bound over the measured time,
 * and a bound above the measured time flagged as a model error, not clamped. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "results/bound.h"

static void profile(device_profile *p)
{
    static const struct {
        const char *name;
        double v;
    } f[] = {
        {"bandwidth_copy", 2},    {"bandwidth_texture_read", 4},   /* GB/s: peak 4 */
        {"fill_rgba8_1x", 1},     {"fill_rgba16f_1x", 0.5},        /* Gsamples/s */
        {"fill_rgba16f_4x", 0.25},
        {"alu_fragment", 16},     {"alu_compute", 8},              /* Gflop/s: peak 16 */
        {"draw_us", 2},           {"state_change_us", 10},         /* a switch alone: 8 */
        {"dispatch_us", 50},
    };
    memset(p, 0, sizeof *p);
    for (size_t i = 0; i < sizeof f / sizeof *f; i++) {
        double x[] = {f[i].v * 0.9, f[i].v, f[i].v * 1.1};   /* spread: 10% */
        assert_true(device_profile_add(p, f[i].name, "", x, 3));
    }
}

static void near(double got, double want)
{
    if (fabs(got - want) > 1e-9 * fmax(1, fabs(want)))
        fail_msg("got %.12g, want %.12g", got, want);
}

static void test_compute(void **state)
{
    (void)state;
    static device_profile p;
    profile(&p);
    bound_rates r;
    assert_true(bound_rates_of(&p, "rgba16f", 1, &r));
    near(r.bandwidth_gbps, 4);
    near(r.fill_gsps, 0.5);
    assert_string_equal(r.fill_figure, "fill_rgba16f_1x");
    near(r.alu_gflops, 16);
    near(r.spread, 0.1);
    bound_work w = {.bytes = 8e6, .samples = 6e5, .evaluations = 1e5, .draws = 100,
                    .dispatches = 2};
    bound_result b;
    bound_compute(&r, &w, 4000, &b);
    near(b.us[BOUND_BYTES], 2000);      /* 8e6 B / 4 GB/s */
    near(b.us[BOUND_FILL], 1200);       /* 6e5 / 0.5 Gsamples/s */
    near(b.us[BOUND_ALU], 400);         /* 1e5 x 64 flops / 16 Gflop/s */
    near(b.us[BOUND_DRAWS], 200);       /* 100 x 2 (state changes are charged nothing) */
    near(b.us[BOUND_DISPATCHES], 100);  /* 2 x 50 */
    near(b.bound_us, 2000);
    assert_string_equal(bound_resource_names[b.limiter], "bytes");
    near(b.pct, 50);
    assert_false(b.model_error);

    /* 4 samples: fill_rgba16f_4x, 0.25: fill is the limiter, above the measured 1500 */
    assert_true(bound_rates_of(&p, "rgba16f", 4, &r));
    assert_string_equal(r.fill_figure, "fill_rgba16f_4x");
    bound_compute(&r, &w, 1500, &b);
    near(b.bound_us, 2400);
    assert_string_equal(bound_resource_names[b.limiter], "fill");
    near(b.pct, 160);
    assert_true(b.model_error);   /* flagged, the bound kept as it is */

    /* no rgba32f figure: fill_rgba32f_1x, then fill_rgba8_1x */
    assert_true(bound_rates_of(&p, "rgba32f", 4, &r));
    assert_string_equal(r.fill_figure, "fill_rgba8_1x");

    /* work not counted (NAN) has no time; the draws decide; no measured time: no pct */
    bound_work d = {.bytes = NAN, .samples = NAN, .evaluations = NAN, .draws = 1000,
                    .dispatches = 0};
    bound_compute(&r, &d, NAN, &b);
    assert_true(isnan(b.us[BOUND_BYTES]) && isnan(b.us[BOUND_FILL]) && isnan(b.us[BOUND_ALU]));
    near(b.us[BOUND_DRAWS], 2000);
    near(b.us[BOUND_DISPATCHES], 0);
    assert_string_equal(bound_resource_names[b.limiter], "draws");
    assert_true(isnan(b.pct));
    assert_false(b.model_error);

    /* an empty profile: no rates, no bound */
    static device_profile none;
    memset(&none, 0, sizeof none);
    assert_false(bound_rates_of(&none, "rgba8", 1, &r));
    bound_compute(&r, &w, 1000, &b);
    assert_int_equal(b.limiter, -1);
    assert_true(isnan(b.bound_us) && isnan(b.pct));
}

static void test_row(void **state)
{
    (void)state;
    const char *const sn[] = {"run_id", "width", "height", "frametime_mean_us",
                              "gbuffer_write_bytes_mean", "gbuffer_read_bytes_mean",
                              "samples_shaded_mean", "samples_mean", "light_evals_per_pixel",
                              "coverage", "draw_calls_mean", "state_changes_mean",
                              "dispatches_mean"};
    const char *const sv[] = {"abc", "640", "360", "9000.5", "1000", "3000", "", "5000", "2.5",
                              "0.5", "12", "3", "0"};
    const char *const pn[] = {"run_id", "hdr", "msaa"};
    const char *const pv[] = {"abc", "rgba32f", "4"};
    bound_row rows[] = {{sn, sv, 13}, {pn, pv, 3}};
    bound_work w;
    double measured;
    const char *format;
    int samples;
    bound_work_of_row(rows, 2, &w, &measured, &format, &samples);
    near(w.bytes, 4000);
    near(w.samples, 5000);   /* samples_shaded empty: samples */
    near(w.evaluations, 2.5 * 0.5 * 640 * 360);
    near(w.draws, 12);
    near(w.dispatches, 0);
    near(measured, 9000.5);
    assert_string_equal(format, "rgba32f");
    assert_int_equal(samples, 4);
    /* an older summary: no coverage, no plan row: no evaluations, rgba8 at 1 sample */
    bound_work_of_row(rows, 1, &w, &measured, &format, &samples);
    assert_string_equal(format, "rgba8");
    assert_int_equal(samples, 1);
    const char *const on[] = {"light_evals_per_pixel", "width", "height"};
    const char *const ov[] = {"2.5", "640", "360"};
    bound_row old = {on, ov, 3};
    bound_work_of_row(&old, 1, &w, &measured, &format, &samples);
    assert_true(isnan(w.evaluations) && isnan(w.bytes) && isnan(measured));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_compute),
        cmocka_unit_test(test_row),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
