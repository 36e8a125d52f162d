#pragma once
/* scenes/math.h: in-tree vector, matrix and quaternion math in the style of cglm.
 *
 * Header-only, every function `static inline`, every name prefixed `sm_`.
 * Types are float arrays; matrices are column-major (m[col][row]), as OpenGL expects:
 *
 *   sm_vec2 sm_vec3 sm_vec4   float[2], float[3], float[4]
 *   sm_mat3 sm_mat4           sm_vec3[3], sm_vec4[4]      (columns)
 *   sm_quat                   sm_vec4: x, y, z, w (w real), like cglm's versor
 *   sphere                    sm_vec4: x, y, z centre, w radius (radius >= 0), like cglm
 *   AABB                      sm_vec3 box[2]: box[0] min corner, box[1] max corner
 *   plane                     sm_vec4: a, b, c, d; signed distance = dot(abc, p) + d
 *
 * Conventions: inputs first, output (`dest`) last. Inputs are `const`; passing a
 * non-const matrix to a `const sm_mat4` parameter is fine in GCC/Clang C11 (only
 * -Wpedantic complains before C2x). Unless a function says otherwise, every output may
 * alias any input (results are built in temporaries first). Functions named `verb(v)`
 * work in place; `verb_to(v, dest)` writes elsewhere.
 *
 * Degenerate input gets a defined, documented result, never a trap or a NaN made from
 * nothing (results that overflow float are +-inf, as for any float arithmetic):
 *   - normalizing a zero vector gives the zero vector; very small and very large finite
 *     vectors are normalized correctly (rescaled first); a vector with a NaN or infinite
 *     component normalizes to all-NaN;
 *   - the inverse of a singular matrix is the zero matrix (see sm_mat4_inv);
 *   - a zero quaternion normalizes to (and rotates like) the identity;
 *   - rotation about a zero axis is the identity;
 *   - sm_lookat with eye == center looks down -Z; with `up` zero or parallel to the view
 *     direction it uses the world axis least aligned with the view direction as up;
 *   - sm_perspective / sm_ortho with invalid parameters give the zero matrix.
 *
 * What it offers:
 *   scalars      SM_PI, SM_PI_2, sm_deg2rad, sm_rad2deg, sm_clamp
 *   vec2/3/4     sm_vecN_make, _copy, _zero, _add, _sub, _scale, _mul (componentwise),
 *   (N=2,3,4)    _dot, _norm, _norm2, _normalize, _normalize_to, _lerp, _min, _max
 *                (componentwise), _negate, _negate_to, _muladds (dest += a * s)
 *   vec3         sm_vec3_cross, sm_vec3_distance, sm_vec3_distance2, sm_vec3_from_vec4
 *   vec4         sm_vec4_from_vec3
 *   mat3         sm_mat3_identity, _zero, _copy, _mul, _mulv, _transpose, _transpose_to,
 *                _det, _inv
 *   mat4         sm_mat4_identity, _zero, _copy, _mul, _mulv, _mulv3, _transpose,
 *                _transpose_to, _det, _inv, _translate_make, _scale_make, _rotate_make,
 *                _trs (T * R * S), _pick3, _normal (normal matrix)
 *   quaternion   sm_quat_identity, _make, _from_axis_angle, _dot, _norm, _normalize,
 *                _normalize_to, _conjugate, _inv, _mul, _rotatev, _to_mat3, _to_mat4, _slerp
 *   camera       sm_lookat, sm_look, sm_perspective, sm_ortho (right-handed, GL clip z -1..1)
 *   planes       sm_plane_normalize, sm_plane_distance, sm_frustum_planes (indexed by
 *                SM_LEFT, SM_RIGHT, SM_BOTTOM, SM_TOP, SM_NEAR, SM_FAR), sm_frustum_corners
 *   bounds       sm_sphere_in_frustum, sm_aabb_in_frustum, sm_aabb_transform,
 *                sm_aabb_empty, sm_aabb_is_empty, sm_aabb_merge, sm_aabb_center,
 *                sm_aabb_to_sphere, sm_aabb_sphere_intersects, sm_sphere_sphere_intersects,
 *                sm_point_in_sphere, sm_sphere_transform, sm_cone_sphere_intersects
 *
 * Names with `sm__` are internal helpers.
 */
#include <float.h>
#include <stdbool.h>
#include <string.h>
/* scenes/meson.build builds with implicit_include_directories : false, so this
 * <math.h> is the C library's, not this file; the check catches a setup where not. */
#include <math.h>
#if !defined(HUGE_VALF) || !defined(NAN) || !defined(INFINITY)
#error "scenes/math.h shadows the system <math.h>: build scenes/ with implicit_include_directories : false"
#endif

typedef float sm_vec2[2];
typedef float sm_vec3[3];
typedef float sm_vec4[4];
typedef sm_vec3 sm_mat3[3];
typedef sm_vec4 sm_mat4[4];
typedef sm_vec4 sm_quat;

/* >>scalars ------------------------------------------------------------------------- */

#define SM_PI   3.14159265358979323846f
#define SM_PI_2 1.57079632679489661923f

static inline float sm_deg2rad(float deg) { return deg * (SM_PI / 180.0f); }
static inline float sm_rad2deg(float rad) { return rad * (180.0f / SM_PI); }

/* x clamped to [lo, hi]; NaN gives lo. */
static inline float sm_clamp(float x, float lo, float hi)
{
    return x >= lo ? (x <= hi ? x : hi) : lo;
}

/* >>internal ------------------------------------------------------------------------- */

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

/* >>vec2 ------------------------------------------------------------------------------ */

static inline void sm_vec2_make(float x, float y, sm_vec2 dest) { dest[0] = x; dest[1] = y; }
static inline void sm_vec2_copy(const sm_vec2 a, sm_vec2 dest) { dest[0] = a[0]; dest[1] = a[1]; }
static inline void sm_vec2_zero(sm_vec2 v) { v[0] = v[1] = 0.0f; }

static inline void sm_vec2_add(const sm_vec2 a, const sm_vec2 b, sm_vec2 dest)
{
    dest[0] = a[0] + b[0];
    dest[1] = a[1] + b[1];
}

static inline void sm_vec2_sub(const sm_vec2 a, const sm_vec2 b, sm_vec2 dest)
{
    dest[0] = a[0] - b[0];
    dest[1] = a[1] - b[1];
}

static inline void sm_vec2_scale(const sm_vec2 v, float s, sm_vec2 dest)
{
    dest[0] = v[0] * s;
    dest[1] = v[1] * s;
}

/* Componentwise product. */
static inline void sm_vec2_mul(const sm_vec2 a, const sm_vec2 b, sm_vec2 dest)
{
    dest[0] = a[0] * b[0];
    dest[1] = a[1] * b[1];
}

