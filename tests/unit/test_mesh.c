/* Procedural meshes, light volumes and textures (scenes/mesh.h, scenes/builtin/texture_gen.h).
 *
 * Every mesh goes through check_mesh: counts as the header's formulas, every float
 * finite, unit normals and tangents (1e-5), tangents orthogonal to normals (1e-5),
 * w = +-1, no degenerate triangle, every vertex normal on the front side of its
 * triangles, the tangent frame agreeing with the triangles' uv derivatives (tangent
 * within a stated angle of the face's dP/du, same handedness as the face's dP/dv),
 * a tight AABB and a bounding sphere holding every vertex.
 * Closed meshes also go through check_closed: welded by exact position, every directed
 * edge once and its reverse once (watertight and consistently wound), the Euler
 * characteristic, and the signed volume (positive: CCW outward) against the analytic one.
 * Light volumes: convex, and every sampled point of the unit sphere / cone (densely, plus
 * each face's own worst point) inside every face plane. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/mesh.h"
#include "scenes/builtin/texture_gen.h"

#define PI 3.14159265358979323846

/* >>checks ----------------------------------------------------------------------------- */

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

static double norm3(const double a[3]) { return sqrt(dot3(a, a)); }

static void to_d(const float *f, double *d, int n)
{
    for (int i = 0; i < n; i++)
        d[i] = f[i];
}

/* Checks everything every mesh must satisfy. tangent_cos: the least cosine allowed
 * between a vertex tangent and the dP/du of a triangle using it (projected onto the
 * vertex's tangent plane); -1 checks the handedness only; EXTREME also skips the
 * handedness and whether vertex normals face their triangles (terrain steeper than any
 * scene's, where central differences and single triangles may disagree). Returns the
 * smallest cosine seen. */
#define EXTREME (-2.0)

static double check_mesh(const mesh *m, const char *name, uint32_t nv, uint32_t ni,
                         double tangent_cos)
{
    if (m->nvertices != nv || m->nindices != ni)
        fail_msg("%s: %u vertices, %u indices; expected %u, %u", name, m->nvertices,
                 m->nindices, nv, ni);
    assert_int_equal(m->nindices % 3, 0);
    assert_non_null(m->vertices);
    assert_non_null(m->indices);

    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < m->nvertices; i++) {
        const mesh_vertex *v = &m->vertices[i];
        const float *f = (const float *)v;
        for (size_t k = 0; k < sizeof *v / sizeof(float); k++)
            if (!isfinite(f[k]))
                fail_msg("%s: vertex %u has a non-finite value", name, i);
        double n[3], t[3];
        to_d(v->normal, n, 3);
        to_d(v->tangent, t, 3);
        if (fabs(norm3(n) - 1.0) > 1e-5 || fabs(norm3(t) - 1.0) > 1e-5)
            fail_msg("%s: vertex %u |n| = %.8f |t| = %.8f", name, i, norm3(n), norm3(t));
        if (fabs(dot3(n, t)) > 1e-5)
            fail_msg("%s: vertex %u dot(n, t) = %g", name, i, dot3(n, t));
        if (v->tangent[3] != 1.0f && v->tangent[3] != -1.0f)
            fail_msg("%s: vertex %u w = %g", name, i, (double)v->tangent[3]);
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], v->position[k]);
            hi[k] = fmaxf(hi[k], v->position[k]);
        }
    }
    /* tight AABB, sphere holding every vertex */
    for (int k = 0; k < 3; k++)
        if (m->aabb[0][k] != lo[k] || m->aabb[1][k] != hi[k])
            fail_msg("%s: aabb axis %d is [%g, %g], vertices span [%g, %g]", name, k,
                     (double)m->aabb[0][k], (double)m->aabb[1][k], (double)lo[k],
                     (double)hi[k]);
    double diag = 0.0;
    for (int k = 0; k < 3; k++)
        diag += ((double)hi[k] - lo[k]) * ((double)hi[k] - lo[k]);
    diag = sqrt(diag);
    assert_true(isfinite(diag));
    for (uint32_t i = 0; i < m->nvertices; i++) {
        double d[3];
        for (int k = 0; k < 3; k++)
            d[k] = (double)m->vertices[i].position[k] - m->sphere[k];
        if (norm3(d) > m->sphere[3])
            fail_msg("%s: vertex %u outside the bounding sphere", name, i);
    }
    /* the bounding sphere is no bigger than the box's */
    assert_true(m->sphere[3] <= 0.5 * diag * (1.0 + 1e-6) + 1e-30);

    double worst = 1.0;
    for (uint32_t t = 0; t < m->nindices; t += 3) {
        const uint32_t *ix = &m->indices[t];
        for (int k = 0; k < 3; k++)
            if (ix[k] >= m->nvertices)
                fail_msg("%s: index %u = %u out of range", name, t + k, ix[k]);
        const mesh_vertex *a = &m->vertices[ix[0]], *b = &m->vertices[ix[1]],
                          *c = &m->vertices[ix[2]];
        double pa[3], pb[3], pc[3], e1[3], e2[3], fn[3];
        to_d(a->position, pa, 3);
        to_d(b->position, pb, 3);
        to_d(c->position, pc, 3);
        for (int k = 0; k < 3; k++) {
            e1[k] = pb[k] - pa[k];
            e2[k] = pc[k] - pa[k];
        }
        cross3(e1, e2, fn);
        double area2 = norm3(fn);
        if (!(area2 > 0.0))
            fail_msg("%s: triangle %u is degenerate", name, t / 3);
        for (int k = 0; k < 3; k++)
            fn[k] /= area2;
        /* uv derivatives of the triangle */
        double du1 = (double)b->uv[0] - a->uv[0], dv1 = (double)b->uv[1] - a->uv[1];
        double du2 = (double)c->uv[0] - a->uv[0], dv2 = (double)c->uv[1] - a->uv[1];
        double det = du1 * dv2 - du2 * dv1;
        double tf[3], bf[3];
        for (int k = 0; k < 3; k++) {
            tf[k] = (e1[k] * dv2 - e2[k] * dv1) / det;
            bf[k] = (e2[k] * du1 - e1[k] * du2) / det;
        }
        for (int k = 0; k < 3; k++) {
            const mesh_vertex *v = &m->vertices[ix[k]];
            double n[3], tv[3], tp[3], nt[3];
            to_d(v->normal, n, 3);
            to_d(v->tangent, tv, 3);
            if (tangent_cos == EXTREME)
                continue;
            if (!(dot3(n, fn) > 0.0))
                fail_msg("%s: vertex %u's normal is behind triangle %u (dot %g)", name,
                         ix[k], t / 3, dot3(n, fn));
            if (fabs(det) < 1e-12)
                continue;
            double s = dot3(n, tf);
            for (int q = 0; q < 3; q++)
                tp[q] = tf[q] - s * n[q];
            double l = norm3(tp);
            if (l < 1e-9 * norm3(tf))
                continue;
            double cosv = dot3(tp, tv) / l;
            if (cosv < worst)
                worst = cosv;
            if (cosv < tangent_cos)
                fail_msg("%s: vertex %u's tangent is %.1f degrees off triangle %u's dP/du",
                         name, ix[k], acos(fmax(-1.0, fmin(1.0, cosv))) * 180.0 / PI, t / 3);
            cross3(n, tv, nt);
            double h = dot3(nt, bf);
            if ((h < 0.0 ? -1.0f : 1.0f) != v->tangent[3])
                fail_msg("%s: vertex %u's handedness %g disagrees with triangle %u", name,
                         ix[k], (double)v->tangent[3], t / 3);
        }
    }
    return worst;
}

