/* The screen coverage of a scene's lights (>>coverage). See scenes/scene_make.c. */
#include "scenes/scene.h"

#include <math.h>
#include <stdlib.h>

// >>coverage

/* Whether the ray o + t d (t >= 0, d unit) meets the ball of radius r about c. */
static bool ray_meets_sphere(const double o[3], const double d[3], const float c[3], double r)
{
    double v[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
    double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (vv <= r * r)
        return true;   /* the eye is inside */
    double b = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
    return b > 0.0 && vv - b * b <= r * r;
}

/* Whether the ray o + t d (t >= 0, d unit) meets the finite cone of apex a, unit axis u,
 * half angle th and height h (the points p with 0 <= (p - a).u <= h and angle(p - a, u) <=
 * th: capped by the plane at distance h along the axis). On the part of the ray within the
 * two planes, (p - a).u >= 0, so p is in the cone exactly when
 *   q(t) = ((p - a).u)^2 - cos^2(th) |p - a|^2 >= 0,
 * a quadratic in t; the ray meets the cone when q's largest value over that part (at an
 * end or at the vertex) is >= 0. */
static bool ray_meets_cone(const double o[3], const double d[3], const float a[3],
                           const double u[3], double th, double h)
{
    double w[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
    double wu = w[0] * u[0] + w[1] * u[1] + w[2] * u[2];
    double du = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    double t0 = 0.0, t1 = INFINITY;
    if (du == 0.0) {
        if (wu < 0.0 || wu > h)
            return false;
    } else {
        double ta = -wu / du, tb = (h - wu) / du;
        t0 = fmax(0.0, fmin(ta, tb));
        t1 = fmax(ta, tb);
        if (t0 > t1)
            return false;
    }
    double c2 = cos(th) * cos(th);
    double dw = d[0] * w[0] + d[1] * w[1] + d[2] * w[2];
    double ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    double A = du * du - c2, B = du * wu - c2 * dw, C = wu * wu - c2 * ww;
#define Q(t) ((A * (t) + 2.0 * B) * (t) + C)
    if (Q(t0) >= 0.0 || (isfinite(t1) && Q(t1) >= 0.0))
        return true;
    if (A < 0.0) {
        double tv = -B / A;
        if (tv > t0 && tv < t1 && Q(tv) >= 0.0)
            return true;
    }
#undef Q
    return false;
}

/* Point: the ball of `radius`. Spot: the cone of half angle spot_angle (clamped to
 * [1e-4, pi/2 - 1e-3], as the renderers clamp it), apex at the light, along its direction
 * (a zero direction counts as -Y, as in the renderers), capped by the PLANE at distance
 * `radius` along the axis: the volume renderers/frame/frontend.c culls with and the deferred
 * renderer rasterizes (mesh_light_cone of height = range). The lit part of it (within
 * `radius` of the light, lighting.inc) is the cone capped by the sphere, inside this.
 * The ray is the whole ray from the eye: neither the near nor the far plane cuts it.
 * An index beyond nlights_total gives 0; whether the light is active does not matter. */
double scene_light_coverage(const scene *s, uint32_t i)
{
    if (!s || i >= s->nlights_total)
        return 0.0;
    const scene_light *l = &s->lights[i];
    if (l->type == LIGHT_DIRECTIONAL)
        return 1.0;
    if (!(l->radius > 0.0f) || !isfinite(l->radius))
        return 0.0;
    double axis[3] = {l->direction[0], l->direction[1], l->direction[2]};
    double len = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (!(len > 0.0) || !isfinite(len)) {
        axis[0] = 0.0;
        axis[1] = -1.0;
        axis[2] = 0.0;
        len = 1.0;
    }
    for (int k = 0; k < 3; k++)
        axis[k] /= len;
    double th = sm_clamp(l->spot_angle, 1e-4f, SM_PI_2 - 1e-3f);

    /* the view's rows are the camera's right, up and backward axes in world space */
    double right[3], up[3], back[3];
    for (int k = 0; k < 3; k++) {
        right[k] = s->view[k][0];
        up[k] = s->view[k][1];
        back[k] = s->view[k][2];
    }
    double ty = tan((double)s->cam.fovy / 2.0), tx = ty * (double)s->width / (double)s->height;
    double eye[3] = {s->cam.eye[0], s->cam.eye[1], s->cam.eye[2]};
    uint32_t sw = s->width < 128 ? (uint32_t)s->width : 128;
    uint32_t sh = s->height < 128 ? (uint32_t)s->height : 128;
    uint64_t hits = 0;
    for (uint32_t j = 0; j < sh; j++) {
        /* the pixel row at the sample's place, and that pixel's centre */
        double py = floor(((double)j + 0.5) * s->height / sh) + 0.5;
        double yn = 1.0 - 2.0 * py / s->height;
        for (uint32_t k = 0; k < sw; k++) {
            double px = floor(((double)k + 0.5) * s->width / sw) + 0.5;
            double xn = 2.0 * px / s->width - 1.0;
            double d[3], dd = 0.0;
            for (int c = 0; c < 3; c++) {
                d[c] = xn * tx * right[c] + yn * ty * up[c] - back[c];
                dd += d[c] * d[c];
            }
            dd = sqrt(dd);
            for (int c = 0; c < 3; c++)
                d[c] /= dd;
            bool hit = l->type == LIGHT_POINT
                           ? ray_meets_sphere(eye, d, l->position, l->radius)
                           : ray_meets_cone(eye, d, l->position, axis, th, l->radius);
            hits += hit;
        }
    }
    return (double)hits / ((double)sw * (double)sh);
}
