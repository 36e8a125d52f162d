/* Trial-level statistics: ratios and their intervals, verdicts, the adaptive stop,
 * outliers, crossovers. Every expected value is worked out by hand in the comment
 * next to it; t quantiles are written out (t(2) = 4.302653, t(3) = 3.182446,
 * t(5) = 2.570582) rather than taken from stats_t975. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/unit/assert_near.h"

#include <math.h>
#include <stdbool.h>

#include "results/verdict.h"

#define EPS 1e-12
#define T2 4.302653
#define T3 3.182446
#define T5 2.570582
/* The quantiles above carry 7 digits: a half-width of about 0.1 moves by < 1e-7. */
#define TEPS 1e-6

/* >>paired */

static void test_paired_exact_ratio(void **state)
{
    (void)state;
    /* a = 1.25 b exactly (every product is exact in binary) */
    const double b[] = {10, 12, 15, 20};
    const double a[] = {12.5, 15, 18.75, 25};
    ratio_ci r;
    verdict_paired_ratio(a, b, 4, &r);
    assert_int_equal(r.n, 4);
    assert_true(r.paired);
    assert_near(r.ratio, 1.25, EPS);
    assert_near(r.lo, 1.25, EPS); /* every round says 1.25: zero width */
    assert_near(r.hi, 1.25, EPS);
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_SLOWER);
    assert_int_equal(verdict_of(&r, 0.0), VERDICT_SLOWER);
    assert_int_equal(verdict_of(&r, 0.30), VERDICT_SAME);

    /* the other way round: 0.8, faster */
    verdict_paired_ratio(b, a, 4, &r);
    assert_near(r.ratio, 0.8, EPS);
    assert_near(r.lo, 0.8, EPS);
    assert_near(r.hi, 0.8, EPS);
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_FASTER);
    assert_int_equal(verdict_of(&r, 0.0), VERDICT_FASTER);
}

static void test_paired_equal_is_same(void **state)
{
    (void)state;
    const double a[] = {3.1, 7.0, 11.5, 2.25, 9.0};
    ratio_ci r;
    verdict_paired_ratio(a, a, 5, &r);
    assert_int_equal(r.n, 5);
    /* log(a / a) = log 1 = 0 exactly: the interval is [1, 1] */
    assert_near(r.ratio, 1.0, 0);
    assert_near(r.lo, 1.0, 0);
    assert_near(r.hi, 1.0, 0);
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_SAME);
    assert_int_equal(verdict_of(&r, 0.0), VERDICT_SAME);
    assert_string_equal(verdict_name(verdict_of(&r, 0.05)), "same");
}

static void test_paired_unusable_pairs_left_out(void **state)
{
    (void)state;
    /* rounds 1 (NAN), 3 (b = 0), 5 (a < 0) and 6 (b infinite) are left out; the
     * other four are exactly 1.25 */
    const double a[] = {12.5, NAN, 15, 7, 18.75, -1, 3, 25};
    const double b[] = {10, 11, 12, 0, 15, 2, INFINITY, 20};
    ratio_ci r;
    verdict_paired_ratio(a, b, 8, &r);
    assert_int_equal(r.n, 4);
    assert_near(r.ratio, 1.25, EPS);
    assert_near(r.lo, 1.25, EPS);
    assert_near(r.hi, 1.25, EPS);
}

/* b[i] = 1 + i and a[i] = b[i] exp(d[i]): the log ratios are d. */
static void paired_from_logs(const double *d, size_t n, ratio_ci *r)
{
    double a[8], b[8];
    for (size_t i = 0; i < n; i++) {
        b[i] = 1.0 + (double)i;
        a[i] = b[i] * exp(d[i]);
    }
    verdict_paired_ratio(a, b, n, r);
}

