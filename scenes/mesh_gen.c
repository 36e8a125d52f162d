/* Procedural meshes: see scenes/mesh.h for the conventions and the counts.
 *
 * Sections: >>helpers >>bounds >>sphere >>icosphere >>cone >>quads (box, room, corridor)
 * >>lathe (cylinder, pillar) >>torus-knot >>terrain >>light-volumes >>editing */
#include "scenes/mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/scene_fail.h"
#include "scenes/texture_gen.h"

/* >>helpers ---------------------------------------------------------------------------- */

#define PI_D 3.14159265358979323846264338327950288
#define TWO_PI (2.0 * PI_D)

static bool positive(float x) { return isfinite(x) && x > 0.0f; }

/* Allocates nv vertices and ni indices into a zeroed *m. */
static bool mesh_alloc(mesh *m, uint64_t nv, uint64_t ni, const char *who, char *err,
                       size_t errlen)
{
    memset(m, 0, sizeof *m);
    if (nv > MESH_MAX_VERTICES || ni > MESH_MAX_INDICES)
        return scene_fail(err, errlen, "%s: %llu vertices and %llu indices are more than the limit "
                          "(%u, %u)", who, (unsigned long long)nv, (unsigned long long)ni,
                          MESH_MAX_VERTICES, MESH_MAX_INDICES);
    m->vertices = calloc(nv ? nv : 1, sizeof *m->vertices);
    m->indices = calloc(ni ? ni : 1, sizeof *m->indices);
    if (!m->vertices || !m->indices) {
        mesh_free(m);
        return scene_fail(err, errlen, "%s: out of memory for %llu vertices", who,
                          (unsigned long long)nv);
    }
    m->nvertices = (uint32_t)nv;
    m->nindices = (uint32_t)ni;
    return true;
}

/* Any unit vector orthogonal to unit n: n crossed with the axis least aligned with it. */
static void any_orthogonal(const sm_vec3 n, sm_vec3 dest)
{
    sm_vec3 axis = {0.0f, 0.0f, 0.0f}, t;
    float ax = fabsf(n[0]), ay = fabsf(n[1]), az = fabsf(n[2]);
    axis[ax <= ay && ax <= az ? 0 : (ay <= az ? 1 : 2)] = 1.0f;
    sm_vec3_cross(axis, n, t);
    sm_vec3_normalize(t);
    if (sm_vec3_norm2(t) == 0.0f)      /* n was zero or NaN: callers never pass one */
        sm_vec3_make(1.0f, 0.0f, 0.0f, t);
    sm_vec3_copy(t, dest);
}

/* v->normal = normalize(n), or `fallback` (unit) when n is zero or not finite. */
static void set_normal(mesh_vertex *v, const sm_vec3 n, const sm_vec3 fallback)
{
    sm_vec3 t;
    sm_vec3_normalize_to(n, t);
    if (!(sm_vec3_norm2(t) > 0.5f))
        sm_vec3_copy(fallback, t);
    sm_vec3_copy(t, v->normal);
}

/* v->tangent from (unnormalized) dP/du and dP/dv and v->normal (unit): xyz = dP/du made
 * orthogonal to the normal; if that vanishes, cross(dP/dv, n); if that vanishes too,
 * any unit vector orthogonal to n. w = sign(dot(cross(n, t), dP/dv)), +1 for 0. */
static void set_frame(mesh_vertex *v, const sm_vec3 dpdu, const sm_vec3 dpdv)
{
    const float *n = v->normal;
    sm_vec3 t, b;
    float lu = sm_vec3_norm(dpdu), lv = sm_vec3_norm(dpdv), lt;

    sm_vec3_copy(dpdu, t);
    sm_vec3_muladds(n, -sm_vec3_dot(n, dpdu), t);
    lt = sm_vec3_norm(t);
    if (!(lt > 1e-6f * lu) || !isfinite(lt)) {
        sm_vec3_cross(dpdv, n, t);
        lt = sm_vec3_norm(t);
        if (!(lt > 1e-6f * lv) || !isfinite(lt))
            lt = 0.0f;
    }
    if (lt > 0.0f) {
        sm_vec3_scale(t, 1.0f / lt, t);
        /* once more against rounding, so |dot(t, n)| stays at float precision */
        sm_vec3_muladds(n, -sm_vec3_dot(n, t), t);
        sm_vec3_normalize(t);
    }
    if (!(sm_vec3_norm2(t) > 0.5f))
        any_orthogonal(n, t);
    sm_vec3_cross(n, t, b);
    float h = sm_vec3_dot(b, dpdv);
    memcpy(v->tangent, t, sizeof t);
    v->tangent[3] = h < 0.0f ? -1.0f : 1.0f;
}

static void tri(uint32_t **ip, uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t *i = *ip;
    i[0] = a;
    i[1] = b;
    i[2] = c;
    *ip = i + 3;
}

/* Longitude direction helpers: a point at angle phi about Y is (sin phi, 0, cos phi), the
 * seam at +Z; east (d/dphi) is (cos phi, 0, -sin phi). Angle j of n is computed once, in
 * double, so every vertex at angle j gets the same bits (j = n is angle 0). */
static void angle_of(uint32_t j, uint32_t n, double offset, float *s, float *c)
{
    double a = TWO_PI * (((double)(j % n) + offset) / (double)n);
    *s = (float)sin(a);
    *c = (float)cos(a);
}

/* >>bounds ----------------------------------------------------------------------------- */

void mesh_compute_bounds(mesh *m)
{
    if (!m->nvertices) {
        sm_aabb_empty(m->aabb);
        sm_vec4_zero(m->sphere);
        return;
    }
    sm_vec3 lo, hi;
    sm_vec3_copy(m->vertices[0].position, lo);
    sm_vec3_copy(m->vertices[0].position, hi);
    for (uint32_t i = 1; i < m->nvertices; i++) {
        sm_vec3_min(lo, m->vertices[i].position, lo);
        sm_vec3_max(hi, m->vertices[i].position, hi);
    }
    sm_vec3_copy(lo, m->aabb[0]);
    sm_vec3_copy(hi, m->aabb[1]);
    sm_vec3 c;
    sm_aabb_center(m->aabb, c);
    double r2 = 0.0;
    for (uint32_t i = 0; i < m->nvertices; i++) {
        double d2 = 0.0;
        for (int k = 0; k < 3; k++) {
            double d = (double)m->vertices[i].position[k] - (double)c[k];
            d2 += d * d;
        }
        if (d2 > r2)
            r2 = d2;
    }
    float r = (float)sqrt(r2);
    if ((double)r < sqrt(r2))
        r = nextafterf(r, INFINITY);
    sm_vec4_from_vec3(c, r, m->sphere);
}

