/* Procedural meshes: see scenes/mesh.h for the conventions and the counts.
 *
 * Sections: >>helpers >>bounds >>editing here; >>sphere >>icosphere >>cone >>quads (box,
 * room, corridor) >>lathe (cylinder, pillar) in mesh_shapes.c; >>torus-knot mesh_knot.c;
 * >>terrain mesh_terrain.c; >>light-volumes mesh_volumes.c. What they share:
 * scenes/builtin/mesh_internal.h. */
#include "scenes/builtin/mesh_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/scene_fail.h"

/* >>helpers ---------------------------------------------------------------------------- */

/* Allocates nv vertices and ni indices into a zeroed *m. */
bool mg_alloc(mesh *m, uint64_t nv, uint64_t ni, const char *who, char *err, size_t errlen)
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
void mg_set_normal(mesh_vertex *v, const sm_vec3 n, const sm_vec3 fallback)
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
void mg_set_frame(mesh_vertex *v, const sm_vec3 dpdu, const sm_vec3 dpdv)
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

void mg_tri(uint32_t **ip, uint32_t a, uint32_t b, uint32_t c)
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
void mg_angle_of(uint32_t j, uint32_t n, double offset, float *s, float *c)
{
    double a = TWO_PI * (((double)(j % n) + offset) / (double)n);
    *s = (float)sin(a);
    *c = (float)cos(a);
}

/* r = a x b, in double. */
void mg_cross_d(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
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
        mg_set_frame(&m->vertices[i], s, t);
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
        mg_set_normal(w, nn, w->normal);
        mg_set_frame(w, t, b);
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
    if (dst->joints || src->joints)   /* joints name a palette of one scene: not merged */
        return scene_fail(err, errlen, "mesh_append: a skinned mesh is not appended");
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
    /* colours when either has them, white for the other's vertices */
    uint32_t *c = NULL;
    if (dst->colors || src->colors) {
        c = malloc((size_t)(nv ? nv : 1) * sizeof *c);
        if (!c) {
            free(v);
            free(ix);
            return scene_fail(err, errlen, "mesh_append: out of memory for %llu colours",
                              (unsigned long long)nv);
        }
        for (uint32_t i = 0; i < dst->nvertices; i++)
            c[i] = dst->colors ? dst->colors[i] : 0xffffffffu;
        for (uint32_t i = 0; i < src->nvertices; i++)
            c[dst->nvertices + i] = src->colors ? src->colors[i] : 0xffffffffu;
    }
    /* the second uv set when either has one, (0, 0) for the other's vertices */
    float (*u2)[2] = NULL;
    if (dst->uv2 || src->uv2) {
        u2 = calloc((size_t)(nv ? nv : 1), sizeof *u2);
        if (!u2) {
            free(v);
            free(ix);
            free(c);
            return scene_fail(err, errlen, "mesh_append: out of memory for %llu uvs",
                              (unsigned long long)nv);
        }
        if (dst->uv2)
            memcpy(u2, dst->uv2, (size_t)dst->nvertices * sizeof *u2);
        if (src->uv2)
            memcpy(u2 + dst->nvertices, src->uv2, (size_t)src->nvertices * sizeof *u2);
    }
    free(dst->uv2);
    dst->uv2 = u2;
    free(dst->colors);
    dst->colors = c;
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
    free(m->colors);
    free(m->uv2);
    free(m->joints);
    free(m->weights);
    memset(m, 0, sizeof *m);
}
