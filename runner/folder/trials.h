#pragma once
/* A run's trials on disk. Each trial runs in a process of its own and writes a folder
 * OUT/runs/<id>/trial-<k>/ with the files a run has (frames.csv, ..., summary.csv with
 * its one row, meta.yaml, images) and its own files.txt (folder_check_trial). When the
 * run's last trial is complete, trials_merge makes the run's files out of them: what
 * --resume, merge, compare and the report read is the same as when one process ran
 * every trial. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "runner/manifest/manifest.h"

/* A run's status from its trials', the one rule that meta.yaml, summary.csv's account,
 * summary.md, summary.json, the report and the terminal all use: "ok" when all `trials`
 * are ok; "partial:<reason>" when `ok` of them are (0 < ok < trials) and the first that
 * is not says "failed:<reason>" (`failure`: that trial's status); else `failure` itself
 * ("failed:not-run" when there is none). Returns out. */
const char *trials_run_status(size_t trials, size_t ok, const char *failure, char *out,
                              size_t len);
/* Whether a run status (above) has measured trials to rank: ok or partial:<reason>. */
bool trials_status_measured(const char *status);

/* What the schedule knows of a run's trials, for meta.yaml. */
typedef struct trials_schedule {
    const char *mode;          /* "interleaved" or "sequential" */
    uint32_t seed;             /* measure.seed */
    size_t point;              /* the sweep point (run_spec.group) */
    const uint32_t *order;     /* order[k - 1]: trial k's place in its round, 1.. */
} trials_schedule;

/* Merges trials 1..n of run `id` (every folder complete) into OUT/runs/<id>/: each CSV
 * with its header once and the trials' rows in trial order, summary.csv a row per
 * trial, the trials' images, meta.yaml (trial 1's, its `status` the run's, `finished`
 * the last trial's, with `schedule` and a `trials` list), then files.txt; then the
 * trial folders are removed. A merge cut off part-way leaves every trial folder whole,
 * so that it can be done again. status: the run's (trials_run_status). */
bool trials_merge(const char *out_dir, const char *id, uint32_t n, const char *status,
                  const trials_schedule *sched, char *err, size_t errlen);