/* >>sphere ----------------------------------------------------------------------------- */

/* Unit-sphere vertex at latitude row i of `stacks` (0: south pole) and angle j of
 * `slices`, offset by `joff` slices (0.5 at the poles). */
static void sphere_vertex(mesh_vertex *v, float radius, uint32_t i, uint32_t stacks,
                          uint32_t j, uint32_t slices, double joff)
{
    float sp, cp, sa, ca;
    angle_of(j, slices, joff, &sp, &cp);
    if (i == 0 || i == stacks) {
        sa = i == 0 ? -1.0f : 1.0f;
        ca = 0.0f;
    } else {
        double a = PI_D * ((double)i / (double)stacks - 0.5);
        sa = (float)sin(a);
        ca = (float)cos(a);
    }
    sm_vec3 n = {ca * sp, sa, ca * cp};
    sm_vec3 up = {0.0f, sa < 0.0f ? -1.0f : 1.0f, 0.0f};
    set_normal(v, n, up);
    for (int k = 0; k < 3; k++)
        v->position[k] = radius * v->normal[k];
    sm_vec3 east = {cp, 0.0f, -sp};
    sm_vec3 north = {-sa * sp, ca, -sa * cp};
    set_frame(v, east, north);
    v->uv[0] = (float)(((double)j + joff) / (double)slices);
    v->uv[1] = (float)((double)i / (double)stacks);
}

bool mesh_sphere(float radius, uint32_t slices, uint32_t stacks, mesh *out,
                 char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!positive(radius))
        return scene_fail(err, errlen, "mesh_sphere: radius must be positive and finite (got %g)",
                          (double)radius);
    if (slices < 3 || stacks < 2)
        return scene_fail(err, errlen,
                          "mesh_sphere: needs slices >= 3 and stacks >= 2 (got %u, %u)", slices,
                          stacks);
    uint64_t S = slices, T = stacks;
    if (!mesh_alloc(out, (T - 1) * (S + 1) + 2 * S, 6 * S * (T - 1), "mesh_sphere", err,
                    errlen))
        return false;
    mesh_vertex *v = out->vertices;
    uint32_t south = 0, ring0 = slices, north = slices + (stacks - 1) * (slices + 1);
    for (uint32_t j = 0; j < slices; j++) {
        sphere_vertex(&v[south + j], radius, 0, stacks, j, slices, 0.5);
        sphere_vertex(&v[north + j], radius, stacks, stacks, j, slices, 0.5);
    }
    for (uint32_t i = 1; i < stacks; i++)
        for (uint32_t j = 0; j <= slices; j++)
            sphere_vertex(&v[ring0 + (i - 1) * (slices + 1) + j], radius, i, stacks, j,
                          slices, 0.0);

    uint32_t *ip = out->indices;
    for (uint32_t j = 0; j < slices; j++) {
        uint32_t r = ring0 + j;
        tri(&ip, south + j, r + 1, r);
    }
    for (uint32_t i = 1; i + 1 < stacks; i++) {
        for (uint32_t j = 0; j < slices; j++) {
            uint32_t a = ring0 + (i - 1) * (slices + 1) + j, d = a + slices + 1;
            tri(&ip, a, a + 1, d + 1);
            tri(&ip, a, d + 1, d);
        }
    }
    for (uint32_t j = 0; j < slices; j++) {
        uint32_t r = ring0 + (stacks - 2) * (slices + 1) + j;
        tri(&ip, r, r + 1, north + j);
    }
    mesh_compute_bounds(out);
    return true;
}

/* >>icosphere -------------------------------------------------------------------------- */

/* Icosahedron: 0 north pole, 1 south pole, 2..6 upper ring A_k at longitude 72k + 36
 * degrees, 7..11 lower ring B_k at 72k degrees; rings at y = +-1/sqrt(5). */
static void ico_vertex(int id, double p[3])
{
    if (id < 2) {
        p[0] = p[2] = 0.0;
        p[1] = id == 0 ? 1.0 : -1.0;
        return;
    }
    int k = (id - 2) % 5;
    bool upper = id < 7;
    double y = (upper ? 1.0 : -1.0) / sqrt(5.0), rho = 2.0 / sqrt(5.0);
    double a = TWO_PI * ((double)k + (upper ? 0.5 : 0.0)) / 5.0;
    p[0] = rho * sin(a);
    p[1] = y;
    p[2] = rho * cos(a);
}

/* The unit-sphere point with integer barycentric weights w over icosahedron vertices
 * ids, computed in a canonical order (by id, zero weights dropped) so that a point on an
 * edge or corner shared by several net triangles comes out bit-identical. */
static void ico_point(const int ids[3], const uint32_t w[3], uint32_t f, sm_vec3 dest)
{
    int id[3] = {ids[0], ids[1], ids[2]};
    uint32_t ww[3] = {w[0], w[1], w[2]};
    for (int a = 0; a < 3; a++)
        for (int b = a + 1; b < 3; b++)
            if (id[b] < id[a]) {
                int ti = id[a];
                id[a] = id[b];
                id[b] = ti;
                uint32_t tw = ww[a];
                ww[a] = ww[b];
                ww[b] = tw;
            }
    double p[3] = {0.0, 0.0, 0.0};
    for (int a = 0; a < 3; a++) {
        if (!ww[a])
            continue;
        double q[3];
        ico_vertex(id[a], q);
        double s = (double)ww[a] / (double)f;
        for (int k = 0; k < 3; k++)
            p[k] += s * q[k];
    }
    double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int k = 0; k < 3; k++)
        dest[k] = (float)(p[k] / len);
}

