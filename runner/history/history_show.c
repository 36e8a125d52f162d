/* `history show` and `history check` (runner/history/history.h): the history's series,
 * one per run and metric in date order (a sweep's point: the mean of the run's ok
 * trials), the sweeps' common drift removed (results/changepoint.h: the median over a
 * sweep's runs, as `compare` corrects two folders), then E-divisive change points with
 * a t-test, printed as a table and written as JSON with Otava's and Perfherder's fields. */
#include "runner/history/history.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "results/drift.h"
#include "results/jsonout.h"

static const char *const metric_names[] = {"wall", "cpu", "gpu"};
enum { NMETRICS = 3 };

typedef struct sweep_row {
    char *key, *date, *commit;
} sweep_row;

typedef struct run_row {
    char *id, *renderer, *metric;
} run_row;

typedef struct series_set {
    sweep_row *sweeps;
    run_row *runs;
    size_t nsweeps, nruns;
    double *sum[NMETRICS];     /* [run * nsweeps + sweep]: sums of ok trials' values */
    unsigned *count[NMETRICS];
} series_set;

static void set_free(series_set *s)
{
    free(s->sweeps);
    free(s->runs);
    for (int m = 0; m < NMETRICS; m++) {
        free(s->sum[m]);
        free(s->count[m]);
    }
}

/* the index of run id in s (added when new); SIZE_MAX: out of memory */
static size_t run_index(series_set *s, char *id, char *renderer, char *metric, size_t cap)
{
    for (size_t i = 0; i < s->nruns; i++)
        if (strcmp(s->runs[i].id, id) == 0)
            return i;
    if (s->nruns == cap)
        return SIZE_MAX;
    s->runs[s->nruns] = (run_row){id, renderer, metric};
    return s->nruns++;
}

/* rows: sweep, date, commit, run_id, renderer, metric, status, frame_us, cpu_us, gpu_us,
 * in date order; the strings stay the result's */
static bool build_set(const hdb_result *r, series_set *s)
{
    *s = (series_set){0};
    size_t n = r->nrows, nc = r->ncols;
    s->sweeps = calloc(n + 1, sizeof *s->sweeps);
    s->runs = calloc(n + 1, sizeof *s->runs);
    size_t *sw = calloc(n + 1, sizeof *sw), *ru = calloc(n + 1, sizeof *ru);
    bool ok = s->sweeps && s->runs && sw && ru;
    for (size_t i = 0; ok && i < n; i++) {
        char **c = r->cell + i * nc;
        if (!s->nsweeps || strcmp(s->sweeps[s->nsweeps - 1].key, c[0]) != 0)
            s->sweeps[s->nsweeps++] = (sweep_row){c[0], c[1], c[2] ? c[2] : ""};
        sw[i] = s->nsweeps - 1;
        ru[i] = run_index(s, c[3], c[4], c[5] ? c[5] : "", n);
    }
    size_t cells = s->nruns * s->nsweeps + 1;
    for (int m = 0; ok && m < NMETRICS; m++) {
        s->sum[m] = calloc(cells, sizeof *s->sum[m]);
        s->count[m] = calloc(cells, sizeof *s->count[m]);
        ok = s->sum[m] && s->count[m];
    }
    for (size_t i = 0; ok && i < n; i++) {
        char **c = r->cell + i * nc;
        if (!c[6] || strcmp(c[6], "ok") != 0)
            continue;
        for (int m = 0; m < NMETRICS; m++) {
            char *end;
            double v = c[7 + m] ? strtod(c[7 + m], &end) : NAN;
            if (!c[7 + m] || end == c[7 + m] || !(v > 0) || !isfinite(v))
                continue;
            s->sum[m][ru[i] * s->nsweeps + sw[i]] += v;
            s->count[m][ru[i] * s->nsweeps + sw[i]]++;
        }
    }
    free(sw);
    free(ru);
    if (!ok)
        set_free(s);
    return ok;
}

/* whether metric m of run r is asked for */
static bool wanted(const history_query *q, const run_row *r, int m)
{
    if (q->run && strcmp(q->run, r->id) != 0)
        return false;
    if (q->renderer && strcmp(q->renderer, r->renderer) != 0)
        return false;
    if (!q->metric)
        return strcmp(r->metric, metric_names[m]) == 0;
    return strcmp(q->metric, "all") == 0 || strcmp(q->metric, metric_names[m]) == 0;
}

