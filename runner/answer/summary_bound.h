#pragma once
/* summary.md's "Bounds" section (issue 38, item 2): each run's bound from the folder's
 * device profile (runner/folder/bound_folder.h), its limiter and the bound over the
 * measured time, and a line naming every run whose bound is above its measured time
 * (a model error, never hidden); without a device.yaml, one line saying so. */
#include <stdio.h>

#include "results/csvread.h"

/* The section into md, for the rows of summary table sm of folder out_dir. */
void summary_bound_md(FILE *md, const char *out_dir, const csv_table *sm);