/* A net triangle's lattice: corner 0 at (a0, b0) in units of 1/f, edges (e1a, e1b) and
 * (e2a, e2b) in edge units; slots are indexed by a * nb + (b + f). */
typedef struct ico_face {
    int32_t a0, b0, e1a, e1b, e2a, e2b, f;
    uint32_t nb;
} ico_face;

static size_t ico_slot(const ico_face *fc, uint32_t i, uint32_t j, int32_t *la, int32_t *lb)
{
    *la = fc->a0 + (int32_t)i * fc->e1a + (int32_t)j * fc->e2a;
    *lb = fc->b0 + (int32_t)i * fc->e1b + (int32_t)j * fc->e2b;
    return (size_t)*la * fc->nb + (size_t)(*lb + fc->f);
}

bool mesh_icosphere(float radius, uint32_t subdivisions, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!positive(radius))
        return scene_fail(err, errlen,
                          "mesh_icosphere: radius must be positive and finite (got %g)",
                          (double)radius);
    if (subdivisions > 8)
        return scene_fail(err, errlen, "mesh_icosphere: at most 8 subdivisions (got %u)",
                          subdivisions);
    uint32_t f = 1u << subdivisions;
    uint64_t F = f;
    if (!mesh_alloc(out, (F + 1) * (10 * F + 1), 60 * F * F, "mesh_icosphere", err, errlen))
        return false;
    /* Net lattice: integer coordinates (a, b) in units of 1/f, a in [0, 5f], b in
     * [-f, 2f]; net position x = (a + b/2) / f, y = b / f (edge lengths, y scaled by
     * sqrt(3)/2). */
    uint32_t na = 5 * f + 1, nb = 3 * f + 1;
    int32_t *slot = malloc((size_t)na * nb * sizeof *slot);
    if (!slot) {
        mesh_free(out);
        return scene_fail(err, errlen, "mesh_icosphere: out of memory");
    }
    for (size_t i = 0; i < (size_t)na * nb; i++)
        slot[i] = -1;

    uint32_t nv = 0;
    uint32_t *ip = out->indices;
    for (int k = 0; k < 5; k++) {
        int A0 = 2 + k, A1 = 2 + (k + 1) % 5, B0 = 7 + k, B1 = 7 + (k + 1) % 5;
        /* corners: 3D id and net lattice (a, b) in edge units; CCW in the net */
        const int faces[4][3][3] = {
            {{A0, k, 1}, {A1, k + 1, 1}, {0, k, 2}},              /* top */
            {{B0, k, 0}, {B1, k + 1, 0}, {A0, k, 1}},             /* middle, up */
            {{B1, k + 1, 0}, {A1, k + 1, 1}, {A0, k, 1}},         /* middle, down */
            {{B0, k, 0}, {1, k + 1, -1}, {B1, k + 1, 0}},         /* bottom */
        };
        for (int fi = 0; fi < 4; fi++) {
            const int (*c)[3] = faces[fi];
            int ids[3] = {c[0][0], c[1][0], c[2][0]};
            /* lattice point (i, j) of this face: corner 0 + i * edge 1 + j * edge 2 */
            ico_face fc = {
                .a0 = c[0][1] * (int32_t)f, .b0 = c[0][2] * (int32_t)f,
                .e1a = c[1][1] - c[0][1], .e1b = c[1][2] - c[0][2],
                .e2a = c[2][1] - c[0][1], .e2b = c[2][2] - c[0][2],
                .f = (int32_t)f, .nb = nb,
            };
            for (uint32_t i = 0; i <= f; i++) {
                for (uint32_t j = 0; i + j <= f; j++) {
                    int32_t la, lb;
                    size_t s = ico_slot(&fc, i, j, &la, &lb);
                    if (slot[s] >= 0)
                        continue;
                    slot[s] = (int32_t)nv;
                    mesh_vertex *v = &out->vertices[nv++];
                    uint32_t w[3] = {f - i - j, i, j};
                    sm_vec3 n;
                    ico_point(ids, w, f, n);
                    memcpy(v->normal, n, sizeof n);
                    for (int q = 0; q < 3; q++)
                        v->position[q] = radius * n[q];
                    v->uv[0] = (float)((2.0 * la + lb) / (11.0 * f));
                    v->uv[1] = (float)(((double)lb / f + 1.0) / 3.0);
                }
            }
            int32_t la, lb;
            for (uint32_t i = 0; i < f; i++) {
                for (uint32_t j = 0; i + j < f; j++) {
                    uint32_t p00 = (uint32_t)slot[ico_slot(&fc, i, j, &la, &lb)];
                    uint32_t p10 = (uint32_t)slot[ico_slot(&fc, i + 1, j, &la, &lb)];
                    uint32_t p01 = (uint32_t)slot[ico_slot(&fc, i, j + 1, &la, &lb)];
                    tri(&ip, p00, p10, p01);
                    if (i + j + 1 < f) {
                        uint32_t p11 = (uint32_t)slot[ico_slot(&fc, i + 1, j + 1, &la, &lb)];
                        tri(&ip, p10, p11, p01);
                    }
                }
            }
        }
    }
    free(slot);
    if (nv != out->nvertices || (uint32_t)(ip - out->indices) != out->nindices) {
        scene_fail(err, errlen, "bug: mesh_icosphere made %u vertices and %u indices, not %u, %u",
                   nv, (uint32_t)(ip - out->indices), out->nvertices, out->nindices);
        mesh_free(out);
        return false;
    }
    if (!mesh_compute_tangents(out)) {
        mesh_free(out);
        return scene_fail(err, errlen, "mesh_icosphere: out of memory");
    }
    mesh_compute_bounds(out);
    return true;
}

/* >>cone ------------------------------------------------------------------------------- */

