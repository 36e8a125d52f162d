#pragma once
/* scenes/math/sm_mat.h: 3x3 and 4x4 matrices, column-major (m[col][row]); conventions in
 * scenes/math/sm_vec.h. The inverse of a singular matrix is the zero matrix (sm_mat4_inv).
 *
 *   mat3  sm_mat3_zero, _mulv, _transpose_to, _det, _inv
 *   mat4  sm_mat4_identity, _zero, _copy, _mul, _mulv, _mulv3, _transpose_to, _det, _inv,
 *         _translate_make, _scale_make, _rotate_make, _pick3, _normal (normal matrix),
 *         _stretch (a bound on the largest singular value)
 */
#include "scenes/math/sm_vec.h"

/* >>mat3 */

static inline void sm_mat3_zero(sm_mat3 dest)
{
    for (int c = 0; c < 3; c++)
        sm_vec3_zero(dest[c]);
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

/* >>mat4 */

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

/* An upper bound on how far the upper 3x3 of m stretches any vector (its largest
 * singular value): sqrt of the largest absolute row sum of M^T M, which bounds M^T M's
 * largest eigenvalue. Exactly 1 for the identity, s for a uniform scale s. */
static inline float sm_mat4_stretch(const sm_mat4 m)
{
    double most = 0.0;
    for (int i = 0; i < 3; i++) {
        double row = 0.0;
        for (int j = 0; j < 3; j++)
            row += fabs((double)m[i][0] * m[j][0] + (double)m[i][1] * m[j][1] +
                        (double)m[i][2] * m[j][2]);
        most = fmax(most, row);
    }
    return (float)sqrt(most);
}
