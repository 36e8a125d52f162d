#pragma once
#include <stdbool.h>
#include "runner/diag.h"
#include "runner/manifest.h"

/* Refuses a plan some of whose runs would fail, or mean nothing, for reasons known
 * before any GL: every problem in d (at most a few), false if any. */
bool plan_check(const experiment *e, const plan *p, diag_list *d);
