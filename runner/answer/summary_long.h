#pragma once
/* OUT/summary_long.csv: summary.csv in long ("tidy") form for scripts
 * (runner/answer/summary_long.c), one row per run x trial x measured value:
 *
 *   experiment, run_id, renderer, scene, KEY..., trial, status, measure, unit, value
 *
 * KEY... are the plan.csv parameters that vary across the plan's runs (renderer and
 * scene aside), one typed column each, named by its manifest key: numbers in plain
 * decimals, true/false, or text; a span (warmup, duration) as KEY_frames and KEY_s, one
 * of them empty; a resolution also as width_px and height_px. `measure` is the
 * summary.csv column, `unit` its unit (output.h summary_column_unit), `value` a plain
 * decimal; a value summary.csv leaves empty has no row. Written by the end-of-sweep step
 * (summary_table_write) of run, run --resume and merge. */
#include <stdbool.h>
#include <stddef.h>

#include "results/csvread.h"

/* Writes OUT/summary_long.csv from plan.csv (pl) and summary.csv (sm) into `set`
 * (fsutil.h: renamed with the folder's other summaries). */
struct afile_set;
bool summary_long_write(const char *out_dir, const csv_table *pl, const csv_table *sm,
                        struct afile_set *set, char *err, size_t errlen);