static void test_paired_t_interval(void **state)
{
    (void)state;
    ratio_ci r;
    /* logs 0.1, 0.2, 0.3: mean 0.2, deviations -0.1, 0, 0.1 -> ss 0.02, sd
     * sqrt(0.02 / 2) = 0.1; half = t(2) 0.1 / sqrt(3) = 0.248414 */
    const double d1[] = {0.1, 0.2, 0.3};
    paired_from_logs(d1, 3, &r);
    double half = T2 * 0.1 / sqrt(3.0);
    assert_int_equal(r.n, 3);
    assert_near(r.ratio, exp(0.2), EPS);
    assert_near(r.lo, exp(0.2 - half), TEPS); /* 0.9527 */
    assert_near(r.hi, exp(0.2 + half), TEPS); /* 1.5655 */
    /* 0.9527 < 1.05 < 1.5655: straddles the threshold */
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_UNDECIDED);
    assert_int_equal(verdict_of(&r, 0.0), VERDICT_UNDECIDED); /* contains 1 */
    assert_string_equal(verdict_name(VERDICT_UNDECIDED), "undecided");

    /* logs 0.2, 0.25, 0.3: mean 0.25, sd 0.05; half = t(2) 0.05 / sqrt(3) = 0.124207;
     * lo = exp(0.125793) = 1.1340 > 1.05: slower */
    const double d2[] = {0.2, 0.25, 0.3};
    paired_from_logs(d2, 3, &r);
    half = T2 * 0.05 / sqrt(3.0);
    assert_near(r.ratio, exp(0.25), EPS);
    assert_near(r.lo, exp(0.25 - half), TEPS);
    assert_near(r.hi, exp(0.25 + half), TEPS);
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_SLOWER);
    assert_int_equal(verdict_of(&r, 0.15), VERDICT_UNDECIDED); /* 1.134 < 1.15 */

    /* logs -0.01, 0.01, -0.02, 0.02: mean 0, ss 0.0001 + 0.0001 + 0.0004 + 0.0004 =
     * 0.001, sd sqrt(0.001 / 3); half = t(3) sd / 2 = 0.029052: [0.97137, 1.02948] */
    const double d3[] = {-0.01, 0.01, -0.02, 0.02};
    paired_from_logs(d3, 4, &r);
    half = T3 * sqrt(0.001 / 3.0) / 2.0;
    assert_int_equal(r.n, 4);
    assert_near(r.ratio, 1.0, EPS);
    assert_near(r.lo, exp(-half), TEPS);
    assert_near(r.hi, exp(half), TEPS);
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_SAME);      /* inside [0.952, 1.05] */
    assert_int_equal(verdict_of(&r, 0.01), VERDICT_UNDECIDED); /* 1.029 > 1.01 */
    assert_int_equal(verdict_of(&r, 0.0), VERDICT_UNDECIDED);  /* contains 1 */
    assert_int_equal(verdict_of(&r, NAN), VERDICT_NONE);
    assert_int_equal(verdict_of(&r, -0.1), VERDICT_NONE);

    /* B / A is the reciprocal interval */
    const double d4[] = {-0.1, -0.2, -0.3};
    ratio_ci inv;
    paired_from_logs(d4, 3, &inv);
    paired_from_logs(d1, 3, &r);
    assert_near(inv.ratio, 1.0 / r.ratio, EPS);
    assert_near(inv.lo, 1.0 / r.hi, EPS);
    assert_near(inv.hi, 1.0 / r.lo, EPS);
}

static void test_paired_too_few(void **state)
{
    (void)state;
    /* two rounds: a point estimate (sqrt(1.5 * 2.0)), no interval, no verdict */
    const double a[] = {3, 4};
    const double b[] = {2, 2};
    ratio_ci r;
    verdict_paired_ratio(a, b, 2, &r);
    assert_int_equal(r.n, 2);
    assert_near(r.ratio, sqrt(3.0), EPS);
    assert_true(isnan(r.lo) && isnan(r.hi));
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_NONE);
    assert_string_equal(verdict_name(VERDICT_NONE), "no verdict");

    /* three rounds, one unusable: still two */
    const double a3[] = {3, NAN, 4};
    const double b3[] = {2, 2, 2};
    verdict_paired_ratio(a3, b3, 3, &r);
    assert_int_equal(r.n, 2);
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_NONE);

    /* nothing */
    verdict_paired_ratio(NULL, NULL, 0, &r);
    assert_int_equal(r.n, 0);
    assert_true(isnan(r.ratio) && isnan(r.lo) && isnan(r.hi));
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_NONE);
}

