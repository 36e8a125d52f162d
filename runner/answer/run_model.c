#include "runner/answer/run_model.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "results/mdtext.h"
#include "results/csvread.h"
#include "runner/manifest/params.h"
#include "runner/folder/trials.h"
#include "runner/plan/workload.h"

typedef struct trial_cols {
    int run_id, renderer, experiment, trial, wall, p99, low1, rmse, status, metric, value;
    int share, steal, reach, evals, coverage, lights, gpu, sm;
} trial_cols;

void summary_free_runs(run_result *runs, size_t n)
{
    for (size_t i = 0; runs && i < n; i++) {
        free(runs[i].value);
        free(runs[i].wall);
        free(runs[i].share);
        free(runs[i].steal);
        free(runs[i].gpu);
        free(runs[i].sm_mhz);
    }
    free(runs);
}

bool summary_load_runs(const char *path, run_result **out, size_t *n, char *err,
                       size_t errlen)
{
    *out = NULL;
    *n = 0;
    csv_table t;
    if (!csv_read(path, &t, err, errlen))
        return false;
    trial_cols c = {
        csv_col(&t, "run_id"), csv_col(&t, "renderer"), csv_col(&t, "experiment"),
        csv_col(&t, "trial"), csv_col(&t, "frametime_mean_us"), csv_col(&t, "frametime_p99_us"),
        csv_col(&t, "fps_1pct_low"), csv_col(&t, "image_rmse"), csv_col(&t, "status"),
        csv_col(&t, "metric"), csv_col(&t, "metric_us"), csv_col(&t, "cpu_share_mean"),
        csv_col(&t, "steal_frac"), csv_col(&t, "lights_reaching_mean"),
        csv_col(&t, "light_evals_per_pixel"), csv_col(&t, "coverage"),
        csv_col(&t, "lights_count"), csv_col(&t, "gpu_mean_us"), csv_col(&t, "sm_clock_mhz"),
    };
    if (c.run_id < 0 || c.trial < 0 || c.wall < 0 || c.status < 0) {
        snprintf(err, errlen, "%s: not a shadesweep summary.csv (no run_id, trial, "
                 "frametime_mean_us or status column)", path);
        csv_table_free(&t);
        return false;
    }
    run_result *runs = calloc(t.nrows ? t.nrows : 1, sizeof *runs);
    if (!runs) {
        csv_table_free(&t);
        snprintf(err, errlen, "out of memory");
        return false;
    }
    size_t nr = 0;
    bool ok = true;
    for (size_t r = 0; ok && r < t.nrows; r++) {
        const char *id = csv_get(&t, r, c.run_id);
        size_t k = 0;
        while (k < nr && strcmp(runs[k].id, id) != 0)
            k++;
        if (k < nr)
            continue;
        run_result *x = &runs[nr++];
        snprintf(x->id, sizeof x->id, "%s", id);
        snprintf(x->renderer, sizeof x->renderer, "%s", csv_get(&t, r, c.renderer));
        snprintf(x->experiment, sizeof x->experiment, "%s", csv_get(&t, r, c.experiment));
        /* the first row that names it (a trial that never had a context does not);
         * a folder written before the column was ranked by wall time */
        snprintf(x->metric, sizeof x->metric, "%s", c.metric >= 0 ? "" : "wall");
        for (size_t q = r; c.metric >= 0 && q < t.nrows && !x->metric[0]; q++)
            if (strcmp(csv_get(&t, q, c.run_id), id) == 0)
                snprintf(x->metric, sizeof x->metric, "%s", csv_get(&t, q, c.metric));
        snprintf(x->status, sizeof x->status, "ok");
        /* the largest trial number of this run */
        for (size_t q = r; q < t.nrows; q++) {
            double k1 = csv_num(&t, q, c.trial);
            if (strcmp(csv_get(&t, q, c.run_id), id) == 0 && k1 >= 1 && k1 <= 1e6 &&
                (size_t)k1 > x->nvalues)
                x->nvalues = (size_t)k1;
        }
        size_t nv = x->nvalues ? x->nvalues : 1;
        x->value = malloc(nv * sizeof *x->value);
        x->wall = malloc(nv * sizeof *x->wall);
        x->share = malloc(nv * sizeof *x->share);
        x->steal = malloc(nv * sizeof *x->steal);
        x->gpu = malloc(nv * sizeof *x->gpu);
        x->sm_mhz = malloc(nv * sizeof *x->sm_mhz);
        if (!x->value || !x->wall || !x->share || !x->steal || !x->gpu || !x->sm_mhz) {
            ok = false;
            break;
        }
        for (size_t i = 0; i < nv; i++)
            x->value[i] = x->wall[i] = x->share[i] = x->steal[i] = x->gpu[i] = x->sm_mhz[i] =
                NAN;
        size_t m = 0;
        double p99 = 0, low = 0;
        x->rmse = NAN;
        /* the workload's figures: sums and counts of the ok trials' finite values */
        double wsum[3] = {0, 0, 0};
        size_t wn[3] = {0, 0, 0};
        const int wcol[3] = {c.reach, c.evals, c.coverage};
        x->lights = NAN;
        for (size_t q = r; q < t.nrows; q++) {
            if (strcmp(csv_get(&t, q, c.run_id), id) != 0)
                continue;
            x->trials++;
            const char *st = csv_get(&t, q, c.status);
            if (strcmp(st, "ok") != 0) {
                if (strcmp(x->status, "ok") == 0)
                    snprintf(x->status, sizeof x->status, "%s", *st ? st : "unknown");
                continue;
            }
            x->trials_ok++;
            double k1 = csv_num(&t, q, c.trial);
            if (k1 >= 1 && k1 <= (double)x->nvalues) {
                size_t i = (size_t)k1 - 1;
                x->wall[i] = csv_num(&t, q, c.wall);
                x->value[i] = c.value >= 0 ? csv_num(&t, q, c.value) : x->wall[i];
                x->share[i] = c.share >= 0 ? csv_num(&t, q, c.share) : NAN;
                x->steal[i] = c.steal >= 0 ? csv_num(&t, q, c.steal) : NAN;
                x->gpu[i] = c.gpu >= 0 ? csv_num(&t, q, c.gpu) : NAN;
                x->sm_mhz[i] = c.sm >= 0 ? csv_num(&t, q, c.sm) : NAN;
            }
            m++;
            double p = c.p99 >= 0 ? csv_num(&t, q, c.p99) : NAN;
            double l = c.low1 >= 0 ? csv_num(&t, q, c.low1) : (p > 0 ? 1e6 / p : NAN);
            p99 += p;
            low += l;
            double e = c.rmse >= 0 ? csv_num(&t, q, c.rmse) : NAN;
            if (isfinite(e) && !(e <= x->rmse))
                x->rmse = e;
            for (int w = 0; w < 3; w++) {
                double v = wcol[w] >= 0 ? csv_num(&t, q, wcol[w]) : NAN;
                if (isfinite(v))
                    wsum[w] += v, wn[w]++;
            }
            double nl = c.lights >= 0 ? csv_num(&t, q, c.lights) : NAN;
            if (isfinite(nl) && !(nl <= x->lights))
                x->lights = nl;
        }
        x->reach_mean = wn[0] ? wsum[0] / (double)wn[0] : NAN;
        x->evals = wn[1] ? wsum[1] / (double)wn[1] : NAN;
        x->coverage = wn[2] ? wsum[2] / (double)wn[2] : NAN;
        char failure[sizeof x->status];
        snprintf(failure, sizeof failure, "%s", x->status);
        trials_run_status(x->trials, x->trials_ok, strcmp(failure, "ok") ? failure : NULL,
                          x->status, sizeof x->status);
        verdict_mean_ci(x->value, x->nvalues, &x->mean, &x->half);
        verdict_mean_ci(x->wall, x->nvalues, &x->wall_mean, &x->wall_half);
        x->p99_us = m ? p99 / (double)m : NAN;
        /* the run's 1% low is that of its mean p99, as the table shows them side by side */
        x->low1_fps = x->p99_us > 0 ? 1e6 / x->p99_us : m ? low / (double)m : NAN;
    }
    csv_table_free(&t);
    if (!ok) {
        summary_free_runs(runs, nr);
        snprintf(err, errlen, "out of memory");
        return false;
    }
    *out = runs;
    *n = nr;
    return true;
}

