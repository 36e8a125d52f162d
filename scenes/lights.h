#pragma once
/* How a run's lights are placed and how many are active over schedule time. */
#include <stdbool.h>
#include <stdint.h>
#include "scenes/rng.h"

/* random: uniform in the scene's light bounds (positions, then colours, per light);
 * none: no lights;
 * grid: on a regular grid of cells in the light bounds, one light at each cell's centre
 *   (coverage studies): columns in x and z, one layer at mid-height unless the bounds are
 *   tall enough that more layers space the lights further apart; the grid is laid out
 *   for the schedule's largest count, filled in row order (x fastest, then z, then y), so
 *   growth never moves earlier lights; colours as random. A radius over half the
 *   neighbours' spacing (spheres that would overlap) fails scene_build, naming the
 *   spacing and the largest radius allowed;
 * scene: the scene's authored lights, in the order scene_*.c lists them; the count caps
 *   how many are ever on (growth turns them on in that order). They keep their own
 *   type, range, colour, attenuation and shadows: seed, rng, radius, overlap, color_max
 *   and attenuation do not apply. A scene without authored lights fails scene_build;
 * surface: near the scene's surfaces as they stand at schedule time 0, in the space in
 *   front of them (never inside a closed mesh, where random placement puts many of a
 *   file scene's lights): per light, a triangle of any object with probability in
 *   proportion to its area, a point uniform on it, then a quarter of the light's radius
 *   along the triangle's front-face normal; colours as random. With overlap > 0 the
 *   radius is the one at which a point of the surfaces is reached by `overlap` lights on
 *   average (n pi r^2 / area = overlap). A scene without triangle area fails scene_build. */
typedef enum light_placement {
    PLACEMENT_RANDOM = 0,
    PLACEMENT_NONE,
    PLACEMENT_GRID,
    PLACEMENT_SCENE,
    PLACEMENT_SURFACE,
} light_placement;

/* The manifest's names of the placements, in enum order, NULL-ended. */
extern const char *const light_placement_names[];
const char *light_placement_name(light_placement p);

/* count `all` (manifest): every authored light of the scene (placement scene only). */
#define LIGHT_COUNT_ALL UINT32_MAX

/* count: a fixed number (growth = false, start = max = n) or a growth schedule:
 * active(t) = min(max, start + step * floor(t / every)). */
typedef struct light_count {
    bool growth;
    uint32_t start, step, max;
    double every;              /* seconds of schedule time */
} light_count;

/* lights.sizing: how a placed light's range and colour are tied (random, grid and
 * surface placement; the scene's own lights keep theirs). The two derived forms need
 * the run's exposure, known only once the metering frame is drawn: lights_size (below)
 * applies them after the build. */
typedef enum light_sizing {
    LIGHT_SIZING_RADIUS = 0,          /* range = radius (or overlap's), colour as drawn */
    LIGHT_SIZING_RANGE_FROM_INTENSITY,/* range = sqrt(max channel x exposure / cutoff) */
    LIGHT_SIZING_INTENSITY_FROM_RANGE,/* colour x cutoff range^2 / (exposure color_max) */
} light_sizing;

typedef struct light_params {
    light_placement placement;
    uint32_t seed;             /* default 1337, as seed 003 */
    rng_kind rng;
    light_count count;
    float radius;              /* range of each point light, world units */
    float overlap;             /* > 0 (random and grid): the radius is
                                * lights_overlap_radius(count max, overlap, light bounds),
                                * so that a point of the light bounds is reached by
                                * `overlap` lights on average; 0: use radius */
    float color_max;           /* each channel uniform in [0, color_max]; seed 003 used 0.3 */
    int attenuation;           /* attenuation_kind (scenes/scene.h) */
    float quadratic[3];        /* a, b, c of 1 / (a d^2 + b d + c) */
    int sizing;                /* light_sizing */
    float cutoff;              /* the derived sizings' light at the range, of display white */
} light_params;

/* Lights active at schedule time t (t < 0 counts as 0). */
uint32_t light_count_at(const light_count *c, double t);
/* The most lights the schedule ever has. */
uint32_t light_count_max(const light_count *c);

/* The radius at which n lights placed uniformly in the box [bmin, bmax] reach, on
 * average, k lights per point of the box: n (4/3 pi r^3) / V = k, so
 * r = cbrt(3 k V / (4 pi n)); a flat box (zero extent in one axis) uses the disc area,
 * n pi r^2 / A = k, r = sqrt(k A / (pi n)); a box flat in two axes the segment length,
 * n 2 r / L = k, r = k L / (2 n). Boundary losses are ignored, as seed 000's and 003's
 * placements did: the mean holds for points at least r inside the box, and is lower
 * nearer its faces. 0 when n = 0, k is not positive and finite, or the box is empty
 * (min > max on an axis, or a single point). */
float lights_overlap_radius(uint32_t n, float k, const float bmin[3], const float bmax[3]);
