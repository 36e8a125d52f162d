#pragma once
/* One measured frame, as the run loop hands it to the result sinks.
 * Plain data, no GL: results/ never includes GL headers. */
#include <stdint.h>

#include "results/metrics.h"

typedef struct frame_record {
    uint32_t frame;        /* index among measured frames (warm-up excluded), from 0 */
    double t_wall_s;       /* end of this frame, seconds since measurement start on the
                            * measured clock (CLOCK_MONOTONIC less the pauses for
                            * screenshots and comparisons, runner/trial/run.c) */
    double t_scene_s;      /* schedule time the scene was drawn at */
    uint32_t lights;       /* lights active in the scene this frame */
    double frametime_us;   /* CPU wall time from frame start to its sync point */
    /* the measured quantities of results/metrics.def (gpu_us, draw_calls, ...): F64
     * members are NAN when the frame has no value */
#define FRAME_METRIC(field, type, ...) METRIC_CTYPE(type) field;
#include "results/metrics.def"
} frame_record;

/* One frame's table columns in frames.csv. */
void metrics_write_frame(csv_writer *w, const frame_record *r);