typedef struct found {
    const run_row *run;
    int metric;
    const sweep_row *sweep;    /* the first sweep after the change */
    change_point cp;
} found;

static void print_table(FILE *out, const char *where, const history_query *q,
                        const series_set *s, const found *f, size_t nf, size_t nreg,
                        size_t nseries)
{
    fprintf(out, "history %s: %zu sweeps, %zu runs, %zu series; change points by E-divisive "
            "means with a t-test (as Apache Otava): p < %g and a change over %g%%%s\n\n",
            where, s->nsweeps, s->nruns, nseries, q->cp.max_pvalue, q->cp.min_magnitude * 100,
            q->drift ? ", on values corrected for the sweeps' common drift" : "");
    if (nf) {
        fprintf(out, "| run | renderer | metric | time | commit | before (ms) | after (ms) | "
                "change | p | verdict |\n|---|---|---|---|---|---|---|---|---|---|\n");
        for (size_t i = 0; i < nf; i++) {
            const change_point *c = &f[i].cp;
            fprintf(out, "| %s | %s | %s | %s | %s | %.4f | %.4f | %+.1f%% | %.2g | %s |\n",
                    f[i].run->id, f[i].run->renderer, metric_names[f[i].metric],
                    f[i].sweep->date, f[i].sweep->commit, c->mean_before / 1000,
                    c->mean_after / 1000, c->forward_change_percent, c->pvalue,
                    c->forward_change_percent > 0 ? "**regression**" : "improvement");
        }
        fputc('\n', out);
    }
    fprintf(out, "%zu change points: %zu regressions, %zu improvements\n", nf, nreg, nf - nreg);
}

static void write_json(FILE *js, const char *where, const history_query *q,
                       const series_set *s, const found *f, size_t nf, size_t nreg)
{
    bool first = true;
    fputc('{', js);
    json_member_string(js, &first, "schema", "shadesweep-history");
    json_member_number(js, &first, "version", 1);
    json_member_string(js, &first, "database", where);
    json_member_number(js, &first, "sweeps", (double)s->nsweeps);
    json_member_number(js, &first, "runs", (double)s->nruns);
    json_member_number(js, &first, "max_pvalue", q->cp.max_pvalue);
    json_member_number(js, &first, "min_change_percent", q->cp.min_magnitude * 100);
    json_key(js, &first, "drift_corrected");
    fputs(q->drift ? "true" : "false", js);
    json_member_number(js, &first, "regressions", (double)nreg);
    json_key(js, &first, "change_points");
    fputc('[', js);
    for (size_t i = 0; i < nf; i++) {
        const change_point *c = &f[i].cp;
        bool fi = true;
        fputs(i ? ",\n{" : "\n{", js);
        json_member_string(js, &fi, "run_id", f[i].run->id);
        json_member_string(js, &fi, "renderer", f[i].run->renderer);
        json_member_string(js, &fi, "metric", metric_names[f[i].metric]);
        json_member_string(js, &fi, "time", f[i].sweep->date);
        json_member_string(js, &fi, "sweep", f[i].sweep->key);
        json_member_string(js, &fi, "commit", f[i].sweep->commit);
        json_member_number(js, &fi, "index", (double)c->index);
        /* Otava's */
        json_member_number(js, &fi, "forward_change_percent", c->forward_change_percent);
        json_member_number(js, &fi, "magnitude", c->magnitude);
        json_member_number(js, &fi, "mean_before", c->mean_before);
        json_member_number(js, &fi, "mean_after", c->mean_after);
        json_member_number(js, &fi, "stddev_before", c->stddev_before);
        json_member_number(js, &fi, "stddev_after", c->stddev_after);
        json_member_number(js, &fi, "pvalue", c->pvalue);
        /* Perfherder's */
        json_member_number(js, &fi, "prev_value", c->mean_before);
        json_member_number(js, &fi, "new_value", c->mean_after);
        json_member_number(js, &fi, "amount_abs", c->mean_after - c->mean_before);
        json_member_number(js, &fi, "amount_pct", fabs(c->forward_change_percent));
        json_member_number(js, &fi, "t_value", fabs(c->t_value));
        json_key(js, &fi, "is_regression");
        fputs(c->forward_change_percent > 0 ? "true}" : "false}", js);
    }
    fputs(nf ? "\n]}\n" : "]}\n", js);
}

