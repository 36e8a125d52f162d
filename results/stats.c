/* Arithmetic on frame times. See stats.h. */
#include "results/stats.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

double stats_percentile_sorted(const double *sorted, size_t n, double p)
{
    if (n == 0 || sorted == NULL || !(p > 0.0))
        return NAN;
    if (p > 100.0)
        p = 100.0;
    /* Nearest rank: the smallest value with at least p% of the data at or below it.
     * p * n is exact for the sizes we see, so an exact quotient stays an integer. */
    double rank = ceil(p * (double)n / 100.0);
    size_t r = rank < 1.0 ? 1 : (size_t)rank;
    if (r > n)
        r = n;
    return sorted[r - 1];
}

static double mean_of(const double *x, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++)
        s += x[i];
    return s / (double)n;
}

/* Sample standard deviation (n - 1) around a known mean; NAN when n < 2. */
static double sd_of(const double *x, size_t n, double mean)
{
    if (n < 2)
        return NAN;
    double ss = 0.0;
    for (size_t i = 0; i < n; i++) {
        double d = x[i] - mean;
        ss += d * d;
    }
    return sqrt(ss / (double)(n - 1));
}

/* Sorts x in place and fills out. */
static void summarize_in_place(double *x, size_t n, sample_summary *out)
{
    out->n = n;
    if (n == 0) {
        out->mean = out->sd = out->p50 = out->p99 = out->min = out->max = NAN;
        return;
    }
    qsort(x, n, sizeof *x, cmp_double);
    out->mean = mean_of(x, n);
    out->sd = sd_of(x, n, out->mean);
    out->p50 = stats_percentile_sorted(x, n, 50.0);
    out->p99 = stats_percentile_sorted(x, n, 99.0);
    out->min = x[0];
    out->max = x[n - 1];
}

/* Without memory for a sorted copy the percentiles are NAN; the rest is exact. */
void stats_summarize(const double *x, size_t n, sample_summary *out)
{
    double *copy = n > 0 && n <= SIZE_MAX / sizeof *copy ? malloc(n * sizeof *copy) : NULL;
    if (copy != NULL || n == 0) {
        if (n > 0)
            memcpy(copy, x, n * sizeof *copy);
        summarize_in_place(copy, n, out);
        free(copy);
        return;
    }
    out->n = n;
    out->mean = mean_of(x, n);
    out->sd = sd_of(x, n, out->mean);
    out->p50 = out->p99 = NAN;
    out->min = out->max = x[0];
    for (size_t i = 1; i < n; i++) {
        out->min = x[i] < out->min ? x[i] : out->min;
        out->max = x[i] > out->max ? x[i] : out->max;
    }
}

/* t(0.975, dof) for dof 1..30 (more digits than the printed tables, which these
 * round to). */
static const double t975_table[30] = {
    12.7062047, 4.3026527, 3.1824463, 2.7764451, 2.5705818, 2.4469119, 2.3646243,
    2.3060041,  2.2621572, 2.2281389, 2.2009852, 2.1788128, 2.1603687, 2.1447867,
    2.1314495,  2.1199053, 2.1098156, 2.1009220, 2.0930241, 2.0859634, 2.0796138,
    2.0738731,  2.0686576, 2.0638986, 2.0595386, 2.0555294, 2.0518305, 2.0484071,
    2.0452296,  2.0422725,
};

/* Beyond 30 the Cornish-Fisher expansion of t around the normal quantile
 * (Abramowitz & Stegun 26.7.5), four terms: its error at dof 31 is below 1e-6
 * and shrinks from there (40: 2.02108, 60: 2.00030, 120: 1.97993, -> 1.95996). */