/* dest += a * s */
static inline void sm_vec2_muladds(const sm_vec2 a, float s, sm_vec2 dest)
{
    dest[0] += a[0] * s;
    dest[1] += a[1] * s;
}

static inline float sm_vec2_dot(const sm_vec2 a, const sm_vec2 b) { return a[0] * b[0] + a[1] * b[1]; }
static inline float sm_vec2_norm2(const sm_vec2 v) { return sm_vec2_dot(v, v); }
static inline float sm_vec2_norm(const sm_vec2 v) { return sm__norm_n(v, 2); }
static inline void sm_vec2_normalize_to(const sm_vec2 v, sm_vec2 dest) { sm__normalize_n(v, 2, dest); }
static inline void sm_vec2_normalize(sm_vec2 v) { sm__normalize_n(v, 2, v); }

/* dest = a + t * (b - a); t is not clamped (like glm_vec3_lerp; cglm 0.8.8's
 * glm_vec2_lerp alone clamps t to [0, 1]). */
static inline void sm_vec2_lerp(const sm_vec2 a, const sm_vec2 b, float t, sm_vec2 dest)
{
    dest[0] = a[0] + t * (b[0] - a[0]);
    dest[1] = a[1] + t * (b[1] - a[1]);
}

/* Componentwise minimum / maximum (fminf/fmaxf: a NaN component yields the other). */
static inline void sm_vec2_min(const sm_vec2 a, const sm_vec2 b, sm_vec2 dest)
{
    dest[0] = fminf(a[0], b[0]);
    dest[1] = fminf(a[1], b[1]);
}

static inline void sm_vec2_max(const sm_vec2 a, const sm_vec2 b, sm_vec2 dest)
{
    dest[0] = fmaxf(a[0], b[0]);
    dest[1] = fmaxf(a[1], b[1]);
}

static inline void sm_vec2_negate_to(const sm_vec2 v, sm_vec2 dest) { dest[0] = -v[0]; dest[1] = -v[1]; }
static inline void sm_vec2_negate(sm_vec2 v) { sm_vec2_negate_to(v, v); }

/* >>vec3 ------------------------------------------------------------------------------ */

static inline void sm_vec3_make(float x, float y, float z, sm_vec3 dest)
{
    dest[0] = x;
    dest[1] = y;
    dest[2] = z;
}

static inline void sm_vec3_copy(const sm_vec3 a, sm_vec3 dest)
{
    dest[0] = a[0];
    dest[1] = a[1];
    dest[2] = a[2];
}

/* The xyz of a vec4. */
static inline void sm_vec3_from_vec4(const sm_vec4 a, sm_vec3 dest) { sm_vec3_copy(a, dest); }

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

/* Componentwise product. */
static inline void sm_vec3_mul(const sm_vec3 a, const sm_vec3 b, sm_vec3 dest)
{
    dest[0] = a[0] * b[0];
    dest[1] = a[1] * b[1];
    dest[2] = a[2] * b[2];
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

/* dest = a + t * (b - a); t is not clamped (same as glm_vec3_lerp). */
static inline void sm_vec3_lerp(const sm_vec3 a, const sm_vec3 b, float t, sm_vec3 dest)
{
    dest[0] = a[0] + t * (b[0] - a[0]);
    dest[1] = a[1] + t * (b[1] - a[1]);
    dest[2] = a[2] + t * (b[2] - a[2]);
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

/* >>vec4 ------------------------------------------------------------------------------ */

static inline void sm_vec4_make(float x, float y, float z, float w, sm_vec4 dest)
{
    dest[0] = x;
    dest[1] = y;
    dest[2] = z;
    dest[3] = w;
}

static inline void sm_vec4_copy(const sm_vec4 a, sm_vec4 dest)
{
    dest[0] = a[0];
    dest[1] = a[1];
    dest[2] = a[2];
    dest[3] = a[3];
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

/* Componentwise product. */
static inline void sm_vec4_mul(const sm_vec4 a, const sm_vec4 b, sm_vec4 dest)
{
    for (int i = 0; i < 4; i++)
        dest[i] = a[i] * b[i];
}

/* dest += a * s */
static inline void sm_vec4_muladds(const sm_vec4 a, float s, sm_vec4 dest)
{
    for (int i = 0; i < 4; i++)
        dest[i] += a[i] * s;
}

static inline float sm_vec4_dot(const sm_vec4 a, const sm_vec4 b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

static inline float sm_vec4_norm2(const sm_vec4 v) { return sm_vec4_dot(v, v); }
static inline float sm_vec4_norm(const sm_vec4 v) { return sm__norm_n(v, 4); }
static inline void sm_vec4_normalize_to(const sm_vec4 v, sm_vec4 dest) { sm__normalize_n(v, 4, dest); }
static inline void sm_vec4_normalize(sm_vec4 v) { sm__normalize_n(v, 4, v); }

/* dest = a + t * (b - a); t is not clamped (same as glm_vec4_lerp). */
static inline void sm_vec4_lerp(const sm_vec4 a, const sm_vec4 b, float t, sm_vec4 dest)
{
    for (int i = 0; i < 4; i++)
        dest[i] = a[i] + t * (b[i] - a[i]);
}

/* Componentwise minimum / maximum (NaN yields the other). */
static inline void sm_vec4_min(const sm_vec4 a, const sm_vec4 b, sm_vec4 dest)
{
    for (int i = 0; i < 4; i++)
        dest[i] = fminf(a[i], b[i]);
}

static inline void sm_vec4_max(const sm_vec4 a, const sm_vec4 b, sm_vec4 dest)
{
    for (int i = 0; i < 4; i++)
        dest[i] = fmaxf(a[i], b[i]);
}

static inline void sm_vec4_negate_to(const sm_vec4 v, sm_vec4 dest)
{
    for (int i = 0; i < 4; i++)
        dest[i] = -v[i];
}

static inline void sm_vec4_negate(sm_vec4 v) { sm_vec4_negate_to(v, v); }

/* >>mat3 ------------------------------------------------------------------------------ */

static inline void sm_mat3_identity(sm_mat3 dest)
{
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++)
            dest[c][r] = c == r ? 1.0f : 0.0f;
}

static inline void sm_mat3_zero(sm_mat3 dest)
{
    for (int c = 0; c < 3; c++)
        sm_vec3_zero(dest[c]);
}

static inline void sm_mat3_copy(const sm_mat3 m, sm_mat3 dest)
{
    for (int c = 0; c < 3; c++)
        sm_vec3_copy(m[c], dest[c]);
}

/* dest = a * b; dest may alias a and/or b. */
static inline void sm_mat3_mul(const sm_mat3 a, const sm_mat3 b, sm_mat3 dest)
{
    sm_mat3 t;
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++)
            t[c][r] = a[0][r] * b[c][0] + a[1][r] * b[c][1] + a[2][r] * b[c][2];
    memcpy(dest, t, sizeof t);
}

/* dest = m * v; dest may alias v. */
static inline void sm_mat3_mulv(const sm_mat3 m, const sm_vec3 v, sm_vec3 dest)
{
    float x = m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2];
    float y = m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2];
    float z = m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2];
    dest[0] = x;
    dest[1] = y;
    dest[2] = z;
}