bool mesh_cone(float radius, float height, uint32_t segments, bool capped, mesh *out,
               char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!positive(radius) || !positive(height))
        return scene_fail(err, errlen, "mesh_cone: radius and height must be positive and finite "
                          "(got %g, %g)", (double)radius, (double)height);
    if (segments < 3)
        return scene_fail(err, errlen, "mesh_cone: needs segments >= 3 (got %u)", segments);
    uint64_t S = segments;
    if (!mesh_alloc(out, capped ? 3 * S + 2 : 2 * S + 1, capped ? 6 * S : 3 * S, "mesh_cone",
                    err, errlen))
        return false;
    mesh_vertex *v = out->vertices;
    uint32_t apex = 0, rim = segments, centre = 2 * segments + 1, cap = centre + 1;
    /* Side: P(u, v) = lerp(rim(phi), apex, v), rim(phi) = (r cos phi, r sin phi, -h);
     * outward normal (h cos phi, h sin phi, r). */
    for (uint32_t j = 0; j <= segments; j++) {
        for (int at_apex = 0; at_apex < 2; at_apex++) {
            if (at_apex && j == segments)
                continue;
            double off = at_apex ? 0.5 : 0.0;
            /* phi from +X towards +Y here */
            float cs, sn;
            angle_of(j, segments, off, &sn, &cs);
            mesh_vertex *w = at_apex ? &v[apex + j] : &v[rim + j];
            if (at_apex) {
                sm_vec3_zero(w->position);
            } else {
                w->position[0] = radius * cs;
                w->position[1] = radius * sn;
                w->position[2] = -height;
            }
            sm_vec3 n = {height * cs, height * sn, radius}, z = {0.0f, 0.0f, 1.0f};
            set_normal(w, n, z);
            sm_vec3 dpdu = {-sn, cs, 0.0f}, dpdv = {-radius * cs, -radius * sn, height};
            set_frame(w, dpdu, dpdv);
            w->uv[0] = (float)(((double)j + off) / (double)segments);
            w->uv[1] = (float)at_apex;
        }
    }
    uint32_t *ip = out->indices;
    for (uint32_t j = 0; j < segments; j++)
        tri(&ip, rim + j, rim + j + 1, apex + j);
    if (capped) {
        sm_vec3 n = {0.0f, 0.0f, -1.0f}, dpdu = {1.0f, 0.0f, 0.0f}, dpdv = {0.0f, -1.0f, 0.0f};
        for (uint32_t j = 0; j <= segments; j++) {
            mesh_vertex *w = j < segments ? &v[cap + j] : &v[centre];
            if (j < segments) {
                sm_vec3_copy(v[rim + j].position, w->position);
            } else {
                sm_vec3_make(0.0f, 0.0f, -height, w->position);
            }
            sm_vec3_copy(n, w->normal);
            set_frame(w, dpdu, dpdv);
            w->uv[0] = 0.5f + 0.5f * w->position[0] / radius;
            w->uv[1] = 0.5f - 0.5f * w->position[1] / radius;
        }
        for (uint32_t j = 0; j < segments; j++)
            tri(&ip, centre, cap + (j + 1) % segments, cap + j);
    }
    mesh_compute_bounds(out);
    return true;
}

/* >>quads ------------------------------------------------------------------------------ */

/* One face: corners c - U - V, c + U - V, c + U + V, c - U + V (uv (0,0), (us,0), (us,vs),
 * (0,vs)), normal along cross(U, V). Components of c, U and V never overlap here, so
 * shared corners of neighbouring faces are bit-identical. */
static void quad_face(mesh *m, uint32_t *nv, uint32_t **ip, const sm_vec3 c, const sm_vec3 U,
                      const sm_vec3 V, float us, float vs)
{
    static const float su[4] = {-1.0f, 1.0f, 1.0f, -1.0f}, sv[4] = {-1.0f, -1.0f, 1.0f, 1.0f};
    sm_vec3 n;
    sm_vec3_cross(U, V, n);
    uint32_t base = *nv;
    for (int k = 0; k < 4; k++) {
        mesh_vertex *v = &m->vertices[base + k];
        for (int q = 0; q < 3; q++)
            v->position[q] = (c[q] + su[k] * U[q]) + sv[k] * V[q];
        set_normal(v, n, n);
        set_frame(v, U, V);
        v->uv[0] = su[k] > 0.0f ? us : 0.0f;
        v->uv[1] = sv[k] > 0.0f ? vs : 0.0f;
    }
    *nv = base + 4;
    tri(ip, base, base + 1, base + 2);
    tri(ip, base, base + 2, base + 3);
}

/* Faces of a box with half extents h: +X -X +Y -Y +Z -Z (bit k of mask), outward or
 * inward (U negated). uv_scale > 0: uv in world units times uv_scale. */
static void box_faces(mesh *m, const sm_vec3 h, unsigned mask, bool inward, float uv_scale)
{
    const float x = h[0], y = h[1], z = h[2];
    const float faces[6][3][3] = {
        {{x, 0, 0}, {0, 0, -z}, {0, y, 0}},
        {{-x, 0, 0}, {0, 0, z}, {0, y, 0}},
        {{0, y, 0}, {x, 0, 0}, {0, 0, -z}},
        {{0, -y, 0}, {x, 0, 0}, {0, 0, z}},
        {{0, 0, z}, {x, 0, 0}, {0, y, 0}},
        {{0, 0, -z}, {-x, 0, 0}, {0, y, 0}},
    };
    uint32_t nv = 0, *ip = m->indices;
    for (int f = 0; f < 6; f++) {
        if (!(mask & (1u << f)))
            continue;
        sm_vec3 U;
        sm_vec3_copy(faces[f][1], U);
        if (inward)
            sm_vec3_negate(U);
        float us = 1.0f, vs = 1.0f;
        if (uv_scale > 0.0f) {
            us = 2.0f * sm_vec3_norm(faces[f][1]) * uv_scale;
            vs = 2.0f * sm_vec3_norm(faces[f][2]) * uv_scale;
        }
        quad_face(m, &nv, &ip, faces[f][0], U, faces[f][2], us, vs);
    }
}

static bool check_half(const sm_vec3 half, const char *who, char *err, size_t errlen)
{
    if (!half || !positive(half[0]) || !positive(half[1]) || !positive(half[2]))
        return scene_fail(err, errlen,
                          "%s: half extents must be positive and finite (got %g, %g, %g)", who,
                          half ? (double)half[0] : 0.0, half ? (double)half[1] : 0.0,
                          half ? (double)half[2] : 0.0);
    return true;
}

static bool check_uv_scale(float s, const char *who, char *err, size_t errlen)
{
    if (!(isfinite(s) && s >= 0.0f))
        return scene_fail(err, errlen, "%s: uv_scale must be >= 0 and finite (got %g)", who,
                          (double)s);
    return true;
}

