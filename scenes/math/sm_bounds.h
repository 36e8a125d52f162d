#pragma once
/* scenes/math/sm_bounds.h: spheres, boxes and cones against each other and against a
 * frustum; conventions in scenes/math/sm_vec.h.
 *
 *   sm_sphere_in_frustum, sm_aabb_empty, sm_aabb_center, sm_sphere_sphere_intersects,
 *   sm_point_in_sphere, sm_cone_sphere_intersects
 */
#include "scenes/math/sm_view.h"

/* >>bounds */

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

static inline void sm_aabb_center(const sm_vec3 box[2], sm_vec3 dest)
{
    for (int i = 0; i < 3; i++)
        dest[i] = 0.5f * (box[0][i] + box[1][i]);
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