/* dest = transpose(m); dest may alias m. */
static inline void sm_mat3_transpose_to(const sm_mat3 m, sm_mat3 dest)
{
    sm_mat3 t;
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++)
            t[c][r] = m[r][c];
    memcpy(dest, t, sizeof t);
}

static inline void sm_mat3_transpose(sm_mat3 m) { sm_mat3_transpose_to((const sm_vec3 *)m, m); }

static inline float sm_mat3_det(const sm_mat3 m)
{
    return m[0][0] * (m[1][1] * m[2][2] - m[2][1] * m[1][2])
         - m[1][0] * (m[0][1] * m[2][2] - m[2][1] * m[0][2])
         + m[2][0] * (m[0][1] * m[1][2] - m[1][1] * m[0][2]);
}

/* Column equilibration for the inverses: e[c] such that scaling column c by 2^-e[c]
 * (exact) brings its largest |entry| into [0.5, 1); 0 when that is already in
 * [2^-16, 2^16], where the cofactor products neither overflow nor underflow. Returns 1
 * when all entries are finite and no column is zero, 0 for a zero column, -1 for a
 * non-finite entry. */
static inline int sm__col_exponents(const float *cols, int n, int e[4])
{
    for (int c = 0; c < n; c++) {
        float mx = 0.0f;
        for (int r = 0; r < n; r++) {
            float x = cols[c * n + r];
            if (!isfinite(x))
                return -1;
            if (fabsf(x) > mx)
                mx = fabsf(x);
        }
        if (mx == 0.0f)
            return 0;
        e[c] = 0;
        if (!(mx >= 0x1p-16f && mx <= 0x1p16f))
            (void)frexpf(mx, &e[c]);
    }
    return 1;
}

/* dest = inverse(m) by cofactors. Singular, defined: when the determinant evaluates to
 * exactly 0 or the inverse is not representable in float (overflow), dest is the zero
 * matrix; a matrix with a NaN or infinite entry gives an all-NaN dest. Columns with very
 * small or very large entries are first scaled by powers of two (exact, undone on the
 * rows of the result), so e.g. a scale of 1e-20 or 1e20 inverts correctly. No tolerance
 * is applied: a nearly singular matrix gets its (large, inaccurate) inverse; compare
 * sm_mat3_det with a threshold of your own if that matters. dest may alias m. */
static inline void sm_mat3_inv(const sm_mat3 m, sm_mat3 dest)
{
    sm_mat3 a, t;
    float det, k;
    int e[4] = {0, 0, 0, 0};
    int ok = sm__col_exponents(&m[0][0], 3, e);

    if (ok <= 0) {
        for (int c = 0; c < 3; c++)
            for (int r = 0; r < 3; r++)
                dest[c][r] = ok < 0 ? NAN : 0.0f;
        return;
    }
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++)
            a[c][r] = e[c] ? ldexpf(m[c][r], -e[c]) : m[c][r];

    /* t = adjugate(a): t[c][r] is the cofactor of a[r][c]. */
    t[0][0] =   a[1][1] * a[2][2] - a[2][1] * a[1][2];
    t[0][1] = -(a[0][1] * a[2][2] - a[2][1] * a[0][2]);
    t[0][2] =   a[0][1] * a[1][2] - a[1][1] * a[0][2];
    t[1][0] = -(a[1][0] * a[2][2] - a[2][0] * a[1][2]);
    t[1][1] =   a[0][0] * a[2][2] - a[2][0] * a[0][2];
    t[1][2] = -(a[0][0] * a[1][2] - a[1][0] * a[0][2]);
    t[2][0] =   a[1][0] * a[2][1] - a[2][0] * a[1][1];
    t[2][1] = -(a[0][0] * a[2][1] - a[2][0] * a[0][1]);
    t[2][2] =   a[0][0] * a[1][1] - a[1][0] * a[0][1];

    det = a[0][0] * t[0][0] + a[1][0] * t[0][1] + a[2][0] * t[0][2];
    k = 1.0f / det;
    if (det == 0.0f || !isfinite(k)) {
        sm_mat3_zero(dest);
        return;
    }
    /* inverse(m) = D inverse(a) with D = diag(2^-e): row r scaled by 2^-e[r]. */
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++) {
            float x = t[c][r] * k;
            t[c][r] = e[r] ? ldexpf(x, -e[r]) : x;
            if (!isfinite(t[c][r])) {
                sm_mat3_zero(dest);
                return;
            }
        }
    memcpy(dest, t, sizeof t);
}

/* >>mat4 ------------------------------------------------------------------------------ */

static inline void sm_mat4_identity(sm_mat4 dest)
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            dest[c][r] = c == r ? 1.0f : 0.0f;
}

static inline void sm_mat4_zero(sm_mat4 dest)
{
    for (int c = 0; c < 4; c++)
        sm_vec4_zero(dest[c]);
}

static inline void sm_mat4_copy(const sm_mat4 m, sm_mat4 dest)
{
    for (int c = 0; c < 4; c++)
        sm_vec4_copy(m[c], dest[c]);
}

/* dest = a * b (b applied first); dest may alias a and/or b. */
static inline void sm_mat4_mul(const sm_mat4 a, const sm_mat4 b, sm_mat4 dest)
{
    sm_mat4 t;
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            t[c][r] = a[0][r] * b[c][0] + a[1][r] * b[c][1]
                    + a[2][r] * b[c][2] + a[3][r] * b[c][3];
    memcpy(dest, t, sizeof t);
}

/* dest = m * v; dest may alias v. */
static inline void sm_mat4_mulv(const sm_mat4 m, const sm_vec4 v, sm_vec4 dest)
{
    sm_vec4 t;
    for (int r = 0; r < 4; r++)
        t[r] = m[0][r] * v[0] + m[1][r] * v[1] + m[2][r] * v[2] + m[3][r] * v[3];
    sm_vec4_copy(t, dest);
}

/* dest = (m * (v, w)).xyz, no division by w (w = 1: a point, w = 0: a direction);
 * dest may alias v. */
