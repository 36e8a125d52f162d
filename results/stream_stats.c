/* Per-trial statistics as frames arrive. See stream_stats.h. */
#include "results/stream_stats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- quantile sketch ---------------------------------------------------------------- */

/* g = (1 + a) / (1 - a); bucket k (1 .. QS_NBUCKETS - 2) holds (g^(k+i0-1), g^(k+i0)],
 * i0 = floor(log_g(QS_LO)); bucket 0 everything <= QS_LO, the last everything > QS_HI. */
static double qs_log_gamma(void) { return log((1.0 + QS_ALPHA) / (1.0 - QS_ALPHA)); }

static double qs_i0(void) { return floor(log(QS_LO) / qs_log_gamma()); }

static size_t qs_bucket_of(double x)
{
    if (!(x > QS_LO))
        return 0;   /* also NAN */
    if (x > QS_HI)
        return QS_NBUCKETS - 1;
    double k = ceil(log(x) / qs_log_gamma()) - qs_i0();
    if (k < 1)
        k = 1;
    if (k > QS_NBUCKETS - 2)
        k = QS_NBUCKETS - 2;
    return (size_t)k;
}

static double qs_bucket_value(const quantile_sketch *q, size_t k)
{
    if (k == 0)
        return q->min;
    if (k == QS_NBUCKETS - 1)
        return q->max;
    double lg = qs_log_gamma(), g = exp(lg);
    return 2.0 * exp(((double)k + qs_i0()) * lg) / (g + 1.0);
}

void qs_reset(quantile_sketch *q)
{
    q->n = 0;
    q->min = q->max = NAN;
    q->histogram = false;
    memset(q->bucket, 0, sizeof q->bucket);
}

void qs_add(quantile_sketch *q, double x)
{
    if (q->n == 0 || x < q->min)
        q->min = x;
    if (q->n == 0 || x > q->max)
        q->max = x;
    if (!q->histogram && q->n == QS_EXACT) {
        for (size_t i = 0; i < q->n; i++)
            q->bucket[qs_bucket_of(q->exact[i])]++;
        q->histogram = true;
    }
    if (q->histogram)
        q->bucket[qs_bucket_of(x)]++;
    else
        q->exact[q->n] = x;
    q->n++;
}

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

double qs_percentile(quantile_sketch *q, double p)
{
    if (q->n == 0 || !(p > 0.0))
        return NAN;
    if (!q->histogram) {
        qsort(q->exact, q->n, sizeof q->exact[0], cmp_double);
        return stats_percentile_sorted(q->exact, q->n, p);
    }
    if (p > 100.0)
        p = 100.0;
    double rank = ceil(p * (double)q->n / 100.0);   /* as stats_percentile_sorted */
    uint64_t r = rank < 1.0 ? 1 : (uint64_t)rank;
    if (r > q->n)
        r = q->n;
    uint64_t seen = 0;
    size_t k = 0;
    for (; k < QS_NBUCKETS; k++) {
        seen += q->bucket[k];
        if (seen >= r)
            break;
    }
    double v = qs_bucket_value(q, k < QS_NBUCKETS ? k : QS_NBUCKETS - 1);
    return v < q->min ? q->min : v > q->max ? q->max : v;
}

/* ---- moments ------------------------------------------------------------------------ */

void moments_add(moments *m, double x)
{
    m->n++;
    double d = x - m->mean;
    m->mean += d / (double)m->n;
    m->m2 += d * (x - m->mean);
}

double moments_sd(const moments *m)
{
    return m->n < 2 ? NAN : sqrt(m->m2 / (double)(m->n - 1));
}

/* ---- batch means over prefix sums --------------------------------------------------- */

void bp_reset(batch_prefix *b)
{
    b->n = 0;
    b->block = 1;
    b->nblocks = 0;
    b->sum = 0;
    memset(b->P, 0, sizeof b->P);
}

void bp_add(batch_prefix *b, double x)
{
    b->sum += x;
    b->n++;
    if (b->n % b->block)
        return;
    if (b->nblocks == BM_BLOCKS) {
        /* full: keep every other block end, blocks twice as long */
        for (size_t j = 0; j < BM_BLOCKS / 2; j++)
            b->P[j] = b->P[2 * j + 1];
        b->nblocks = BM_BLOCKS / 2;
        b->block *= 2;
    }
    if (b->n % b->block == 0)
        b->P[b->nblocks++] = b->sum;
}

