/* The code results/metrics.def generates that needs no frame: the NAN initialisation,
 * the summary writer and the table of columns. See metrics.h; a frame's row is
 * results/record.c's. */
#include "results/metrics.h"

#include <math.h>

void metric_totals_none(metric_totals *m)
{
#define FRAME_METRIC(field, type, frames, fprec, from, agg, with, trial, ...) m->trial = NAN;
#define FRAME_STAT(field, agg, with, trial, ...) m->trial = NAN;
#define TRIAL_METRIC(trial, ...) m->trial = NAN;
#include "results/metrics.def"
}

void metrics_write_summary(csv_writer *w, const metric_totals *m, metric_slot s)
{
#define IN_SLOT(slot) (s == METRIC_CAT(METRIC_SLOT_, slot))
#define FRAME_METRIC(field, type, frames, fprec, from, agg, with, trial, sprec, slot, ...) \
    if (IN_SLOT(slot))                                                                   \
        csv_f64(w, m->trial, sprec);
#define FRAME_STAT(field, agg, with, trial, sprec, slot, ...) \
    if (IN_SLOT(slot))                                        \
        csv_f64(w, m->trial, sprec);
#define FRAME_DERIVED(name, frames, fexpr, fprec, sexpr, sprec, slot, ...) \
    if (IN_SLOT(slot))                                                     \
        csv_f64(w, sexpr, sprec);
#define TRIAL_METRIC(trial, sprec, from, slot, ...) \
    if (IN_SLOT(slot))                              \
        csv_f64(w, m->trial, sprec);
#include "results/metrics.def"
#undef IN_SLOT
}

/* ---- the table of columns ------------------------------------------------------------ */

#define METRIC_FRAMES_NAME_F(name) name
#define METRIC_FRAMES_NAME__(name) ""
#define METRIC_AGG_TEXT_MEAN "mean over every frame"
#define METRIC_AGG_TEXT_MEAN_FINITE "mean over the frames that have one"
#define METRIC_AGG_TEXT_MAX_FINITE "largest over the frames that have one"
#define METRIC_AGG_TEXT_P50 "median (nearest rank) over the frames that have one"

const metric_doc metric_docs[] = {
#define FRAME_METRIC(field, type, frames, fprec, from, agg, with, trial, sprec, slot, unit,   \
                     none, doc)                                                              \
    {METRIC_CAT(METRIC_FRAMES_NAME_, frames)(#field), #trial, #slot,                          \
     METRIC_AGG_TEXT_##agg, unit, none, doc},
#define FRAME_STAT(field, agg, with, trial, sprec, slot, unit, none, doc) \
    {"", #trial, #slot, METRIC_AGG_TEXT_##agg, unit, none, doc},
#define FRAME_DERIVED(name, frames, fexpr, fprec, sexpr, sprec, slot, unit, none, doc) \
    {METRIC_CAT(METRIC_FRAMES_NAME_, frames)(#name), #name, #slot, "derived", unit, none, doc},
#define TRIAL_METRIC(trial, sprec, from, slot, unit, none, doc) \
    {"", #trial, #slot, "once per trial", unit, none, doc},
#include "results/metrics.def"
};
const size_t metric_ndocs = sizeof metric_docs / sizeof metric_docs[0];