bool mesh_box(const sm_vec3 half, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!check_half(half, "mesh_box", err, errlen) ||
        !mesh_alloc(out, 24, 36, "mesh_box", err, errlen))
        return false;
    box_faces(out, half, 0x3f, false, 0.0f);
    mesh_compute_bounds(out);
    return true;
}

bool mesh_room(const sm_vec3 half, float uv_scale, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!check_half(half, "mesh_room", err, errlen) ||
        !check_uv_scale(uv_scale, "mesh_room", err, errlen) ||
        !mesh_alloc(out, 24, 36, "mesh_room", err, errlen))
        return false;
    box_faces(out, half, 0x3f, true, uv_scale);
    mesh_compute_bounds(out);
    return true;
}

bool mesh_corridor(float width, float height, float length, float uv_scale, mesh *out,
                   char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    sm_vec3 half = {0.5f * width, 0.5f * height, 0.5f * length};
    if (!positive(width) || !positive(height) || !positive(length) || !positive(half[0]) ||
        !positive(half[1]) || !positive(half[2]))
        return scene_fail(err, errlen,
                          "mesh_corridor: width, height and length must be positive and "
                          "finite (got %g, %g, %g)", (double)width, (double)height, (double)length);
    if (!check_uv_scale(uv_scale, "mesh_corridor", err, errlen) ||
        !mesh_alloc(out, 16, 24, "mesh_corridor", err, errlen))
        return false;
    box_faces(out, half, 0x0f, true, uv_scale);
    mesh_compute_bounds(out);
    return true;
}

/* >>lathe ------------------------------------------------------------------------------ */

bool mesh_lathe(const sm_vec2 *profile, uint32_t npoints, uint32_t segments, mesh *out,
                char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!profile || npoints < 2 || segments < 3)
        return scene_fail(err, errlen,
                          "mesh_lathe: needs a profile of >= 2 points and segments >= 3 "
                          "(got %u points, %u segments)", profile ? npoints : 0, segments);
    uint64_t nv = 0, ni = 0, S = segments;
    double total = 0.0;
    for (uint32_t k = 0; k < npoints; k++) {
        const float *p = profile[k];
        if (!isfinite(p[0]) || !isfinite(p[1]) || p[0] < 0.0f)
            return scene_fail(err, errlen,
                              "mesh_lathe: profile point %u (%g, %g) must be finite with " "r >= 0",
                              k, (double)p[0], (double)p[1]);
        if (k == 0)
            continue;
        const float *q = profile[k - 1];
        double dr = (double)p[0] - q[0], dy = (double)p[1] - q[1];
        double len = sqrt(dr * dr + dy * dy);
        if (!(len > 0.0) || !isfinite(len) || (p[0] == 0.0f && q[0] == 0.0f))
            return scene_fail(err, errlen,
                              "mesh_lathe: profile segment %u..%u is empty or lies on the " "axis",
                              k - 1, k);
        total += len;
        bool axis = p[0] == 0.0f || q[0] == 0.0f;
        nv += axis ? 2 * S + 1 : 2 * (S + 1);
        ni += axis ? 3 * S : 6 * S;
    }
    if (!isfinite(total))
        return scene_fail(err, errlen, "mesh_lathe: profile too long");
    if (!mesh_alloc(out, nv, ni, "mesh_lathe", err, errlen))
        return false;
    uint32_t base = 0, *ip = out->indices;
    double run = 0.0;
    for (uint32_t k = 0; k + 1 < npoints; k++) {
        const float *p0 = profile[k], *p1 = profile[k + 1];
        float dr = p1[0] - p0[0], dy = p1[1] - p0[1];
        double len = sqrt((double)dr * dr + (double)dy * dy);
        float v0 = (float)(run / total), v1 = (float)((run + len) / total);
        run += len;
        uint32_t first[2];
        for (int e = 0; e < 2; e++) {
            const float *p = e ? p1 : p0;
            bool axis = p[0] == 0.0f;
            uint32_t n = axis ? segments : segments + 1;
            first[e] = base;
            for (uint32_t j = 0; j < n; j++) {
                mesh_vertex *v = &out->vertices[base + j];
                double off = axis ? 0.5 : 0.0;
                float s, c;
                angle_of(j, segments, off, &s, &c);
                v->position[0] = p[0] * s;
                v->position[1] = p[1];
                v->position[2] = p[0] * c;
                sm_vec3 nrm = {s * dy, -dr, c * dy}, fb = {0.0f, 1.0f, 0.0f};
                set_normal(v, nrm, fb);
                sm_vec3 east = {c, 0.0f, -s}, dpdv = {dr * s, dy, dr * c};
                set_frame(v, east, dpdv);
                v->uv[0] = (float)(((double)j + off) / (double)segments);
                v->uv[1] = e ? v1 : v0;
            }
            base += n;
        }
        for (uint32_t j = 0; j < segments; j++) {
            uint32_t a = first[0] + j, d = first[1] + j;
            if (p0[0] == 0.0f) {
                tri(&ip, a, d + 1, d);
            } else if (p1[0] == 0.0f) {
                tri(&ip, a, a + 1, d);
            } else {
                tri(&ip, a, a + 1, d + 1);
                tri(&ip, a, d + 1, d);
            }
        }
    }
    mesh_compute_bounds(out);
    return true;
}

bool mesh_cylinder(float radius, float height, uint32_t segments, mesh *out,
                   char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    float h = 0.5f * height;
    if (!positive(radius) || !positive(height) || !positive(h))
        return scene_fail(err, errlen,
                          "mesh_cylinder: radius and height must be positive and finite "
                          "(got %g, %g)", (double)radius, (double)height);
    const sm_vec2 prof[4] = {{0.0f, -h}, {radius, -h}, {radius, h}, {0.0f, h}};
    return mesh_lathe(prof, 4, segments, out, err, errlen);
}

