#pragma once
/* The run model: the runs of a folder's summary.csv with their trials' values, the
 * sweep points that group them, and what every answer asks of them (loading, the
 * paired ratio, `differs`, the warnings, whether two runs share a sweep point).
 * summary_md.c, crossovers.c, point_verdict.c, summary_json.c, compare.c and ratios.c
 * read it; it reads none of them. */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include "results/csvread.h"
#include "results/stats.h"
#include "results/verdict.h"

struct param;

/* One run of a summary.csv: its trials' values. */
typedef struct run_result {
    char id[13];
    char renderer[32];
    char experiment[64];
    char metric[8];            /* what decides: "wall", "cpu", "gpu" (summary.csv `metric`;
                                * "wall" for a folder written before the column; "" when
                                * no trial of the run had a context) */
    size_t trials, trials_ok;
    double *value;             /* value[k - 1]: trial k's metric_us; NAN: failed or absent */
    double *wall;              /* wall[k - 1]: trial k's frametime_mean_us, the same way */
    double *share, *steal;     /* trial k's cpu_share_mean and steal_frac (NAN: none) */
    double *gpu, *sm_mhz;      /* trial k's gpu_mean_us and sm_clock_mhz (NAN: none) */
    size_t nvalues;            /* the largest trial number */
    double mean, half;         /* the metric over the ok trials, and its 95% t half-width */
    double wall_mean, wall_half;   /* frame time, the same way */
    double p99_us;             /* mean of the ok trials' frametime_p99_us */
    double low1_fps;           /* 1e6 / p99_us (the trials' fps_1pct_low without a p99) */
    double rmse;               /* largest image_rmse of the ok trials; NAN: not measured */
    /* the workload, means over the ok trials that have it (NAN: none): the lights that
     * reach a covered pixel, the renderer's light evaluations a pixel, the covered
     * fraction, and the most lights (lights_count, the largest over the trials) */
    double reach_mean, evals, coverage, lights;
    char status[96];           /* the run's: trials_run_status (runner/folder/trials.h) */
} run_result;

/* The runs of DIR/summary.csv in the order they first appear (plan order). False
 * with a message when the file is missing or unreadable. Free with summary_free_runs. */
bool summary_load_runs(const char *path, run_result **out, size_t *n, char *err,
                       size_t errlen);
void summary_free_runs(run_result *runs, size_t n);

/* What makes a run's verdicts doubtful, a line per trial (hyperfine warns the same way):
 * a trial whose value is an outlier among the run's (verdict_outliers: interference only
 * adds time), and a trial that ran on a busy machine (it got under 3/4 of the CPU share
 * its run's other trials got, or the hypervisor stole over 5% of the machine); and a
 * line per run whose workload is brute force (workload_brute_force: the lights reaching
 * a pixel average over half its lights). Each line starts with `prefix`; md: names are
 * escaped for Markdown (results/mdtext.h). Returns how many. */
size_t summary_warnings(const run_result *runs, size_t n, FILE *out, const char *prefix, bool md);

/* a / b of two runs measured in the same rounds (trial k with trial k): paired */
void summary_paired_ratio(const run_result *a, const run_result *b, ratio_ci *out);

/* `differs` of a ratio's interval (results/verdict.h at threshold 0): "yes" when it
 * excludes 1, "no" when it holds 1, "n/a" with fewer than 3 trials. */
const char *summary_differs(const ratio_ci *r);

/* Whether runs a and b (run ids) of a plan.csv belong to the same sweep point: their
 * parameters are equal but for the renderer and the parameters only some renderers
 * read. Their trials then ran in the same rounds, and their ratio is paired. False
 * when either id is not in the plan. */
bool summary_same_point(const csv_table *pl, const char *a, const char *b);

/* A plan.csv column that is not a parameter (index, run_id, shard, folded, renderer). */
bool summary_meta_column(const char *name);

/* A plan.csv column of a parameter only some renderers read: part of a row's
 * configuration, not of its sweep point (runner/answer/run_model.c); NULL otherwise. */
const struct param *summary_config_column(const char *name);

/* Whether plan rows a and b (-1: not in the plan) are the same sweep point. */
bool summary_same_row(const csv_table *pl, long a, long b);

/* One sweep point of the ranked table: its label and its runs, ranked. */
typedef struct summary_point {
    char *label;               /* "k=v, k=v" of the parameters that vary; "all runs" */
    size_t *runs;              /* indices into the run array, ranked */
    size_t nruns;
} summary_point;
