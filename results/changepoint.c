/* E-divisive means with a t-test, after Apache Otava's otava/analysis.py (split, merge,
 * TTestSignificanceTester) and otava/change_point_divisive/ (detector.py, the candidate
 * of calculator.py): Matteson and James' E-divisive with power 1, each candidate kept
 * while its t-test is significant (Otava's replacement of the permutation test). The
 * sweeps' common drift, removed before it, is the median idea of results/drift.c over
 * a series. docs/notes/history.md. */
#include "results/changepoint.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

cp_options changepoint_defaults(void)
{
    return (cp_options){.max_pvalue = 0.001, .min_magnitude = 0.05, .window_len = 50};
}

/* The continued fraction of the incomplete beta function (modified Lentz). */
static double beta_cf(double a, double b, double x)
{
    const double tiny = 1e-300;
    double c = 1, d = 1 - (a + b) * x / (a + 1);
    if (fabs(d) < tiny)
        d = tiny;
    d = 1 / d;
    double h = d;
    for (int m = 1; m <= 300; m++) {
        double m2 = 2.0 * m;
        double aa = m * (b - m) * x / ((a + m2 - 1) * (a + m2));
        d = 1 + aa * d;
        d = fabs(d) < tiny ? 1 / tiny : 1 / d;
        c = 1 + aa / c;
        if (fabs(c) < tiny)
            c = tiny;
        h *= d * c;
        aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1));
        d = 1 + aa * d;
        d = fabs(d) < tiny ? 1 / tiny : 1 / d;
        c = 1 + aa / c;
        if (fabs(c) < tiny)
            c = tiny;
        double del = d * c;
        h *= del;
        if (fabs(del - 1) < 1e-15)
            break;
    }
    return h;
}

/* I_x(a, b), the regularized incomplete beta function */
static double beta_inc(double a, double b, double x)
{
    if (x <= 0)
        return 0;
    if (x >= 1)
        return 1;
    double lbt = lgamma(a + b) - lgamma(a) - lgamma(b) + a * log(x) + b * log1p(-x);
    if (x < (a + 1) / (a + b + 2))
        return exp(lbt) * beta_cf(a, b, x) / a;
    return 1 - exp(lbt) * beta_cf(b, a, 1 - x) / b;
}

double changepoint_t_pvalue(double t, double dof)
{
    if (isnan(t) || !(dof > 0))
        return 1;
    if (isinf(t))
        return 0;
    return beta_inc(dof / 2, 0.5, dof / (dof + t * t));
}

static void mean_sd(const double *x, size_t n, double *mean, double *sd)
{
    double s = 0, q = 0;
    for (size_t i = 0; i < n; i++)
        s += x[i];
    *mean = s / (double)n;
    for (size_t i = 0; i < n; i++)
        q += (x[i] - *mean) * (x[i] - *mean);
    *sd = n >= 2 ? sqrt(q / (double)n) : 0;
}

/* Otava's TTestSignificanceTester.compare: x[a..b) against x[b..c), scipy's
 * ttest_ind_from_stats (equal variances) on numpy's population sd. */
static void t_test(const double *x, size_t a, size_t b, size_t c, change_point *cp)
{
    size_t n1 = b - a, n2 = c - b;
    mean_sd(x + a, n1, &cp->mean_before, &cp->stddev_before);
    mean_sd(x + b, n2, &cp->mean_after, &cp->stddev_after);
    double m1 = cp->mean_before, m2 = cp->mean_after;
    cp->t_value = 0;
    cp->pvalue = 1;
    if (n1 + n2 > 2) {
        double dof = (double)(n1 + n2 - 2);
        double sp2 = ((double)(n1 - 1) * cp->stddev_before * cp->stddev_before +
                      (double)(n2 - 1) * cp->stddev_after * cp->stddev_after) / dof;
        double se = sqrt(sp2 * (1.0 / (double)n1 + 1.0 / (double)n2));
        if (se > 0) {
            cp->t_value = (m2 - m1) / se;
            cp->pvalue = changepoint_t_pvalue(cp->t_value, dof);
        } else if (m1 != m2) {   /* two flat pieces at different levels */
            cp->t_value = m2 > m1 ? INFINITY : -INFINITY;
            cp->pvalue = 0;
        }
    }
    double fwd = m1 != 0 ? m2 / m1 - 1 : 0, bwd = m2 != 0 ? m1 / m2 - 1 : 0;
    cp->forward_change_percent = fwd * 100;
    cp->magnitude = fmax(fabs(fwd), fabs(bwd));
}

