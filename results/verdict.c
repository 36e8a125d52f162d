/* Trial-level statistics. See verdict.h. */
#include "results/verdict.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "results/stats.h"

/* Usable as a time (and as an argument of log). */
static bool usable(double v)
{
    return isfinite(v) && v > 0.0;
}

/* log(a / b) for usable a, b: the quotient first (exact for a == b, and more precise
 * when they are close), the difference of logs where it would overflow or underflow. */
static double log_ratio(double a, double b)
{
    double q = a / b;
    return usable(q) ? log(q) : log(a) - log(b);
}

static void ratio_unknown(ratio_ci *out, size_t n, bool paired)
{
    out->ratio = out->lo = out->hi = NAN;
    out->n = n;
    out->paired = paired;
}

void verdict_paired_ratio(const double *a, const double *b, size_t n, ratio_ci *out)
{
    size_t k = 0;
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (usable(a[i]) && usable(b[i])) {
            sum += log_ratio(a[i], b[i]);
            k++;
        }
    }
    ratio_unknown(out, k, true);
    if (k == 0)
        return;
    double m = sum / (double)k;
    out->ratio = exp(m);
    if (k < 3)
        return;
    double ss = 0.0;  /* second pass: no cancellation for nearly equal ratios */
    for (size_t i = 0; i < n; i++) {
        if (usable(a[i]) && usable(b[i])) {
            double d = log_ratio(a[i], b[i]) - m;
            ss += d * d;
        }
    }
    double half = stats_t975(k - 1) * sqrt(ss / (double)(k - 1)) / sqrt((double)k);
    out->lo = exp(m - half);
    out->hi = exp(m + half);
}

/* Mean and sample variance (n - 1) of the logs of the usable values; the count. */
static size_t log_moments(const double *x, size_t n, double *mean, double *var)
{
    size_t k = 0;
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (usable(x[i])) {
            sum += log(x[i]);
            k++;
        }
    }
    *mean = k > 0 ? sum / (double)k : NAN;
    double ss = 0.0;
    for (size_t i = 0; i < n && k > 1; i++) {
        if (usable(x[i])) {
            double d = log(x[i]) - *mean;
            ss += d * d;
        }
    }
    *var = k > 1 ? ss / (double)(k - 1) : NAN;
    return k;
}

void verdict_unpaired_ratio(const double *a, size_t na, const double *b, size_t nb,
                            ratio_ci *out)
{
    double ma, va, mb, vb;
    size_t ka = log_moments(a, na, &ma, &va);
    size_t kb = log_moments(b, nb, &mb, &vb);
    ratio_unknown(out, ka < kb ? ka : kb, false);
    if (ka == 0 || kb == 0)
        return;
    double d = ma - mb;
    out->ratio = exp(d);
    if (ka < 3 || kb < 3)
        return;
    double wa = va / (double)ka, wb = vb / (double)kb;
    double se2 = wa + wb;
    if (!(se2 > 0.0)) {   /* both samples constant: no spread to widen the interval */
        out->lo = out->hi = out->ratio;
        return;
    }
    /* Welch-Satterthwaite, with both terms scaled by the larger so that tiny
     * variances cannot underflow its squares. */
    double big = wa > wb ? wa : wb;
    double ra = wa / big, rb = wb / big;
    double dof = (ra + rb) * (ra + rb) /
                 (ra * ra / (double)(ka - 1) + rb * rb / (double)(kb - 1));
    double half = stats_t975_real(dof) * sqrt(se2);
    out->lo = exp(d - half);
    out->hi = exp(d + half);
}

verdict verdict_of(const ratio_ci *r, double threshold)
{
    if (r->n < 3 || isnan(r->lo) || isnan(r->hi) || !(threshold >= 0.0))
        return VERDICT_NONE;
    double up = 1.0 + threshold, down = 1.0 / up;
    if (r->lo > up)
        return VERDICT_SLOWER;
    if (r->hi < down)
        return VERDICT_FASTER;
    if (r->lo >= down && r->hi <= up)
        return VERDICT_SAME;
    return VERDICT_UNDECIDED;
}

const char *verdict_name(verdict v)
{
    switch (v) {
    case VERDICT_NONE: return "no verdict";
    case VERDICT_SAME: return "same";
    case VERDICT_SLOWER: return "slower";
    case VERDICT_FASTER: return "faster";
    case VERDICT_UNDECIDED: return "undecided";
    }
    return "?";
}

size_t verdict_mean_ci(const double *x, size_t n, double *mean, double *half)
{
    size_t k = 0;
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (isfinite(x[i])) {
            sum += x[i];
            k++;
        }
    }
    *mean = k > 0 ? sum / (double)k : NAN;
    *half = NAN;
    if (k < 2)
        return k;
    double ss = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (isfinite(x[i])) {
            double d = x[i] - *mean;
            ss += d * d;
        }
    }
    *half = stats_t975(k - 1) * sqrt(ss / (double)(k - 1)) / sqrt((double)k);
    return k;
}

