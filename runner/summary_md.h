#pragma once
/* The answer at the end of a sweep (runner/summary_md.c): the runs of OUT/summary.csv,
 * grouped by sweep point (the runs whose plan.csv parameters are equal but for the
 * renderer), each point's renderers ranked by mean frame time with its 95% CI, the
 * ratio to the fastest, whether the difference to the fastest is significant (Welch's
 * t on the trials' batch means, stats_pool_trials), the worst image RMSE where
 * measured, p99 frame time and the 1% low FPS (1e6 / p99 frame time: the rate the
 * slowest 1% of frames run at or below). A compact table to a terminal and
 * OUT/summary.md. Shared with `compare` (runner/compare.c): the per-run loading. */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include "results/stats.h"

/* One run of a summary.csv: its ok trials pooled. */
typedef struct run_result {
    char id[13];
    char renderer[32];
    char experiment[64];
    size_t trials, trials_ok;
    mean_estimate ft;          /* frame time, us, over the ok trials */
    double p99_us;             /* mean of the ok trials' frametime_p99_us */
    double low1_fps;           /* 1e6 / p99_us (the trials' fps_1pct_low without a p99) */
    double rmse;               /* largest image_rmse of the ok trials; NAN: not measured */
    char status[96];           /* "ok", or the first trial status that is not */
} run_result;

/* The runs of DIR/summary.csv in the order they first appear (plan order). False
 * with a message when the file is missing or unreadable. *out is malloc'ed. */
bool summary_load_runs(const char *path, run_result **out, size_t *n, char *err,
                       size_t errlen);

/* Writes OUT/summary.md and prints the compact table to `terminal` (NULL: none).
 * False with a message (nothing written) when summary.csv or plan.csv is unreadable. */
bool summary_table_write(const char *out_dir, FILE *terminal, char *err, size_t errlen);