/* E-divisive's candidate in x[s..e): the tau of the largest
 * Q(tau, kappa) = 2 / (m + n) sum |X_i - Y_j| - 2m / ((m + n)(n - 1)) sum_{i<k} |X_i - X_k|
 *               - 2n / ((m + n)(m - 1)) sum_{j<k} |Y_j - Y_k|
 * over X = x[s..tau), Y = x[tau..kappa), s < tau < kappa <= e (calculator.py; a term
 * with n - 1 or m - 1 = 0 is 0). The sums grow one point at a time: O(len^3). */
static double candidate(const double *x, size_t s, size_t e, size_t *tau_out)
{
    double best = -INFINITY, wx = 0;
    for (size_t tau = s + 1; tau < e; tau++) {
        double n = (double)(tau - s), cross = 0, wy = 0;
        for (size_t i = s; i + 1 < tau; i++)   /* X gained x[tau - 1] */
            wx += fabs(x[i] - x[tau - 1]);
        for (size_t kappa = tau + 1; kappa <= e; kappa++) {
            size_t j = kappa - 1;   /* Y gained x[j] */
            for (size_t i = s; i < tau; i++)
                cross += fabs(x[i] - x[j]);
            for (size_t l = tau; l < j; l++)
                wy += fabs(x[l] - x[j]);
            double m = (double)(kappa - tau);
            double q = 2 / (m + n) * cross - (n > 1 ? 2 * m / ((m + n) * (n - 1)) * wx : 0) -
                       (m > 1 ? 2 * n / ((m + n) * (m - 1)) * wy : 0);
            if (q > best) {
                best = q;
                *tau_out = tau;
            }
        }
    }
    return best;
}

/* Stats of cps[k] between its neighbours (Otava's get_intervals), within x[0..n). */
static void restat(const double *x, size_t n, change_point *cps, size_t ncp, size_t k)
{
    size_t a = k ? cps[k - 1].index : 0, c = k + 1 < ncp ? cps[k + 1].index : n;
    t_test(x, a, cps[k].index, c, &cps[k]);
}

static void insert_sorted(change_point *cps, size_t *ncp, const change_point *cp)
{
    size_t k = 0;
    while (k < *ncp && cps[k].index < cp->index)
        k++;
    memmove(cps + k + 1, cps + k, (*ncp - k) * sizeof *cps);
    cps[k] = *cp;
    (*ncp)++;
}

/* detector.py's get_change_points over x[0..n): the best candidate among the pieces
 * between the change points so far, kept while significant at pmax. cps holds n. */
static size_t detect(const double *x, size_t n, double pmax, change_point *cps)
{
    size_t ncp = 0;
    for (;;) {
        double best = -INFINITY;
        size_t tau = 0, a = 0, c = n;
        for (size_t k = 0; k <= ncp; k++) {
            size_t s = k ? cps[k - 1].index : 0, e = k < ncp ? cps[k].index : n, t = 0;
            if (e - s < 2)
                continue;
            double q = candidate(x, s, e, &t);
            if (q > best) {
                best = q;
                tau = t, a = s, c = e;
            }
        }
        if (best == -INFINITY)
            break;
        change_point cp = {.index = tau, .qhat = best};
        t_test(x, a, tau, c, &cp);
        if (!(cp.pvalue <= pmax))
            break;
        insert_sorted(cps, &ncp, &cp);
    }
    return ncp;
}