bool mesh_pillar(float radius, float height, uint32_t segments, mesh *out,
                 char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    float h = 0.5f * height, R = 1.4f * radius;
    if (!positive(radius) || !positive(height) || !positive(R) || !positive(h))
        return scene_fail(err, errlen, "mesh_pillar: radius and height must be positive and finite "
                          "(got %g, %g)", (double)radius, (double)height);
    const float a = 0.06f * height, b = 0.10f * height;
    const sm_vec2 prof[8] = {
        {0.0f, -h}, {R, -h}, {R, -h + a}, {radius, -h + b},
        {radius, h - b}, {R, h - a}, {R, h}, {0.0f, h},
    };
    return mesh_lathe(prof, 8, segments, out, err, errlen);
}

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

static void cross_d(const double a[3], const double b[3], double r[3]);
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
    cross_d(f->t, f->c, f->b);
    normalize_d(f->b);
    cross_d(f->b, f->t, f->n);
}

static void normalize_d(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++)
        v[i] /= l;
}

static void cross_d(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

bool mesh_torus_knot(uint32_t p, uint32_t q, float radius, float tube_radius,
                     uint32_t segments, uint32_t sides, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (p < 1 || q < 1 || gcd_u32(p, q) != 1 || p > 1000 || q > 1000)
        return scene_fail(err, errlen,
                          "mesh_torus_knot: p and q must be coprime, 1..1000 (got %u, %u)", p, q);
    if (!positive(radius) || !positive(tube_radius) || !(tube_radius < radius / 3.0f))
        return scene_fail(err, errlen,
                          "mesh_torus_knot: needs 0 < tube_radius < radius / 3, finite "
                          "(got radius %g, tube_radius %g)", (double)radius, (double)tube_radius);
    if (segments < 3 || sides < 3)
        return scene_fail(err, errlen,
                          "mesh_torus_knot: needs segments >= 3 and sides >= 3 (got %u, %u)",
                          segments, sides);
    uint64_t S = segments, N = sides;
    if (!mesh_alloc(out, (S + 1) * (N + 1), 6 * S * N, "mesh_torus_knot", err, errlen))
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
            set_normal(w, n, dpdv);
            set_frame(w, dpdu, dpdv);
            w->uv[0] = (float)(reps * (double)j / (double)segments);
            w->uv[1] = (float)((double)s / (double)sides);
        }
    }
    uint32_t *ip = out->indices;
    for (uint32_t j = 0; j < segments; j++) {
        for (uint32_t s = 0; s < sides; s++) {
            uint32_t a = j * row + s, b = a + row;
            tri(&ip, a, b, b + 1);
            tri(&ip, a, b + 1, a + 1);
        }
    }
    mesh_compute_bounds(out);
    return true;
}

/* >>terrain ---------------------------------------------------------------------------- */

void mesh_terrain_init(mesh_terrain *t, float size_x, float size_z, float height_scale,
                       uint32_t seed)
{
    memset(t, 0, sizeof *t);
    texture_noise_keys(seed, t->keys, MESH_TERRAIN_OCTAVES);
    float side = fmaxf(fabsf(size_x), fabsf(size_z));
    t->frequency = isfinite(side) && side > 0.0f ? 4.0f / side : 0.0f;
    t->height_scale = isfinite(height_scale) ? height_scale : 0.0f;
}

float mesh_terrain_height(float x, float z, void *terrain)
{
    const mesh_terrain *t = terrain;
    if (!isfinite(x))
        x = 0.0f;
    if (!isfinite(z))
        z = 0.0f;
    float h = texture_fbm2(x * t->frequency, z * t->frequency, t->keys, MESH_TERRAIN_OCTAVES,
                           0, 0);
    return t->height_scale * h;
}

bool mesh_heightfield_fn(float size_x, float size_z, uint32_t cells_x, uint32_t cells_z,
                         mesh_height_fn fn, void *user, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!positive(size_x) || !positive(size_z) || !fn)
        return scene_fail(err, errlen,
                          "mesh_heightfield: sizes must be positive and finite (got %g, %g)%s",
                          (double)size_x, (double)size_z,
                          fn ? "" : ", and a height function is needed");
    if (cells_x < 1 || cells_z < 1)
        return scene_fail(err, errlen,
                          "mesh_heightfield: needs at least 1 cell each way (got %u x %u)", cells_x,
                          cells_z);
    uint64_t cx = cells_x, cz = cells_z;
    if (!mesh_alloc(out, (cx + 1) * (cz + 1), 6 * cx * cz, "mesh_heightfield", err, errlen))
        return false;
    /* Heights on the grid and one cell beyond it, each sampled once, so a vertex's normal
     * is made of its neighbours' very heights. */
    uint32_t gw = cells_x + 3, row = cells_x + 1;
    float *hg = malloc((size_t)gw * (cells_z + 3) * sizeof *hg);
    if (!hg) {
        mesh_free(out);
        return scene_fail(err, errlen, "mesh_heightfield: out of memory");
    }
    for (uint32_t k = 0; k < cells_z + 3; k++) {
        for (uint32_t i = 0; i < gw; i++) {
            float u = (float)((int32_t)i - 1) / (float)cells_x;
            float w = (float)((int32_t)k - 1) / (float)cells_z;
            float x = size_x * (u - 0.5f), z = size_z * (0.5f - w);
            float h = fn(x, z, user);
            if (!isfinite(h)) {
                scene_fail(err, errlen, "mesh_heightfield: the height function returned %g at "
                           "(%g, %g)", (double)h, (double)x, (double)z);
                free(hg);
                mesh_free(out);
                return false;
            }
            hg[(size_t)k * gw + i] = h;
            if (i >= 1 && i <= cells_x + 1 && k >= 1 && k <= cells_z + 1) {
                mesh_vertex *v = &out->vertices[(k - 1) * row + (i - 1)];
                sm_vec3_make(x, h, z, v->position);
                v->uv[0] = u;
                v->uv[1] = w;
            }
        }
    }
    double dx = (double)size_x / cells_x, dz = (double)size_z / cells_z;
    for (uint32_t k = 0; k <= cells_z; k++) {
        for (uint32_t i = 0; i <= cells_x; i++) {
            mesh_vertex *v = &out->vertices[k * row + i];
            const float *c = &hg[(size_t)(k + 1) * gw + (i + 1)];
            /* slopes dh/dx and dh/dz in double (differences of large heights must not
             * overflow), scaled down by the largest so the frame stays finite */
            double sx = ((double)c[1] - c[-1]) / (2.0 * dx);
            double sz = ((double)c[-(ptrdiff_t)gw] - c[gw]) / (2.0 * dz);   /* k grows to -z */
            double m = fmax(1.0, fmax(fabs(sx), fabs(sz)));
            sm_vec3 n = {(float)(-sx / m), (float)(1.0 / m), (float)(-sz / m)};
            sm_vec3 up = {0.0f, 1.0f, 0.0f};
            set_normal(v, n, up);
            if (!(v->normal[1] > 0.0f))     /* a cliff steeper than float can tell */
                sm_vec3_copy(up, v->normal);
            /* dP/du along +x, dP/dv along -z */
            sm_vec3 dpdu = {(float)(1.0 / m), (float)(sx / m), 0.0f};
            sm_vec3 dpdv = {0.0f, (float)(-sz / m), (float)(-1.0 / m)};
            set_frame(v, dpdu, dpdv);
        }
    }
    free(hg);
    uint32_t *ip = out->indices;
    for (uint32_t k = 0; k < cells_z; k++) {
        for (uint32_t i = 0; i < cells_x; i++) {
            uint32_t a = k * row + i, d = a + row;
            tri(&ip, a, a + 1, d + 1);
            tri(&ip, a, d + 1, d);
        }
    }
    mesh_compute_bounds(out);
    return true;
}