/* >>unpaired */

static void test_unpaired_welch(void **state)
{
    (void)state;
    /* logs of a: 0.3, 0.4, 0.5 (mean 0.4, var 0.02 / 2 = 0.01);
     * logs of b: -0.1 .. 0.3 by 0.1 (mean 0.1, ss 0.04 + 0.01 + 0 + 0.01 + 0.04 = 0.1,
     * var 0.1 / 4 = 0.025). d = 0.3; wa = 0.01 / 3, wb = 0.025 / 5 = 0.005;
     * se^2 = 0.0083333; dof = se^4 / (wa^2 / 2 + wb^2 / 4) = 6.9444e-5 / 1.18056e-5
     * = 5.88, floored to 5 */
    const double a[] = {exp(0.3), exp(0.4), exp(0.5)};
    const double b[] = {exp(-0.1), exp(0.0), exp(0.1), exp(0.2), exp(0.3)};
    double wa = 0.01 / 3.0, wb = 0.005, se2 = wa + wb;
    double dof = se2 * se2 / (wa * wa / 2.0 + wb * wb / 4.0);
    assert_true(dof > 5.0 && dof < 6.0);
    double half = T5 * sqrt(se2); /* 0.234663 */
    ratio_ci r;
    verdict_unpaired_ratio(a, 3, b, 5, &r);
    assert_false(r.paired);
    assert_int_equal(r.n, 3);
    assert_near(r.ratio, exp(0.3), EPS);
    assert_near(r.lo, exp(0.3 - half), TEPS); /* 1.0673 */
    assert_near(r.hi, exp(0.3 + half), TEPS); /* 1.7066 */
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_SLOWER);
    assert_int_equal(verdict_of(&r, 0.10), VERDICT_UNDECIDED);

    /* swapped: the reciprocal */
    ratio_ci s;
    verdict_unpaired_ratio(b, 5, a, 3, &s);
    assert_near(s.ratio, exp(-0.3), EPS);
    assert_near(s.lo, 1.0 / r.hi, EPS);
    assert_near(s.hi, 1.0 / r.lo, EPS);
    assert_int_equal(verdict_of(&s, 0.05), VERDICT_FASTER);
}

static void test_unpaired_edges(void **state)
{
    (void)state;
    ratio_ci r;
    /* both constant: 2 exactly, zero width */
    const double two[] = {2, 2, 2};
    const double one[] = {1, 1, 1, 1};
    verdict_unpaired_ratio(two, 3, one, 4, &r);
    assert_near(r.ratio, 2.0, EPS);
    assert_near(r.lo, 2.0, EPS);
    assert_near(r.hi, 2.0, EPS);
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_SLOWER);

    /* one constant: dof = that of the other, 2; logs of b 0, 0.1, 0.2 (var 0.01);
     * d = log 2 - 0.1; half = t(2) sqrt(0.01 / 3) */
    const double b[] = {1.0, exp(0.1), exp(0.2)};
    verdict_unpaired_ratio(two, 3, b, 3, &r);
    double half = T2 * sqrt(0.01 / 3.0);
    assert_near(r.ratio, 2.0 / exp(0.1), EPS);
    assert_near(r.lo, exp(log(2.0) - 0.1 - half), TEPS);
    assert_near(r.hi, exp(log(2.0) - 0.1 + half), TEPS);

    /* unusable values left out: b keeps 2 of 4, so n = 2, no interval */
    const double b2[] = {1.0, NAN, -3.0, 1.5};
    verdict_unpaired_ratio(two, 3, b2, 4, &r);
    assert_int_equal(r.n, 2);
    assert_near(r.ratio, 2.0 / sqrt(1.5), EPS); /* geometric mean of b: sqrt(1.5) */
    assert_true(isnan(r.lo) && isnan(r.hi));
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_NONE);

    /* nothing on one side */
    verdict_unpaired_ratio(two, 3, NULL, 0, &r);
    assert_int_equal(r.n, 0);
    assert_true(isnan(r.ratio) && isnan(r.lo) && isnan(r.hi));
}