typedef struct wpos {
    float p[3];
    uint32_t index;
} wpos;

static int cmp_wpos(const void *a, const void *b)
{
    const wpos *x = a, *y = b;
    for (int k = 0; k < 3; k++) {
        if (x->p[k] < y->p[k])
            return -1;
        if (x->p[k] > y->p[k])
            return 1;
    }
    return 0;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Topology by exact position: *nverts distinct positions used, directed edges sorted
 * into *edges (caller frees), each a << 32 | b. */
static uint64_t *directed_edges(const mesh *m, uint32_t *nverts)
{
    wpos *w = malloc(m->nvertices * sizeof *w);
    uint32_t *id = malloc(m->nvertices * sizeof *id);
    uint64_t *e = malloc(m->nindices * sizeof *e);
    assert_non_null(w);
    assert_non_null(id);
    assert_non_null(e);
    for (uint32_t i = 0; i < m->nvertices; i++) {
        memcpy(w[i].p, m->vertices[i].position, sizeof w[i].p);
        w[i].index = i;
    }
    qsort(w, m->nvertices, sizeof *w, cmp_wpos);
    uint32_t next = 0;
    for (uint32_t i = 0; i < m->nvertices; i++) {
        if (i > 0 && cmp_wpos(&w[i - 1], &w[i]) != 0)
            next++;
        id[w[i].index] = next;
    }
    /* count only the positions the triangles use */
    uint8_t *used = calloc(next + 1, 1);
    assert_non_null(used);
    *nverts = 0;
    for (uint32_t t = 0; t < m->nindices; t++) {
        uint32_t a = id[m->indices[t]];
        if (!used[a]) {
            used[a] = 1;
            (*nverts)++;
        }
        uint32_t b = id[m->indices[t % 3 == 2 ? t - 2 : t + 1]];
        e[t] = (uint64_t)a << 32 | b;
    }
    qsort(e, m->nindices, sizeof *e, cmp_u64);
    free(used);
    free(w);
    free(id);
    return e;
}

/* Every directed edge at most once; returns the number of edges whose reverse is missing
 * (the boundary) and the number of undirected edges. */
static void edge_census(const mesh *m, const char *name, uint32_t *nverts, uint32_t *nedges,
                        uint32_t *boundary)
{
    uint64_t *e = directed_edges(m, nverts);
    *nedges = 0;
    *boundary = 0;
    for (uint32_t i = 0; i < m->nindices; i++) {
        if (i > 0 && e[i] == e[i - 1])
            fail_msg("%s: directed edge %u -> %u used twice (inconsistent winding or a "
                     "non-manifold edge)", name, (uint32_t)(e[i] >> 32), (uint32_t)e[i]);
        uint64_t rev = (e[i] << 32) | (e[i] >> 32);
        if (!bsearch(&rev, e, m->nindices, sizeof *e, cmp_u64)) {
            (*boundary)++;
            (*nedges)++;
        } else if ((uint32_t)(e[i] >> 32) < (uint32_t)e[i]) {
            (*nedges)++;
        }
    }
    free(e);
}

static double signed_volume(const mesh *m)
{
    double v = 0.0;
    for (uint32_t t = 0; t < m->nindices; t += 3) {
        double a[3], b[3], c[3], bc[3];
        to_d(m->vertices[m->indices[t]].position, a, 3);
        to_d(m->vertices[m->indices[t + 1]].position, b, 3);
        to_d(m->vertices[m->indices[t + 2]].position, c, 3);
        cross3(b, c, bc);
        v += dot3(a, bc);
    }
    return v / 6.0;
}

/* Watertight, consistently wound, Euler characteristic `euler`, signed volume within
 * rel_tol of `volume`. Returns the volume. */
static double check_closed(const mesh *m, const char *name, int euler, double volume,
                           double rel_tol)
{
    uint32_t V, E, B;
    edge_census(m, name, &V, &E, &B);
    if (B)
        fail_msg("%s: %u edges with one triangle (not watertight)", name, B);
    int chi = (int)V - (int)E + (int)(m->nindices / 3);
    if (chi != euler)
        fail_msg("%s: Euler characteristic %d (V %u E %u F %u), expected %d", name, chi, V, E,
                 m->nindices / 3, euler);
    double vol = signed_volume(m);
    if (!(fabs(vol - volume) <= rel_tol * fabs(volume)))
        fail_msg("%s: signed volume %.9g, expected %.9g within %g", name, vol, volume, rel_tol);
    return vol;
}

/* >>solids ----------------------------------------------------------------------------- */

/* Smooth vertex tangents follow the longitude at the vertex, a triangle's dP/du the
 * chord across its slice: they differ by up to half a slice, pi / S (plus a little
 * where the triangle's v runs askew). The allowed angle: 1.25 pi / S. */
static double slice_cos(uint32_t S) { return cos(fmin(1.25 * PI / S, 1.5)); }

static void test_sphere(void **state)
{
    (void)state;
    static const uint32_t cases[][2] = {{3, 2}, {4, 3}, {16, 8}, {128, 64}, {7, 5}, {0, 0}};
    char err[256];
    for (int c = 0; cases[c][0]; c++) {
        uint32_t S = cases[c][0], T = cases[c][1];
        mesh m;
        assert_true(mesh_sphere(2.0f, S, T, &m, err, sizeof err));
        char name[64];
        snprintf(name, sizeof name, "sphere %ux%u", S, T);
        check_mesh(&m, name, (T - 1) * (S + 1) + 2 * S, 6 * S * (T - 1), slice_cos(S));
        double exact = 4.0 / 3.0 * PI * 8.0;
        /* fine tessellation: the polytope's volume is within 0.2% of the sphere's */
        check_closed(&m, name, 2, exact, S >= 128 ? 2e-3 : 0.8);
        /* every vertex on the sphere; poles exactly */
        for (uint32_t i = 0; i < m.nvertices; i++) {
            double p[3];
            to_d(m.vertices[i].position, p, 3);
            assert_true(fabs(norm3(p) - 2.0) < 1e-5);
        }
        assert_true(m.vertices[0].position[1] == -2.0f);
        mesh_free(&m);
    }
}

static void test_icosphere(void **state)
{
    (void)state;
    char err[256];
    for (uint32_t n = 0; n <= 5; n++) {
        mesh m;
        assert_true(mesh_icosphere(1.5f, n, &m, err, sizeof err));
        uint32_t f = 1u << n;
        char name[64];
        snprintf(name, sizeof name, "icosphere %u", n);
        /* the net spreads the 5 triangles about each of the 12 original vertices (300
         * degrees) over 360: the u direction there bends by up to 18 degrees */
        check_mesh(&m, name, (f + 1) * (10 * f + 1), 60 * f * f, cos(20.0 * PI / 180.0));
        double exact = 4.0 / 3.0 * PI * 1.5 * 1.5 * 1.5;
        /* subdivision 4 (5120 triangles) is within 0.5% of the sphere */
        check_closed(&m, name, 2, exact, n >= 4 ? 5e-3 : 0.7);
        /* unique positions: 10 f^2 + 2 */
        uint32_t V, E, B;
        edge_census(&m, name, &V, &E, &B);
        assert_int_equal(V, 10 * f * f + 2);
        assert_int_equal(E, 30 * f * f);
        for (uint32_t i = 0; i < m.nvertices; i++) {
            double p[3];
            to_d(m.vertices[i].position, p, 3);
            assert_true(fabs(norm3(p) - 1.5) < 1e-5);
            assert_true(m.vertices[i].tangent[3] == 1.0f);
            assert_true(m.vertices[i].uv[0] >= 0.0f && m.vertices[i].uv[0] <= 1.0f);
            assert_true(m.vertices[i].uv[1] >= 0.0f && m.vertices[i].uv[1] <= 1.0f);
        }
        mesh_free(&m);
    }
}

static void test_cone(void **state)
{
    (void)state;
    char err[256];
    static const uint32_t segs[] = {3, 5, 16, 64, 0};
    for (int c = 0; segs[c]; c++) {
        uint32_t S = segs[c];
        mesh m;
        char name[64];
        assert_true(mesh_cone(1.0f, 2.0f, S, true, &m, err, sizeof err));
        snprintf(name, sizeof name, "cone %u capped", S);
        check_mesh(&m, name, 3 * S + 2, 6 * S, slice_cos(S));
        /* a pyramid on the inscribed polygon: exactly (1/3) (S/2 r^2 sin(2 pi/S)) h */
        double exact = (1.0 / 3.0) * (0.5 * S * sin(2.0 * PI / S)) * 2.0;
        check_closed(&m, name, 2, exact, 1e-5);
        /* apex at the origin, base at z = -height */
        assert_true(m.aabb[1][2] == 0.0f && m.aabb[0][2] == -2.0f);
        mesh_free(&m);

        assert_true(mesh_cone(1.0f, 2.0f, S, false, &m, err, sizeof err));
        snprintf(name, sizeof name, "cone %u open", S);
        check_mesh(&m, name, 2 * S + 1, 3 * S, slice_cos(S));
        uint32_t V, E, B;
        edge_census(&m, name, &V, &E, &B);
        assert_int_equal(B, S);                 /* the rim */
        mesh_free(&m);
    }
}

static void test_box(void **state)
{
    (void)state;
    char err[256];
    sm_vec3 h = {1.0f, 2.0f, 0.5f};
    mesh m;
    assert_true(mesh_box(h, &m, err, sizeof err));
    check_mesh(&m, "box", 24, 36, 0.999999);
    assert_true(check_closed(&m, "box", 2, 8.0, 0.0) == 8.0);   /* exact */
    for (uint32_t i = 0; i < 24; i++) {
        /* flat faces: the normal is the face's */
        const mesh_vertex *v = &m.vertices[i];
        int axis = fabsf(v->normal[0]) == 1.0f ? 0 : fabsf(v->normal[1]) == 1.0f ? 1 : 2;
        assert_true(fabsf(v->normal[axis]) == 1.0f);
        assert_true(v->position[axis] == v->normal[axis] * h[axis]);
    }
    assert_true(m.aabb[0][1] == -2.0f && m.aabb[1][1] == 2.0f);
    mesh_free(&m);
}

static void test_lathe_cylinder_pillar(void **state)
{
    (void)state;
    char err[256];
    for (uint32_t S = 3; S <= 48; S += 15) {
        mesh m;
        char name[64];
        double k = 0.5 * S * sin(2.0 * PI / S);      /* polygon area per r^2 */
        assert_true(mesh_cylinder(0.5f, 3.0f, S, &m, err, sizeof err));
        snprintf(name, sizeof name, "cylinder %u", S);
        check_mesh(&m, name, 6 * S + 4, 12 * S, slice_cos(S));
        check_closed(&m, name, 2, k * 0.25 * 3.0, 1e-5);
        mesh_free(&m);

        assert_true(mesh_pillar(0.5f, 4.0f, S, &m, err, sizeof err));
        snprintf(name, sizeof name, "pillar %u", S);
        check_mesh(&m, name, 14 * S + 12, 36 * S, slice_cos(S));
        /* polygonal frustums: sum of k dy / 3 (r0^2 + r0 r1 + r1^2) */
        double r = 0.5, R = 0.7, H = 4.0;
        double prof[8][2] = {{0, -2}, {R, -2}, {R, -2 + 0.06 * H}, {r, -2 + 0.1 * H},
                             {r, 2 - 0.1 * H}, {R, 2 - 0.06 * H}, {R, 2}, {0, 2}};
        double vol = 0.0;
        for (int i = 0; i < 7; i++) {
            double r0 = prof[i][0], r1 = prof[i + 1][0], dy = prof[i + 1][1] - prof[i][1];
            vol += k * dy / 3.0 * (r0 * r0 + r0 * r1 + r1 * r1);
        }
        check_closed(&m, name, 2, vol, 1e-5);
        assert_true(m.aabb[0][1] == -2.0f && m.aabb[1][1] == 2.0f);
        assert_true(m.aabb[1][2] == 1.4f * 0.5f);  /* the plinth's rim at angle 0 (+Z) */
        mesh_free(&m);
    }
    /* an open lathe (a vase: starts on the axis, ends on a rim), with a profile going in
     * and down again: every vertex still valid, the rim the only boundary */
    const sm_vec2 vase[] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.5f, 1.0f}, {0.8f, 2.0f},
                            {0.8f, 1.9f}, {1.2f, 2.5f}};
    mesh m;
    assert_true(mesh_lathe(vase, 6, 12, &m, err, sizeof err));
    check_mesh(&m, "vase", (2 * 12 + 1) + 4 * 2 * 13, 3 * 12 + 4 * 6 * 12, slice_cos(12));
    uint32_t V, E, B;
    edge_census(&m, "vase", &V, &E, &B);
    assert_int_equal(B, 12);
    assert_int_equal((int)V - (int)E + (int)(m.nindices / 3), 1);   /* a disc */
    mesh_free(&m);
}

