#pragma once
/* Progress on stderr: a line redrawn in place when stderr is a terminal, one plain
 * line per finished run otherwise (CI logs stay readable). */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

typedef struct progress {
    FILE *out;
    bool tty;
    size_t total, done, failed;   /* trials */
    size_t runs_done, runs_failed;
    double t0, run_t0, last_draw;
    char label[160];           /* the current run: "k/n id renderer=... " */
} progress;

double progress_now(void);     /* CLOCK_MONOTONIC seconds */
void progress_init(progress *pg, size_t total, FILE *out);
/* Trial `trial` of `trials` (0: trials: auto) of a run, the k-th trial of this
 * sweep; a run of one trial is labelled as a run. */
void progress_run_begin(progress *pg, size_t k, const char *id, const char *renderer,
                        int width, int height, unsigned trial, unsigned trials);
/* During a run: at most a few redraws a second, terminal only. */
void progress_tick(progress *pg, unsigned trial, unsigned lights, double fps);
void progress_run_end(progress *pg, const char *status, double fps);
/* A run whose files are complete (all its trials merged), with its status. */
void progress_run_complete(progress *pg, const char *status);
/* "COUNTS (N trials), in T": counts says what the folder holds (output_account_counts;
 * NULL: this sweep's runs are counted instead), then how many trials this sweep ran
 * where they differ from the runs ("no trial run now" when none). */
void progress_finish(progress *pg, const char *counts);
