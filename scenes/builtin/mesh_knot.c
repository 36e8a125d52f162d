/* Procedural meshes: the torus knot (>>torus-knot). See scenes/mesh.h. */
#include "scenes/builtin/mesh_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/scene_fail.h"

/* >>torus-knot ------------------------------------------------------------------------- */

static uint32_t gcd_u32(uint32_t a, uint32_t b)
{
    while (b) {
        uint32_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* Centre line and its derivative at t, in double. */
static void knot_curve(double t, double p, double q, double k, double c[3], double d[3])
{
    double rho = 2.0 + cos(q * t), drho = -q * sin(q * t);
    c[0] = k * rho * sin(p * t);
    c[1] = k * sin(q * t);
    c[2] = k * rho * cos(p * t);
    d[0] = k * (drho * sin(p * t) + p * rho * cos(p * t));
    d[1] = k * q * cos(q * t);
    d[2] = k * (drho * cos(p * t) - p * rho * sin(p * t));
}

static void normalize_d(double v[3]);

/* Centre line c, its derivative d, and the tube's frame: t unit along d, b = unit
 * t x c (never zero: the curve always turns about Y), n = b x t. */
typedef struct knot_frame {
    double c[3], d[3], t[3], n[3], b[3];
} knot_frame;

static void knot_frame_at(double t, double p, double q, double k, knot_frame *f)
{
    knot_curve(t, p, q, k, f->c, f->d);
    memcpy(f->t, f->d, sizeof f->t);
    normalize_d(f->t);
    mg_cross_d(f->t, f->c, f->b);
    normalize_d(f->b);
    mg_cross_d(f->b, f->t, f->n);
}

static void normalize_d(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++)
        v[i] /= l;
}

bool mesh_torus_knot(uint32_t p, uint32_t q, float radius, float tube_radius,
                     uint32_t segments, uint32_t sides, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (p < 1 || q < 1 || gcd_u32(p, q) != 1 || p > 1000 || q > 1000)
        return scene_fail(err, errlen,
                          "mesh_torus_knot: p and q must be coprime, 1..1000 (got %u, %u)", p, q);
    if (!mg_positive(radius) || !mg_positive(tube_radius) || !(tube_radius < radius / 3.0f))
        return scene_fail(err, errlen,
                          "mesh_torus_knot: needs 0 < tube_radius < radius / 3, finite "
                          "(got radius %g, tube_radius %g)", (double)radius, (double)tube_radius);
    if (segments < 3 || sides < 3)
        return scene_fail(err, errlen,
                          "mesh_torus_knot: needs segments >= 3 and sides >= 3 (got %u, %u)",
                          segments, sides);
    uint64_t S = segments, N = sides;
    if (!mg_alloc(out, (S + 1) * (N + 1), 6 * S * N, "mesh_torus_knot", err, errlen))
        return false;
    double k = (double)radius / 3.0, pd = p, qd = q;
    /* length of the centre line, for square-ish texels */
    double length = 0.0, prev[3], c[3], d[3];
    uint64_t nsteps = 64 * (uint64_t)(p + q) * 16;
    knot_curve(0.0, pd, qd, k, prev, d);
    for (uint64_t i = 1; i <= nsteps; i++) {
        knot_curve(TWO_PI * (double)i / (double)nsteps, pd, qd, k, c, d);
        double dx = c[0] - prev[0], dy = c[1] - prev[1], dz = c[2] - prev[2];
        length += sqrt(dx * dx + dy * dy + dz * dz);
        memcpy(prev, c, sizeof c);
    }
    double reps = floor(length / (TWO_PI * tube_radius) + 0.5);
    if (reps < 1.0)
        reps = 1.0;

    mesh_vertex *v = out->vertices;
    uint32_t row = sides + 1;
    for (uint32_t j = 0; j <= segments; j++) {
        if (j == segments) {
            for (uint32_t s = 0; s <= sides; s++) {
                v[j * row + s] = v[s];
                v[j * row + s].uv[0] = (float)reps;
            }
            continue;
        }
        double t = TWO_PI * (double)j / (double)segments, dt = 1e-5;
        knot_frame fr, f0, f1;
        knot_frame_at(t, pd, qd, k, &fr);
        knot_frame_at(t - dt, pd, qd, k, &f0);
        knot_frame_at(t + dt, pd, qd, k, &f1);
        for (uint32_t s = 0; s <= sides; s++) {
            mesh_vertex *w = &v[j * row + s];
            if (s == sides) {
                *w = v[j * row];
                w->uv[1] = 1.0f;
                continue;
            }
            /* the angle runs clockwise about T, so that (along, around) is CCW outside */
            double a = -TWO_PI * (double)s / (double)sides;
            double ca = cos(a), sa = sin(a);
            sm_vec3 n, dpdu, dpdv;
            for (int i = 0; i < 3; i++) {
                double ni = ca * fr.n[i] + sa * fr.b[i];
                n[i] = (float)ni;
                w->position[i] = (float)(fr.c[i] + tube_radius * ni);
                /* dX/dt = c' + r dn/dt: the frame turns about T along the curve, so the
                 * surface's u lines lean off T by the tube radius times that rate */
                double dn = (ca * (f1.n[i] - f0.n[i]) + sa * (f1.b[i] - f0.b[i])) / (2.0 * dt);
                dpdu[i] = (float)(fr.d[i] + tube_radius * dn);
                dpdv[i] = (float)(sa * fr.n[i] - ca * fr.b[i]);   /* -dn/da */
            }
            mg_set_normal(w, n, dpdv);
            mg_set_frame(w, dpdu, dpdv);
            w->uv[0] = (float)(reps * (double)j / (double)segments);
            w->uv[1] = (float)((double)s / (double)sides);
        }
    }
    uint32_t *ip = out->indices;
    for (uint32_t j = 0; j < segments; j++) {
        for (uint32_t s = 0; s < sides; s++) {
            uint32_t a = j * row + s, b = a + row;
            mg_tri(&ip, a, b, b + 1);
            mg_tri(&ip, a, b + 1, a + 1);
        }
    }
    mesh_compute_bounds(out);
    return true;
}
