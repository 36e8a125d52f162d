#pragma once
/* The run loop (DESIGN.md "The data's way through"): for each run of the plan
 * (of one shard), a GL context at the run's resolution, the scene, the renderer
 * and its pass plan; per trial a warm-up, then measured frames, each ending at
 * glFinish or a fence wait; then per-second bins, the trial's summary and the
 * run's files. */
#include <stdbool.h>
#include "renderers/gl/context.h"
#include "runner/manifest.h"

typedef struct run_options {
    const char *out_dir;       /* the experiment's output folder; exists */
    gl_backend backend;
    int device;                /* -1: EGL surfaceless; N: EGL device N */
    bool debug_gl;             /* debug context: any GL error fails the run */
    unsigned shard;            /* only runs of this shard (0 = all) */
} run_options;

/* 0: every run succeeded; 1: some run failed (its rows say why); 2: the sweep
 * could not go on (message printed). */
int run_plan(const experiment *e, const plan *p, const run_options *o);