/* >>verdicts */

static ratio_ci ci(double lo, double ratio, double hi, size_t n)
{
    ratio_ci r = {.ratio = ratio, .lo = lo, .hi = hi, .n = n, .paired = true};
    return r;
}

static void test_verdict_bounds(void **state)
{
    (void)state;
    /* th = 0.05: [1/1.05, 1.05] = [0.952381, 1.05] */
    ratio_ci r = ci(0.96, 1.0, 1.04, 5);
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_SAME);
    r = ci(1.0 / 1.05, 1.0, 1.05, 5); /* the bounds themselves: still inside */
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_SAME);
    r = ci(1.02, 1.04, 1.06, 5);      /* surely slower, but maybe by less than 5% */
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_UNDECIDED);
    assert_int_equal(verdict_of(&r, 0.0), VERDICT_SLOWER);
    r = ci(1.051, 1.1, 1.2, 5);
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_SLOWER);
    r = ci(1.05, 1.1, 1.2, 5);        /* lo exactly at 1 + th: not beyond it */
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_UNDECIDED);
    r = ci(0.8, 0.85, 0.95, 5);       /* 0.95 < 0.952381 */
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_FASTER);
    r = ci(0.8, 0.9, 0.96, 5);        /* 0.96 > 0.952381 */
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_UNDECIDED);
    r = ci(0.5, 1.0, 2.0, 5);         /* straddles both */
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_UNDECIDED);
    r = ci(1.1, 1.2, 1.3, 2);         /* n < 3, whatever the bounds say */
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_NONE);
    r = ci(NAN, 1.2, NAN, 5);
    assert_int_equal(verdict_of(&r, 0.05), VERDICT_NONE);

    assert_string_equal(verdict_name(VERDICT_SLOWER), "slower");
    assert_string_equal(verdict_name(VERDICT_FASTER), "faster");
    assert_string_equal(verdict_name((verdict)42), "?");
}

static void test_all_decided(void **state)
{
    (void)state;
    /* precision 0.02: narrow means hi / lo <= 1.02^2 = 1.0404 */
    ratio_ci r[3];
    r[0] = ci(0.99, 1.0, 1.01, 5);  /* 1.0202: narrow, contains 1 */
    r[1] = ci(1.1, 1.3, 1.5, 5);    /* wide, excludes 1 */
    assert_true(verdict_all_decided(r, 2, 0.02));
    r[2] = ci(0.9, 1.0, 1.1, 5);    /* 1.222: wide, contains 1 */
    assert_false(verdict_all_decided(r, 3, 0.02));
    assert_true(verdict_all_decided(r, 3, 0.11)); /* 1.2321 >= 1.222 */
    r[2] = ci(0.5, 0.6, 0.9, 5);    /* wide, excludes 1 below */
    assert_true(verdict_all_decided(r, 3, 0.02));
    r[2] = ci(0.99, 0.995, 1.0, 5); /* hi == 1 does not exclude 1, but narrow */
    assert_true(verdict_all_decided(r, 3, 0.02));
    r[2] = ci(0.6, 0.8, 1.0, 5);    /* hi == 1 does not exclude 1, and wide */
    assert_false(verdict_all_decided(r, 3, 0.02));

    /* n < 3 is never decided, however narrow */
    r[2] = ci(1.0, 1.0, 1.0, 2);
    assert_false(verdict_all_decided(r, 3, 0.02));
    r[2] = ci(NAN, 1.0, NAN, 5);
    assert_false(verdict_all_decided(r, 3, 0.02));

    /* nothing to decide */
    assert_true(verdict_all_decided(NULL, 0, 0.02));

    /* from the functions: the exact 1.25 is decided, two rounds are not */
    const double b[] = {10, 12, 15, 20};
    const double a[] = {12.5, 15, 18.75, 25};
    verdict_paired_ratio(a, b, 4, &r[0]);
    verdict_paired_ratio(a, b, 2, &r[1]);
    assert_true(verdict_all_decided(r, 1, 0.01));
    assert_false(verdict_all_decided(r, 2, 0.01));
}