/* Length of the knot's centre line, by fine polyline (the same curve as the header). */
static double knot_length(int p, int q, double R)
{
    double k = R / 3.0, len = 0.0, prev[3] = {0, 0, 0};
    int n = 200000;
    for (int i = 0; i <= n; i++) {
        double t = 2.0 * PI * i / n, rho = 2.0 + cos(q * t);
        double c[3] = {k * rho * sin(p * t), k * sin(q * t), k * rho * cos(p * t)};
        if (i) {
            double d[3] = {c[0] - prev[0], c[1] - prev[1], c[2] - prev[2]};
            len += norm3(d);
        }
        memcpy(prev, c, sizeof c);
    }
    return len;
}

static void test_torus_knot(void **state)
{
    (void)state;
    char err[256];
    static const struct { uint32_t p, q, seg, sides; float R, r; } cases[] = {
        {2, 3, 512, 32, 1.0f, 0.08f},
        {3, 2, 600, 24, 2.0f, 0.15f},
        {1, 1, 64, 8, 1.0f, 0.2f},              /* the unknot */
        {3, 7, 1024, 16, 3.0f, 0.1f},
        {0, 0, 0, 0, 0.0f, 0.0f},
    };
    for (int c = 0; cases[c].p; c++) {
        uint32_t S = cases[c].seg, N = cases[c].sides;
        mesh m;
        char name[64];
        assert_true(mesh_torus_knot(cases[c].p, cases[c].q, cases[c].R, cases[c].r, S, N, &m,
                                    err, sizeof err));
        snprintf(name, sizeof name, "torus knot (%u,%u)", cases[c].p, cases[c].q);
        check_mesh(&m, name, (S + 1) * (N + 1), 6 * S * N, 0.99);
        /* a tube: its cross-section's area times the centre line's length (Pappus); the
         * cross-section is the N-gon inscribed in the tube's circle */
        double r = cases[c].r, area = 0.5 * N * sin(2.0 * PI / N) * r * r;
        double exact = area * knot_length((int)cases[c].p, (int)cases[c].q, cases[c].R);
        check_closed(&m, name, 0, exact, 0.01);
        for (uint32_t i = 0; i < m.nvertices; i++)
            assert_true(m.vertices[i].tangent[3] == 1.0f);
        mesh_free(&m);
    }
}

