#pragma once
/* Who wins at a sweep point, in one line (runner/answer/point_verdict.c): "fastest X, then Y at
 * 1.23x (1.10-1.35)", or "X and Y tie (...)" where the paired ratio's 95% interval of
 * the runner-up to the fastest holds 1. By the metric that ranks (summary.csv
 * metric_us), from the same paired ratios as `x fastest`. On the terminal at the end of
 * a run, under each point's table in summary.md, in summary.json and report.md. */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "runner/answer/run_model.h"

/* The verdict of point p (its runs ranked, the fastest first) into out: the fastest,
 * the runs that tie with it (their ratio to it holds 1, in rank order until the first
 * that does not), then the next with its ratio to the fastest. cfg[r]: run r's
 * configuration label. False, out "", when fewer than two runs have a value, or the
 * first two are one configuration (the one-renderer table of every point). */
bool point_verdict(const run_result *runs, const summary_point *p, char *const *cfg,
                   char *out, size_t len);
/* A line a point with a verdict, "verdict: LABEL: ...", at most 24 (then how many more
 * summary.md has). */
void point_verdicts_print(FILE *t, const run_result *runs, const summary_point *pts, size_t n,
                          char *const *cfg);