/* >>mean */

static void test_mean_ci(void **state)
{
    (void)state;
    double m, h;
    /* 1, 2, 3: mean 2, sd 1, half t(2) / sqrt(3) */
    const double x[] = {1, NAN, 2, INFINITY, 3};
    assert_int_equal(verdict_mean_ci(x, 5, &m, &h), 3);
    assert_near(m, 2.0, EPS);
    assert_near(h, T2 / sqrt(3.0), TEPS);

    const double one[] = {16.5};
    assert_int_equal(verdict_mean_ci(one, 1, &m, &h), 1);
    assert_near(m, 16.5, 0);
    assert_true(isnan(h));

    assert_int_equal(verdict_mean_ci(NULL, 0, &m, &h), 0);
    assert_true(isnan(m) && isnan(h));
}

/* >>outliers */

/* The median of the finite values: odd count, even count (the middle two averaged),
 * none. */
static void test_median(void **state)
{
    (void)state;
    double scratch[4], m;
    const double odd[] = {3.0, NAN, 1.0, 2.0};
    assert_int_equal(verdict_median(odd, 4, scratch, &m), 3);
    assert_true(m == 2.0);
    const double even[] = {4.0, 1.0, 3.0, 2.0};
    assert_int_equal(verdict_median(even, 4, scratch, &m), 4);
    assert_true(m == 2.5);
    const double none[] = {NAN, INFINITY};
    assert_int_equal(verdict_median(none, 2, scratch, &m), 0);
    assert_true(isnan(m));
}

static void test_outliers_flagged(void **state)
{
    (void)state;
    /* sorted 5, 9.9, 9.95, 10, 10.05, 10.1, 20: median 10; |x - 10| sorted 0, 0.05,
     * 0.05, 0.1, 0.1, 5, 10: MAD 0.1. 20: 0.6745 * 10 / 0.1 = 67.5 > 3.5, flagged;
     * 5: z = -33.7, fast, not flagged (one-sided); NAN: left out */
    const double x[] = {10, 10.1, 9.9, NAN, 10.05, 9.95, 20, 5};
    bool out[8] = {true, true, true, true, true, true, false, true};
    assert_int_equal(verdict_outliers(x, 8, out), 1);
    for (int i = 0; i < 8; i++)
        assert_int_equal(out[i], i == 6);
}

static void test_outliers_threshold(void **state)
{
    (void)state;
    /* 1..8 and v >= 9: median 5 (the 5th of 9); |x - 5| = 4,3,2,1,0,1,2,3,v-5 sorted
     * 0,1,1,2,2,3,3,4,v-5: MAD 2. Flagged when 0.6745 (v - 5) / 2 > 3.5, i.e.
     * v > 5 + 7 / 0.6745 = 15.378 */
    double x[9] = {1, 2, 3, 4, 5, 6, 7, 8, 15.3};
    bool out[9];
    assert_int_equal(verdict_outliers(x, 9, out), 0);
    x[8] = 15.5;
    assert_int_equal(verdict_outliers(x, 9, out), 1);
    assert_true(out[8]);
    for (int i = 0; i < 8; i++)
        assert_false(out[i]);

    /* an even count: 1..9 and v >= 10: median (5 + 6) / 2 = 5.5; |x - 5.5| sorted
     * 0.5, 0.5, 1.5, 1.5, 2.5, 2.5, 3.5, 3.5, 4.5, v-5.5: MAD (2.5 + 2.5) / 2 = 2.5.
     * Flagged when v > 5.5 + 3.5 * 2.5 / 0.6745 = 18.473 */
    double y[10] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 18.4};
    bool yout[10];
    assert_int_equal(verdict_outliers(y, 10, yout), 0);
    y[9] = 18.6;
    assert_int_equal(verdict_outliers(y, 10, yout), 1);
    assert_true(yout[9]);
}

