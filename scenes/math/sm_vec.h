#pragma once
/* scenes/math/sm_vec.h: in-tree vector math in the style of cglm (with sm_mat.h, sm_view.h
 * and sm_bounds.h, each including the one before it).
 *
 * Header-only, every function `static inline`, every name prefixed `sm_`; only what
 * the product uses (git history has the quaternions and vec2 operations a later
 * feature may want back). Types are float arrays; matrices are column-major
 * (m[col][row]), as OpenGL expects:
 *
 *   sm_vec2 sm_vec3 sm_vec4   float[2], float[3], float[4]
 *   sm_mat3 sm_mat4           sm_vec3[3], sm_vec4[4]      (columns)
 *   sphere                    sm_vec4: x, y, z centre, w radius (radius >= 0), like cglm
 *   AABB                      sm_vec3 box[2]: box[0] min corner, box[1] max corner
 *   plane                     sm_vec4: a, b, c, d; signed distance = dot(abc, p) + d
 *
 * Conventions, degenerate input and the list of functions: the comment above the types. */
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <string.h>

/* Conventions: inputs first, output (`dest`) last. Inputs are `const`; passing a
 * non-const matrix to a `const sm_mat4` parameter is fine in GCC/Clang C11 (only
 * -Wpedantic complains before C2x). Unless a function says otherwise, every output may
 * alias any input (results are built in temporaries first). Functions named `verb(v)`
 * work in place; `verb_to(v, dest)` writes elsewhere.
 *
 * Degenerate input gets a defined, documented result, never a trap or a NaN made from
 * nothing (results that overflow float are +-inf, as for any float arithmetic):
 * normalizing a zero vector gives the zero vector; very small and very large finite
 * vectors are normalized correctly (rescaled first); a vector with a NaN or infinite
 * component normalizes to all-NaN. (The matrices, the camera and the bounds say theirs.)
 *
 * Here: SM_PI, SM_PI_2, sm_deg2rad, sm_rad2deg, sm_clamp;
 *   vec3  sm_vec3_make, _copy, _zero, _add, _sub, _scale, _muladds (dest += a * s), _dot,
 *         _norm, _norm2, _normalize, _normalize_to, _min, _max (componentwise), _negate,
 *         _negate_to, _cross, _distance, _distance2
 *   vec4  sm_vec4_make, _copy, _from_vec3, _zero, _add, _sub, _scale
 * Names with `sm__` are internal helpers.
 */
typedef float sm_vec2[2];
typedef float sm_vec3[3];
typedef float sm_vec4[4];
typedef sm_vec3 sm_mat3[3];
typedef sm_vec4 sm_mat4[4];

/* >>scalars */

#define SM_PI   3.14159265358979323846f
#define SM_PI_2 1.57079632679489661923f

static inline float sm_deg2rad(float deg) { return deg * (SM_PI / 180.0f); }
static inline float sm_rad2deg(float rad) { return rad * (180.0f / SM_PI); }

/* x clamped to [lo, hi]; NaN gives lo. */
static inline float sm_clamp(float x, float lo, float hi)
{
    return x >= lo ? (x <= hi ? x : hi) : lo;
}

/* >>internal */

/* Euclidean norm of n floats without spurious overflow or underflow: the plain sum of
 * squares is used when it is a normal float; otherwise the vector is rescaled by its
 * largest component first. NaN component: NaN; infinite component: +inf. */
static inline float sm__norm_n(const float *v, int n)
{
    float n2 = 0.0f, m = 0.0f, s = 0.0f;
    for (int i = 0; i < n; i++)
        n2 += v[i] * v[i];
    if (n2 >= FLT_MIN && n2 <= FLT_MAX)
        return sqrtf(n2);
    if (isnan(n2))
        return n2;
    for (int i = 0; i < n; i++)
        if (fabsf(v[i]) > m)
            m = fabsf(v[i]);
    if (m == 0.0f || m > FLT_MAX)
        return m;
    for (int i = 0; i < n; i++) {
        float t = v[i] / m;
        s += t * t;
    }
    return m * sqrtf(s);
}

/* dest = v / |v| for n floats; zero gives zero, NaN or inf components give all-NaN.
 * dest may alias v. */
static inline void sm__normalize_n(const float *v, int n, float *dest)
{
    float n2 = 0.0f, m = 0.0f, s = 0.0f, k;
    for (int i = 0; i < n; i++)
        n2 += v[i] * v[i];
    if (n2 >= FLT_MIN && n2 <= FLT_MAX) {
        k = 1.0f / sqrtf(n2);
        for (int i = 0; i < n; i++)
            dest[i] = v[i] * k;
        return;
    }
    for (int i = 0; i < n; i++)
        if (fabsf(v[i]) > m)
            m = fabsf(v[i]);
    if (isnan(n2) || m > FLT_MAX) {
        for (int i = 0; i < n; i++)
            dest[i] = NAN;
        return;
    }
    if (m == 0.0f) {
        for (int i = 0; i < n; i++)
            dest[i] = 0.0f;
        return;
    }
    /* Rescale by the largest magnitude: the sum of squares is then in [1, n], and
     * neither |v| nor 1/|v| (which may not be representable) is formed. */
    for (int i = 0; i < n; i++) {
        float t = v[i] / m;
        s += t * t;
    }
    k = 1.0f / sqrtf(s);
    for (int i = 0; i < n; i++)
        dest[i] = (v[i] / m) * k;
}

