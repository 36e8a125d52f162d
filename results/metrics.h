#pragma once
/* The measured quantities of results/metrics.def: a trial's values (metric_totals),
 * the CSV columns they make in frames.csv and summary.csv, their writers, and the
 * table of columns (`shadesweep columns`, docs/columns.md). No GL. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "results/csv.h"

/* type column: the C type of a frame_record member */
#define METRIC_CTYPE_F64 double
#define METRIC_CTYPE_U64 uint64_t
#define METRIC_CTYPE(type) METRIC_CAT(METRIC_CTYPE_, type)

#define METRIC_CAT_(a, b) a##b
#define METRIC_CAT(a, b) METRIC_CAT_(a, b)

/* METRIC_IF(tag, want, ...): the arguments where tag is want (S1, S2, S3 or F), else
 * nothing: a slot's or frames.csv's columns, chosen at compile time. */
#define METRIC_IF(tag, want, ...) METRIC_CAT(METRIC_IF_, METRIC_CAT(tag, want))(__VA_ARGS__)
#define METRIC_IF_S1S1(...) __VA_ARGS__
#define METRIC_IF_S1S2(...)
#define METRIC_IF_S1S3(...)
#define METRIC_IF_S2S1(...)
#define METRIC_IF_S2S2(...) __VA_ARGS__
#define METRIC_IF_S2S3(...)
#define METRIC_IF_S3S1(...)
#define METRIC_IF_S3S2(...)
#define METRIC_IF_S3S3(...) __VA_ARGS__
#define METRIC_IF_FF(...) __VA_ARGS__
#define METRIC_IF__F(...)

/* What a trial states, one double per summary.csv column of the table (NAN: empty). */
typedef struct metric_totals {
#define FRAME_METRIC(field, type, frames, fprec, from, agg, with, trial, ...) double trial;
#define FRAME_STAT(field, agg, with, trial, ...) double trial;
#define TRIAL_METRIC(trial, ...) double trial;
#include "results/metrics.def"
} metric_totals;

/* Every member NAN: a trial that measured nothing (summary.csv: empty fields). */
void metric_totals_none(metric_totals *m);

/* The table's column names, as initialisers of a `const char *const []`: define
 * METRIC_WANT as the slot (S1, S2, S3), or METRIC_WANT_FRAMES for frames.csv's, then
 * #include "results/metric_names.inc" (it undefines them). */
typedef enum metric_slot { METRIC_SLOT_S1, METRIC_SLOT_S2, METRIC_SLOT_S3 } metric_slot;

/* One trial's table columns of `slot` in summary.csv (a frame's: record.h). */
void metrics_write_summary(csv_writer *w, const metric_totals *m, metric_slot slot);

/* One row of the table of columns (docs/columns.md, `shadesweep columns`). */
typedef struct metric_doc {
    const char *frames;        /* frames.csv column, "" when none */
    const char *summary;       /* summary.csv column */
    const char *slot;          /* "S1", "S2", "S3" */
    const char *agg;           /* how the trial states it, in words */
    const char *unit, *none, *doc;
} metric_doc;
extern const metric_doc metric_docs[];
extern const size_t metric_ndocs;