static void test_outliers_mad_zero(void **state)
{
    (void)state;
    bool out[5];
    /* median 10, MAD 0: 10.05 is 0.5% above, not flagged */
    const double a[] = {10, 10, 10, 10.05, 10};
    assert_int_equal(verdict_outliers(a, 5, out), 0);
    /* 10.2 is 2% above: flagged */
    const double b[] = {10, 10, 10, 10.2, 10};
    assert_int_equal(verdict_outliers(b, 5, out), 1);
    assert_true(out[3]);
    /* 9 is 10% below: fast, not flagged */
    const double c[] = {10, 9, 10, 10, 10};
    assert_int_equal(verdict_outliers(c, 5, out), 0);
    /* NAN left out: 10, 10, 10, 30: median 10, MAD median(0, 0, 0, 20) = 0; 30 flagged */
    const double d[] = {10, NAN, 10, 10, 30};
    assert_int_equal(verdict_outliers(d, 5, out), 1);
    assert_false(out[1]);
    assert_true(out[4]);
    /* fewer than 3 finite values: none */
    const double e[] = {1, 100, NAN};
    out[1] = true;
    assert_int_equal(verdict_outliers(e, 3, out), 0);
    assert_false(out[1]);
}

/* >>crossover */

/* The log ratio is slope (log x - log 20) and the interval +- h in logs, at
 * x = 1, 2, 4, ..., 256: a line in log x, which interpolation recovers exactly. */
static void line(double slope, double h, double *x, ratio_ci *r)
{
    for (int k = 0; k < 9; k++) {
        x[k] = ldexp(1.0, k);
        double p = slope * (log(x[k]) - log(20.0));
        r[k] = ci(exp(p - h), exp(p), exp(p + h), 5);
    }
}

static void test_crossover_line(void **state)
{
    (void)state;
    double x[9];
    ratio_ci r[9];
    ratio_crossover c;

    /* rising: A / B = 1 at 20 (between 16 and 32); hi reaches 1 where
     * 0.25 (log x - log 20) = -0.1, x = 20 exp(-0.4) = 13.406; lo where it is +0.1,
     * x = 20 exp(0.4) = 29.836 */
    line(0.25, 0.1, x, r);
    assert_true(verdict_crossover(x, r, 9, 0, &c));
    assert_int_equal(c.i, 4);
    assert_int_equal(c.j, 5);
    assert_int_equal(c.dir, 1);
    assert_near(c.x, 20.0, 1e-9);
    assert_near(c.lo, 20.0 * exp(-0.4), 1e-9);
    assert_near(c.hi, 20.0 * exp(0.4), 1e-9);
    assert_false(verdict_crossover(x, r, 9, c.j, &c));

    /* falling: the same points, the bounds' roles swapped */
    line(-0.25, 0.1, x, r);
    assert_true(verdict_crossover(x, r, 9, 0, &c));
    assert_int_equal(c.dir, -1);
    assert_near(c.x, 20.0, 1e-9);
    assert_near(c.lo, 20.0 * exp(-0.4), 1e-9);
    assert_near(c.hi, 20.0 * exp(0.4), 1e-9);

    /* narrow: both bounds cross within the same segment as the estimate, 16 .. 32,
     * at 20 exp(-+0.2) = 16.375 and 24.428 */
    line(0.25, 0.05, x, r);
    assert_true(verdict_crossover(x, r, 9, 0, &c));
    assert_near(c.lo, 20.0 * exp(-0.2), 1e-9);
    assert_near(c.hi, 20.0 * exp(0.2), 1e-9);

    /* wide: the bounds would cross at 20 exp(-+8), outside 1 .. 256 */
    line(0.25, 2.0, x, r);
    assert_true(verdict_crossover(x, r, 9, 0, &c));
    assert_near(c.x, 20.0, 1e-9);
    assert_true(isnan(c.lo) && isnan(c.hi));

    /* from past the crossing: none */
    line(0.25, 0.1, x, r);
    assert_false(verdict_crossover(x, r, 9, 5, &c));
}

