#pragma once
/* The common change between two folders measured apart (issue 41, item 1): the
 * machine's drift, which moves every run together, estimated robustly from the runs'
 * own NEW / BASE ratios, and each run's ratio corrected for it.
 * Assumes most runs did not change: the median of the per-run log ratios follows the
 * unchanged majority and is not pulled by one or two changed runs. Pure arithmetic;
 * docs/notes/answer.md says why this estimate and not a control workload. */
#include <stdbool.h>
#include <stddef.h>

#include "results/verdict.h"

/* The fewest runs with an interval that the estimate takes: with 5, two changed runs
 * still leave the median on an unchanged one. */
#define DRIFT_MIN_RUNS 5

typedef struct common_change {
    double ratio, lo, hi;   /* NEW / BASE common to the runs, its 95% interval; NAN
                             * when not estimated (fewer than DRIFT_MIN_RUNS runs) */
    size_t n;               /* runs used: finite ratio > 0 and a finite interval */
    bool applied;           /* the interval excludes 1: verdicts on corrected ratios */
} common_change;

/* From the runs' ratios r[0..n): m = median of log ratio_i, MAD = median |log
 * ratio_i - m|, and the half-width of log ratio in the 95% interval
 * H = 1.2533 max(t975(k - 1) 1.4826 MAD, median(h_i)) / sqrt(k) over the k runs used,
 * h_i = log(hi_i / lo_i) / 2: the median's 95% half-width from the runs' spread
 * (1.4826 MAD estimates sd; the median's standard error is sqrt(pi / 2) = 1.2533
 * times the mean's), floored by the same from the runs' own intervals (runs that
 * agree exactly still each carry their trials' noise). ratio = exp(m), lo / hi = exp(m -+ H).
 * Returns whether it was estimated (k >= DRIFT_MIN_RUNS). */
bool drift_common_change(const ratio_ci *r, size_t n, common_change *out);

/* raw / c when c->applied, with the interval widened in log space, half-width
 * sqrt(h_raw^2 + H_c^2); otherwise *out = *raw (the verdict is what it was). */
void drift_correct(const ratio_ci *raw, const common_change *c, ratio_ci *out);