/* s, escaped when it goes into Markdown. */
static void put(FILE *fp, const char *s, bool md)
{
    if (md)
        md_put(fp, s);
    else
        fputs(s, fp);
}

size_t summary_warnings(const run_result *runs, size_t n, FILE *out, const char *prefix, bool md)
{
    size_t count = 0;
    for (size_t r = 0; r < n; r++) {
        const run_result *x = &runs[r];
        if (!x->nvalues)
            continue;
        bool *flag = calloc(x->nvalues, sizeof *flag);
        double *scratch = malloc(x->nvalues * sizeof *scratch);
        if (!flag || !scratch) {
            free(flag);
            free(scratch);
            continue;
        }
        verdict_outliers(x->value, x->nvalues, flag);
        double med, shmed;
        verdict_median(x->value, x->nvalues, scratch, &med);
        if (verdict_median(x->share, x->nvalues, scratch, &shmed) < 3)
            shmed = NAN;   /* too few trials to call one of them starved */
        for (size_t k = 0; k < x->nvalues; k++) {
            if (flag[k]) {
                fprintf(out, "%srun ", prefix);
                put(out, x->id, md);
                fputs(" (", out);
                put(out, x->renderer, md);
                fprintf(out, ") trial %zu is an outlier: %.4g ms of ", k + 1, x->value[k] / 1000);
                put(out, x->metric[0] ? x->metric : "wall", md);
                fprintf(out, " time a frame, the run's median %.4g ms\n", med / 1000);
                count++;
            }
            bool starved = isfinite(shmed) && x->share[k] < 0.75 * shmed;
            bool stolen = x->steal[k] > 0.05;
            if (starved || stolen) {
                fprintf(out, "%srun ", prefix);
                put(out, x->id, md);
                fputs(" (", out);
                put(out, x->renderer, md);
                fprintf(out, ") trial %zu ran on a busy machine: ", k + 1);
                /* the median needs 3 trials: fewer (a one-trial run) name the steal alone */
                if (isfinite(shmed))
                    fprintf(out, "it got %.0f%% of the CPU it could use (the run's median "
                            "%.0f%%), steal %.0f%%\n", x->share[k] * 100, shmed * 100,
                            isfinite(x->steal[k]) ? x->steal[k] * 100 : 0.0);
                else
                    fprintf(out, "the hypervisor stole %.0f%% of the machine's CPU time\n",
                            x->steal[k] * 100);
                count++;
            }
        }
        free(flag);
        free(scratch);
    }
    for (size_t r = 0; r < n; r++) {
        char msg[256];
        if (workload_brute_force(runs[r].reach_mean, runs[r].lights, msg, sizeof msg)) {
            fprintf(out, "%srun ", prefix);
            put(out, runs[r].id, md);
            fputs(" (", out);
            put(out, runs[r].renderer, md);
            fputs("): ", out);
            put(out, msg, md);
            fputc('\n', out);
            count++;
        }
    }
    return count;
}

