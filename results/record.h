#pragma once
/* One measured frame, as the run loop hands it to the result sinks.
 * Plain data, no GL: results/ never includes GL headers. */
#include <stdint.h>

typedef struct frame_record {
    uint32_t frame;        /* index among measured frames (warm-up excluded), from 0 */
    double t_wall_s;       /* end of this frame, seconds since measurement start on the
                            * measured clock (CLOCK_MONOTONIC less the pauses for
                            * screenshots and comparisons, runner/run.c) */
    double t_scene_s;      /* schedule time the scene was drawn at */
    uint32_t lights;       /* lights active in the scene this frame */
    double frametime_us;   /* CPU wall time from frame start to its sync point */
    double gpu_us;         /* GL_TIME_ELAPSED sum over passes; NAN when unavailable */
    uint64_t draw_calls;
    uint64_t state_changes;
    double fragments;      /* fragment shader invocations; NAN when unavailable */
    double samples;        /* GL_SAMPLES_PASSED of the shading draws; NAN when unavailable */
    uint64_t dispatches;   /* compute dispatches (not in draw_calls) */
    /* tiled and clustered renderers (NAN for the others): mean and largest light-list
     * length over the tiles or clusters, light evaluations per shaded pixel */
    double cell_lights_mean, cell_lights_max, light_evals_per_pixel;
    /* G-buffer renderers (NAN for the others): seed 002's G-buffer bytes written by the
     * G-buffer pass and read by the light passes (results/bandwidth.h) */
    double gbuffer_write_bytes, gbuffer_read_bytes;
    /* msaa: fragment shader runs in samples (frame_stats.total.samples_shaded; NAN when
     * unavailable), and deferred's fraction of edge pixels (NAN for the others) */
    double samples_shaded, edge_fraction;
} frame_record;