/* Sum of the first i frames; i is 0, n, or a block end. */
static double bp_prefix(const batch_prefix *b, size_t i)
{
    if (i == 0)
        return 0;
    if (i == b->n)
        return b->sum;
    return b->P[i / b->block - 1];
}

static double mean10(const double *x)
{
    double s = 0;
    for (size_t i = 0; i < STATS_BATCHES; i++)
        s += x[i];
    return s / STATS_BATCHES;
}

double bp_ci95(const batch_prefix *b, const moments *m)
{
    size_t n = b->n;
    if (n < 2)
        return NAN;
    if (n < 2 * (size_t)STATS_BATCHES)
        return stats_t975(n - 1) * moments_sd(m) / sqrt((double)n);
    size_t size = n / STATS_BATCHES, cut[STATS_BATCHES + 1];
    size_t last_end = b->nblocks * b->block;
    cut[0] = 0;
    cut[STATS_BATCHES] = n;   /* the remainder goes to the last batch */
    for (size_t k = 1; k < STATS_BATCHES; k++) {
        size_t at = (k * size + b->block / 2) / b->block * b->block;   /* nearest block end */
        cut[k] = at > last_end ? last_end : at;
    }
    double bm[STATS_BATCHES];
    for (size_t k = 0; k < STATS_BATCHES; k++)
        bm[k] = (bp_prefix(b, cut[k + 1]) - bp_prefix(b, cut[k])) / (double)(cut[k + 1] - cut[k]);
    double mb = mean10(bm), ss = 0;
    for (size_t k = 0; k < STATS_BATCHES; k++)
        ss += (bm[k] - mb) * (bm[k] - mb);
    double sd = sqrt(ss / (STATS_BATCHES - 1));
    return stats_t975(STATS_BATCHES - 1) * sd / sqrt((double)STATS_BATCHES);
}

/* ---- the quantities of results/metrics.def ------------------------------------------ */

/* One statistic's state, by its `agg`: a sum (MEAN, MEAN_FINITE), a maximum
 * (MAX_FINITE), each with the frames counted; a quantile sketch (P50). */
typedef struct metric_sum {
    double sum, max;
    size_t n;
} metric_sum;

#define METRIC_STATE_MEAN metric_sum
#define METRIC_STATE_MEAN_FINITE metric_sum
#define METRIC_STATE_MAX_FINITE metric_sum
#define METRIC_STATE_P50 quantile_sketch

typedef struct metric_acc {
#define FRAME_METRIC(field, type, frames, fprec, from, agg, with, trial, ...) \
    METRIC_STATE_##agg trial;
#define FRAME_STAT(field, agg, with, trial, ...) METRIC_STATE_##agg trial;
#include "results/metrics.def"
} metric_acc;

static void sum_reset(metric_sum *s) { *s = (metric_sum){0}; }
#define METRIC_RESET_MEAN sum_reset
#define METRIC_RESET_MEAN_FINITE sum_reset
#define METRIC_RESET_MAX_FINITE sum_reset
#define METRIC_RESET_P50 qs_reset

static void metric_acc_reset(metric_acc *a)
{
#define FRAME_METRIC(field, type, frames, fprec, from, agg, with, trial, ...) \
    METRIC_RESET_##agg(&a->trial);
#define FRAME_STAT(field, agg, with, trial, ...) METRIC_RESET_##agg(&a->trial);
#include "results/metrics.def"
}

/* x: the frame's value; has: whether the frame has one (it and `with` finite) */
static void add_mean(metric_sum *s, double x, bool has)
{
    (void)has;
    s->sum += x;
}

static void add_mean_finite(metric_sum *s, double x, bool has)
{
    if (has) {
        s->sum += x;
        s->n++;
    }
}

static void add_max_finite(metric_sum *s, double x, bool has)
{
    if (has && (s->n++ == 0 || x > s->max))
        s->max = x;
}

static void add_p50(quantile_sketch *q, double x, bool has)
{
    if (has)
        qs_add(q, x);
}
#define METRIC_ADD_MEAN add_mean
#define METRIC_ADD_MEAN_FINITE add_mean_finite
#define METRIC_ADD_MAX_FINITE add_max_finite
#define METRIC_ADD_P50 add_p50

