#pragma once
/* `shadesweep merge -o OUT DIR...`: combines the output folders of shards of one
 * manifest (their sweep.yaml must name the same manifest hash and their plan.csv
 * must be the same) into OUT: every complete run copied, plan.csv, sweep.yaml and
 * summary.csv in plan order. Returns the exit code: 0 every run of the plan is
 * there; 1 some are missing (listed); 2 the folders cannot be merged. */
#include <stdbool.h>

/* Folders that are not shadesweep's output (the test of run --resume) are refused, and
 * so, unless allow_mixed, are runs made by different builds (meta.yaml's version and
 * commit), before OUT is touched. */
int merge_main(const char *out, bool force, bool allow_mixed, int ndirs, char **dirs);