static inline void sm_mat4_mulv3(const sm_mat4 m, const sm_vec3 v, float w, sm_vec3 dest)
{
    sm_vec3 t;
    for (int r = 0; r < 3; r++)
        t[r] = m[0][r] * v[0] + m[1][r] * v[1] + m[2][r] * v[2] + m[3][r] * w;
    sm_vec3_copy(t, dest);
}

/* dest = transpose(m); dest may alias m. */
static inline void sm_mat4_transpose_to(const sm_mat4 m, sm_mat4 dest)
{
    sm_mat4 t;
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            t[c][r] = m[r][c];
    memcpy(dest, t, sizeof t);
}

static inline void sm_mat4_transpose(sm_mat4 m) { sm_mat4_transpose_to((const sm_vec4 *)m, m); }

/* The 2x2 minors of the Laplace expansion of a 4x4 matrix along its first two columns
 * (s) and last two columns (c): det = s0 c5 - s1 c4 + s2 c3 + s3 c2 - s4 c1 + s5 c0. */
static inline void sm__mat4_minors(const sm_mat4 m, float s[6], float c[6])
{
    s[0] = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    s[1] = m[0][0] * m[1][2] - m[0][2] * m[1][0];
    s[2] = m[0][0] * m[1][3] - m[0][3] * m[1][0];
    s[3] = m[0][1] * m[1][2] - m[0][2] * m[1][1];
    s[4] = m[0][1] * m[1][3] - m[0][3] * m[1][1];
    s[5] = m[0][2] * m[1][3] - m[0][3] * m[1][2];
    c[0] = m[2][0] * m[3][1] - m[2][1] * m[3][0];
    c[1] = m[2][0] * m[3][2] - m[2][2] * m[3][0];
    c[2] = m[2][0] * m[3][3] - m[2][3] * m[3][0];
    c[3] = m[2][1] * m[3][2] - m[2][2] * m[3][1];
    c[4] = m[2][1] * m[3][3] - m[2][3] * m[3][1];
    c[5] = m[2][2] * m[3][3] - m[2][3] * m[3][2];
}

static inline float sm_mat4_det(const sm_mat4 m)
{
    float s[6], c[6];
    sm__mat4_minors(m, s, c);
    return s[0] * c[5] - s[1] * c[4] + s[2] * c[3] + s[3] * c[2] - s[4] * c[1] + s[5] * c[0];
}

/* dest = inverse(m) by cofactors (Laplace expansion in 2x2 minors). Singular, defined:
 * when the determinant evaluates to exactly 0 or the inverse is not representable in
 * float (overflow), dest is the zero matrix; a matrix with a NaN or infinite entry gives
 * an all-NaN dest. Columns with very small or very large entries are first scaled by
 * powers of two (exact, undone on the rows of the result), so e.g. a scale of 1e-20 or
 * 1e20 inverts correctly. No tolerance is applied: a nearly singular matrix gets its
 * (large, inaccurate) inverse; compare sm_mat4_det with a threshold of your own if that
 * matters. dest may alias m. */
static inline void sm_mat4_inv(const sm_mat4 m, sm_mat4 dest)
{
    sm_mat4 a, t;
    float s[6], c[6], det, k;
    int e[4] = {0, 0, 0, 0};
    int ok = sm__col_exponents(&m[0][0], 4, e);

    if (ok <= 0) {
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++)
                dest[i][j] = ok < 0 ? NAN : 0.0f;
        return;
    }
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            a[i][j] = e[i] ? ldexpf(m[i][j], -e[i]) : m[i][j];

    sm__mat4_minors((const sm_vec4 *)a, s, c);
    det = s[0] * c[5] - s[1] * c[4] + s[2] * c[3] + s[3] * c[2] - s[4] * c[1] + s[5] * c[0];
    k = 1.0f / det;
    if (det == 0.0f || !isfinite(k)) {
        sm_mat4_zero(dest);
        return;
    }

    /* Adjugate. Writing a_ij for a[i][j] (the transpose of the math matrix; the
     * adjugate of the transpose is the transpose of the adjugate, so storing b_ij in
     * t[i][j] yields the inverse in the same column-major layout). */
    t[0][0] =  a[1][1] * c[5] - a[1][2] * c[4] + a[1][3] * c[3];
    t[0][1] = -a[0][1] * c[5] + a[0][2] * c[4] - a[0][3] * c[3];
    t[0][2] =  a[3][1] * s[5] - a[3][2] * s[4] + a[3][3] * s[3];
    t[0][3] = -a[2][1] * s[5] + a[2][2] * s[4] - a[2][3] * s[3];

    t[1][0] = -a[1][0] * c[5] + a[1][2] * c[2] - a[1][3] * c[1];
    t[1][1] =  a[0][0] * c[5] - a[0][2] * c[2] + a[0][3] * c[1];
    t[1][2] = -a[3][0] * s[5] + a[3][2] * s[2] - a[3][3] * s[1];
    t[1][3] =  a[2][0] * s[5] - a[2][2] * s[2] + a[2][3] * s[1];

    t[2][0] =  a[1][0] * c[4] - a[1][1] * c[2] + a[1][3] * c[0];
    t[2][1] = -a[0][0] * c[4] + a[0][1] * c[2] - a[0][3] * c[0];
    t[2][2] =  a[3][0] * s[4] - a[3][1] * s[2] + a[3][3] * s[0];
    t[2][3] = -a[2][0] * s[4] + a[2][1] * s[2] - a[2][3] * s[0];

    t[3][0] = -a[1][0] * c[3] + a[1][1] * c[1] - a[1][2] * c[0];
    t[3][1] =  a[0][0] * c[3] - a[0][1] * c[1] + a[0][2] * c[0];
    t[3][2] = -a[3][0] * s[3] + a[3][1] * s[1] - a[3][2] * s[0];
    t[3][3] =  a[2][0] * s[3] - a[2][1] * s[1] + a[2][2] * s[0];

    /* inverse(m) = D inverse(a) with D = diag(2^-e): row j scaled by 2^-e[j]. */
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            float x = t[i][j] * k;
            t[i][j] = e[j] ? ldexpf(x, -e[j]) : x;
            if (!isfinite(t[i][j])) {
                sm_mat4_zero(dest);
                return;
            }
        }
    memcpy(dest, t, sizeof t);
}

/* Translation by v. */
static inline void sm_mat4_translate_make(const sm_vec3 v, sm_mat4 dest)
{
    sm_mat4_identity(dest);
    dest[3][0] = v[0];
    dest[3][1] = v[1];
    dest[3][2] = v[2];
}

/* Scale by v along the axes. */
static inline void sm_mat4_scale_make(const sm_vec3 v, sm_mat4 dest)
{
    sm_mat4_identity(dest);
    dest[0][0] = v[0];
    dest[1][1] = v[1];
    dest[2][2] = v[2];
}

