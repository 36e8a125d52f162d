#pragma once
/* What the procedural mesh generators share (scenes/builtin/mesh_*.c); not part of the scenes
 * interface (nothing outside scenes/ includes it). Defined in scenes/builtin/mesh_gen.c. */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "scenes/mesh.h"

#define PI_D 3.14159265358979323846264338327950288
#define TWO_PI (2.0 * PI_D)

static inline bool mg_positive(float x) { return isfinite(x) && x > 0.0f; }

/* Allocates nv vertices and ni indices into a zeroed *m. */
bool mg_alloc(mesh *m, uint64_t nv, uint64_t ni, const char *who, char *err, size_t errlen);
/* v->normal = normalize(n), or `fallback` (unit) when n is zero or not finite. */
void mg_set_normal(mesh_vertex *v, const sm_vec3 n, const sm_vec3 fallback);
/* v->tangent from (unnormalized) dP/du and dP/dv and v->normal (unit). */
void mg_set_frame(mesh_vertex *v, const sm_vec3 dpdu, const sm_vec3 dpdv);
/* Writes triangle (a, b, c) at *ip and moves *ip past it. */
void mg_tri(uint32_t **ip, uint32_t a, uint32_t b, uint32_t c);
/* sin and cos of angle j of n about Y (offset by `offset` steps), computed once in double. */
void mg_angle_of(uint32_t j, uint32_t n, double offset, float *s, float *c);
/* r = a x b, in double. */
void mg_cross_d(const double a[3], const double b[3], double r[3]);
