#pragma once
#include <stdbool.h>
#include <stddef.h>
#include "runner/manifest/manifest.h"

/* --resume: true when every run of dir's plan.csv is a run of p (or dir has no
 * plan.csv yet); else false with "--resume: the plan differs from DIR's: N of its M
 * runs are not in this plan (WHAT CHANGED); use --force to start over ...", naming
 * a changed scene file by its path and content hashes, or the keys whose values
 * changed. An unreadable plan.csv is refused too. Reads only. */
bool resume_plan_check(const char *dir, const plan *p, char *err, size_t errlen);