void summary_paired_ratio(const run_result *a, const run_result *b, ratio_ci *out)
{
    size_t n = a->nvalues < b->nvalues ? a->nvalues : b->nvalues;
    verdict_paired_ratio(a->value, b->value, n, out);
}

/* ---- grouping by sweep point */

bool summary_meta_column(const char *name)
{
    return strcmp(name, "index") == 0 || strcmp(name, "run_id") == 0 ||
           strcmp(name, "shard") == 0 || strcmp(name, "folded") == 0 ||
           strcmp(name, "renderer") == 0;
}

/* A parameter only some renderers read (params.def: gbuffer.*, deferred.*, ...): not
 * part of the sweep point, whose renderers are ranked together, but of the row's
 * configuration ("deferred fat/volume"): a forward baseline then stands beside every
 * G-buffer variant at the same resolution and lights. */
const param *summary_config_column(const char *name)
{
    const param *pd = param_find(name);
    return pd && pd->size && !param_every_run_reads(pd) ? pd : NULL;
}

/* The pl row of a run id, or -1. */
static long plan_row(const csv_table *pl, int idcol, const char *id)
{
    for (size_t r = 0; r < pl->nrows; r++)
        if (strcmp(csv_get(pl, r, idcol), id) == 0)
            return (long)r;
    return -1;
}

bool summary_same_row(const csv_table *pl, long a, long b)
{
    if (a < 0 || b < 0)
        return a == b;
    for (size_t c = 0; c < pl->ncols; c++)
        if (!summary_meta_column(pl->header[c]) && !summary_config_column(pl->header[c]) &&
            strcmp(pl->rows[a][c], pl->rows[b][c]) != 0)
            return false;
    return true;
}

bool summary_same_point(const csv_table *pl, const char *a, const char *b)
{
    int idcol = csv_col(pl, "run_id");
    if (idcol < 0)
        return false;
    long ra = plan_row(pl, idcol, a), rb = plan_row(pl, idcol, b);
    return ra >= 0 && rb >= 0 && summary_same_row(pl, ra, rb);
}

const char *summary_differs(const ratio_ci *r)
{
    switch (verdict_of(r, 0)) {
    case VERDICT_SLOWER:
    case VERDICT_FASTER: return "yes";
    case VERDICT_NONE: return "n/a";
    default: return "no";
    }
}