/* >>shells ----------------------------------------------------------------------------- */

static void test_room_corridor(void **state)
{
    (void)state;
    char err[256];
    sm_vec3 h = {5.0f, 1.5f, 4.0f};
    mesh m;
    assert_true(mesh_room(h, 0.5f, &m, err, sizeof err));
    check_mesh(&m, "room", 24, 36, 0.999999);
    /* inward: the signed volume is minus the box's, exactly */
    assert_true(check_closed(&m, "room", 2, -8.0 * 5.0 * 1.5 * 4.0, 0.0) < 0.0);
    for (uint32_t i = 0; i < m.nvertices; i++) {
        /* normals point at the centre; uv in world units times 0.5 */
        const mesh_vertex *v = &m.vertices[i];
        double p[3], n[3];
        to_d(v->position, p, 3);
        to_d(v->normal, n, 3);
        assert_true(dot3(p, n) < 0.0);
        assert_true(v->uv[0] >= 0.0f && v->uv[0] <= 5.0f && v->uv[1] <= 5.0f);
    }
    /* the floor (normal +Y) spans 10 x 8 world units: uv to 5 x 4 */
    float umax = 0.0f;
    for (uint32_t i = 0; i < m.nvertices; i++)
        if (m.vertices[i].normal[1] == 1.0f)
            umax = fmaxf(umax, m.vertices[i].uv[0]);
    assert_true(umax == 5.0f);
    mesh_free(&m);

    assert_true(mesh_room(h, 0.0f, &m, err, sizeof err));
    for (uint32_t i = 0; i < m.nvertices; i++)
        assert_true(m.vertices[i].uv[0] <= 1.0f && m.vertices[i].uv[1] <= 1.0f);
    mesh_free(&m);

    assert_true(mesh_corridor(3.0f, 2.5f, 20.0f, 1.0f, &m, err, sizeof err));
    check_mesh(&m, "corridor", 16, 24, 0.999999);
    uint32_t V, E, B;
    edge_census(&m, "corridor", &V, &E, &B);
    assert_int_equal(B, 8);                     /* the two open ends */
    assert_int_equal((int)V - (int)E + (int)(m.nindices / 3), 0);
    for (uint32_t t = 0; t < m.nindices; t += 3) {
        /* each face's normal points towards the corridor's axis */
        double c[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
            for (int q = 0; q < 3; q++)
                c[q] += m.vertices[m.indices[t + k]].position[q] / 3.0;
        double n[3], to_axis[3] = {-c[0], -c[1], 0.0};
        to_d(m.vertices[m.indices[t]].normal, n, 3);
        assert_true(dot3(n, to_axis) > 0.0);
    }
    assert_true(m.aabb[0][2] == -10.0f && m.aabb[1][2] == 10.0f);
    mesh_free(&m);
}

/* >>terrain ---------------------------------------------------------------------------- */

static float canyon(float x, float z, void *user)
{
    (void)z;
    float depth = *(const float *)user;
    float d = fabsf(x) - 10.0f;           /* floor 20 wide, walls rising 1:1 beyond */
    return d > 0.0f ? fminf(d, depth) : 0.0f;
}

static float bad_height(float x, float z, void *user)
{
    (void)user;
    return x > 0.5f && z > 0.0f ? NAN : 0.0f;
}

static void test_heightfield(void **state)
{
    (void)state;
    char err[256];
    mesh a, b, c;
    assert_true(mesh_heightfield(100.0f, 60.0f, 64, 40, 8.0f, 1337, &a, err, sizeof err));
    assert_true(mesh_heightfield(100.0f, 60.0f, 64, 40, 8.0f, 1337, &b, err, sizeof err));
    assert_true(mesh_heightfield(100.0f, 60.0f, 64, 40, 8.0f, 1338, &c, err, sizeof err));
    check_mesh(&a, "heightfield", 65 * 41, 6 * 64 * 40, 0.95);
    /* deterministic for a seed, different for another */
    assert_memory_equal(a.vertices, b.vertices, a.nvertices * sizeof *a.vertices);
    assert_memory_equal(a.indices, b.indices, a.nindices * sizeof *a.indices);
    assert_true(memcmp(a.vertices, c.vertices, a.nvertices * sizeof *a.vertices) != 0);
    /* not flat, within +-height_scale, normals up, triangles CCW from above */
    assert_true(a.aabb[1][1] - a.aabb[0][1] > 2.0f);
    assert_true(a.aabb[0][1] >= -8.0f && a.aabb[1][1] <= 8.0f);
    assert_true(a.aabb[0][0] == -50.0f && a.aabb[1][0] == 50.0f);
    assert_true(a.aabb[0][2] == -30.0f && a.aabb[1][2] == 30.0f);
    for (uint32_t i = 0; i < a.nvertices; i++)
        assert_true(a.vertices[i].normal[1] > 0.0f);
    for (uint32_t t = 0; t < a.nindices; t += 3) {
        double p[3][3], e1[3], e2[3], n[3];
        for (int k = 0; k < 3; k++)
            to_d(a.vertices[a.indices[t + k]].position, p[k], 3);
        for (int k = 0; k < 3; k++) {
            e1[k] = p[1][k] - p[0][k];
            e2[k] = p[2][k] - p[0][k];
        }
        cross3(e1, e2, n);
        assert_true(n[1] > 0.0);
    }
    uint32_t V, E, B;
    edge_census(&a, "heightfield", &V, &E, &B);
    assert_int_equal(B, 2 * (64 + 40));
    assert_int_equal((int)V - (int)E + (int)(a.nindices / 3), 1);
    /* the height function does not depend on the tessellation: a vertex of a grid twice
     * as fine at the same place has the same height */
    mesh fine;
    assert_true(mesh_heightfield(100.0f, 60.0f, 128, 80, 8.0f, 1337, &fine, err, sizeof err));
    for (uint32_t k = 0; k <= 40; k += 8)
        for (uint32_t i = 0; i <= 64; i += 8)
            assert_true(a.vertices[k * 65 + i].position[1] ==
                        fine.vertices[2 * k * 129 + 2 * i].position[1]);
    mesh_terrain t;
    mesh_terrain_init(&t, 100.0f, 60.0f, 8.0f, 1337);
    assert_true(mesh_terrain_height(a.vertices[77].position[0], a.vertices[77].position[2], &t)
                == a.vertices[77].position[1]);
    assert_true(isfinite(mesh_terrain_height(NAN, INFINITY, &t)));
    mesh_free(&fine);
    mesh_free(&a);
    mesh_free(&b);
    mesh_free(&c);

    /* flat: normals exactly up, tangents along +x */
    assert_true(mesh_heightfield(10.0f, 10.0f, 4, 4, 0.0f, 7, &a, err, sizeof err));
    check_mesh(&a, "flat heightfield", 25, 96, 0.999999);
    for (uint32_t i = 0; i < a.nvertices; i++) {
        const mesh_vertex *v = &a.vertices[i];
        assert_true(v->normal[0] == 0.0f && v->normal[1] == 1.0f && v->normal[2] == 0.0f);
        assert_true(v->tangent[0] == 1.0f && v->tangent[3] == 1.0f);
        assert_true(v->position[1] == 0.0f);
    }
    mesh_free(&a);

    /* very steep (heights to 1e30 over 1 unit): still finite, still up */
    assert_true(mesh_heightfield(1.0f, 1.0f, 32, 32, 1e30f, 3, &a, err, sizeof err));
    check_mesh(&a, "steep heightfield", 33 * 33, 6 * 32 * 32, EXTREME);
    for (uint32_t i = 0; i < a.nvertices; i++)
        assert_true(a.vertices[i].normal[1] > 0.0f);
    mesh_free(&a);
    /* steep but sane (heights +-2.5 over 10 x 10, slopes to ~8), finely sampled: every
     * check */
    assert_true(mesh_heightfield(10.0f, 10.0f, 256, 256, 2.5f, 3, &a, err, sizeof err));
    check_mesh(&a, "steep heightfield", 257 * 257, 6 * 256 * 256, -1.0);
    mesh_free(&a);

    /* a canyon from a custom height function, high-poly */
    float depth = 30.0f;
    assert_true(mesh_heightfield_fn(100.0f, 400.0f, 256, 512, canyon, &depth, &a, err,
                                    sizeof err));
    check_mesh(&a, "canyon", 257 * 513, 6 * 256 * 512, 0.99);
    assert_true(a.aabb[0][1] == 0.0f && a.aabb[1][1] == 30.0f);
    mesh_free(&a);

    assert_false(mesh_heightfield_fn(2.0f, 2.0f, 4, 4, bad_height, NULL, &a, err, sizeof err));
    assert_non_null(strstr(err, "non-finite") ? err : strstr(err, "nan"));
    assert_null(a.vertices);
}

/* >>light-volumes ---------------------------------------------------------------------- */

typedef struct plane {
    double n[3], d;   /* unit normal, dot(n, p) <= d inside */
} plane;

static plane *face_planes(const mesh *m)
{
    plane *pl = malloc((m->nindices / 3) * sizeof *pl);
    assert_non_null(pl);
    for (uint32_t t = 0; t < m->nindices; t += 3) {
        double a[3], b[3], c[3], e1[3], e2[3], n[3];
        to_d(m->vertices[m->indices[t]].position, a, 3);
        to_d(m->vertices[m->indices[t + 1]].position, b, 3);
        to_d(m->vertices[m->indices[t + 2]].position, c, 3);
        for (int k = 0; k < 3; k++) {
            e1[k] = b[k] - a[k];
            e2[k] = c[k] - a[k];
        }
        cross3(e1, e2, n);
        double l = norm3(n);
        plane *p = &pl[t / 3];
        for (int k = 0; k < 3; k++)
            p->n[k] = n[k] / l;
        p->d = dot3(p->n, a);
    }
    return pl;
}

/* Convex: every vertex on the inner side of every face plane (within rounding). */
static void check_convex(const mesh *m, const plane *pl, const char *name)
{
    for (uint32_t f = 0; f < m->nindices / 3; f++)
        for (uint32_t i = 0; i < m->nvertices; i++) {
            double p[3];
            to_d(m->vertices[i].position, p, 3);
            if (dot3(pl[f].n, p) - pl[f].d > 1e-6)
                fail_msg("%s: vertex %u outside face %u's plane: not convex", name, i, f);
        }
}

/* How far inside every plane p is (negative: outside one). */
static double inside_by(const plane *pl, uint32_t nf, const double p[3])
{
    double worst = INFINITY;
    for (uint32_t f = 0; f < nf; f++) {
        double s = pl[f].d - dot3(pl[f].n, p);
        if (s < worst)
            worst = s;
    }
    return worst;
}

static void test_light_sphere(void **state)
{
    (void)state;
    char err[256];
    static const uint32_t cases[][2] = {{16, 8}, {3, 2}, {8, 4}, {12, 6}, {32, 16}, {0, 0}};
    for (int c = 0; cases[c][0]; c++) {
        uint32_t S = cases[c][0], T = cases[c][1];
        mesh m;
        char name[64];
        snprintf(name, sizeof name, "light sphere %ux%u", S, T);
        assert_true(mesh_light_sphere(S, T, &m, err, sizeof err));
        check_mesh(&m, name, (T - 1) * (S + 1) + 2 * S, 6 * S * (T - 1), slice_cos(S));
        double R = m.sphere[3];
        /* closed, convex, more than the unit ball, less than the ball through its vertices */
        double vol = check_closed(&m, name, 2, 0.5 * (4.0 / 3.0 * PI) * (1.0 + R * R * R),
                                  0.5 * (R * R * R - 1.0) / (0.5 * (1.0 + R * R * R)) + 1e-9);
        assert_true(vol > 4.0 / 3.0 * PI);
        uint32_t nf = m.nindices / 3;
        plane *pl = face_planes(&m);
        check_convex(&m, pl, name);
        /* each face's worst point of the unit sphere (along its normal) is inside */
        double worst = INFINITY;
        for (uint32_t f = 0; f < nf; f++)
            worst = fmin(worst, inside_by(pl, nf, pl[f].n));
        /* and a dense Fibonacci lattice of 20000 points, plus the poles */
        for (int i = 0; i < 20000; i++) {
            double y = 1.0 - 2.0 * (i + 0.5) / 20000.0, r = sqrt(1.0 - y * y);
            double a = i * PI * (3.0 - sqrt(5.0));
            double p[3] = {r * cos(a), y, r * sin(a)};
            worst = fmin(worst, inside_by(pl, nf, p));
        }
        double poles[2][3] = {{0, 1, 0}, {0, -1, 0}};
        worst = fmin(worst, fmin(inside_by(pl, nf, poles[0]), inside_by(pl, nf, poles[1])));
        if (!(worst > 0.0))
            fail_msg("%s: a point of the unit sphere is %g outside", name, -worst);
        /* the margin is small: the inscribed sphere is within 1e-3 of the unit one */
        assert_true(worst < 1e-3);
        if (S == 16 && T == 8) {
            print_message("light sphere 16x8 (seed 000's): circumradius %.5f, so the "
                          "plain D3DX sphere needed a scale of %.4f; seed 000 used 1.1\n", R, R);
            assert_true(fabs(R - 1.0389) < 1e-4);     /* the value scenes/mesh.h states */
        }
        free(pl);
        mesh_free(&m);
    }
}

static void test_light_cone(void **state)
{
    (void)state;
    char err[256];
    static const double angles[] = {5.0, 22.5, 30.0, 45.0, 60.0, 80.0, 0.0};
    static const uint32_t segs[] = {3, 8, 16, 32, 0};
    for (int ai = 0; angles[ai] > 0.0; ai++) {
        for (int si = 0; segs[si]; si++) {
            double ang = angles[ai] * PI / 180.0, tn = tan(ang);
            uint32_t S = segs[si];
            mesh m;
            char name[64];
            snprintf(name, sizeof name, "light cone %.1f deg, %u", angles[ai], S);
            assert_true(mesh_light_cone((float)ang, S, &m, err, sizeof err));
            check_mesh(&m, name, 3 * S + 2, 6 * S, slice_cos(S));
            double true_vol = PI * tn * tn / 3.0;
            double vol = check_closed(&m, name, 2, true_vol, 1.0);
            assert_true(vol > true_vol);
            uint32_t nf = m.nindices / 3;
            plane *pl = face_planes(&m);
            check_convex(&m, pl, name);
            /* the true cone is the hull of its apex and base circle: sample the apex, the
             * base circle densely (including each side face's point of tangency), the
             * lateral surface and the base disc */
            double worst_apex = inside_by(pl, nf, (double[3]){0, 0, 0});
            double worst = INFINITY;
            for (int i = 0; i < 4096 + (int)S; i++) {
                double phi = i < 4096 ? 2.0 * PI * i / 4096.0
                                      : 2.0 * PI * ((i - 4096) + 0.5) / S;
                for (int k = 1; k <= 16; k++) {
                    double t = k / 16.0;
                    double side[3] = {t * tn * cos(phi), t * tn * sin(phi), -t};
                    double disc[3] = {t * tn * cos(phi), t * tn * sin(phi), -1.0};
                    worst = fmin(worst, fmin(inside_by(pl, nf, side), inside_by(pl, nf, disc)));
                }
            }
            if (!(worst > 0.0))
                fail_msg("%s: a point of the true cone is %g outside", name, -worst);
            /* the apex strictly inside, 1e-4 from the mesh's apex */
            assert_true(worst_apex > 0.0);
            /* no bigger than needed: the cap plane at 1 + 1e-4, the apex at 1e-4 */
            assert_true(fabs(m.aabb[0][2] + 1.0001) < 1e-6);
            assert_true(fabs(m.aabb[1][2] - 0.0001) < 1e-9);
            /* the true cone's base circle within 1e-3 of the polygon's inradius */
            assert_true(worst < 1e-3 * tn + 1e-6);
            free(pl);
            mesh_free(&m);
        }
    }
}

/* >>editing ---------------------------------------------------------------------------- */

static void test_transform_append(void **state)
{
    (void)state;
    char err[256];
    mesh m;
    assert_true(mesh_sphere(1.0f, 32, 16, &m, err, sizeof err));
    double v0 = signed_volume(&m);
    /* a mirror with non-uniform scale: still CCW outward, w flipped, frames valid */
    sm_mat4 s, r, mat;
    sm_vec3 sc = {-2.0f, 1.0f, 0.5f}, axis = {0.3f, 1.0f, -0.2f};
    sm_mat4_scale_make(sc, s);
    sm_mat4_rotate_make(0.7f, axis, r);
    sm_mat4_mul(r, s, mat);
    assert_true(mesh_transform(&m, mat, err, sizeof err));
    check_mesh(&m, "mirrored sphere", 15 * 33 + 64, 6 * 32 * 15, 0.9);
    check_closed(&m, "mirrored sphere", 2, v0 * 1.0, 1e-4);
    for (uint32_t i = 0; i < m.nvertices; i++)
        assert_true(m.vertices[i].tangent[3] == -1.0f);
    /* mirrored twice: back to w = +1 */
    assert_true(mesh_transform(&m, mat, err, sizeof err));
    /* stretched 16:1 twice over, a coarse sphere's face and vertex tangents part more
     * than a slice: only the handedness is checked */
    check_mesh(&m, "twice mirrored sphere", 15 * 33 + 64, 6 * 32 * 15, -1.0);
    for (uint32_t i = 0; i < m.nvertices; i++)
        assert_true(m.vertices[i].tangent[3] == 1.0f);
    /* singular: refused, mesh unchanged */
    sm_mat4 z;
    sm_vec3 flat = {1.0f, 0.0f, 1.0f};
    sm_mat4_scale_make(flat, z);
    mesh_vertex before = m.vertices[5];
    assert_false(mesh_transform(&m, z, err, sizeof err));
    assert_non_null(strstr(err, "singular"));
    assert_memory_equal(&before, &m.vertices[5], sizeof before);
    mesh_free(&m);

    /* append: a box and a translated torus knot into one mesh (a static batch) */
    mesh all = {0}, box, knot;
    sm_vec3 h = {1.0f, 1.0f, 1.0f}, off = {5.0f, 0.0f, 0.0f};
    assert_true(mesh_box(h, &box, err, sizeof err));
    assert_true(mesh_torus_knot(2, 3, 1.0f, 0.1f, 128, 12, &knot, err, sizeof err));
    sm_mat4 tr;
    sm_mat4_translate_make(off, tr);
    assert_true(mesh_append(&all, &box, NULL, err, sizeof err));
    assert_true(mesh_append(&all, &knot, tr, err, sizeof err));
    check_mesh(&all, "batch", 24 + 129 * 13, 36 + 6 * 128 * 12, 0.9);
    /* two components: a sphere-like box (2) and a torus (0) */
    check_closed(&all, "batch", 2, 8.0 + signed_volume(&knot), 1e-6);
    assert_true(all.aabb[0][0] == -1.0f && all.aabb[1][0] > 5.9f);
    mesh_free(&all);
    mesh_free(&box);
    mesh_free(&knot);
    mesh_free(&all);                            /* twice: harmless */
    mesh_free(NULL);

    /* recomputing tangents from uv reproduces the analytic frames of a torus knot */
    assert_true(mesh_torus_knot(2, 3, 1.0f, 0.1f, 256, 16, &knot, err, sizeof err));
    mesh copy = knot;
    copy.vertices = malloc(knot.nvertices * sizeof *knot.vertices);
    assert_non_null(copy.vertices);
    memcpy(copy.vertices, knot.vertices, knot.nvertices * sizeof *knot.vertices);
    assert_true(mesh_compute_tangents(&copy));
    for (uint32_t i = 0; i < knot.nvertices; i++) {
        double a[3], b[3];
        to_d(knot.vertices[i].tangent, a, 3);
        to_d(copy.vertices[i].tangent, b, 3);
        if (!(dot3(a, b) > 0.995))
            fail_msg("knot vertex %u: recomputed tangent %g degrees off", i,
                     acos(fmin(1.0, dot3(a, b))) * 180.0 / PI);
        assert_true(knot.vertices[i].tangent[3] == copy.vertices[i].tangent[3]);
    }
    free(copy.vertices);
    mesh_free(&knot);
}

/* >>bad-parameters --------------------------------------------------------------------- */

static void expect_fail(bool ok, const mesh *m, const char *err, const char *who)
{
    if (ok)
        fail_msg("%s accepted bad parameters", who);
    assert_null(m->vertices);
    assert_int_equal(m->nvertices, 0);
    if (!strstr(err, who))
        fail_msg("message '%s' does not name %s", err, who);
}

static void test_bad_parameters(void **state)
{
    (void)state;
    char err[256];
    mesh m;
    sm_vec3 zero_y = {1.0f, 0.0f, 1.0f}, neg = {1.0f, -1.0f, 1.0f}, ok = {1.0f, 1.0f, 1.0f};
    sm_vec2 one[1] = {{1.0f, 0.0f}};
    sm_vec2 on_axis[3] = {{0.0f, 0.0f}, {0.0f, 1.0f}, {1.0f, 1.0f}};
    sm_vec2 repeated[3] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 0.0f}};
    sm_vec2 negative_r[2] = {{-1.0f, 0.0f}, {1.0f, 1.0f}};
