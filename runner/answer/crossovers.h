#pragma once
/* Where two configurations change places along the numeric parameters a sweep varies
 * (lights.count, a resolution as its pixels, tiles.size, camera.hold, ...; not a seed,
 * which is a label). For each such parameter the runs are grouped by the other varying
 * parameters; in each group, for each pair of configurations (a renderer and its own
 * keys), the paired ratio of their trial values at each value both ran
 * (summary_paired_ratio: the runs of one value are of one sweep point, measured in the
 * same rounds), and results/verdict.c's verdict_crossover says where it crosses 1 and
 * the interval of where, between two values run (never beyond them). Kept only between
 * the leaders (the fastest of all configurations at the value before and at the value
 * after) and with evidence: the ratio's interval excludes 1 on both sides, or two values
 * each side agree. Written into summary.md and printed at the end of a run
 * (runner/answer/summary_md.c). */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "results/csvread.h"
#include "runner/answer/run_model.h"

typedef struct crossover_found {
    const char *axis;          /* the plan column */
    const char *group;         /* "k=v, ..." of the other varying parameters; "" */
    const char *below, *above; /* the configuration faster below / above the crossing */
    double x0, x1;             /* the values run either side */
    double x, lo, hi;          /* the crossing and its 95% interval (NAN: not within) */
    const char *differs0, *differs1;   /* summary_differs of the ratio at x0, x1 */
} crossover_found;

typedef struct crossover_list {
    crossover_found *item;
    size_t n, cap;
    size_t axes;               /* how many numeric axes were searched */
    size_t pruned;             /* crossings left out: not between the leaders, or too
                                * little evidence (crossovers.h's opening) */
    char **strings;            /* owned group labels */
    size_t nstrings, capstrings;
} crossover_list;

/* Every crossing, by axis in plan column order, then group, then configuration pair.
 * prow[r]: run r's plan.csv row (-1: none); varies[c]: column c varies across sweep
 * points (not the renderer's own keys); rcfg[r]: run r's configuration label (the strings
 * must outlive out). False when out of memory. Free with crossovers_free. */
bool crossovers_find(const run_result *runs, size_t nruns, const csv_table *pl,
                     const long *prow, const bool *varies, char *const *rcfg,
                     crossover_list *out);
/* Appends the crossings along a light count that grows over time (lights.count
 * {start, step, ...}) within each sweep point of two configurations or more: per run,
 * per trial, the mean of its metric's frames.csv column (cpu_us, gpu_us, frametime_us)
 * over the frames drawn at each count; per pair, the paired ratio at each count both
 * drew, and verdict_crossover. A run without frames.csv is left out. False when out of
 * memory. */
bool crossovers_growth(const char *out_dir, const run_result *runs, const summary_point *pts,
                       size_t npts, const csv_table *pl, const long *prow,
                       char *const *rcfg, crossover_list *out);
void crossovers_free(crossover_list *l);

/* The "## Crossovers" section of summary.md. */
void crossovers_write_md(FILE *fp, const crossover_list *l);
/* One line a crossing for the terminal; one line saying there is none where numeric
 * axes were searched. */
void crossovers_print(FILE *t, const crossover_list *l);