/* Rotation by `angle` radians about `axis` (any length; normalized here),
 * counter-clockwise looking down the axis towards the origin (right-handed), same
 * as glm_rotate_make. A zero axis gives the identity. */
static inline void sm_mat4_rotate_make(float angle, const sm_vec3 axis, sm_mat4 dest)
{
    sm_vec3 n;
    float c = cosf(angle), s = sinf(angle), k = 1.0f - c;

    sm_vec3_normalize_to(axis, n);
    if (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f) {
        sm_mat4_identity(dest);
        return;
    }
    dest[0][0] = n[0] * n[0] * k + c;
    dest[0][1] = n[0] * n[1] * k + n[2] * s;
    dest[0][2] = n[0] * n[2] * k - n[1] * s;
    dest[1][0] = n[1] * n[0] * k - n[2] * s;
    dest[1][1] = n[1] * n[1] * k + c;
    dest[1][2] = n[1] * n[2] * k + n[0] * s;
    dest[2][0] = n[2] * n[0] * k + n[1] * s;
    dest[2][1] = n[2] * n[1] * k - n[0] * s;
    dest[2][2] = n[2] * n[2] * k + c;
    dest[0][3] = dest[1][3] = dest[2][3] = 0.0f;
    dest[3][0] = dest[3][1] = dest[3][2] = 0.0f;
    dest[3][3] = 1.0f;
}

/* The upper-left 3x3 of m. */
static inline void sm_mat4_pick3(const sm_mat4 m, sm_mat3 dest)
{
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++)
            dest[c][r] = m[c][r];
}

/* Normal matrix: transpose(inverse(upper-left 3x3 of m)), which maps object-space
 * normals to world space for any invertible linear part (non-uniform scale, shear,
 * mirror). A singular 3x3 (e.g. a zero scale) gives the zero matrix, as sm_mat3_inv. */
static inline void sm_mat4_normal(const sm_mat4 m, sm_mat3 dest)
{
    sm_mat3 t;
    sm_mat4_pick3(m, t);
    sm_mat3_inv((const sm_vec3 *)t, t);
    sm_mat3_transpose_to((const sm_vec3 *)t, dest);
}

/* >>quaternion ------------------------------------------------------------------------ */

static inline void sm_quat_identity(sm_quat dest) { sm_vec4_make(0.0f, 0.0f, 0.0f, 1.0f, dest); }

static inline void sm_quat_make(float x, float y, float z, float w, sm_quat dest)
{
    sm_vec4_make(x, y, z, w, dest);
}

static inline float sm_quat_dot(const sm_quat p, const sm_quat q) { return sm_vec4_dot(p, q); }
static inline float sm_quat_norm(const sm_quat q) { return sm_vec4_norm(q); }

/* Rotation by `angle` radians about `axis` (any length; normalized here), same as
 * glm_quatv. A zero axis gives the identity. */
static inline void sm_quat_from_axis_angle(const sm_vec3 axis, float angle, sm_quat dest)
{
    sm_vec3 n;
    float s = sinf(angle * 0.5f), c = cosf(angle * 0.5f);

    sm_vec3_normalize_to(axis, n);
    if (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f) {
        sm_quat_identity(dest);
        return;
    }
    sm_vec4_make(n[0] * s, n[1] * s, n[2] * s, c, dest);
}

/* Unit quaternion; a zero quaternion gives the identity, a NaN/inf one all-NaN.
 * dest may alias q. */
static inline void sm_quat_normalize_to(const sm_quat q, sm_quat dest)
{
    if (q[0] == 0.0f && q[1] == 0.0f && q[2] == 0.0f && q[3] == 0.0f) {
        sm_quat_identity(dest);
        return;
    }
    sm__normalize_n(q, 4, dest);
}

static inline void sm_quat_normalize(sm_quat q) { sm_quat_normalize_to(q, q); }

/* (-x, -y, -z, w): the inverse rotation of a unit quaternion. dest may alias q. */
static inline void sm_quat_conjugate(const sm_quat q, sm_quat dest)
{
    sm_vec4_make(-q[0], -q[1], -q[2], q[3], dest);
}

/* conjugate(q) / |q|^2; a zero quaternion gives the identity. dest may alias q. */
static inline void sm_quat_inv(const sm_quat q, sm_quat dest)
{
    float n2 = sm_vec4_norm2(q);
    sm_quat u;

    if (n2 >= FLT_MIN && n2 <= FLT_MAX) {
        sm_quat_conjugate(q, dest);
        sm_vec4_scale(dest, 1.0f / n2, dest);
        return;
    }
    /* zero, or |q|^2 out of range: conjugate(q / |q|) / |q| */
    if (q[0] == 0.0f && q[1] == 0.0f && q[2] == 0.0f && q[3] == 0.0f) {
        sm_quat_identity(dest);
        return;
    }
    n2 = sm__norm_n(q, 4);
    sm__normalize_n(q, 4, u);
    sm_quat_conjugate(u, u);
    sm_vec4_scale(u, 1.0f / n2, dest);
}

/* dest = p * q (Hamilton product): the rotation q followed by p. dest may alias p, q. */
static inline void sm_quat_mul(const sm_quat p, const sm_quat q, sm_quat dest)
{
    float x = p[3] * q[0] + p[0] * q[3] + p[1] * q[2] - p[2] * q[1];
    float y = p[3] * q[1] - p[0] * q[2] + p[1] * q[3] + p[2] * q[0];
    float z = p[3] * q[2] + p[0] * q[1] - p[1] * q[0] + p[2] * q[3];
    float w = p[3] * q[3] - p[0] * q[0] - p[1] * q[1] - p[2] * q[2];
    sm_vec4_make(x, y, z, w, dest);
}

/* dest = v rotated by q (q is normalized first, like glm_quat_rotatev; a zero q leaves
 * v unchanged). v' = v + w t + u x t with t = 2 u x v. dest may alias v. */
static inline void sm_quat_rotatev(const sm_quat q, const sm_vec3 v, sm_vec3 dest)
{
    sm_quat p;
    sm_vec3 t, ut;
    sm_quat_normalize_to(q, p);
    sm_vec3_cross(p, v, t);
    sm_vec3_scale(t, 2.0f, t);
    sm_vec3_cross(p, t, ut);
    for (int i = 0; i < 3; i++)
        dest[i] = v[i] + p[3] * t[i] + ut[i];
}

/* Rotation matrix of q. Uses s = 2 / |q|^2, so any non-zero q gives the rotation of
 * q / |q| (glm_quat_mat4 assumes |q| = 1). A zero q gives the identity. */