static void test_crossover_points(void **state)
{
    (void)state;
    ratio_crossover c;
    /* a 0 on the axis: linear in x; log 0.5 and log 2 are -+0.693, halfway: 5 */
    const double x0[] = {0, 10};
    ratio_ci r0[] = {ci(NAN, 0.5, NAN, 2), ci(NAN, 2.0, NAN, 2)};
    assert_true(verdict_crossover(x0, r0, 2, 0, &c));
    assert_near(c.x, 5.0, 1e-12);
    assert_true(isnan(c.lo) && isnan(c.hi)); /* no bounds */

    /* two crossings: up between 1 and 2, down between 3 and 4 (halfway in log x:
     * sqrt(12)); from c.j finds the second, then none */
    const double x[] = {1, 2, 3, 4};
    ratio_ci r[] = {ci(NAN, 0.5, NAN, 2), ci(NAN, 2.0, NAN, 2), ci(NAN, 2.0, NAN, 2),
                    ci(NAN, 0.5, NAN, 2)};
    assert_true(verdict_crossover(x, r, 4, 0, &c));
    assert_int_equal(c.i, 0);
    assert_int_equal(c.j, 1);
    assert_int_equal(c.dir, 1);
    assert_near(c.x, sqrt(2.0), 1e-12);
    assert_true(verdict_crossover(x, r, 4, c.j, &c));
    assert_int_equal(c.i, 2);
    assert_int_equal(c.j, 3);
    assert_int_equal(c.dir, -1);
    assert_near(c.x, sqrt(12.0), 1e-12);
    assert_false(verdict_crossover(x, r, 4, c.j, &c));

    /* a ratio of exactly 1 (and a NAN one) skipped: between 1 and 4, at 2 */
    const double x3[] = {1, 2, 3, 4};
    ratio_ci r3[] = {ci(NAN, 0.5, NAN, 2), ci(NAN, 1.0, NAN, 2), ci(NAN, NAN, NAN, 0),
                     ci(NAN, 2.0, NAN, 2)};
    assert_true(verdict_crossover(x3, r3, 4, 0, &c));
    assert_int_equal(c.i, 0);
    assert_int_equal(c.j, 3);
    assert_near(c.x, 2.0, 1e-12);

    /* always faster: none */
    ratio_ci below[] = {ci(NAN, 0.5, NAN, 2), ci(NAN, 0.9, NAN, 2), ci(NAN, 0.7, NAN, 2),
                        ci(NAN, 0.99, NAN, 2)};
    assert_false(verdict_crossover(x, below, 4, 0, &c));
    assert_false(verdict_crossover(NULL, NULL, 0, 0, &c));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paired_exact_ratio),
        cmocka_unit_test(test_median),
        cmocka_unit_test(test_paired_equal_is_same),
        cmocka_unit_test(test_paired_unusable_pairs_left_out),
        cmocka_unit_test(test_paired_t_interval),
        cmocka_unit_test(test_paired_too_few),
        cmocka_unit_test(test_unpaired_welch),
        cmocka_unit_test(test_unpaired_edges),
        cmocka_unit_test(test_verdict_bounds),
        cmocka_unit_test(test_all_decided),
        cmocka_unit_test(test_mean_ci),
        cmocka_unit_test(test_outliers_flagged),
        cmocka_unit_test(test_outliers_threshold),
        cmocka_unit_test(test_outliers_mad_zero),
        cmocka_unit_test(test_crossover_line),
        cmocka_unit_test(test_crossover_points),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
