#pragma once
/* Progress on stderr: a line redrawn in place when stderr is a terminal, one plain
 * line per finished run otherwise (CI logs stay readable); the ETA from the measured
 * cost of trials of the same renderer, size and scene. */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* Trials that cost alike (one renderer, size and scene): the ETA's unit. */
typedef struct progress_kind {
    char key[128];             /* "renderer WxH scene" */
    size_t left;               /* trials of it still to run */
    size_t measured;           /* trials of it that ended, ... */
    double seconds;            /* ... and their wall time together */
} progress_kind;

typedef struct progress {
    FILE *out;
    bool tty;
    size_t total, done, failed;   /* trials */
    size_t runs_done, runs_failed;
    double t0, run_t0, last_draw;
    char label[160];           /* the current run: "k/n id renderer=... " */
    progress_kind *kinds;      /* the ETA's (progress_expect) */
    size_t nkinds, cap;
    size_t cur;                /* the kind of the trial running; SIZE_MAX: none */
} progress;

double progress_now(void);     /* CLOCK_MONOTONIC seconds */
void progress_init(progress *pg, size_t total, FILE *out);
/* Frees what progress_expect took. */
void progress_free(progress *pg);
/* `trials` more trials of renderer at width x height on scene will run (the ETA
 * counts them); false: no memory (the ETA then leaves them out). */
bool progress_expect(progress *pg, const char *renderer, int width, int height,
                     const char *scene, size_t trials);
/* `trials` of them will not run after all (their run ended early). */
void progress_unexpect(progress *pg, const char *renderer, int width, int height,
                       const char *scene, size_t trials);
/* A trial of the current kind ended after `seconds` (progress_run_end's measure). */
void progress_record(progress *pg, double seconds);
/* Seconds left: each kind's trials left times its mean measured cost, less the
 * `elapsed` seconds of the trial running; a kind not yet measured counts at the
 * slowest measured kind's cost, and *guessed says how many trials were counted so.
 * NAN ("ETA unknown") before any trial ended. */
double progress_eta_s(const progress *pg, double elapsed, size_t *guessed);
/* Trial `trial` of `trials` (0: trials: auto) of a run, the k-th trial of this
 * sweep; a run of one trial is labelled as a run. */
void progress_run_begin(progress *pg, size_t k, const char *id, const char *renderer,
                        int width, int height, const char *scene, unsigned trial,
                        unsigned trials);
/* During a run: at most a few redraws a second, terminal only. */
void progress_tick(progress *pg, unsigned trial, unsigned lights, double fps);
void progress_run_end(progress *pg, const char *status, double fps);
/* A run whose files are complete (all its trials merged), with its status. */
void progress_run_complete(progress *pg, const char *status);
/* "COUNTS (N trials), in T": counts says what the folder holds (output_account_counts;
 * NULL: this sweep's runs are counted instead), then how many trials this sweep ran
 * where they differ from the runs ("no trial run now" when none). */
void progress_finish(progress *pg, const char *counts);
