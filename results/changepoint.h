#pragma once
/* Change points in a series of measurements (issue 41, item 2): E-divisive means with a
 * Student t-test, as Apache Otava (formerly DataStax's hunter) finds them: a split step
 * over sliding windows at a relaxed p-value (the weak change points), then a merge step
 * that drops the weakest until every one left has p < max_pvalue and a relative change
 * above min_magnitude. And the common drift of whole sweeps, removed before the search.
 * Pure arithmetic; docs/notes/history.md gives the sources and the departures. */
#include <stdbool.h>
#include <stddef.h>

typedef struct cp_options {
    double max_pvalue;      /* significance of a change point (Otava's default 0.001) */
    double min_magnitude;   /* its smallest relative change (0.05: 5%) */
    size_t window_len;      /* the split step's window (Otava's default 50) */
} cp_options;

/* One change point: the series before it (from the previous change point) against the
 * series after it (to the next), Otava's TTestStats. */
typedef struct change_point {
    size_t index;           /* the first point after the change */
    double qhat;            /* E-divisive's Q at the split */
    double mean_before, mean_after;
    double stddev_before, stddev_after;   /* population sd (numpy's std, as Otava) */
    double pvalue;          /* two-sided Student t-test, pooled variance */
    double t_value;         /* its t statistic, after minus before */
    double forward_change_percent;   /* (mean_after / mean_before - 1) x 100 */
    double magnitude;       /* max(|after / before - 1|, |before / after - 1|) */
} change_point;

/* cp_options with Otava's defaults and a 5% floor */
cp_options changepoint_defaults(void);

/* The change points of x[0..n) (finite values), sorted by index, into *out (malloc'd,
 * NULL when none; the caller frees). Returns how many. */
size_t changepoint_find(const double *x, size_t n, const cp_options *o, change_point **out);

/* Two-sided p of Student's t with dof degrees of freedom. */
double changepoint_t_pvalue(double t, double dof);

/* The common drift of whole sweeps: v[r * nsweeps + s] is run r's value in sweep s (NAN
 * where the run is missing). Each run's level is the median of its log values; a sweep's
 * drift is the median over its runs of log v - level, taken where the sweep has at least
 * min_runs runs (else 0: not estimated). drift[s] = exp of it; v is divided by it in
 * place. A run that changed alone does not move the median of five or more. */
void changepoint_remove_drift(double *v, size_t nruns, size_t nsweeps, size_t min_runs,
                              double *drift);