static void metric_acc_add(metric_acc *a, const frame_record *r)
{
#define FRAME_METRIC(field, type, frames, fprec, from, agg, with, trial, ...) \
    METRIC_ADD_##agg(&a->trial, (double)r->field,                            \
                     isfinite((double)r->field) && isfinite((double)r->with));
#define FRAME_STAT(field, agg, with, trial, ...)                                         \
    METRIC_ADD_##agg(&a->trial, (double)r->field, \
                     isfinite((double)r->field) && isfinite((double)r->with));
#include "results/metrics.def"
}

/* n: the trial's frames */
static double end_mean(metric_sum *s, size_t n) { return n ? s->sum / (double)n : NAN; }
static double end_mean_finite(metric_sum *s, size_t n)
{
    (void)n;
    return s->n ? s->sum / (double)s->n : NAN;
}
static double end_max_finite(metric_sum *s, size_t n)
{
    (void)n;
    return s->n ? s->max : NAN;
}
static double end_p50(quantile_sketch *q, size_t n)
{
    (void)n;
    return qs_percentile(q, 50.0);
}
#define METRIC_END_MEAN end_mean
#define METRIC_END_MEAN_FINITE end_mean_finite
#define METRIC_END_MAX_FINITE end_max_finite
#define METRIC_END_P50 end_p50

/* The trial's values; the TRIAL_METRICs (the runner measures them) NAN. */
static void metric_acc_end(metric_acc *a, size_t n, metric_totals *m)
{
    metric_totals_none(m);
#define FRAME_METRIC(field, type, frames, fprec, from, agg, with, trial, ...) \
    m->trial = METRIC_END_##agg(&a->trial, n);
#define FRAME_STAT(field, agg, with, trial, ...) m->trial = METRIC_END_##agg(&a->trial, n);
#include "results/metrics.def"
}

/* ---- a trial ------------------------------------------------------------------------ */

/* Bins are not made beyond this second (as stats_bin_seconds refuses them). */
#define STREAM_MAX_SECOND (((size_t)1 << 20) - 1)

typedef struct bin_acc {
    size_t second, frames;
    unsigned lights_min, lights_max;
    moments ft;
    double draw_calls;
    quantile_sketch q;
} bin_acc;

struct trial_stream {
    double rel;
    second_sink on_second;
    convergence_sink on_point;
    void *ctx;

    moments ft;
    quantile_sketch q;
    batch_prefix bp;
    metric_acc acc;             /* results/metrics.def's frame quantities */
    unsigned lmax;
    double last_t;

    bin_acc bin;
    size_t next_point;          /* whole second of the next convergence point */
    double converged_since;
};

trial_stream *trial_stream_new(void)
{
    trial_stream *ts = malloc(sizeof *ts);
    if (ts)   /* every page written now, so that the resident size does not grow later */
        trial_stream_begin(ts, 0.01, NULL, NULL, NULL);
    return ts;
}

void trial_stream_free(trial_stream *ts) { free(ts); }

static void bin_start(bin_acc *b, size_t second)
{
    b->second = second;
    b->frames = 0;
    b->lights_min = b->lights_max = 0;
    b->ft = (moments){0};
    b->draw_calls = 0;
    if (b->q.n || b->q.histogram)
        qs_reset(&b->q);
}

static void bin_emit(trial_stream *ts, bool complete)
{
    bin_acc *a = &ts->bin;
    second_bin b = {
        .second = (unsigned)a->second,
        .frames = a->frames,
        .complete = complete,
        .lights_min = a->lights_min,
        .lights_max = a->lights_max,
        .frametime_mean_us = a->frames ? a->ft.mean : NAN,
        .frametime_sd_us = moments_sd(&a->ft),
        .frametime_p50_us = qs_percentile(&a->q, 50.0),
        .frametime_p99_us = qs_percentile(&a->q, 99.0),
        .draw_calls_mean = a->frames ? a->draw_calls / (double)a->frames : NAN,
    };
    if (ts->on_second)
        ts->on_second(ts->ctx, &b);
}

static void point_emit(trial_stream *ts, double at)
{
    convergence_point p = {
        .elapsed_s = at,
        .frames = ts->bp.n,
        .mean_us = ts->bp.n ? ts->bp.sum / (double)ts->bp.n : NAN,
        .ci95_us = bp_ci95(&ts->bp, &ts->ft),
    };
    bool within = p.mean_us > 0 && p.ci95_us <= ts->rel * p.mean_us;
    if (!within)
        ts->converged_since = NAN;
    else if (isnan(ts->converged_since))
        ts->converged_since = at;
    if (ts->on_point)
        ts->on_point(ts->ctx, &p);
}