#define BAD(call, who)                                      \
    do {                                                    \
        err[0] = 0;                                         \
        memset(&m, 0x5a, sizeof m);                         \
        expect_fail(call, &m, err, who);                    \
    } while (0)
    BAD(mesh_sphere(1.0f, 0, 8, &m, err, sizeof err), "mesh_sphere");
    BAD(mesh_sphere(1.0f, 8, 1, &m, err, sizeof err), "mesh_sphere");
    BAD(mesh_sphere(-1.0f, 8, 8, &m, err, sizeof err), "mesh_sphere");
    BAD(mesh_sphere(0.0f, 8, 8, &m, err, sizeof err), "mesh_sphere");
    BAD(mesh_sphere(NAN, 8, 8, &m, err, sizeof err), "mesh_sphere");
    BAD(mesh_sphere(INFINITY, 8, 8, &m, err, sizeof err), "mesh_sphere");
    BAD(mesh_sphere(1.0f, 100000, 100000, &m, err, sizeof err), "mesh_sphere");
    assert_non_null(strstr(err, "limit"));
    BAD(mesh_icosphere(1.0f, 9, &m, err, sizeof err), "mesh_icosphere");
    BAD(mesh_icosphere(-2.0f, 1, &m, err, sizeof err), "mesh_icosphere");
    BAD(mesh_cone(1.0f, 1.0f, 2, true, &m, err, sizeof err), "mesh_cone");
    BAD(mesh_cone(-1.0f, 1.0f, 8, true, &m, err, sizeof err), "mesh_cone");
    BAD(mesh_cone(1.0f, 0.0f, 8, false, &m, err, sizeof err), "mesh_cone");
    BAD(mesh_box(zero_y, &m, err, sizeof err), "mesh_box");
    BAD(mesh_box(neg, &m, err, sizeof err), "mesh_box");
    BAD(mesh_room(ok, -1.0f, &m, err, sizeof err), "mesh_room");
    BAD(mesh_room(neg, 1.0f, &m, err, sizeof err), "mesh_room");
    BAD(mesh_corridor(0.0f, 1.0f, 1.0f, 0.0f, &m, err, sizeof err), "mesh_corridor");
    BAD(mesh_corridor(1.0f, 1.0f, 1.0f, NAN, &m, err, sizeof err), "mesh_corridor");
    BAD(mesh_lathe(one, 1, 8, &m, err, sizeof err), "mesh_lathe");
    BAD(mesh_lathe(on_axis, 3, 8, &m, err, sizeof err), "mesh_lathe");
    BAD(mesh_lathe(repeated, 3, 8, &m, err, sizeof err), "mesh_lathe");
    BAD(mesh_lathe(negative_r, 2, 8, &m, err, sizeof err), "mesh_lathe");
    BAD(mesh_lathe(NULL, 2, 8, &m, err, sizeof err), "mesh_lathe");
    BAD(mesh_lathe(repeated, 2, 2, &m, err, sizeof err), "mesh_lathe");
    BAD(mesh_cylinder(1.0f, -1.0f, 8, &m, err, sizeof err), "mesh_cylinder");
    BAD(mesh_pillar(0.0f, 1.0f, 8, &m, err, sizeof err), "mesh_pillar");
    BAD(mesh_pillar(1.0f, 1.0f, 0, &m, err, sizeof err), "mesh_lathe");
    BAD(mesh_torus_knot(2, 4, 1.0f, 0.1f, 64, 8, &m, err, sizeof err), "mesh_torus_knot");
    BAD(mesh_torus_knot(0, 3, 1.0f, 0.1f, 64, 8, &m, err, sizeof err), "mesh_torus_knot");
    BAD(mesh_torus_knot(2, 3, 1.0f, 0.5f, 64, 8, &m, err, sizeof err), "mesh_torus_knot");
    BAD(mesh_torus_knot(2, 3, 1.0f, -0.1f, 64, 8, &m, err, sizeof err), "mesh_torus_knot");
    BAD(mesh_torus_knot(2, 3, 1.0f, 0.1f, 2, 8, &m, err, sizeof err), "mesh_torus_knot");
    BAD(mesh_heightfield(10.0f, 10.0f, 0, 4, 1.0f, 1, &m, err, sizeof err), "mesh_heightfield");
    BAD(mesh_heightfield(10.0f, -10.0f, 4, 4, 1.0f, 1, &m, err, sizeof err), "mesh_heightfield");
    BAD(mesh_heightfield(10.0f, 10.0f, 4, 4, -1.0f, 1, &m, err, sizeof err), "mesh_heightfield");
    BAD(mesh_heightfield(10.0f, 10.0f, 4, 4, NAN, 1, &m, err, sizeof err), "mesh_heightfield");
    BAD(mesh_heightfield_fn(10.0f, 10.0f, 4, 4, NULL, NULL, &m, err, sizeof err),
        "mesh_heightfield");
    BAD(mesh_light_sphere(2, 8, &m, err, sizeof err), "mesh_light_sphere");
    BAD(mesh_light_cone(0.0f, 8, &m, err, sizeof err), "mesh_light_cone");
    BAD(mesh_light_cone((float)(PI / 2), 8, &m, err, sizeof err), "mesh_light_cone");
    BAD(mesh_light_cone(-0.5f, 8, &m, err, sizeof err), "mesh_light_cone");
    BAD(mesh_light_cone(NAN, 8, &m, err, sizeof err), "mesh_light_cone");
    BAD(mesh_light_cone(0.5f, 2, &m, err, sizeof err), "mesh_light_cone");
