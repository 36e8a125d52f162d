#pragma once
/* The bound of an output folder's runs (issue 38, item 2; the arithmetic is
 * results/bound.h): the device profile (DIR/device.yaml, or one named), each run's
 * counted work from its summary.csv rows and its plan.csv row (the target's format and
 * samples), and the time each resource of the device needs for it. Fills summary.csv's
 * `bound_us`, `limiter` and `bound_pct`, and answers summary.md's section and
 * `shadesweep bound`. Columns of an older summary.csv are found by name. */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "results/bound.h"
#include "results/csvread.h"
#include "results/device_profile.h"

typedef struct folder_bound {
    bool have;                 /* a profile was read */
    device_profile prof;
    char why[4400];            /* without one: why (no device.yaml, unreadable) */
    csv_table plan;            /* DIR/plan.csv, for each run's hdr and msaa */
    csv_index plan_ix;
} folder_bound;

/* The profile at `profile` (NULL: DIR/device.yaml) and DIR/plan.csv; false, fb->why
 * saying so, without a profile (fb stays usable: every bound empty). */
bool folder_bound_open(folder_bound *fb, const char *dir, const char *profile);
void folder_bound_close(folder_bound *fb);

/* The bound of one summary.csv row (its names and fields), and its measured time. */
void folder_bound_row(const folder_bound *fb, const char *const *names,
                      const char *const *values, size_t n, bound_result *res,
                      double *measured_us);

/* The rates for run `id` (its plan.csv row's hdr and msaa); false without a profile. */
bool folder_bound_rates(const folder_bound *fb, const char *id, bound_rates *r);

/* One run: the mean of its ok trials' work and measured time, bounded. */
typedef struct run_bound {
    char id[13], renderer[32];
    double measured_us;
    bound_result b;
} run_bound;
/* The runs of summary table t in file order, each once; *n of them (free the array).
 * NULL when out of memory or t has none. */
run_bound *folder_bound_runs(const folder_bound *fb, const csv_table *t, size_t *n);

/* DIR/summary.csv's bound_us, limiter and bound_pct filled from the profile (left empty
 * without one); a summary.csv without those columns is left as it is. False with a
 * message when it cannot be read or written. */
bool folder_bound_fill_summary(const char *dir, const folder_bound *fb, char *err,
                               size_t errlen);

/* The line summary.md and `bound` print where a folder has no device.yaml (Markdown; no
 * word "device": a GPU's summary.md names none, tests/cli/device_labels.sh). */
extern const char folder_bound_no_profile[];