bool mesh_heightfield(float size_x, float size_z, uint32_t cells_x, uint32_t cells_z,
                      float height_scale, uint32_t seed, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!(isfinite(height_scale) && height_scale >= 0.0f))
        return scene_fail(err, errlen,
                          "mesh_heightfield: height_scale must be >= 0 and finite (got %g)",
                          (double)height_scale);
    mesh_terrain t;
    mesh_terrain_init(&t, size_x, size_z, height_scale, seed);
    return mesh_heightfield_fn(size_x, size_z, cells_x, cells_z, mesh_terrain_height, &t, out,
                               err, errlen);
}

/* >>light-volumes ---------------------------------------------------------------------- */

#define LIGHT_VOLUME_MARGIN 1e-4

/* The smallest distance from the origin to a triangle's plane (positive: the origin is
 * on the inner side of every face), in double from the float positions. */
static double min_face_distance(const mesh *m, double scale)
{
    double dmin = INFINITY;
    for (uint32_t t = 0; t + 2 < m->nindices; t += 3) {
        double p[3][3];
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 3; i++)
                p[k][i] = (double)(float)(m->vertices[m->indices[t + k]].position[i] * scale);
        double e1[3], e2[3], n[3];
        for (int i = 0; i < 3; i++) {
            e1[i] = p[1][i] - p[0][i];
            e2[i] = p[2][i] - p[0][i];
        }
        cross_d(e1, e2, n);
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double d = (n[0] * p[0][0] + n[1] * p[0][1] + n[2] * p[0][2]) / len;
        if (d < dmin)
            dmin = d;
    }
    return dmin;
}

bool mesh_light_sphere(uint32_t slices, uint32_t stacks, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (slices < 3 || stacks < 2)
        return scene_fail(err, errlen,
                          "mesh_light_sphere: needs slices >= 3 and stacks >= 2 (got %u, %u)",
                          slices, stacks);
    if (!mesh_sphere(1.0f, slices, stacks, out, err, errlen))
        return false;
    /* Scale so that every face plane is at least 1 + margin out, checking the rounded
     * float positions (the quads' two triangles are coplanar only up to rounding). */
    double d = min_face_distance(out, 1.0);
    double scale = (1.0 + LIGHT_VOLUME_MARGIN) / d;
    while (min_face_distance(out, scale) < 1.0 + 0.5 * LIGHT_VOLUME_MARGIN)
        scale *= 1.0 + 1e-6;
    for (uint32_t i = 0; i < out->nvertices; i++)
        for (int k = 0; k < 3; k++)
            out->vertices[i].position[k] = (float)(out->vertices[i].position[k] * scale);
    mesh_compute_bounds(out);
    return true;
}

bool mesh_light_cone(float half_angle, uint32_t segments, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!(isfinite(half_angle) && half_angle > 0.0f && half_angle < SM_PI_2))
        return scene_fail(err, errlen,
                          "mesh_light_cone: half_angle must be in (0, pi/2) radians (got %g)",
                          (double)half_angle);
    if (segments < 3)
        return scene_fail(err, errlen, "mesh_light_cone: needs segments >= 3 (got %u)", segments);
    /* The pyramid with its apex m behind the origin and its base m beyond z = -1,
     * inradius tan(half_angle) (1 + 2m) there: at z = -1 its inradius is
     * tan(half_angle) (1 + m), so apex and base circle of the true cone, and with them
     * their hull, are strictly inside. (Scaling about the apex would not do: a cone is
     * its own image, and its sides would stay tangent.) */
    double m = LIGHT_VOLUME_MARGIN;
    double r = tan((double)half_angle) * (1.0 + 2.0 * m) / cos(PI_D / (double)segments);
    float radius = (float)r, height = (float)(1.0 + 2.0 * m);
    if (!positive(radius))
        return scene_fail(err, errlen, "mesh_light_cone: half_angle %g too close to pi/2",
                          (double)half_angle);
    if (!mesh_cone(radius, height, segments, true, out, err, errlen))
        return false;
    for (uint32_t i = 0; i < out->nvertices; i++)
        out->vertices[i].position[2] += (float)m;
    mesh_compute_bounds(out);
    return true;
}

/* >>editing ---------------------------------------------------------------------------- */

