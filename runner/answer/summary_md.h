#pragma once
/* The answer at the end of a sweep (runner/answer/summary_md.c): the runs of OUT/summary.csv,
 * grouped by sweep point (the runs whose plan.csv parameters are equal but for the
 * renderer), each point's configurations ranked by the mean over their trials of the
 * metric that decides (summary.csv `metric`, `metric_us`: measure.metric), with its
 * 95% t interval over the trials; `x fastest` is the geometric mean of the per-round
 * ratios to the fastest (paired: round k ran trial k of each, results/verdict.h) with
 * its 95% interval, and `differs` says whether that interval excludes 1. The trial is
 * the unit: nothing pools frames across trials, and fewer than 3 trials give no
 * verdict. Wall time is shown beside the metric; the worst image RMSE where measured;
 * p99 frame time and the 1% low FPS. A compact table to a terminal and OUT/summary.md.
 * The runs it ranks, and their loading, are the run model (runner/answer/run_model.h). */
#include <stdbool.h>
#include <stdio.h>
#include "runner/answer/run_model.h"

/* Writes OUT/summary.md, summary.json and summary_long.csv, renamed together, and prints
 * the compact table to `terminal` (NULL: none). False with a message when summary.csv or
 * plan.csv is unreadable or a summary could not be written: then none of the three is
 * left from before (the message names those removed, or any that could not be). */
bool summary_table_write(const char *out_dir, FILE *terminal, char *err, size_t errlen);