void trial_stream_begin(trial_stream *ts, double rel, second_sink on_second,
                        convergence_sink on_point, void *ctx)
{
    ts->rel = rel;
    ts->on_second = on_second;
    ts->on_point = on_point;
    ts->ctx = ctx;
    ts->ft = (moments){0};
    qs_reset(&ts->q);
    bp_reset(&ts->bp);
    metric_acc_reset(&ts->acc);
    ts->lmax = 0;
    ts->last_t = 0;
    qs_reset(&ts->bin.q);
    bin_start(&ts->bin, 0);
    ts->next_point = 1;
    ts->converged_since = NAN;
}

/* Second in which a frame ended, as stats_bin_seconds counts it. */
static size_t second_of(double t)
{
    size_t s = t >= 1.0 ? (t < (double)STREAM_MAX_SECOND ? (size_t)floor(t) : STREAM_MAX_SECOND) : 0;
    return s;
}

void trial_stream_add(trial_stream *ts, const frame_record *r)
{
    double t = r->t_wall_s;
    /* the whole seconds this frame ended after: their points hold the frames before it */
    while ((double)ts->next_point < t && ts->next_point <= STREAM_MAX_SECOND)
        point_emit(ts, (double)ts->next_point++);
    size_t s = second_of(t);
    while (ts->bin.second < s) {
        bin_emit(ts, true);   /* a later frame ended at or after its end */
        bin_start(&ts->bin, ts->bin.second + 1);
    }

    bin_acc *b = &ts->bin;
    if (b->frames == 0 || r->lights < b->lights_min)
        b->lights_min = r->lights;
    if (b->frames == 0 || r->lights > b->lights_max)
        b->lights_max = r->lights;
    b->frames++;
    moments_add(&b->ft, r->frametime_us);
    b->draw_calls += (double)r->draw_calls;
    qs_add(&b->q, r->frametime_us);

    moments_add(&ts->ft, r->frametime_us);
    qs_add(&ts->q, r->frametime_us);
    bp_add(&ts->bp, r->frametime_us);
    metric_acc_add(&ts->acc, r);
    if (r->lights > ts->lmax)
        ts->lmax = r->lights;
    if (t > ts->last_t)
        ts->last_t = t;
}

void trial_stream_end(trial_stream *ts, double t_end, trial_totals *out)
{
    size_t n = ts->ft.n;
    /* bins 0 .. max(floor(last), ceil(t_end) - 1), as stats_bin_seconds */
    double want = n > 0 ? floor(ts->last_t) + 1.0 : 0.0;
    double by_end = t_end > 0.0 ? ceil(t_end) : 0.0;
    if (by_end > want)
        want = by_end;
    if (want > (double)STREAM_MAX_SECOND + 1)
        want = (double)STREAM_MAX_SECOND + 1;
    size_t nb = (size_t)want;
    while (ts->bin.second < nb) {
        bin_emit(ts, (double)ts->bin.second + 1.0 <= t_end);
        bin_start(&ts->bin, ts->bin.second + 1);
    }

    /* convergence: every whole second up to t_end, then t_end itself (once) */
    if (n > 0) {
        size_t seconds = t_end > 0 && t_end < 1e7 ? (size_t)floor(t_end) : 0;
        while (ts->next_point <= seconds)
            point_emit(ts, (double)ts->next_point++);
        if (!(seconds > 0 && t_end == (double)seconds))
            point_emit(ts, t_end);
    }

    memset(out, 0, sizeof *out);
    out->ft.n = n;
    out->ft.mean = n ? ts->ft.mean : NAN;
    out->ft.sd = moments_sd(&ts->ft);
    out->ft.min = ts->q.min;
    out->ft.max = ts->q.max;
    out->ft.p50 = qs_percentile(&ts->q, 50.0);
    out->ft.p99 = qs_percentile(&ts->q, 99.0);
    out->ft_ci95 = bp_ci95(&ts->bp, &ts->ft);
    out->ci_converged_after_s = n ? ts->converged_since : NAN;
    metric_acc_end(&ts->acc, n, &out->m);
    out->lights_max = ts->lmax;
}
