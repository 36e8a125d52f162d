#pragma once
/* The workload a run measured, shown beside its time (issue 36): how many of the frame's
 * lights reach each pixel's surface, whatever the renderer culls (counted on the GPU by
 * renderer_lights_reaching, between frames), its statistics, its heat map, and the
 * lights themselves (lights.csv). No GL here. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "scenes/scene.h"

/* Over the covered pixels (a count other than UINT32_MAX): the mean, the nearest-rank
 * median and 99th percentile, the largest, and how many pixels; every value NAN (and
 * covered 0) when no pixel is covered. */
typedef struct workload_reach {
    double mean, p50, p99, max;
    uint64_t covered;
} workload_reach;

/* counts: n pixels, each at most nlights or UINT32_MAX (no geometry). False only when
 * out of memory (*out then all NAN). */
bool workload_reach_stats(const uint32_t *counts, size_t n, uint32_t nlights,
                          workload_reach *out);

/* The brute-force warning: with at least WORKLOAD_WARN_MIN_LIGHTS lights, the lights
 * reaching a pixel average more than half of them. True with the one-line message in
 * msg (no newline); false (msg "") otherwise, or when either value is not finite. */
#define WORKLOAD_WARN_MIN_LIGHTS 8
bool workload_brute_force(double reach_mean, double lights, char *msg, size_t len);

/* The heat map of counts (width x height, GL's rows: row 0 at the bottom) as an RGB PNG
 * at path (image_write: atomically): a covered pixel grey, 255 x count / nlights rounded
 * (black: no light, white: every light of the frame; nlights 0: black), a pixel without
 * geometry blue (0, 0, 255). False with a message. */
bool workload_heat_map(const char *path, const uint32_t *counts, int width, int height,
                       uint32_t nlights, char *err, size_t errlen);

/* lights.csv at path (atomically): a row per light the run will ever have, in the
 * scene's order, as s holds them now: light (index), kind (point, spot, directional), x,
 * y, z (world space; empty for directional), range (empty for directional), r, g, b,
 * dir_x, dir_y, dir_z (spot and directional, world space, the way light travels),
 * cone_rad (spot: the outer half-angle), on_s (the schedule time it turns on: 0 for a
 * fixed count; empty for a light a growth schedule never turns on). Floats as the
 * shortest decimal that strtof reads back to the same float (num_plain_float). False with
 * a message. */
bool workload_lights_csv(const char *path, const scene *s, char *err, size_t errlen);