double stats_t975(size_t dof)
{
    if (dof == 0)
        return NAN;
    if (dof <= 30)
        return t975_table[dof - 1];
    const double z = 1.959963984540054; /* Phi^-1(0.975) */
    double z2 = z * z, z3 = z2 * z, z5 = z3 * z2, z7 = z5 * z2, z9 = z7 * z2;
    double g1 = (z3 + z) / 4.0;
    double g2 = (5.0 * z5 + 16.0 * z3 + 3.0 * z) / 96.0;
    double g3 = (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / 384.0;
    double g4 = (79.0 * z9 + 776.0 * z7 + 1482.0 * z5 - 1920.0 * z3 - 945.0 * z) / 92160.0;
    double v = (double)dof;
    return z + g1 / v + g2 / (v * v) + g3 / (v * v * v) + g4 / (v * v * v * v);
}

double stats_ci95_batch_means(const double *x, size_t n)
{
    if (n < 2 || x == NULL)
        return NAN;
    if (n < 2 * (size_t)STATS_BATCHES) {
        double m = mean_of(x, n);
        return stats_t975(n - 1) * sd_of(x, n, m) / sqrt((double)n);
    }
    double bm[STATS_BATCHES];
    size_t size = n / STATS_BATCHES;
    for (size_t b = 0; b < STATS_BATCHES; b++) {
        size_t lo = b * size;
        size_t hi = b + 1 == STATS_BATCHES ? n : lo + size; /* remainder to the last */
        bm[b] = mean_of(x + lo, hi - lo);
    }
    double m = mean_of(bm, STATS_BATCHES);
    return stats_t975(STATS_BATCHES - 1) * sd_of(bm, STATS_BATCHES, m) /
           sqrt((double)STATS_BATCHES);
}

/* Second in which a frame ended (negative or NAN times count as second 0). */
static size_t second_of(double t)
{
    return t >= 1.0 ? (size_t)floor(t) : 0;
}

/* Bins are refused beyond this (about 11.6 days of seconds): a larger count means a
 * corrupt time, and the allocation would be absurd. */
#define STATS_MAX_BINS ((size_t)1 << 20)

bool stats_bin_seconds(const frame_record *frames, size_t n, double t_end,
                       second_bin **out, size_t *nbins)
{
    *out = NULL;
    *nbins = 0;

    double last = 0.0;
    for (size_t i = 0; i < n; i++)
        last = frames[i].t_wall_s > last ? frames[i].t_wall_s : last;
    double want = n > 0 ? floor(last) + 1.0 : 0.0;
    double by_end = t_end > 0.0 ? ceil(t_end) : 0.0; /* also false for NAN */
    if (by_end > want)
        want = by_end;
    if (!(want <= (double)STATS_MAX_BINS))
        return false;
    size_t nb = (size_t)want;
    if (nb == 0)
        return true;

    second_bin *bins = calloc(nb, sizeof *bins);
    size_t *start = calloc(nb + 1, sizeof *start);
    double *ft = n > 0 ? malloc(n * sizeof *ft) : NULL;
    size_t *fill = calloc(nb, sizeof *fill);
    if (bins == NULL || start == NULL || fill == NULL || (n > 0 && ft == NULL)) {
        free(bins);
        free(start);
        free(ft);
        free(fill);
        return false;
    }

    /* Counting sort of the frame times by bin, so the order of frames[] does not matter. */
    for (size_t i = 0; i < n; i++)
        start[second_of(frames[i].t_wall_s) + 1]++;
    for (size_t b = 0; b < nb; b++)
        start[b + 1] += start[b];
    for (size_t b = 0; b < nb; b++) {
        second_bin *s = &bins[b];
        s->second = (unsigned)b;
        s->complete = (double)b + 1.0 <= t_end;
        s->draw_calls_mean = 0.0;
    }
    for (size_t i = 0; i < n; i++) {
        size_t b = second_of(frames[i].t_wall_s);
        second_bin *s = &bins[b];
        ft[start[b] + fill[b]++] = frames[i].frametime_us;
        if (s->frames == 0 || frames[i].lights < s->lights_min)
            s->lights_min = frames[i].lights;
        if (s->frames == 0 || frames[i].lights > s->lights_max)
            s->lights_max = frames[i].lights;
        s->frames++;
        s->draw_calls_mean += (double)frames[i].draw_calls;
    }
    for (size_t b = 0; b < nb; b++) {
        second_bin *s = &bins[b];
        sample_summary sum;
        summarize_in_place(ft != NULL ? ft + start[b] : NULL, s->frames, &sum);
        s->frametime_mean_us = sum.mean;
        s->frametime_sd_us = sum.sd;
        s->frametime_p50_us = sum.p50;
        s->frametime_p99_us = sum.p99;
        s->draw_calls_mean = s->frames > 0 ? s->draw_calls_mean / (double)s->frames : NAN;
    }

    free(start);
    free(ft);
    free(fill);
    *out = bins;
    *nbins = nb;
    return true;
}

/* The batch-means half-width over x[0..m) from prefix sums P (P[i] = x[0] + ... + x[i-1]),
 * the same estimator as stats_ci95_batch_means; under 2 * STATS_BATCHES frames, the
 * per-frame interval computed directly. */
static double ci95_prefix(const double *x, const double *P, size_t m)
{
    if (m < 2)
        return NAN;
    if (m < 2 * (size_t)STATS_BATCHES)
        return stats_ci95_batch_means(x, m);
    double bm[STATS_BATCHES];
    size_t size = m / STATS_BATCHES;
    for (size_t b = 0; b < STATS_BATCHES; b++) {
        size_t lo = b * size;
        size_t hi = b + 1 == STATS_BATCHES ? m : lo + size;
        bm[b] = (P[hi] - P[lo]) / (double)(hi - lo);
    }
    double mb = mean_of(bm, STATS_BATCHES);
    return stats_t975(STATS_BATCHES - 1) * sd_of(bm, STATS_BATCHES, mb) /
           sqrt((double)STATS_BATCHES);
}

bool stats_convergence(const frame_record *frames, size_t n, double t_end,
                       convergence_point **out, size_t *npoints)
{
    *out = NULL;
    *npoints = 0;
    if (n == 0)
        return true;
    double *x = malloc(n * sizeof *x);
    double *P = malloc((n + 1) * sizeof *P);
    size_t seconds = t_end > 0 && t_end < 1e7 ? (size_t)floor(t_end) : 0;
    convergence_point *pts = calloc(seconds + 1, sizeof *pts);
    if (!x || !P || !pts) {
        free(x);
        free(P);
        free(pts);
        return false;
    }
    P[0] = 0;
    for (size_t i = 0; i < n; i++) {
        x[i] = frames[i].frametime_us;
        P[i + 1] = P[i] + x[i];
    }
    size_t np = 0, m = 0;
    for (size_t s = 1; s <= seconds + 1; s++) {
        double at = s <= seconds ? (double)s : t_end;
        if (s > seconds && seconds > 0 && at == (double)seconds)
            break;   /* t_end on a whole second: that point is already there */
        while (m < n && frames[m].t_wall_s <= at)
            m++;
        pts[np].elapsed_s = at;
        pts[np].frames = m;
        pts[np].mean_us = m ? P[m] / (double)m : NAN;
        pts[np].ci95_us = ci95_prefix(x, P, m);
        np++;
    }
    free(x);
    free(P);
    *out = pts;
    *npoints = np;
    return true;
}

double stats_converged_after(const convergence_point *p, size_t n, double rel)
{
    double since = NAN;
    for (size_t i = 0; i < n; i++) {
        bool within = p[i].mean_us > 0 && p[i].ci95_us <= rel * p[i].mean_us;
        if (!within)
            since = NAN;
        else if (isnan(since))
            since = p[i].elapsed_s;
    }
    return since;
}

double stats_t975_real(double dof)
{
    if (!(dof >= 1))
        return NAN;
    return stats_t975(dof > 1e9 ? (size_t)1e9 : (size_t)floor(dof));
}