/* >>vec3 */

static inline void sm_vec3_make(float x, float y, float z, sm_vec3 dest)
{
    dest[0] = x;
    dest[1] = y;
    dest[2] = z;
}

static inline void sm_vec3_copy(const sm_vec3 a, sm_vec3 dest)
{
    sm_vec3_make(a[0], a[1], a[2], dest);
}

static inline void sm_vec3_zero(sm_vec3 v) { v[0] = v[1] = v[2] = 0.0f; }

static inline void sm_vec3_add(const sm_vec3 a, const sm_vec3 b, sm_vec3 dest)
{
    dest[0] = a[0] + b[0];
    dest[1] = a[1] + b[1];
    dest[2] = a[2] + b[2];
}

static inline void sm_vec3_sub(const sm_vec3 a, const sm_vec3 b, sm_vec3 dest)
{
    dest[0] = a[0] - b[0];
    dest[1] = a[1] - b[1];
    dest[2] = a[2] - b[2];
}

static inline void sm_vec3_scale(const sm_vec3 v, float s, sm_vec3 dest)
{
    dest[0] = v[0] * s;
    dest[1] = v[1] * s;
    dest[2] = v[2] * s;
}

/* dest += a * s */
static inline void sm_vec3_muladds(const sm_vec3 a, float s, sm_vec3 dest)
{
    dest[0] += a[0] * s;
    dest[1] += a[1] * s;
    dest[2] += a[2] * s;
}

static inline float sm_vec3_dot(const sm_vec3 a, const sm_vec3 b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline float sm_vec3_norm2(const sm_vec3 v) { return sm_vec3_dot(v, v); }
static inline float sm_vec3_norm(const sm_vec3 v) { return sm__norm_n(v, 3); }
static inline void sm_vec3_normalize_to(const sm_vec3 v, sm_vec3 dest) { sm__normalize_n(v, 3, dest); }
static inline void sm_vec3_normalize(sm_vec3 v) { sm__normalize_n(v, 3, v); }

/* dest = a x b (right-handed); dest may alias a or b. */
static inline void sm_vec3_cross(const sm_vec3 a, const sm_vec3 b, sm_vec3 dest)
{
    float x = a[1] * b[2] - a[2] * b[1];
    float y = a[2] * b[0] - a[0] * b[2];
    float z = a[0] * b[1] - a[1] * b[0];
    dest[0] = x;
    dest[1] = y;
    dest[2] = z;
}

static inline float sm_vec3_distance2(const sm_vec3 a, const sm_vec3 b)
{
    sm_vec3 d;
    sm_vec3_sub(a, b, d);
    return sm_vec3_norm2(d);
}

static inline float sm_vec3_distance(const sm_vec3 a, const sm_vec3 b)
{
    sm_vec3 d;
    sm_vec3_sub(a, b, d);
    return sm_vec3_norm(d);
}

/* Componentwise minimum / maximum (like glm_vec3_minv / maxv; NaN yields the other). */
static inline void sm_vec3_min(const sm_vec3 a, const sm_vec3 b, sm_vec3 dest)
{
    dest[0] = fminf(a[0], b[0]);
    dest[1] = fminf(a[1], b[1]);
    dest[2] = fminf(a[2], b[2]);
}

static inline void sm_vec3_max(const sm_vec3 a, const sm_vec3 b, sm_vec3 dest)
{
    dest[0] = fmaxf(a[0], b[0]);
    dest[1] = fmaxf(a[1], b[1]);
    dest[2] = fmaxf(a[2], b[2]);
}

static inline void sm_vec3_negate_to(const sm_vec3 v, sm_vec3 dest)
{
    dest[0] = -v[0];
    dest[1] = -v[1];
    dest[2] = -v[2];
}

static inline void sm_vec3_negate(sm_vec3 v) { sm_vec3_negate_to(v, v); }

/* >>vec4 */

static inline void sm_vec4_make(float x, float y, float z, float w, sm_vec4 dest)
{
    dest[0] = x;
    dest[1] = y;
    dest[2] = z;
    dest[3] = w;
}

static inline void sm_vec4_copy(const sm_vec4 a, sm_vec4 dest)
{
    sm_vec4_make(a[0], a[1], a[2], a[3], dest);
}

/* (v.xyz, w) */
static inline void sm_vec4_from_vec3(const sm_vec3 v, float w, sm_vec4 dest)
{
    dest[0] = v[0];
    dest[1] = v[1];
    dest[2] = v[2];
    dest[3] = w;
}

static inline void sm_vec4_zero(sm_vec4 v) { v[0] = v[1] = v[2] = v[3] = 0.0f; }

static inline void sm_vec4_add(const sm_vec4 a, const sm_vec4 b, sm_vec4 dest)
{
    for (int i = 0; i < 4; i++)
        dest[i] = a[i] + b[i];
}

static inline void sm_vec4_sub(const sm_vec4 a, const sm_vec4 b, sm_vec4 dest)
{
    for (int i = 0; i < 4; i++)
        dest[i] = a[i] - b[i];
}

static inline void sm_vec4_scale(const sm_vec4 v, float s, sm_vec4 dest)
{
    for (int i = 0; i < 4; i++)
        dest[i] = v[i] * s;
}
