#pragma once
/* Stochastic light culling (lights.culling: stochastic; Tokuyoshi and Harada, "Stochastic
 * Light Culling", JCGT 5(1), 2016; docs/notes/stochastic-culling.md): each frame, each
 * point or spot light j draws xi_j, uniform in (0, 1], from a stream seeded by the
 * scene's lights.seed and the schedule time, and its culling range becomes the distance
 * where I_j a(d) falls to culling_error x xi_j (I_j: its largest channel x exposure,
 * a(d): its attenuation), never beyond its own range. The shader (lighting.inc's
 * STOCHASTIC: light_cull_range, stochastic_weight) culls and drops beyond that range
 * and weights what it keeps by 1 / P(d), P(d) = min(1, I_j a(d) / culling_error): the
 * expected image is the exact one. A renderer that culls this way calls
 * stochastic_ranges on its packed lights before the upload and compiles its programs
 * with STOCHASTIC (renderer_base.stochastic); directional lights are left as they are. */
#include <stdint.h>

#include "renderers/frame/shading.h"
#include "scenes/scene.h"

/* The frame's stream: lights.seed mixed with the bits of the schedule time t. */
uint64_t stochastic_stream(uint32_t seed, double t);
/* Light `index`'s (its index in the scene) uniform of the stream, in [2^-24, 1]. */
double stochastic_xi(uint64_t stream, uint32_t index);
/* The distance where the attenuation of packed light l (lighting.inc's, its kind in
 * v[3][1]) falls to `threshold` (> 0), at most its range; 0 where it never reaches it. */
double stochastic_solve(const gpu_light *l, double threshold);
/* The n packed lights (ids[k]: light k's index in s->lights) made stochastic for the
 * frame of s at culling_error (> 0): v[3][3] the culling range, v[4][3] q =
 * culling_error / I_j (0: the light is kept whole, as a directional one). */
void stochastic_ranges(gpu_light *lights, const uint32_t *ids, uint32_t n, const scene *s,
                       float culling_error);
