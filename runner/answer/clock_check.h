#pragma once
/* compare's reading of the GPU clocks (issue 38, item 3): each trial's median SM clock
 * from NVML (summary.csv sm_clock_mhz, runner/trial/run_clocks.c). Rounds whose two
 * clocks differ by more than CLOCK_TOLERANCE are flagged, and GPU time is set beside
 * the same time at BASE's clock: a trial's gpu_mean_us x its clock / the BASE run's
 * median clock, which holds where the GPU time scales with the SM clock (a pass bound
 * by memory does not: the raw ratio stays beside it). */
#include <stdbool.h>
#include <stddef.h>

#include "results/verdict.h"
#include "runner/answer/run_model.h"

#define CLOCK_TOLERANCE 0.02
#define CLOCK_MAX_FLAGGED 16

typedef struct clock_check {
    bool any;                  /* a trial of either side has a clock */
    double base_mhz, new_mhz;  /* the medians over each side's trials (NAN: none) */
    size_t nflagged;           /* paired: rounds flagged; unpaired: 1 when the medians are */
    unsigned flagged[CLOCK_MAX_FLAGGED];   /* paired: the first of those rounds (1-based) */
    ratio_ci gpu, gpu_norm;    /* NEW / BASE of GPU time, raw and at BASE's clock (NAN:
                                * no GPU time, or no clock on a trial that has one) */
} clock_check;

/* The clocks of run a (BASE) and b (NEW); paired: trial k of both ran in round k. */
void clock_check_pair(const run_result *a, const run_result *b, bool paired,
                      clock_check *out);