static inline void sm_quat_to_mat3(const sm_quat q, sm_mat3 dest)
{
    sm_quat u;
    float n2 = sm_vec4_norm2(q), s, x, y, z, w;

    if (n2 >= FLT_MIN && n2 <= FLT_MAX) {
        sm_vec4_copy(q, u);
    } else {
        sm_quat_normalize_to(q, u);
        n2 = sm_vec4_norm2(u);
    }
    s = 2.0f / n2;
    x = u[0]; y = u[1]; z = u[2]; w = u[3];
    dest[0][0] = 1.0f - s * (y * y + z * z);
    dest[1][1] = 1.0f - s * (x * x + z * z);
    dest[2][2] = 1.0f - s * (x * x + y * y);
    dest[0][1] = s * (x * y + w * z);
    dest[1][0] = s * (x * y - w * z);
    dest[1][2] = s * (y * z + w * x);
    dest[2][1] = s * (y * z - w * x);
    dest[2][0] = s * (x * z + w * y);
    dest[0][2] = s * (x * z - w * y);
}

static inline void sm_quat_to_mat4(const sm_quat q, sm_mat4 dest)
{
    sm_mat3 r;
    sm_quat_to_mat3(q, r);
    for (int c = 0; c < 3; c++) {
        sm_vec4_from_vec3(r[c], 0.0f, dest[c]);
    }
    sm_vec4_make(0.0f, 0.0f, 0.0f, 1.0f, dest[3]);
}

/* Spherical linear interpolation between unit quaternions a (t = 0) and b (t = 1) along
 * the shorter arc: when dot(a, b) < 0, -a is used (as glm_quat_slerp does), so the result
 * may be the negative of what a naive formula gives (the same rotation). t is not clamped.
 * The angle comes from 2 atan2(|a - b|, |a + b|), accurate for small angles; below
 * 1e-4 rad, normalized lerp is used (its error there is below float precision). */
static inline void sm_quat_slerp(const sm_quat a, const sm_quat b, float t, sm_quat dest)
{
    sm_quat p, d, s;
    float theta, sn, wa, wb;

    sm_vec4_copy(a, p);
    if (sm_vec4_dot(a, b) < 0.0f)
        sm_vec4_negate(p);
    sm_vec4_sub(p, b, d);
    sm_vec4_add(p, b, s);
    theta = 2.0f * atan2f(sm_vec4_norm(d), sm_vec4_norm(s));
    if (theta < 1e-4f) {
        sm_vec4_lerp(p, b, t, dest);
        sm_quat_normalize(dest);
        return;
    }
    sn = sinf(theta);
    wa = sinf((1.0f - t) * theta) / sn;
    wb = sinf(t * theta) / sn;
    for (int i = 0; i < 4; i++)
        dest[i] = wa * p[i] + wb * b[i];
}

/* dest = T(translation) * R(rotation) * S(scale): scale, then rotate, then translate. */
static inline void sm_mat4_trs(const sm_vec3 translation, const sm_quat rotation,
                               const sm_vec3 scale, sm_mat4 dest)
{
    sm_mat3 r;
    sm_quat_to_mat3(rotation, r);
    for (int c = 0; c < 3; c++) {
        sm_vec3_scale(r[c], scale[c], r[c]);
        sm_vec4_from_vec3(r[c], 0.0f, dest[c]);
    }
    sm_vec4_from_vec3(translation, 1.0f, dest[3]);
}

/* >>camera ---------------------------------------------------------------------------- */

/* Right-handed view matrix looking from eye at center, the same as glm_lookat (cglm's
 * default right-handed clip space): the camera looks down its -Z, +Y is up.
 * Degenerate input, defined: eye == center looks down world -Z; an `up` that is zero or
 * within 1e-5 rad of the view direction (or its opposite) is replaced by the world axis
 * least aligned with the view direction (ties: x before y before z). The rotation part
 * is always orthonormal for finite input. */
static inline void sm_lookat(const sm_vec3 eye, const sm_vec3 center, const sm_vec3 up, sm_mat4 dest)
{
    sm_vec3 f, s, u, upn;

    sm_vec3_sub(center, eye, f);
    sm_vec3_normalize(f);
    if (f[0] == 0.0f && f[1] == 0.0f && f[2] == 0.0f)
        sm_vec3_make(0.0f, 0.0f, -1.0f, f);

    sm_vec3_normalize_to(up, upn);
    sm_vec3_cross(f, upn, s);
    /* |s| = sin(angle(f, up)) for unit vectors: parallel within rounding noise when < 1e-5. */
    if (!(sm_vec3_norm2(s) >= 1e-10f)) {
        int k = 0;
        for (int i = 1; i < 3; i++)
            if (fabsf(f[i]) < fabsf(f[k]))
                k = i;
        sm_vec3_zero(upn);
        upn[k] = 1.0f;
        sm_vec3_cross(f, upn, s);
    }
    sm_vec3_normalize(s);
    sm_vec3_cross(s, f, u);

    dest[0][0] = s[0];
    dest[0][1] = u[0];
    dest[0][2] = -f[0];
    dest[1][0] = s[1];
    dest[1][1] = u[1];
    dest[1][2] = -f[1];
    dest[2][0] = s[2];
    dest[2][1] = u[2];
    dest[2][2] = -f[2];
    dest[3][0] = -sm_vec3_dot(s, eye);
    dest[3][1] = -sm_vec3_dot(u, eye);
    dest[3][2] = sm_vec3_dot(f, eye);
    dest[0][3] = dest[1][3] = dest[2][3] = 0.0f;
    dest[3][3] = 1.0f;
}

/* sm_lookat(eye, eye + dir, up, dest). */
static inline void sm_look(const sm_vec3 eye, const sm_vec3 dir, const sm_vec3 up, sm_mat4 dest)
{
    sm_vec3 center;
    sm_vec3_add(eye, dir, center);
    sm_lookat(eye, center, up, dest);
}

/* Right-handed perspective projection, GL clip space (z/w in -1..1 between znear and
 * zfar), the same as glm_perspective. zfar may be +INFINITY (infinite far plane, the
 * limit of the finite formula). Invalid parameters give the zero matrix (nothing is
 * drawn): fovy outside (0, pi), aspect not positive and finite, znear not positive and
 * finite, zfar <= znear. */
static inline void sm_perspective(float fovy, float aspect, float znear, float zfar, sm_mat4 dest)
{
    float f, fn;

    sm_mat4_zero(dest);
    if (!(fovy > 0.0f && fovy < SM_PI && aspect > 0.0f && aspect <= FLT_MAX
          && znear > 0.0f && znear <= FLT_MAX && zfar > znear))
        return;
    f = 1.0f / tanf(fovy * 0.5f);
    dest[0][0] = f / aspect;
    dest[1][1] = f;
    dest[2][3] = -1.0f;
    if (isinf(zfar)) {
        dest[2][2] = -1.0f;
        dest[3][2] = -2.0f * znear;
    } else {
        fn = 1.0f / (znear - zfar);
        dest[2][2] = (znear + zfar) * fn;
        dest[3][2] = 2.0f * znear * (zfar * fn);   /* zfar * fn first: no overflow */
    }
}

