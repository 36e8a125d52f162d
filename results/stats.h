#pragma once
/* Arithmetic on frame times: summaries, per-second bins, confidence intervals. */
#include <stdbool.h>
#include <stddef.h>
#include "results/record.h"

typedef struct sample_summary {
    size_t n;
    double mean, sd;      /* sd: sample standard deviation (n-1); NAN when n < 2 */
    double p50, p99;      /* nearest-rank percentiles; NAN when n == 0 */
    double min, max;
} sample_summary;

/* Summary of n values (the input is not modified). n == 0 gives NANs and n = 0. */
void stats_summarize(const double *x, size_t n, sample_summary *out);

/* Nearest-rank percentile (0 < p <= 100) of a sorted array. */
double stats_percentile_sorted(const double *sorted, size_t n, double p);

/* Two-sided 95% critical value of Student's t with dof degrees of freedom (dof >= 1). */
double stats_t975(size_t dof);

/* Half-width of the 95% confidence interval of the mean frame time by batch means:
 * the frames (in order) are cut into STATS_BATCHES contiguous batches of equal size
 * (the remainder goes to the last), and t(0.975, B-1) * sd(batch means) / sqrt(B).
 * Batching absorbs the autocorrelation of consecutive frame times.
 * With fewer than 2 * STATS_BATCHES frames it falls back to t * sd / sqrt(n) over
 * frames; NAN when n < 2. */
#define STATS_BATCHES 10
double stats_ci95_batch_means(const double *x, size_t n);

/* One second of a run: frames whose end time t_wall_s lies in [second, second + 1). */
typedef struct second_bin {
    unsigned second;
    size_t frames;          /* FPS of this second = frames */
    bool complete;          /* the measurement covered the whole second */
    unsigned lights_min, lights_max;  /* 0,0 when frames == 0 */
    double frametime_mean_us, frametime_sd_us, frametime_p50_us, frametime_p99_us; /* NAN if empty */
    double draw_calls_mean; /* NAN if empty */
} second_bin;

/* Bins frames[0..n) (t_wall_s non-decreasing, >= 0) by the second in which each
 * frame ended. t_end (>= the last t_wall_s) is the end of the measurement; the bins
 * are seconds 0 .. max(floor(last t_wall_s), ceil(t_end) - 1), every one present,
 * those with no frame with frames = 0. A bin is complete when second + 1 <= t_end.
 * *out is malloc'ed (caller frees; NULL when *nbins == 0). False only when out of memory. */
bool stats_bin_seconds(const frame_record *frames, size_t n, double t_end,
                       second_bin **out, size_t *nbins);

/* How the uncertainty of the mean frame time shrinks as a trial runs: one point at
 * the end of every whole second of measurement (the frames that ended by then) and
 * one at t_end, each with the mean frame time and the half-width of its 95%
 * confidence interval by the same estimator as stats_ci95_batch_means (computed
 * from prefix sums: O(n + points x STATS_BATCHES)). */
typedef struct convergence_point {
    double elapsed_s;
    size_t frames;
    double mean_us;
    double ci95_us;            /* NAN with fewer than 2 frames */
} convergence_point;

bool stats_convergence(const frame_record *frames, size_t n, double t_end,
                       convergence_point **out, size_t *npoints);

/* The elapsed time from which ci95 / mean stayed within `rel` (e.g. 0.01) at every
 * later point to the end; NAN when the last point is not within it (it never did). */
double stats_converged_after(const convergence_point *p, size_t n, double rel);

/* Two-sided 95% critical value for fractional degrees of freedom (Welch): the
 * value at floor(dof), which is conservative; NAN when dof < 1. */
double stats_t975_real(double dof);
