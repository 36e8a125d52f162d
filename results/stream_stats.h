#pragma once
/* Per-trial statistics computed as frames arrive, in memory that does not grow with
 * the number of frames (results/stats.c holds the exact, array-based definitions they
 * follow; tests/unit/test_stats.c checks one against the other).
 *
 * Moments, percentiles, the batch-means CI and the per-second callbacks, each with its
 * precision: the comment above the limits below. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "results/record.h"
#include "results/stats.h"

/* - Moments (mean, sd, min, max): exact (Welford's update).
 * - Percentiles: nearest rank, exact while a sketch holds at most QS_EXACT values;
 *   beyond that from a fixed logarithmic histogram whose buckets are (g^(i-1), g^i]
 *   with g = (1 + QS_ALPHA) / (1 - QS_ALPHA), each represented by 2 g^i / (g + 1):
 *   the value returned is within a relative QS_ALPHA (0.5%) of the exact nearest-rank
 *   value for values in [QS_LO, QS_HI] us (outside that range the extreme buckets
 *   report the smallest / largest value seen), and never outside [min, max].
 * - The 95% CI by batch means (10 batches, Student t) from prefix sums kept at block
 *   ends: exact while the trial has at most BM_BLOCKS (65536) frames; beyond, blocks
 *   double (pairwise merged) and each batch boundary moves to the nearest block end,
 *   so a batch's size differs from n / 10 by at most half a block, i.e. by at most
 *   10 / BM_BLOCKS (0.015%) of it. (For independent frames that moves each batch mean
 *   by about sqrt(10 / BM_BLOCKS) = 1.2% of its standard error.)
 * - Per-second bins and convergence points are handed to callbacks as each second
 *   ends, with the same definitions as stats_bin_seconds and stats_convergence. */
#define QS_EXACT 1024
#define QS_ALPHA 0.005
#define QS_LO 1e-3              /* us */
#define QS_HI 1e10              /* us */
#define QS_NBUCKETS 3000        /* covers [QS_LO, QS_HI] at QS_ALPHA, plus under/overflow */
#define BM_BLOCKS 65536

typedef struct quantile_sketch {
    size_t n;
    double min, max;
    bool histogram;             /* false: exact[0..n) holds every value */
    double exact[QS_EXACT];
    uint64_t bucket[QS_NBUCKETS];
} quantile_sketch;

void qs_reset(quantile_sketch *q);
void qs_add(quantile_sketch *q, double x);
/* Nearest-rank percentile (0 < p <= 100); NAN when empty. Reorders exact[]. */
double qs_percentile(quantile_sketch *q, double p);

/* Running mean and sum of squared deviations (Welford). */
typedef struct moments {
    size_t n;
    double mean, m2;
} moments;

void moments_add(moments *m, double x);
double moments_sd(const moments *m);   /* n - 1; NAN when n < 2 */

/* Prefix sums of the frame times at block ends, for batch means over any prefix. */
typedef struct batch_prefix {
    size_t n;                   /* frames added */
    size_t block;               /* frames per block: 1, 2, 4, ... */
    size_t nblocks;             /* complete blocks whose end is in P */
    double sum;                 /* over all n frames */
    double P[BM_BLOCKS];        /* P[j]: sum of the first (j + 1) * block frames */
} batch_prefix;

void bp_reset(batch_prefix *b);
void bp_add(batch_prefix *b, double x);
/* The half-width of stats_ci95_batch_means over the frames added so far; m holds their
 * moments (for the per-frame fallback under 2 * STATS_BATCHES frames). */
double bp_ci95(const batch_prefix *b, const moments *m);

typedef void (*second_sink)(void *ctx, const second_bin *b);
typedef void (*convergence_sink)(void *ctx, const convergence_point *p);

/* What a finished trial states (the columns of summary.csv that come from frames). */
typedef struct trial_totals {
    sample_summary ft;          /* frame time, us */
    double ft_ci95;
    double ci_converged_after_s;   /* stats_converged_after(points, rel); NAN: never */
    metric_totals m;            /* results/metrics.def's summary columns: each entry's
                                 * aggregate (its `agg`); TRIAL_METRICs NAN (the runner's) */
    unsigned lights_max;
} trial_totals;

typedef struct trial_stream trial_stream;

/* One allocation, reused for every trial (NULL when out of memory). */
trial_stream *trial_stream_new(void);
void trial_stream_free(trial_stream *ts);   /* NULL is fine */
/* Starts a trial: bins go to on_second, convergence points to on_point (either may be
 * NULL), with ctx; rel: the relative CI half-width of ci_converged_after_s. */
void trial_stream_begin(trial_stream *ts, double rel, second_sink on_second,
                        convergence_sink on_point, void *ctx);
/* Frames in order of t_wall_s (non-decreasing, >= 0). */
void trial_stream_add(trial_stream *ts, const frame_record *r);
/* t_end (>= the last t_wall_s): the end of the measurement. Emits the last bins and
 * points and fills *out. */
void trial_stream_end(trial_stream *ts, double t_end, trial_totals *out);
