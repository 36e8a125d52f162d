/* Procedural meshes, the shapes: >>sphere >>icosphere >>cone >>quads (box, room,
 * corridor) >>lathe (cylinder, pillar). See scenes/mesh.h and scenes/builtin/mesh_gen.c. */
#include "scenes/builtin/mesh_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/scene_fail.h"

/* >>sphere ----------------------------------------------------------------------------- */

/* Unit-sphere vertex at latitude row i of `stacks` (0: south pole) and angle j of
 * `slices`, offset by `joff` slices (0.5 at the poles). */
static void sphere_vertex(mesh_vertex *v, float radius, uint32_t i, uint32_t stacks,
                          uint32_t j, uint32_t slices, double joff)
{
    float sp, cp, sa, ca;
    mg_angle_of(j, slices, joff, &sp, &cp);
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
    mg_set_normal(v, n, up);
    for (int k = 0; k < 3; k++)
        v->position[k] = radius * v->normal[k];
    sm_vec3 east = {cp, 0.0f, -sp};
    sm_vec3 north = {-sa * sp, ca, -sa * cp};
    mg_set_frame(v, east, north);
    v->uv[0] = (float)(((double)j + joff) / (double)slices);
    v->uv[1] = (float)((double)i / (double)stacks);
}

bool mesh_sphere(float radius, uint32_t slices, uint32_t stacks, mesh *out,
                 char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!mg_positive(radius))
        return scene_fail(err, errlen, "mesh_sphere: radius must be positive and finite (got %g)",
                          (double)radius);
    if (slices < 3 || stacks < 2)
        return scene_fail(err, errlen,
                          "mesh_sphere: needs slices >= 3 and stacks >= 2 (got %u, %u)", slices,
                          stacks);
    uint64_t S = slices, T = stacks;
    if (!mg_alloc(out, (T - 1) * (S + 1) + 2 * S, 6 * S * (T - 1), "mesh_sphere", err,
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
        mg_tri(&ip, south + j, r + 1, r);
    }
    for (uint32_t i = 1; i + 1 < stacks; i++) {
        for (uint32_t j = 0; j < slices; j++) {
            uint32_t a = ring0 + (i - 1) * (slices + 1) + j, d = a + slices + 1;
            mg_tri(&ip, a, a + 1, d + 1);
            mg_tri(&ip, a, d + 1, d);
        }
    }
    for (uint32_t j = 0; j < slices; j++) {
        uint32_t r = ring0 + (stacks - 2) * (slices + 1) + j;
        mg_tri(&ip, r, r + 1, north + j);
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
    if (!mg_positive(radius))
        return scene_fail(err, errlen,
                          "mesh_icosphere: radius must be positive and finite (got %g)",
                          (double)radius);
    if (subdivisions > 8)
        return scene_fail(err, errlen, "mesh_icosphere: at most 8 subdivisions (got %u)",
                          subdivisions);
    uint32_t f = 1u << subdivisions;
    uint64_t F = f;
    if (!mg_alloc(out, (F + 1) * (10 * F + 1), 60 * F * F, "mesh_icosphere", err, errlen))
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
                    mg_tri(&ip, p00, p10, p01);
                    if (i + j + 1 < f) {
                        uint32_t p11 = (uint32_t)slot[ico_slot(&fc, i + 1, j + 1, &la, &lb)];
                        mg_tri(&ip, p10, p11, p01);
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
    if (!mg_positive(radius) || !mg_positive(height))
        return scene_fail(err, errlen, "mesh_cone: radius and height must be positive and finite "
                          "(got %g, %g)", (double)radius, (double)height);
    if (segments < 3)
        return scene_fail(err, errlen, "mesh_cone: needs segments >= 3 (got %u)", segments);
    uint64_t S = segments;
    if (!mg_alloc(out, capped ? 3 * S + 2 : 2 * S + 1, capped ? 6 * S : 3 * S, "mesh_cone",
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
            mg_angle_of(j, segments, off, &sn, &cs);
            mesh_vertex *w = at_apex ? &v[apex + j] : &v[rim + j];
            if (at_apex) {
                sm_vec3_zero(w->position);
            } else {
                w->position[0] = radius * cs;
                w->position[1] = radius * sn;
                w->position[2] = -height;
            }
            sm_vec3 n = {height * cs, height * sn, radius}, z = {0.0f, 0.0f, 1.0f};
            mg_set_normal(w, n, z);
            sm_vec3 dpdu = {-sn, cs, 0.0f}, dpdv = {-radius * cs, -radius * sn, height};
            mg_set_frame(w, dpdu, dpdv);
            w->uv[0] = (float)(((double)j + off) / (double)segments);
            w->uv[1] = (float)at_apex;
        }
    }
    uint32_t *ip = out->indices;
    for (uint32_t j = 0; j < segments; j++)
        mg_tri(&ip, rim + j, rim + j + 1, apex + j);
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
            mg_set_frame(w, dpdu, dpdv);
            w->uv[0] = 0.5f + 0.5f * w->position[0] / radius;
            w->uv[1] = 0.5f - 0.5f * w->position[1] / radius;
        }
        for (uint32_t j = 0; j < segments; j++)
            mg_tri(&ip, centre, cap + (j + 1) % segments, cap + j);
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
        mg_set_normal(v, n, n);
        mg_set_frame(v, U, V);
        v->uv[0] = su[k] > 0.0f ? us : 0.0f;
        v->uv[1] = sv[k] > 0.0f ? vs : 0.0f;
    }
    *nv = base + 4;
    mg_tri(ip, base, base + 1, base + 2);
    mg_tri(ip, base, base + 2, base + 3);
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
    if (!half || !mg_positive(half[0]) || !mg_positive(half[1]) || !mg_positive(half[2]))
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
        !mg_alloc(out, 24, 36, "mesh_box", err, errlen))
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
        !mg_alloc(out, 24, 36, "mesh_room", err, errlen))
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
    if (!mg_positive(width) || !mg_positive(height) || !mg_positive(length) ||
        !mg_positive(half[0]) || !mg_positive(half[1]) || !mg_positive(half[2]))
        return scene_fail(err, errlen,
                          "mesh_corridor: width, height and length must be positive and "
                          "finite (got %g, %g, %g)", (double)width, (double)height, (double)length);
    if (!check_uv_scale(uv_scale, "mesh_corridor", err, errlen) ||
        !mg_alloc(out, 16, 24, "mesh_corridor", err, errlen))
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
    if (!mg_alloc(out, nv, ni, "mesh_lathe", err, errlen))
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
                mg_angle_of(j, segments, off, &s, &c);
                v->position[0] = p[0] * s;
                v->position[1] = p[1];
                v->position[2] = p[0] * c;
                sm_vec3 nrm = {s * dy, -dr, c * dy}, fb = {0.0f, 1.0f, 0.0f};
                mg_set_normal(v, nrm, fb);
                sm_vec3 east = {c, 0.0f, -s}, dpdv = {dr * s, dy, dr * c};
                mg_set_frame(v, east, dpdv);
                v->uv[0] = (float)(((double)j + off) / (double)segments);
                v->uv[1] = e ? v1 : v0;
            }
            base += n;
        }
        for (uint32_t j = 0; j < segments; j++) {
            uint32_t a = first[0] + j, d = first[1] + j;
            if (p0[0] == 0.0f) {
                mg_tri(&ip, a, d + 1, d);
            } else if (p1[0] == 0.0f) {
                mg_tri(&ip, a, a + 1, d);
            } else {
                mg_tri(&ip, a, a + 1, d + 1);
                mg_tri(&ip, a, d + 1, d);
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
    if (!mg_positive(radius) || !mg_positive(height) || !mg_positive(h))
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
    if (!mg_positive(radius) || !mg_positive(height) || !mg_positive(R) || !mg_positive(h))
        return scene_fail(err, errlen, "mesh_pillar: radius and height must be positive and finite "
                          "(got %g, %g)", (double)radius, (double)height);
    const float a = 0.06f * height, b = 0.10f * height;
    const sm_vec2 prof[8] = {
        {0.0f, -h}, {R, -h}, {R, -h + a}, {radius, -h + b},
        {radius, h - b}, {R, h - a}, {R, h}, {0.0f, h},
    };
    return mesh_lathe(prof, 8, segments, out, err, errlen);
}