/* Right-handed orthographic projection, GL clip space, the same as glm_ortho. Invalid
 * parameters give the zero matrix: left == right, bottom == top, znear == zfar, or a
 * non-finite one. */
static inline void sm_ortho(float left, float right, float bottom, float top,
                            float znear, float zfar, sm_mat4 dest)
{
    float rl = 1.0f / (right - left), tb = 1.0f / (top - bottom), fn = -1.0f / (zfar - znear);

    sm_mat4_zero(dest);
    if (!(isfinite(rl) && isfinite(tb) && isfinite(fn) && isfinite(left + right)
          && isfinite(bottom + top) && isfinite(znear + zfar)))
        return;
    dest[0][0] = 2.0f * rl;
    dest[1][1] = 2.0f * tb;
    dest[2][2] = 2.0f * fn;
    dest[3][0] = -(right + left) * rl;
    dest[3][1] = -(top + bottom) * tb;
    dest[3][2] = (zfar + znear) * fn;
    dest[3][3] = 1.0f;
}

/* >>planes and frustum ---------------------------------------------------------------- */

/* Scale the plane so that its normal (xyz) has unit length; a zero normal gives the zero
 * plane (as glm_plane_normalize). */
static inline void sm_plane_normalize(sm_vec4 plane)
{
    float n = sm_vec3_norm(plane);
    if (n == 0.0f) {
        sm_vec4_zero(plane);
        return;
    }
    sm_vec4_scale(plane, 1.0f / n, plane);
}

/* Signed distance of point from plane (true distance when the plane is normalized). */
static inline float sm_plane_distance(const sm_vec4 plane, const sm_vec3 point)
{
    return sm_vec3_dot(plane, point) + plane[3];
}

enum { SM_LEFT = 0, SM_RIGHT, SM_BOTTOM, SM_TOP, SM_NEAR, SM_FAR };

/* The six planes of the view volume of `viewproj` (Gribb/Hartmann), in world space if
 * viewproj = proj * view: order left, right, bottom, top, near, far (SM_LEFT..SM_FAR),
 * normalized, normals pointing inside (inside = positive distance). The same as
 * glm_frustum_planes. */
static inline void sm_frustum_planes(const sm_mat4 viewproj, sm_vec4 dest[6])
{
    sm_mat4 t;
    sm_mat4_transpose_to(viewproj, t);   /* rows of viewproj */
    sm_vec4_add(t[3], t[0], dest[0]);
    sm_vec4_sub(t[3], t[0], dest[1]);
    sm_vec4_add(t[3], t[1], dest[2]);
    sm_vec4_sub(t[3], t[1], dest[3]);
    sm_vec4_add(t[3], t[2], dest[4]);
    sm_vec4_sub(t[3], t[2], dest[5]);
    for (int i = 0; i < 6; i++)
        sm_plane_normalize(dest[i]);
}

/* The eight corners of the view volume, from the inverse of viewproj (sm_mat4_inv),
 * in glm_frustum_corners' order: near left-bottom, left-top, right-top, right-bottom,
 * then the same four on the far plane. w of each is 1. A corner that maps to w = 0 (the
 * matrix is not the inverse of a projection, e.g. a zero matrix) is all NaN. */
static inline void sm_frustum_corners(const sm_mat4 inv_viewproj, sm_vec4 dest[8])
{
    static const float ndc[8][3] = {
        {-1.0f, -1.0f, -1.0f}, {-1.0f, 1.0f, -1.0f}, {1.0f, 1.0f, -1.0f}, {1.0f, -1.0f, -1.0f},
        {-1.0f, -1.0f, 1.0f},  {-1.0f, 1.0f, 1.0f},  {1.0f, 1.0f, 1.0f},  {1.0f, -1.0f, 1.0f},
    };
    for (int i = 0; i < 8; i++) {
        sm_vec4 p;
        sm_vec4_from_vec3(ndc[i], 1.0f, p);
        sm_mat4_mulv(inv_viewproj, p, p);
        if (p[3] == 0.0f) {
            sm_vec4_make(NAN, NAN, NAN, NAN, dest[i]);
        } else {
            sm_vec4_scale(p, 1.0f / p[3], dest[i]);
            dest[i][3] = 1.0f;
        }
    }
}

/* >>bounds ---------------------------------------------------------------------------- */

/* False only when the sphere lies entirely on the outside of one plane (distance <
 * -radius); conservative: a sphere outside the frustum near an edge or corner may still
 * give true. planes from sm_frustum_planes. */
static inline bool sm_sphere_in_frustum(const sm_vec4 planes[6], const sm_vec4 sphere)
{
    for (int i = 0; i < 6; i++)
        if (sm_plane_distance(planes[i], sphere) < -sphere[3])
            return false;
    return true;
}

/* An empty box: min = +FLT_MAX, max = -FLT_MAX (merging anything into it gives that). */
static inline void sm_aabb_empty(sm_vec3 box[2])
{
    sm_vec3_make(FLT_MAX, FLT_MAX, FLT_MAX, box[0]);
    sm_vec3_make(-FLT_MAX, -FLT_MAX, -FLT_MAX, box[1]);
}

/* True when min > max (or NaN) on some axis. A box with min == max is a point, not empty. */
static inline bool sm_aabb_is_empty(const sm_vec3 box[2])
{
    return !(box[0][0] <= box[1][0] && box[0][1] <= box[1][1] && box[0][2] <= box[1][2]);
}

/* Smallest box holding both; dest may alias either. */
static inline void sm_aabb_merge(const sm_vec3 a[2], const sm_vec3 b[2], sm_vec3 dest[2])
{
    if (sm_aabb_is_empty(a)) {
        sm_vec3_copy(b[0], dest[0]);
        sm_vec3_copy(b[1], dest[1]);
        return;
    }
    if (sm_aabb_is_empty(b)) {
        sm_vec3_copy(a[0], dest[0]);
        sm_vec3_copy(a[1], dest[1]);
        return;
    }
    sm_vec3_min(a[0], b[0], dest[0]);
    sm_vec3_max(a[1], b[1], dest[1]);
}

static inline void sm_aabb_center(const sm_vec3 box[2], sm_vec3 dest)
{
    for (int i = 0; i < 3; i++)
        dest[i] = 0.5f * (box[0][i] + box[1][i]);
}