#undef BAD
    /* no message buffer is fine */
    assert_false(mesh_sphere(1.0f, 1, 1, &m, NULL, 0));
    assert_false(mesh_sphere(1.0f, 1, 1, &m, err, 0));
    /* the smallest accepted cases */
    assert_true(mesh_heightfield(1.0f, 1.0f, 1, 1, 1.0f, 0, &m, NULL, 0));
    check_mesh(&m, "1-cell heightfield", 4, 6, -1.0);
    mesh_free(&m);
}

/* >>textures --------------------------------------------------------------------------- */

static void test_textures_deterministic(void **state)
{
    (void)state;
    char err[256];
    for (int p = 0; p < TEXTURE_PATTERN_COUNT; p++) {
        texture_desc d = {.width = 128, .height = 64, .pattern = (texture_pattern)p,
                          .cells = 4, .seed = 99, .noise = 0.5f};
        bool (*const fns[4])(const texture_desc *, texture_image *, char *, size_t) = {
            texture_diffuse, texture_gloss, texture_normal_map, texture_emissive};
        const uint32_t channels[4] = {4, 1, 4, 4};
        for (int f = 0; f < 4; f++) {
            texture_image a, b, c;
            assert_true(fns[f](&d, &a, err, sizeof err));
            assert_true(fns[f](&d, &b, err, sizeof err));
            assert_int_equal(a.width, 128);
            assert_int_equal(a.height, 64);
            assert_int_equal(a.channels, channels[f]);
            assert_memory_equal(a.data, b.data, (size_t)128 * 64 * a.channels);
            texture_desc d2 = d;
            d2.seed = 100;
            assert_true(fns[f](&d2, &c, err, sizeof err));
            /* the seed matters wherever noise is involved */
            if (p == TEXTURE_NOISE || f != 3)
                assert_true(memcmp(a.data, c.data, (size_t)128 * 64 * a.channels) != 0);
            texture_free(&a);
            texture_free(&b);
            texture_free(&c);
            texture_free(&c);
        }
    }
    /* a zero desc is a 256x256 checker */
    texture_desc zero = {0};
    texture_image img;
    assert_true(texture_diffuse(&zero, &img, err, sizeof err));
    assert_int_equal(img.width, 256);
    assert_int_equal(img.height, 256);
    /* square (0,0) is colour a, square (1,0) colour b (0.75, 0.35 grey), at their centres */
    assert_int_equal(img.data[(16 * 256 + 16) * 4], 191);
    assert_int_equal(img.data[(16 * 256 + 48) * 4], 89);
    assert_int_equal(img.data[(16 * 256 + 16) * 4 + 3], 255);
    texture_free(&img);
    /* 1x1 works */
    texture_desc tiny = {.width = 1, .height = 1, .cells = 1, .pattern = TEXTURE_NOISE};
    assert_true(texture_normal_map(&tiny, &img, err, sizeof err));
    assert_int_equal(img.data[2] >= 128, 1);
    texture_free(&img);
}