bool verdict_all_decided(const ratio_ci *r, size_t nr, double precision)
{
    double wide = (1.0 + precision) * (1.0 + precision);
    for (size_t i = 0; i < nr; i++) {
        if (r[i].n < 3 || !(r[i].lo > 0.0) || !(r[i].hi > 0.0))
            return false;   /* also NAN bounds */
        bool narrow = r[i].hi / r[i].lo <= wide;
        bool excludes_one = r[i].lo > 1.0 || r[i].hi < 1.0;
        if (!narrow && !excludes_one)
            return false;
    }
    return true;
}

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* Median of n >= 1 values, sorting them in place. */
static double median_in_place(double *v, size_t n)
{
    qsort(v, n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

size_t verdict_median(const double *x, size_t n, double *scratch, double *median)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i]))
            scratch[k++] = x[i];
    *median = k ? median_in_place(scratch, k) : NAN;
    return k;
}

size_t verdict_outliers(const double *x, size_t n, bool *out)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        out[i] = false;
        k += isfinite(x[i]) ? 1 : 0;
    }
    if (k < 3)
        return 0;
    double *v = k <= SIZE_MAX / sizeof *v ? malloc(k * sizeof *v) : NULL;
    if (v == NULL)
        return 0;
    size_t j = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i]))
            v[j++] = x[i];
    double med = median_in_place(v, k);
    for (size_t i = 0; i < k; i++)
        v[i] = fabs(v[i] - med);
    double mad = median_in_place(v, k);
    free(v);

    size_t flagged = 0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]))
            continue;
        double above = x[i] - med;
        out[i] = mad > 0.0 ? 0.6745 * above / mad > 3.5 : above > 0.01 * fabs(med);
        flagged += out[i] ? 1 : 0;
    }
    return flagged;
}

/* Where the curve through (xa, ca) and (xb, cb) reaches 0 (ca != cb, on opposite
 * sides of 0 or one of them 0): linear in log x, in x where xa <= 0. */
static double zero_between(double xa, double xb, double ca, double cb)
{
    double t = ca / (ca - cb);
    if (xa > 0.0)
        return exp(log(xa) + t * (log(xb) - log(xa)));
    return xa + t * (xb - xa);
}

/* The log of a bound as the crossing's direction sees it: for a rising ratio log(v),
 * for a falling one -log(v), so that both cross 0 upwards; NAN when unusable. */
static double oriented_log(double v, int dir)
{
    return usable(v) ? dir * log(v) : NAN;
}

bool verdict_crossover(const double *x, const ratio_ci *r, size_t n, size_t from,
                       ratio_crossover *out)
{
    /* The point curve: consecutive kept points on opposite sides of 1. */
    size_t i = SIZE_MAX;
    bool found = false;
    for (size_t k = from; k < n && !found; k++) {
        if (!isfinite(x[k]) || !usable(r[k].ratio) || r[k].ratio == 1.0)
            continue;
        if (i != SIZE_MAX && (r[i].ratio < 1.0) != (r[k].ratio < 1.0)) {
            out->i = i;
            out->j = k;
            found = true;
        } else {
            i = k;
        }
    }
    if (!found)
        return false;
    i = out->i;
    size_t j = out->j;
    int dir = r[i].ratio < 1.0 ? 1 : -1;
    out->dir = dir;
    double pi = log(r[i].ratio), pj = log(r[j].ratio);
    out->x = zero_between(x[i], x[j], pi, pj);

    /* Oriented so that each rises through 0: near = the bound that crosses first
     * (hi for a rising ratio), far = the one that crosses last. */
    out->lo = out->hi = NAN;
    size_t prev_near = SIZE_MAX, prev_far = SIZE_MAX;
    for (size_t k = 0; k < n; k++) {
        if (!isfinite(x[k]))
            continue;
        double near = oriented_log(dir > 0 ? r[k].hi : r[k].lo, dir);
        double far = oriented_log(dir > 0 ? r[k].lo : r[k].hi, dir);
        if (!isnan(near)) {
            if (prev_near != SIZE_MAX && prev_near < j) {
                double c = oriented_log(dir > 0 ? r[prev_near].hi : r[prev_near].lo, dir);
                if (c < 0.0 && near >= 0.0)   /* the last such rise before x[j] */
                    out->lo = zero_between(x[prev_near], x[k], c, near);
            }
            prev_near = k;
        }
        if (!isnan(far)) {
            if (prev_far != SIZE_MAX && k > i && isnan(out->hi)) {
                double c = oriented_log(dir > 0 ? r[prev_far].lo : r[prev_far].hi, dir);
                if (c <= 0.0 && far > 0.0)    /* the first such rise after x[i] */
                    out->hi = zero_between(x[prev_far], x[k], c, far);
            }
            prev_far = k;
        }
    }
    return true;
}