/* The sphere through the box's corners (centre, half diagonal). */
static inline void sm_aabb_to_sphere(const sm_vec3 box[2], sm_vec4 dest)
{
    sm_vec3 c;
    float r = 0.5f * sm_vec3_distance(box[0], box[1]);
    sm_aabb_center(box, c);
    sm_vec4_from_vec3(c, r, dest);
}

/* False only when the box lies entirely outside one plane (its corner furthest along
 * the plane normal is outside), as glm_aabb_frustum; conservative like
 * sm_sphere_in_frustum. An empty box gives false. */
static inline bool sm_aabb_in_frustum(const sm_vec4 planes[6], const sm_vec3 box[2])
{
    if (sm_aabb_is_empty(box))
        return false;
    for (int i = 0; i < 6; i++) {
        const float *p = planes[i];
        float dp = p[0] * box[p[0] > 0.0f][0] + p[1] * box[p[1] > 0.0f][1]
                 + p[2] * box[p[2] > 0.0f][2];
        if (dp < -p[3])
            return false;
    }
    return true;
}

/* The box holding the image of box under the affine m (Arvo 1990: per axis, the min and
 * max of each column's contribution), as glm_aabb_transform. An empty box stays empty
 * (sm_aabb_empty). dest may alias box. */
static inline void sm_aabb_transform(const sm_vec3 box[2], const sm_mat4 m, sm_vec3 dest[2])
{
    sm_vec3 lo, hi;
    if (sm_aabb_is_empty(box)) {
        sm_aabb_empty(dest);
        return;
    }
    sm_vec3_copy(m[3], lo);
    sm_vec3_copy(m[3], hi);
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++) {
            float a = m[c][r] * box[0][c], b = m[c][r] * box[1][c];
            lo[r] += fminf(a, b);
            hi[r] += fmaxf(a, b);
        }
    sm_vec3_copy(lo, dest[0]);
    sm_vec3_copy(hi, dest[1]);
}

/* True when the solid sphere and the box share a point: the squared distance from the
 * centre to the box is <= radius^2. (Note: glm_aabb_sphere of cglm 0.8.8 measures to the
 * max face on both sides and misses spheres below the min corner.) Empty box: false. */
static inline bool sm_aabb_sphere_intersects(const sm_vec3 box[2], const sm_vec4 sphere)
{
    float d2 = 0.0f;
    if (sm_aabb_is_empty(box))
        return false;
    for (int i = 0; i < 3; i++) {
        float d = 0.0f;
        if (sphere[i] < box[0][i])
            d = box[0][i] - sphere[i];
        else if (sphere[i] > box[1][i])
            d = sphere[i] - box[1][i];
        d2 += d * d;
    }
    return d2 <= sphere[3] * sphere[3];
}

/* True when the solid spheres share a point (touching counts), as glm_sphere_sphere. */
static inline bool sm_sphere_sphere_intersects(const sm_vec4 a, const sm_vec4 b)
{
    float r = a[3] + b[3];
    return sm_vec3_distance2(a, b) <= r * r;
}

/* True when p is in the solid sphere (on the surface counts), as glm_sphere_point. */
static inline bool sm_point_in_sphere(const sm_vec3 p, const sm_vec4 sphere)
{
    return sm_vec3_distance2(p, sphere) <= sphere[3] * sphere[3];
}

/* A sphere holding the image of `sphere` under the affine m: the centre is transformed,
 * the radius scaled by a bound on m's largest stretch, sqrt of the largest Gershgorin row
 * sum of the Gram matrix of the upper 3x3 columns. That is exactly the largest column
 * length when the columns are orthogonal (any T * R * S) and an upper bound otherwise
 * (shear), so the result always contains the image. dest may alias sphere. */
static inline void sm_sphere_transform(const sm_vec4 sphere, const sm_mat4 m, sm_vec4 dest)
{
    float g[3][3], best = 0.0f, r = sphere[3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            g[i][j] = fabsf(sm_vec3_dot(m[i], m[j]));
    for (int i = 0; i < 3; i++) {
        float row = g[i][0] + g[i][1] + g[i][2];
        if (row > best)
            best = row;
    }
    sm_mat4_mulv3(m, sphere, 1.0f, dest);
    dest[3] = r * sqrtf(best);
}

/* Whether a cone may touch a sphere (a spot light's volume against an object's bounding
 * sphere). The cone: apex, unit axis unit_dir (must be unit length: it is not normalized
 * here), half_angle in radians (clamped to [0, pi]; NaN counts as 0), capped by the plane
 * at distance height along the axis (clamped to >= 0; +INFINITY: no cap), i.e. the
 * points p with angle(p - apex, unit_dir) <= half_angle and dot(p - apex, unit_dir) <=
 * height. A spot light of range R lies inside the cone of height R, so height = range
 * is conservative for it. A negative radius counts as 0.
 *
 * Method (Eberly, "Intersection of a Sphere and a Cone"; W. Wronski, "Cull that cone!"
 * 2017): with v = centre - apex, a = dot(v, dir) and p = |v x dir|, the sphere is
 * certainly outside, and false is returned, when
 *   - cos(half_angle) p - sin(half_angle) a > r: the centre's signed distance to the
 *     cone's side line in the plane through the axis; never more than the true distance
 *     to the infinite cone, so this rejects only spheres that miss it;
 *   - a > height + r: entirely beyond the cap plane;
 *   - a < -r while half_angle <= pi/2: entirely behind the apex plane.
 * Otherwise true. Conservative: it never says false for a sphere that touches the cone
 * (each test alone proves a miss, and a relative slack of 1e-5 of the distances involved
 * absorbs float rounding), but may say true for a near miss close to the cap's rim or
 * behind the apex (within a few radii for half angles up to ~60 degrees). */
static inline bool sm_cone_sphere_intersects(const sm_vec3 apex, const sm_vec3 unit_dir,
                                             float half_angle, float height, const sm_vec4 sphere)
{
    sm_vec3 v, x;
    float ang = fminf(fmaxf(half_angle, 0.0f), SM_PI);
    float h = fmaxf(height, 0.0f);
    float r = fmaxf(sphere[3], 0.0f);
    float len, axial, perp, slack;

    sm_vec3_sub(sphere, apex, v);
    len = sm_vec3_norm(v);
    axial = sm_vec3_dot(v, unit_dir);
    sm_vec3_cross(v, unit_dir, x);
    perp = sm_vec3_norm(x);            /* no cancellation, unlike sqrt(|v|^2 - a^2) */
    slack = 1e-5f * (len + r);

    if (axial > h + r + slack + 1e-5f * h)
        return false;
    if (ang <= SM_PI_2 && axial < -r - slack)
        return false;
    if (cosf(ang) * perp - sinf(ang) * axial > r + slack)
        return false;
    return true;
}