bool mesh_compute_tangents(mesh *m)
{
    uint32_t nv = m->nvertices;
    float *acc = calloc(nv ? (size_t)nv * 6 : 1, sizeof *acc);   /* sdir, tdir per vertex */
    if (!acc)
        return false;
    for (uint32_t t = 0; t + 2 < m->nindices; t += 3) {
        const uint32_t *ix = &m->indices[t];
        const mesh_vertex *a = &m->vertices[ix[0]], *b = &m->vertices[ix[1]],
                          *c = &m->vertices[ix[2]];
        sm_vec3 e1, e2;
        sm_vec3_sub(b->position, a->position, e1);
        sm_vec3_sub(c->position, a->position, e2);
        float du1 = b->uv[0] - a->uv[0], dv1 = b->uv[1] - a->uv[1];
        float du2 = c->uv[0] - a->uv[0], dv2 = c->uv[1] - a->uv[1];
        float det = du1 * dv2 - du2 * dv1;
        if (!(fabsf(det) > 0.0f) || !isfinite(det))
            continue;
        float r = 1.0f / det;
        if (!isfinite(r))
            continue;
        for (int i = 0; i < 3; i++) {
            float sd = (e1[i] * dv2 - e2[i] * dv1) * r;
            float td = (e2[i] * du1 - e1[i] * du2) * r;
            for (int k = 0; k < 3; k++) {
                acc[(size_t)ix[k] * 6 + i] += sd;
                acc[(size_t)ix[k] * 6 + 3 + i] += td;
            }
        }
    }
    for (uint32_t i = 0; i < nv; i++) {
        sm_vec3 s, t;
        memcpy(s, &acc[(size_t)i * 6], sizeof s);
        memcpy(t, &acc[(size_t)i * 6 + 3], sizeof t);
        set_frame(&m->vertices[i], s, t);
    }
    free(acc);
    return true;
}

static bool mat_ok(const sm_mat4 mat, float *det3)
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            if (!isfinite(mat[c][r]))
                return false;
    sm_mat3 m3;
    sm_mat4_pick3(mat, m3);
    *det3 = sm_mat3_det((const sm_vec3 *)m3);
    sm_mat3 nm;
    sm_mat4_normal(mat, nm);
    float s = 0.0f;
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++)
            s += fabsf(nm[c][r]);
    return isfinite(*det3) && *det3 != 0.0f && s > 0.0f && isfinite(s);
}

/* Transforms n vertices (the matrix is checked); the caller fixes the winding. The new
 * handedness comes from the old bitangent carried through the matrix, which flips it
 * exactly when the matrix mirrors. */
static void transform_vertices(mesh_vertex *v, uint32_t n, const sm_mat4 mat)
{
    sm_mat3 nm, m3;
    sm_mat4_normal(mat, nm);
    sm_mat4_pick3(mat, m3);
    for (uint32_t i = 0; i < n; i++) {
        mesh_vertex *w = &v[i];
        sm_vec3 p, nn, t, b, old_b;
        sm_mat4_mulv3(mat, w->position, 1.0f, p);
        sm_vec3_copy(p, w->position);
        /* the old bitangent, carried along to fix the new handedness */
        sm_vec3_cross(w->normal, w->tangent, old_b);
        sm_vec3_scale(old_b, w->tangent[3], old_b);
        sm_mat3_mulv((const sm_vec3 *)nm, w->normal, nn);
        sm_mat3_mulv((const sm_vec3 *)m3, w->tangent, t);
        sm_mat3_mulv((const sm_vec3 *)m3, old_b, b);
        set_normal(w, nn, w->normal);
        set_frame(w, t, b);
    }
}

bool mesh_transform(mesh *m, const sm_mat4 mat, char *err, size_t errlen)
{
    float det3;
    if (!mat || !mat_ok(mat, &det3))
        return scene_fail(err, errlen, "mesh_transform: the matrix is singular or not finite");
    transform_vertices(m->vertices, m->nvertices, mat);
    if (det3 < 0.0f)
        for (uint32_t t = 0; t + 2 < m->nindices; t += 3) {
            uint32_t x = m->indices[t + 1];
            m->indices[t + 1] = m->indices[t + 2];
            m->indices[t + 2] = x;
        }
    mesh_compute_bounds(m);
    return true;
}

bool mesh_append(mesh *dst, const mesh *src, const sm_mat4 mat, char *err, size_t errlen)
{
    float det3 = 1.0f;
    if (mat && !mat_ok(mat, &det3))
        return scene_fail(err, errlen, "mesh_append: the matrix is singular or not finite");
    uint64_t nv = (uint64_t)dst->nvertices + src->nvertices;
    uint64_t ni = (uint64_t)dst->nindices + src->nindices;
    if (nv > MESH_MAX_VERTICES || ni > MESH_MAX_INDICES)
        return scene_fail(err, errlen,
                          "mesh_append: %llu vertices and %llu indices are more than the "
                          "limit (%u, %u)", (unsigned long long)nv, (unsigned long long)ni,
                          MESH_MAX_VERTICES, MESH_MAX_INDICES);
    mesh_vertex *v = malloc((size_t)(nv ? nv : 1) * sizeof *v);
    uint32_t *ix = malloc((size_t)(ni ? ni : 1) * sizeof *ix);
    if (!v || !ix) {
        free(v);
        free(ix);
        return scene_fail(err, errlen, "mesh_append: out of memory for %llu vertices",
                          (unsigned long long)nv);
    }
    if (dst->nvertices)
        memcpy(v, dst->vertices, (size_t)dst->nvertices * sizeof *v);
    if (src->nvertices)
        memcpy(v + dst->nvertices, src->vertices, (size_t)src->nvertices * sizeof *v);
    if (dst->nindices)
        memcpy(ix, dst->indices, (size_t)dst->nindices * sizeof *ix);
    for (uint32_t i = 0; i < src->nindices; i++)
        ix[dst->nindices + i] = src->indices[i] + dst->nvertices;
    if (mat) {
        transform_vertices(v + dst->nvertices, src->nvertices, mat);
        if (det3 < 0.0f)
            for (uint32_t t = dst->nindices; t + 2 < ni; t += 3) {
                uint32_t x = ix[t + 1];
                ix[t + 1] = ix[t + 2];
                ix[t + 2] = x;
            }
    }
    free(dst->vertices);
    free(dst->indices);
    dst->vertices = v;
    dst->indices = ix;
    dst->nvertices = (uint32_t)nv;
    dst->nindices = (uint32_t)ni;
    mesh_compute_bounds(dst);
    return true;
}

void mesh_free(mesh *m)
{
    if (!m)
        return;
    free(m->vertices);
    free(m->indices);
    memset(m, 0, sizeof *m);
}