size_t changepoint_find(const double *x, size_t n, const cp_options *o, change_point **out)
{
    *out = NULL;
    if (n < 3)
        return 0;
    size_t w = o->window_len < 2 ? 2 : o->window_len, step = w / 2;
    double p = o->max_pvalue;
    double weak_p = p < 0.05 ? p * 10 : p < 0.5 ? p * 2 : p;   /* analysis.py's first pass */
    change_point *cps = calloc(n, sizeof *cps), *local = calloc(n, sizeof *local);
    if (!cps || !local) {
        free(cps);
        free(local);
        return 0;
    }
    size_t ncp = 0;
    /* split: windows of w points, each step at least w / 2 or to the last new point */
    for (size_t start = 0; start < n;) {
        size_t end = start + w < n ? start + w : n;
        size_t nl = detect(x + start, end - start, weak_p, local), last = 0;
        for (size_t k = 0; k < nl; k++) {
            local[k].index += start;
            last = local[k].index;
            bool seen = false;
            for (size_t i = 0; i < ncp && !seen; i++)
                seen = cps[i].index == local[k].index;
            if (!seen)
                insert_sorted(cps, &ncp, &local[k]);
        }
        start = last > start + step ? last : start + step;
    }
    free(local);
    /* merge: drop the weakest (largest p; once all are significant, the smallest
     * change) until each left is significant and above the floor. Otava restats the
     * two after the one dropped; its neighbours on both sides change, all are restated. */
    for (size_t k = 0; k < ncp; k++)
        restat(x, n, cps, ncp, k);
    while (ncp) {
        size_t weak = 0;
        for (size_t k = 1; k < ncp; k++)
            if (cps[k].pvalue > cps[weak].pvalue)
                weak = k;
        if (cps[weak].pvalue < p) {
            weak = 0;
            for (size_t k = 1; k < ncp; k++)
                if (cps[k].magnitude < cps[weak].magnitude)
                    weak = k;
            if (cps[weak].magnitude > o->min_magnitude)
                break;
        }
        memmove(cps + weak, cps + weak + 1, (ncp - weak - 1) * sizeof *cps);
        ncp--;
        for (size_t k = 0; k < ncp; k++)
            restat(x, n, cps, ncp, k);
    }
    if (!ncp) {
        free(cps);
        return 0;
    }
    *out = cps;
    return ncp;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* median of the finite values of buf[0..n) (sorted in place); NAN when none */
static double median_finite(double *buf, size_t n)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(buf[i]))
            buf[k++] = buf[i];
    if (!k)
        return NAN;
    qsort(buf, k, sizeof *buf, cmp_double);
    return k % 2 ? buf[k / 2] : (buf[k / 2 - 1] + buf[k / 2]) / 2;
}

void changepoint_remove_drift(double *v, size_t nruns, size_t nsweeps, size_t min_runs,
                              double *drift)
{
    size_t big = nruns > nsweeps ? nruns : nsweeps;
    double *buf = malloc((big ? big : 1) * sizeof *buf);
    double *level = malloc((nruns ? nruns : 1) * sizeof *level);
    for (size_t s = 0; s < nsweeps; s++)
        drift[s] = 1;
    if (!buf || !level) {
        free(buf);
        free(level);
        return;
    }
    for (size_t r = 0; r < nruns; r++) {
        for (size_t s = 0; s < nsweeps; s++) {
            double x = v[r * nsweeps + s];
            buf[s] = x > 0 ? log(x) : NAN;
        }
        level[r] = median_finite(buf, nsweeps);
    }
    for (size_t s = 0; s < nsweeps; s++) {
        size_t k = 0;
        for (size_t r = 0; r < nruns; r++) {
            double x = v[r * nsweeps + s];
            if (x > 0 && isfinite(x) && isfinite(level[r]))
                buf[k++] = log(x) - level[r];
        }
        if (k < min_runs || !k)
            continue;
        drift[s] = exp(median_finite(buf, k));
        for (size_t r = 0; r < nruns; r++)
            v[r * nsweeps + s] /= drift[s];
    }
    free(buf);
    free(level);
}
