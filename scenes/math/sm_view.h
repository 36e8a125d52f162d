#pragma once
/* scenes/math/sm_view.h: cameras and the planes of a view frustum (right-handed, GL clip z
 * -1..1); conventions in scenes/math/sm_vec.h. sm_lookat with eye == center looks down -Z;
 * with `up` zero or parallel to the view direction it uses the world axis least aligned
 * with the view direction as up; sm_perspective / sm_ortho with invalid parameters give
 * the zero matrix.
 *
 *   camera  sm_lookat, sm_look, sm_perspective, sm_ortho
 *   planes  sm_plane_normalize, sm_plane_distance, sm_frustum_planes (indexed by SM_LEFT,
 *           SM_RIGHT, SM_BOTTOM, SM_TOP, SM_NEAR, SM_FAR), sm_frustum_corners
 */
#include "scenes/math/sm_mat.h"

/* >>camera */

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

/* >>planes and frustum */

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