/* The change points of every series asked for into *f (malloc'd); *nseries: how many
 * series had at least 3 sweeps. False: out of memory. */
static bool find_all(series_set *s, const history_query *q, found **f, size_t *nf,
                     size_t *nseries)
{
    size_t cells = s->nruns * s->nsweeps;
    double *v = malloc((cells + 1) * sizeof *v), *x = malloc((s->nsweeps + 1) * sizeof *x);
    double *drift = malloc((s->nsweeps + 1) * sizeof *drift);
    size_t *at = malloc((s->nsweeps + 1) * sizeof *at), cap = 0;
    bool ok = v && x && drift && at;
    *f = NULL;
    *nf = *nseries = 0;
    for (int m = 0; ok && m < NMETRICS; m++) {
        for (size_t i = 0; i < cells; i++)
            v[i] = s->count[m][i] ? s->sum[m][i] / s->count[m][i] : NAN;
        if (q->drift)
            changepoint_remove_drift(v, s->nruns, s->nsweeps, DRIFT_MIN_RUNS, drift);
        for (size_t r = 0; ok && r < s->nruns; r++) {
            if (!wanted(q, &s->runs[r], m))
                continue;
            size_t n = 0;
            for (size_t k = 0; k < s->nsweeps; k++)
                if (isfinite(v[r * s->nsweeps + k])) {
                    x[n] = v[r * s->nsweeps + k];
                    at[n++] = k;
                }
            if (n < 3)
                continue;
            ++*nseries;
            change_point *cp;
            size_t ncp = changepoint_find(x, n, &q->cp, &cp);
            if (*nf + ncp > cap) {
                cap = 2 * (*nf + ncp) + 8;
                found *g = realloc(*f, cap * sizeof *g);
                ok = g != NULL;
                if (ok)
                    *f = g;
            }
            for (size_t i = 0; ok && i < ncp; i++)
                (*f)[(*nf)++] = (found){&s->runs[r], m, &s->sweeps[at[cp[i].index]], cp[i]};
            free(cp);
        }
    }
    free(v);
    free(x);
    free(drift);
    free(at);
    return ok;
}

bool history_show(hdb *db, const char *where, const history_query *q, FILE *out, FILE *json,
                  size_t *regressions, char *err, size_t errlen)
{
    *regressions = 0;
    hdb_result r = {0};
    bool ok = db->ops->exec(db, "BEGIN", NULL, 0, NULL, err, errlen);
    bool in_tx = ok;
    ok = ok && hdb_schema(db, false, err, errlen);
    ok = ok && db->ops->exec(db,
        "SELECT s.sweep, s.date, s.commit_id, t.run_id, r.renderer, r.metric, t.status, "
        "t.frame_us, t.cpu_us, t.gpu_us FROM trials t JOIN runs r ON r.sweep = t.sweep AND "
        "r.run_id = t.run_id JOIN sweeps s ON s.sweep = t.sweep "
        "ORDER BY s.date, s.sweep, t.run_id, t.trial", NULL, 0, &r, err, errlen);
    if (in_tx)
        hdb_rollback(db);   /* read only */
    if (!ok)
        return false;
    series_set s;
    found *f = NULL;
    size_t nf = 0, nseries = 0;
    bool built = build_set(&r, &s);
    if (!built || !find_all(&s, q, &f, &nf, &nseries)) {
        snprintf(err, errlen, "out of memory");
        if (built)
            set_free(&s);
        free(f);
        hdb_result_free(&r);
        return false;
    }
    for (size_t i = 0; i < nf; i++)
        *regressions += f[i].cp.forward_change_percent > 0;
    if (out)
        print_table(out, where, q, &s, f, nf, *regressions, nseries);
    if (json)
        write_json(json, where, q, &s, f, nf, *regressions);
    free(f);
    set_free(&s);
    hdb_result_free(&r);
    return true;
}