static void test_normal_maps(void **state)
{
    (void)state;
    char err[256];
    for (int p = 0; p < TEXTURE_PATTERN_COUNT; p++) {
        for (float bump = 0.5f; bump < 100.0f; bump *= 8.0f) {
            texture_desc d = {.width = 64, .height = 128, .pattern = (texture_pattern)p,
                              .cells = 4, .seed = 5, .noise = 1.0f, .bump = bump};
            texture_desc r;
            assert_true(texture_desc_resolve(&d, &r, err, sizeof err));
            texture_image img;
            assert_true(texture_normal_map(&d, &img, err, sizeof err));
            int checked = 0;
            for (uint32_t y = 0; y < 128; y++) {
                for (uint32_t x = 0; x < 64; x++) {
                    const uint8_t *t = &img.data[(y * 64 + x) * 4];
                    double n[3];
                    for (int k = 0; k < 3; k++)
                        n[k] = t[k] / 255.0 * 2.0 - 1.0;
                    /* unit within 8-bit precision, pointing out of the surface */
                    if (fabs(norm3(n) - 1.0) > 0.012)
                        fail_msg("normal map %d: texel (%u, %u) decodes to length %g", p, x, y,
                                 norm3(n));
                    assert_true(n[2] > 0.0);
                    /* x follows -dh/du, y follows -dh/dv (v grows with the row) */
                    float u = (x + 0.5f) / 64.0f, v = (y + 0.5f) / 128.0f;
                    double hx = 0.5 * ((double)texture_height(&r, u + 1.0f / 64.0f, v) -
                                       texture_height(&r, u - 1.0f / 64.0f, v));
                    double hy = 0.5 * ((double)texture_height(&r, u, v + 1.0f / 128.0f) -
                                       texture_height(&r, u, v - 1.0f / 128.0f));
                    double want[3] = {-bump * hx, -bump * hy, 1.0};
                    double l = norm3(want);
                    for (int k = 0; k < 3; k++)
                        if (fabs(want[k] / l - n[k]) > 0.01)
                            fail_msg("normal map %d: texel (%u, %u) component %d is %g, the "
                                     "height says %g", p, x, y, k, n[k], want[k] / l);
                    if (fabs(n[0]) > 0.02)
                        checked++;
                    /* alpha is the height */
                    assert_true(abs((int)t[3] - (int)lrint(texture_height(&r, u, v) * 255.0)) <= 1);
                }
            }
            if (!checked)                       /* there was relief to check */
                fail_msg("normal map %d, bump %g: flat", p, (double)bump);
            texture_free(&img);
        }
    }
    /* periodic: the height repeats with period 1 in u and v */
    for (int p = 0; p < TEXTURE_PATTERN_COUNT; p++) {
        texture_desc d = {.pattern = (texture_pattern)p, .cells = 8, .seed = 3}, r;
        assert_true(texture_desc_resolve(&d, &r, err, sizeof err));
        for (float u = 0.01f; u < 1.0f; u += 0.0917f)
            assert_true(fabsf(texture_height(&r, u, 0.3f) - texture_height(&r, u + 1.0f, 1.3f))
                        < 2e-3f);
    }
}

