/* The common change between two folders (results/drift.c) on exact inputs: the median
 * follows the unchanged runs and not the changed one, the floor from the runs' own
 * intervals, the spread's interval (MAD), fewer runs than DRIFT_MIN_RUNS, and the
 * corrected ratio with its widened interval. t(4) = 2.776445 written out. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/unit/assert_near.h"

#include <math.h>
#include <stdbool.h>

#include "results/drift.h"

#define EPS 1e-12

/* a ratio with a log half-width h */
static ratio_ci rc(double ratio, double h)
{
    return (ratio_ci){.ratio = ratio, .lo = ratio * exp(-h), .hi = ratio * exp(h), .n = 5};
}

static void test_drift_one_changed_run(void **state)
{
    (void)state;
    /* five runs 12% faster (the machine), one of them also +10% (0.968) */
    ratio_ci r[6];
    for (int i = 0; i < 6; i++)
        r[i] = rc(i == 3 ? 0.88 * 1.10 : 0.88, 0.01);
    common_change c;
    assert_true(drift_common_change(r, 6, &c));
    assert_int_equal(c.n, 6);
    /* median of the logs: log 0.88; MAD 0, so the floor: 1.2533 0.01 / sqrt(6) */
    double hc = 1.2533141373155 * 0.01 / sqrt(6);
    assert_near(c.ratio, 0.88, EPS);
    assert_near(c.lo, 0.88 * exp(-hc), EPS);
    assert_near(c.hi, 0.88 * exp(hc), EPS);
    assert_true(c.applied);
    ratio_ci out;
    drift_correct(&r[3], &c, &out);
    /* 0.968 / 0.88 = 1.1, half-width sqrt(0.01^2 + hc^2) */
    double h = sqrt(0.01 * 0.01 + hc * hc);
    assert_near(out.ratio, 1.1, EPS);
    assert_near(out.lo, 1.1 * exp(-h), EPS);
    assert_near(out.hi, 1.1 * exp(h), EPS);
    assert_int_equal(verdict_of(&out, 0.05), VERDICT_SLOWER);
    drift_correct(&r[0], &c, &out);
    assert_near(out.ratio, 1, EPS);
    assert_int_equal(verdict_of(&out, 0.05), VERDICT_SAME);
    assert_int_equal(verdict_of(&r[0], 0.05), VERDICT_FASTER);   /* raw */
}

static void test_drift_spread_holds_one(void **state)
{
    (void)state;
    /* logs -0.02 -0.01 0 0.01 0.02: median 0, MAD 0.01, t(4) 1.2533 1.4826 0.01 / sqrt 5 */
    ratio_ci r[5];
    for (int i = 0; i < 5; i++)
        r[i] = rc(exp((i - 2) * 0.01), 0.001);
    common_change c;
    assert_true(drift_common_change(r, 5, &c));
    double half = 2.776445 * 1.2533141373155 * 1.4826 * 0.01 / sqrt(5);
    assert_near(c.ratio, 1, EPS);
    assert_near(c.lo, exp(-half), 1e-8);
    assert_near(c.hi, exp(half), 1e-8);
    assert_false(c.applied);
    ratio_ci out;   /* not applied: the raw ratio as it is */
    drift_correct(&r[4], &c, &out);
    assert_near(out.ratio, r[4].ratio, 0);
    assert_near(out.lo, r[4].lo, 0);
    assert_near(out.hi, r[4].hi, 0);
}

static void test_drift_too_few_runs(void **state)
{
    (void)state;
    /* six runs, but two without an interval (fewer than 3 trials) and one NAN: 3 used */
    ratio_ci r[6];
    for (int i = 0; i < 6; i++)
        r[i] = rc(0.8, 0.01);
    r[1].lo = r[1].hi = NAN;
    r[2].lo = r[2].hi = NAN;
    r[5].ratio = NAN;
    common_change c;
    assert_false(drift_common_change(r, 6, &c));
    assert_int_equal(c.n, 3);
    assert_true(isnan(c.ratio) && isnan(c.lo) && isnan(c.hi));
    assert_false(c.applied);
    ratio_ci out;
    drift_correct(&r[0], &c, &out);
    assert_near(out.ratio, 0.8, 0);
    assert_false(drift_common_change(r, 0, &c));
    assert_int_equal(c.n, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_drift_one_changed_run),
        cmocka_unit_test(test_drift_spread_holds_one),
        cmocka_unit_test(test_drift_too_few_runs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
