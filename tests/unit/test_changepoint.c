/* Change points (results/changepoint.c) on synthetic series with seeded Gaussian noise:
 * one 10% step found at its index +-2, two steps both found, a flat noisy series gives
 * none, the minimum relative change drops a small significant step, the t-test's p
 * against a t table, and the sweeps' common drift removed while one run's own step
 * stays. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/unit/assert_near.h"

#include <math.h>
#include <stdlib.h>

#include "results/changepoint.h"

static uint64_t rng_state;

static double gauss(void)   /* Box-Muller on a 64-bit LCG */
{
    double u[2];
    for (int i = 0; i < 2; i++) {
        rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
        u[i] = ((double)(rng_state >> 11) + 0.5) / 9007199254740992.0;
    }
    return sqrt(-2 * log(u[0])) * cos(6.283185307179586 * u[1]);
}

/* n points at 1000 with noise of sd `noise` (relative), times step[k] from at[k] on */
static void series(double *x, size_t n, double noise, const size_t *at, const double *step,
                   size_t nsteps, uint64_t seed)
{
    rng_state = seed;
    for (size_t i = 0; i < n; i++) {
        double f = 1;
        for (size_t k = 0; k < nsteps; k++)
            if (i >= at[k])
                f *= step[k];
        x[i] = 1000 * f * (1 + noise * gauss());
    }
}

static void test_one_step(void **state)
{
    (void)state;
    cp_options o = changepoint_defaults();
    for (uint64_t seed = 1; seed <= 5; seed++) {
        double x[40];
        size_t at = 18;
        double step = 1.10;
        series(x, 40, 0.02, &at, &step, 1, seed);
        change_point *cp;
        size_t n = changepoint_find(x, 40, &o, &cp);
        assert_int_equal(n, 1);
        assert_true(cp[0].index + 2 >= at && cp[0].index <= at + 2);
        assert_true(cp[0].forward_change_percent > 7 && cp[0].forward_change_percent < 13);
        assert_true(cp[0].pvalue < 0.001);
        assert_true(cp[0].t_value > 0);
        free(cp);
    }
}

static void test_two_steps(void **state)
{
    (void)state;
    cp_options o = changepoint_defaults();
    double x[50];
    size_t at[2] = {15, 35};
    double step[2] = {1.15, 0.88};
    series(x, 50, 0.02, at, step, 2, 7);
    change_point *cp;
    size_t n = changepoint_find(x, 50, &o, &cp);
    assert_int_equal(n, 2);
    assert_true(cp[0].index + 2 >= 15 && cp[0].index <= 17);
    assert_true(cp[1].index + 2 >= 35 && cp[1].index <= 37);
    assert_true(cp[0].forward_change_percent > 0 && cp[1].forward_change_percent < 0);
    /* the second's "before" is the piece between the two */
    assert_true(fabs(cp[1].mean_before / 1150 - 1) < 0.03);
    free(cp);
}

static void test_flat_none(void **state)
{
    (void)state;
    cp_options o = changepoint_defaults();
    for (uint64_t seed = 1; seed <= 10; seed++) {
        double x[60];
        series(x, 60, 0.03, NULL, NULL, 0, seed);
        change_point *cp;
        assert_int_equal(changepoint_find(x, 60, &o, &cp), 0);
        assert_null(cp);
    }
}

static void test_min_change_floor(void **state)
{
    (void)state;
    double x[50];
    size_t at = 25;
    double step = 1.03;
    series(x, 50, 0.003, &at, &step, 1, 3);
    cp_options o = changepoint_defaults();
    change_point *cp;
    assert_int_equal(changepoint_find(x, 50, &o, &cp), 0);   /* 3% < the 5% floor */
    o.min_magnitude = 0.01;
    assert_int_equal(changepoint_find(x, 50, &o, &cp), 1);
    assert_true(cp[0].index + 2 >= at && cp[0].index <= at + 2);
    assert_true(cp[0].pvalue < 1e-6);
    free(cp);
}

static void test_t_pvalue(void **state)
{
    (void)state;
    assert_near(changepoint_t_pvalue(2.228139, 10), 0.05, 1e-6);   /* t(10), 97.5% */
    assert_near(changepoint_t_pvalue(-2.228139, 10), 0.05, 1e-6);
    assert_near(changepoint_t_pvalue(1.959964, 1e7), 0.05, 1e-5);   /* the normal's */
    assert_near(changepoint_t_pvalue(0, 5), 1, 1e-12);
    assert_near(changepoint_t_pvalue(INFINITY, 5), 0, 0);
}

static void test_remove_drift(void **state)
{
    (void)state;
    enum { R = 6, S = 12 };
    double v[R * S], drift[S];
    for (size_t r = 0; r < R; r++)
        for (size_t s = 0; s < S; s++)   /* the machine 12% faster from sweep 4 */
            v[r * S + s] = (100.0 + 50 * (double)r) * (s >= 4 ? 0.88 : 1) *
                           (r == 2 && s >= 8 ? 1.10 : 1);
    changepoint_remove_drift(v, R, S, 5, drift);
    for (size_t s = 0; s < S; s++)
        for (size_t r = 0; r < R; r++) {
            double want = (100.0 + 50 * (double)r) * 0.88 * (r == 2 && s >= 8 ? 1.10 : 1);
            /* at the runs' median level: the machine's after sweep 4 */
            assert_near(v[r * S + s] / want, 1, 1e-12);
        }
    assert_near(drift[0], 1 / 0.88, 1e-12);
    assert_near(drift[5], 1, 1e-12);
    /* under min_runs: not estimated, untouched */
    double w[4 * 2] = {1, 2, 1, 2, 1, 2, 1, 2};
    changepoint_remove_drift(w, 4, 2, 5, drift);
    assert_near(w[1], 2, 0);
    assert_near(drift[1], 1, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_step),     cmocka_unit_test(test_two_steps),
        cmocka_unit_test(test_flat_none),    cmocka_unit_test(test_min_change_floor),
        cmocka_unit_test(test_t_pvalue),     cmocka_unit_test(test_remove_drift),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