static void test_gloss_emissive(void **state)
{
    (void)state;
    char err[256];
    /* bricks: mortar (colour b, gloss b) is darker and duller than the bricks */
    texture_desc d = {.width = 256, .height = 256, .pattern = TEXTURE_BRICKS, .cells = 8,
                      .seed = 11, .gloss_a = 0.6f, .gloss_b = 0.1f,
                      .emissive_fraction = 0.3f, .emissive_color = {1.0f, 0.5f, 0.0f}};
    texture_image g, e;
    assert_true(texture_gloss(&d, &g, err, sizeof err));
    assert_int_equal(g.channels, 1);
    /* a brick's centre and a mortar line (row 0's top edge, v = 0) */
    assert_int_equal(g.data[16 * 256 + 40], 153);
    assert_int_equal(g.data[0 * 256 + 40], 26);
    assert_true(texture_emissive(&d, &e, err, sizeof err));
    size_t lit = 0, n = 256 * 256;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *t = &e.data[i * 4];
        /* rgb = colour * mask, alpha = mask */
        assert_true(abs((int)t[0] - (int)t[3]) <= 1);
        assert_true(abs((int)t[1] - (int)lrint(t[3] * 0.5)) <= 1);
        assert_int_equal(t[2], 0);
        lit += t[3] > 127;
    }
    /* some bricks lit, not all; never on mortar */
    assert_true(lit > n / 20 && lit < n / 2);
    assert_int_equal(e.data[(0 * 256 + 40) * 4 + 3], 0);
    texture_free(&g);
    texture_free(&e);

    /* noise: the brightest emissive_fraction of the area is lit */
    texture_desc dn = {.width = 128, .height = 128, .pattern = TEXTURE_NOISE, .cells = 4,
                       .seed = 2, .emissive_fraction = 0.2f};
    assert_true(texture_emissive(&dn, &e, err, sizeof err));
    lit = 0;
    for (size_t i = 0; i < 128 * 128; i++)
        lit += e.data[i * 4 + 3] > 127;
    assert_true(fabs((double)lit / (128 * 128) - 0.2) < 0.02);
    texture_free(&e);
}

static void test_texture_bad(void **state)
{
    (void)state;
    char err[256];
    texture_image img;
    static const texture_desc bad[] = {
        {.width = 100},
        {.height = 16384},
        {.pattern = TEXTURE_PATTERN_COUNT},
        {.pattern = TEXTURE_BRICKS, .cells = 3},
        {.width = 16, .cells = 32},
        {.bump = -1.0f},
        {.noise = 2.0f},
        {.color_a = {NAN, 0.0f, 0.0f}},
        {.gloss_a = 1.5f},
        {.emissive_fraction = -0.1f},
        {.emissive_color = {0.0f, 0.0f, INFINITY}},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        err[0] = 0;
        memset(&img, 0x5a, sizeof img);
        if (texture_diffuse(&bad[i], &img, err, sizeof err))
            fail_msg("bad texture desc %zu accepted", i);
        assert_null(img.data);
        assert_non_null(strstr(err, "texture"));
    }
    assert_false(texture_gloss(NULL, &img, err, sizeof err));
    assert_string_equal(texture_pattern_name(TEXTURE_BRICKS), "bricks");
    assert_null(texture_pattern_name(TEXTURE_PATTERN_COUNT));
    texture_free(NULL);

    /* noise: in range, periodic, finite for any input */
    uint32_t keys[4];
    texture_noise_keys(1, keys, 4);
    for (float x = -50.0f; x < 50.0f; x += 0.37f) {
        float n = texture_fbm2(x, 0.5f * x, keys, 4, 0, 0);
        assert_true(n >= -1.0f && n <= 1.0f);
        assert_true(fabsf(texture_noise2(x, 1.7f, keys[0], 8, 8) -
                          texture_noise2(x + 8.0f, 1.7f, keys[0], 8, 8)) < 1e-4f);
    }
    assert_true(texture_noise2(3.0f, 4.0f, keys[0], 0, 0) == 0.0f);
    assert_true(isfinite(texture_noise2(NAN, 1e30f, keys[0], 0, 0)));
    assert_true(isfinite(texture_fbm2(-INFINITY, 1e38f, keys, 4, 3, 0)));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere),
        cmocka_unit_test(test_icosphere),
        cmocka_unit_test(test_cone),
        cmocka_unit_test(test_box),
        cmocka_unit_test(test_lathe_cylinder_pillar),
        cmocka_unit_test(test_torus_knot),
        cmocka_unit_test(test_room_corridor),
        cmocka_unit_test(test_heightfield),
        cmocka_unit_test(test_light_sphere),
        cmocka_unit_test(test_light_cone),
        cmocka_unit_test(test_transform_append),
        cmocka_unit_test(test_bad_parameters),
        cmocka_unit_test(test_textures_deterministic),
        cmocka_unit_test(test_normal_maps),
        cmocka_unit_test(test_gloss_emissive),
        cmocka_unit_test(test_texture_bad),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
