#pragma once
/* The run loop (DESIGN.md "The data's way through"): for each run of the plan
 * (of one shard), a GL context at the run's resolution, the scene, the renderer
 * and its pass plan; per trial a warm-up, then measured frames, each ending at
 * glFinish or a fence wait; then per-second bins, the trial's summary and the
 * run's files. */
#include <stdbool.h>
#include "renderers/gl/context.h"
#include "runner/manifest/manifest.h"
#include "runner/plan/progress.h"

typedef struct run_options {
    const char *out_dir;       /* the experiment's output folder; exists */
    gl_backend backend;
    int device;                /* -1: EGL surfaceless; N: EGL device N */
    bool debug_gl;             /* debug context: any GL error fails the run */
    unsigned shard, nshards;   /* only runs of shard `shard` of `nshards` (0 = all) */
    bool resume;               /* skip runs whose files are complete */
    bool retry_failed;         /* with resume: complete runs with a failed row run again */
    unsigned round;            /* run trials up to this round only (compare --exe); 0: all */
} run_options;

/* The sweep (runner/cli/schedule.c): the runs of each sweep point in rounds, round k
 * running trial k of each of them in a seeded random order (schedule: interleaved) or
 * each run's trials back to back (sequential), every trial in a child process of its own
 * (isolate.h) with its own time limit (run_trial_timeout_s); a crash, hang or OOM kill
 * fails that run and the sweep goes on. A run's files are merged from its trials' when its
 * last trial is complete (runner/folder/trials.c). SIGINT/SIGTERM/SIGHUP discard the trial in
 * progress, write the summary of the complete runs and return 128 + the signal, after
 * printing how to resume. The folder is open and locked (folder.h) and has its
 * sweep.yaml.
 * 0: every run of the folder (this shard) is complete and ok; 1: some run failed or
 * is missing (its rows say why); 2: the sweep could not go on (message printed). */
int run_plan(const experiment *e, const plan *p, const run_options *o);

/* The whole of `shadesweep run` after the manifest is loaded: the output folder (out,
 * or out/<name> when NULL) opened with folder_open (force, o->resume: its mode; the
 * lock held throughout), --device checked up front, run_plan, the folder closed.
 * o->out_dir is set here. Returns run_plan's status, or 2 (message printed). */
int run_sweep(const experiment *e, const plan *p, const char *out, bool force, run_options *o);

/* What became of one trial run by run_trial_isolated. */
typedef struct trial_outcome {
    char status[96];           /* "ok", "failed:<reason>", or "interrupted, discarded" */
    char message[512];         /* why it failed */
    double fps;                /* its mean FPS (0: none) */
    double seconds;            /* the child's wall time, start-up included */
    bool interrupted;          /* a stop signal: its folder was removed */
} trial_outcome;

/* Trial `trial` (1..) of run s, `order`-th in its round, in a child process with a time limit: OUT/runs/<id>/
 * trial-<k>/ ends complete (folder_check_trial), whatever became of the child (a child
 * that died has its row written by the parent), or removed when a stop signal came.
 * The child's stderr is appended to OUT/runs/<id>/log.txt. False (message printed)
 * when the trial could not be started at all (no memory, no folder). */
bool run_trial_isolated(const experiment *e, const run_spec *s, const run_options *o,
                        progress *pg, uint32_t trial, uint32_t order, double timeout_s,
                        trial_outcome *out);

/* The folder of a trial that will not run (its run ended at an earlier trial): its
 * row with `status` (failed:not-run or the run's failure) and `message`, and nothing
 * measured. */
bool run_write_missing_trial(const experiment *e, const run_spec *s, const run_options *o,
                             uint32_t trial, uint32_t order, const char *status,
                             const char *message);

/* Whether a trial's status ends its run (no more trials): anything but ok, failed:error
 * and failed:nonfinite (verdicts on what was measured). */
bool run_status_ends_run(const char *status);

/* "SIGINT", "SIGTERM" or "SIGHUP". */
const char *run_stop_name(int sig);

/* Each trial's time limit, its start-up, priming and warm-up included: the run's
 * `timeout`, or 600 + 3 x (warm-up + duration) seconds (spans in frames count 0). */
double run_trial_timeout_s(const run_params *p);
/* That limit as messages quote it: "timeout: 3 s a trial, warm-up included". */
void run_timeout_text(const run_params *p, char *buf, size_t len);

/* From now on SIGINT, SIGTERM and SIGHUP (to this process or its whole group) only
 * ask the sweep to stop: run_plan discards the run in progress and returns 128 + the
 * signal; SIGPIPE is ignored (a closed pipe on stderr fails writes, not the sweep).
 * run_plan calls it too; calling it first (before the output folder is made) makes a
 * signal at any moment after it an orderly stop. Not undone. */
void run_catch_stop_signals(void);
/* The stop signal caught so far, or 0. */
int run_stop_signal(void);

/* Whether EGL device `device` exists (asked in a child process); false with a message. */
bool run_probe_device(int device, char *err, size_t errlen);

/* fn(arg, answer, len) runs in a child process (so that this one never loads a GL
 * driver; its stderr goes to /dev/null) and the text it leaves in answer comes back
 * here; with timeout_s > 0 a child still running then is killed. False with a message
 * when no answer came. */
bool run_ask_child(void (*fn)(void *arg, char *answer, size_t len), void *arg,
                   double timeout_s, char *answer, size_t len, char *err, size_t errlen);

/* The limits of the GL context a run would get (backend, device: as run_setup opens
 * it), asked in a child within timeout_s (0: no bound): out's max_* and renderer are
 * filled, the rest is zero. With device >= 0, run_probe_device first. False with why. */
bool run_probe_gl(gl_backend backend, int device, double timeout_s, gl_info *out, char *err,
                  size_t errlen);
