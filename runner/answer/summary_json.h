#pragma once
/* OUT/summary.json: what summary.md says, for scripts (runner/answer/summary_json.c). The
 * schema, its version and every field are docs/summary-json.md; a change that removes
 * or retypes a field raises SUMMARY_JSON_VERSION. */
#include <stdbool.h>
#include <stddef.h>

#include "results/csvread.h"
#include "runner/answer/crossovers.h"
#include "runner/answer/run_model.h"

#define SUMMARY_JSON_VERSION 1

/* The ranked table as runner/answer/summary_md.c built it. */
typedef struct summary_view {
    const char *experiment;
    const run_result *runs;
    size_t nruns;
    const csv_table *pl;
    const csv_table *sm;          /* summary.csv as text: the trials' measured values */
    const long *prow;             /* each run's plan row; -1: not in the plan */
    const bool *varies;           /* plan columns that vary across sweep points */
    char *const *rcfg;            /* each run's configuration label */
    const summary_point *points;  /* ranked */
    size_t npoints;
    const crossover_list *cx;
    const struct device_note *device;   /* runner/answer/device_note.h */
} summary_view;

/* Writes OUT/summary.json into `set` (fsutil.h: renamed with the folder's other
 * summaries); false with a message. */
struct afile_set;
bool summary_json_write(const char *out_dir, const summary_view *v, struct afile_set *set,
                        char *err, size_t errlen);
