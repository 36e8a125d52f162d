#pragma once
/* Trial-level statistics: the trial (one process execution) is the unit of
 * replication. Every interval and test here takes one value per trial (e.g. a
 * trial's mean frame time), never frames: frames of one process share its
 * placement, caches and clocks, so intervals over pooled frames are far too narrow
 * on a noisy machine.
 *
 * Within a round k the configurations run back to back in a random order, so trial
 * k of A and trial k of B are paired: whatever slowed the machine during round k
 * slowed both, and the per-round ratio a_k / b_k cancels it.
 *
 * Ratios, non-finite values and allocation: the comment above ratio_ci below. */
#include <stdbool.h>
#include <stddef.h>

/* Ratios are A / B of times: above 1, A is slower. They are estimated on logs
 * (geometric means), so that A / B and B / A give reciprocal intervals.
 *
 * A non-finite value (a failed trial) is left out everywhere, and the ratio
 * functions also leave out values <= 0 (log needs > 0); each function says which
 * count it reports.
 * Pure arithmetic: no I/O; verdict_outliers allocates a scratch copy. */

/* A ratio of times A / B and its 95% confidence interval. */
typedef struct ratio_ci {
    double ratio;     /* point estimate of a/b (geometric); NAN with no usable value */
    double lo, hi;    /* 95% interval; NAN when n < 3 */
    size_t n;         /* pairs (paired) or min(na, nb) (unpaired) used */
    bool paired;
} ratio_ci;

/* Paired: a[i] and b[i] measured in the same round i (n rounds). A pair with a
 * non-finite or <= 0 value is left out (n counts the pairs kept).
 * ratio = exp(mean(log(a_i / b_i))), the geometric mean of the per-round ratios; the
 * interval is the t interval (n - 1 dof) of the mean log ratio, exponentiated:
 * exp(m -+ t975(n - 1) sd / sqrt(n)). Identical ratios give lo == hi == ratio. */
void verdict_paired_ratio(const double *a, const double *b, size_t n, ratio_ci *out);

/* Unpaired: two independent samples (e.g. two output folders measured at different
 * times), na and nb values, unusable ones left out. ratio = exp(mean(log a) -
 * mean(log b)), the ratio of geometric means; the interval is Welch's on the logs:
 * exp(d -+ t975_real(dof) se), se^2 = var(log a) / na + var(log b) / nb, dof by
 * Welch-Satterthwaite (stats_t975_real floors it: conservative). n = min(na, nb)
 * of the usable values; the interval is NAN when either has fewer than 3. Two
 * constant samples give lo == hi == ratio. */
void verdict_unpaired_ratio(const double *a, size_t na, const double *b, size_t nb,
                            ratio_ci *out);

/* What an interval says at a relative threshold th (0.05: differences within 5%
 * do not matter). Equivalence-test style: SLOWER / FASTER only when the whole
 * interval lies beyond the threshold, SAME only when it lies within it. */
typedef enum verdict {
    VERDICT_NONE = 0,   /* n < 3 (or no interval, or th < 0 / NAN): no verdict, say so */
    VERDICT_SAME,       /* the interval lies inside [1/(1+th), 1+th] (bounds included) */
    VERDICT_SLOWER,     /* lo > 1 + th: A is slower than B by more than th */
    VERDICT_FASTER,     /* hi < 1/(1+th): A is faster than B by more than th */
    VERDICT_UNDECIDED,  /* anything else: the interval straddles a threshold */
} verdict;

/* The verdict of r at threshold th >= 0. With th == 0 it is a plain significance
 * test: SLOWER / FASTER when the interval excludes 1, UNDECIDED when it contains 1
 * (SAME only for lo == hi == 1). */
verdict verdict_of(const ratio_ci *r, double threshold);

/* "no verdict", "same", "slower", "faster", "undecided"; "?" for any other value. */
const char *verdict_name(verdict v);

/* One configuration's trial values: *mean and the half-width *half of its 95% t
 * interval, t975(n - 1) sd / sqrt(n), over the finite values (others left out).
 * *mean is NAN with no usable value, *half with fewer than 2. Returns the count used. */
size_t verdict_mean_ci(const double *x, size_t n, double *mean, double *half);

/* The adaptive stop (trials: auto): true when every one of the nr ratios is
 * decided, i.e. n >= 3 and its interval either is narrow, hi / lo <= (1 +
 * precision)^2 (a half-width in log terms of at most log(1 + precision)), or
 * excludes 1 (lo > 1 or hi < 1). A ratio with n < 3 or NAN bounds is never decided.
 * nr == 0 gives true (nothing left to decide): the caller sets any minimum count. */
bool verdict_all_decided(const ratio_ci *r, size_t nr, double precision);

/* The median of the finite values of x[0..n) (an even count averages the middle two),
 * into *median (NAN when there is none), with scratch (n values) as working space.
 * Returns how many values it took. */
size_t verdict_median(const double *x, size_t n, double *scratch, double *median);

/* Outliers among trial values, a warning as hyperfine gives one: the modified
 * z-score of Iglewicz and Hoaglin, 0.6745 (x - median) / MAD > 3.5, with MAD the
 * median of |x - median| (medians of an even count average the middle two).
 * One-sided: interference only adds time, so only slow trials are flagged. With
 * MAD == 0 (most values equal) a value is flagged when it exceeds the median by
 * more than 1% of it. Non-finite values are left out of the medians and never
 * flagged. out[i] says whether x[i] is flagged; returns how many. Fewer than 3
 * finite values, or no memory for the scratch copy: none flagged, 0. */
size_t verdict_outliers(const double *x, size_t n, bool *out);

/* Where A / B crosses 1 along a numeric axis (e.g. the light count): r[k] is the
 * ratio at x[k], x strictly ascending (a point with a non-finite x is skipped).
 * Points whose ratio is not finite and > 0, or is exactly 1, are skipped; a crossing
 * lies between consecutive kept points i < j whose ratios are on opposite sides of 1.
 * Between two points the log ratio is interpolated linearly in log x (in x where the
 * left point's x <= 0, e.g. a 0-light point), and out->x is where it reaches 0.
 * The interval [out->lo, out->hi] comes from the bound curves, log lo and log hi,
 * interpolated the same way, each over the points where that bound is finite and
 * > 0. For a rising ratio (dir = +1): out->lo is the x of the last rise of the hi
 * curve to 1 in a segment that starts before x[j] (below it A was surely faster),
 * out->hi the x of the first rise of the lo curve above 1 in a segment that ends
 * after x[i] (from it A is surely slower). For a falling ratio the same with lo and
 * hi swapped (the lo curve's fall to 1, then the hi curve's fall below 1). Each is
 * NAN where its curve does not cross within the data. Returns the first crossing
 * with i >= from, false when there is none; pass out->j as from for the next. */
typedef struct ratio_crossover {
    size_t i, j;      /* the crossing lies between x[i] and x[j] */
    int dir;          /* +1: the ratio rises through 1 (A becomes the slower), -1: falls */
    double x;         /* where the point estimate crosses 1 */
    double lo, hi;    /* where the interval bounds cross 1; NAN where one does not */
} ratio_crossover;
bool verdict_crossover(const double *x, const ratio_ci *r, size_t n, size_t from,
                       ratio_crossover *out);
