#pragma once
/* How a run's lights are placed and how many are active over schedule time. */
#include <stdbool.h>
#include <stdint.h>
#include "scenes/rng.h"

/* random: uniform in the scene's light bounds (positions, then colours, per light);
 * none: no lights; grid: non-overlapping lights on a regular grid in the light bounds
 * (coverage studies); scene: the scene's authored lights (scene.c documents each). */
typedef enum light_placement {
    PLACEMENT_RANDOM = 0,
    PLACEMENT_NONE,
    PLACEMENT_GRID,
    PLACEMENT_SCENE,
} light_placement;

/* count: a fixed number (growth = false, start = max = n) or a growth schedule:
 * active(t) = min(max, start + step * floor(t / every)). */
typedef struct light_count {
    bool growth;
    uint32_t start, step, max;
    double every;              /* seconds of schedule time */
} light_count;

typedef struct light_params {
    light_placement placement;
    uint32_t seed;             /* default 1337, as seed 003 */
    rng_kind rng;
    light_count count;
    float radius;              /* range of each point light, world units */
    float overlap;             /* > 0: derive the radius so that the mean number of lights
                                * reaching a point of the light bounds is `overlap`
                                * (scene.c: lights_overlap_radius); 0: use radius */
    float color_max;           /* each channel uniform in [0, color_max]; seed 003 used 0.3 */
    int attenuation;           /* attenuation_kind (scenes/scene.h) */
    float quadratic[3];        /* a, b, c of 1 / (a d^2 + b d + c) */
} light_params;

/* Lights active at schedule time t (t < 0 counts as 0). */
uint32_t light_count_at(const light_count *c, double t);
/* The most lights the schedule ever has. */
uint32_t light_count_max(const light_count *c);

/* The radius at which n lights placed uniformly in the box [bmin, bmax] reach, on
 * average, k lights per point of the box: n (4/3 pi r^3) / V = k (a flat box, zero
 * extent in one axis, uses the disc area: n pi r^2 / A = k). Boundary losses are
 * ignored, as seed 000's and 003's placements did. 0 when n = 0 or the box is empty. */
float lights_overlap_radius(uint32_t n, float k, const float bmin[3], const float bmax[3]);
