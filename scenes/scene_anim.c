/* A file's node animation (scene_anim.h). */
#include "scenes/scene_anim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The key interval of time t in k (k->n >= 1): i and the fraction f towards key i + 1
 * (f 0 before the first key and at or after the last). */
static uint32_t key_at(const anim_keys *k, float t, float *f)
{
    *f = 0.0f;
    if (k->n == 1 || t <= k->t[0])
        return 0;
    if (t >= k->t[k->n - 1])
        return k->n - 1;
    uint32_t lo = 0, hi = k->n - 1;   /* k->t[lo] <= t < k->t[hi] */
    while (hi - lo > 1) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (k->t[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    float span = k->t[hi] - k->t[lo];
    *f = span > 0.0f ? (t - k->t[lo]) / span : 0.0f;
    return lo;
}

static void lerpn(const anim_keys *k, float t, uint32_t width, float *out)
{
    float f;
    uint32_t i = key_at(k, t, &f);
    const float *a = k->v + width * (size_t)i, *b = f > 0.0f ? a + width : a;
    for (uint32_t c = 0; c < width; c++)
        out[c] = a[c] + (b[c] - a[c]) * f;
}

static void lerp3(const anim_keys *k, float t, float out[3])
{
    lerpn(k, t, 3, out);
}

/* Spherical interpolation of unit quaternions, the shorter way round. */
static void slerp(const anim_keys *k, float t, float out[4])
{
    float f;
    uint32_t i = key_at(k, t, &f);
    const float *a = k->v + 4 * (size_t)i, *b = f > 0.0f ? a + 4 : a;
    float d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    float sb = 1.0f;
    if (d < 0.0f) {
        d = -d;
        sb = -1.0f;
    }
    float wa = 1.0f - f, wb = f;
    if (d < 0.9995f) {   /* else nearly parallel: linear, normalised below */
        float th = acosf(d), s = sinf(th);
        wa = sinf((1.0f - f) * th) / s;
        wb = sinf(f * th) / s;
    }
    float n2 = 0.0f;
    for (int c = 0; c < 4; c++) {
        out[c] = wa * a[c] + wb * sb * b[c];
        n2 += out[c] * out[c];
    }
    float inv = n2 > 0.0f ? 1.0f / sqrtf(n2) : 0.0f;
    for (int c = 0; c < 4; c++)
        out[c] = n2 > 0.0f ? out[c] * inv : (c == 3 ? 1.0f : 0.0f);
}

/* T R S as one matrix (column-major, as sm_mat4). */
static void compose(const float p[3], const float q[4], const float s[3], sm_mat4 out)
{
    float x = q[0], y = q[1], z = q[2], w = q[3];
    float r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)},
                     {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)},
                     {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)}};
    for (int c = 0; c < 3; c++) {
        for (int k = 0; k < 3; k++)
            out[c][k] = r[c][k] * s[c];
        out[c][3] = 0.0f;
    }
    out[3][0] = p[0];
    out[3][1] = p[1];
    out[3][2] = p[2];
    out[3][3] = 1.0f;
}

/* Mesh m rebuilt from the morph's own vertices and its targets at weights w. */
static void morph(const anim_morph *mo, const float *w, mesh *m)
{
    for (uint32_t v = 0; v < m->nvertices; v++) {
        mesh_vertex *out = &m->vertices[v];
        *out = mo->base[v];
        sm_vec3 n;
        sm_vec3_copy(out->normal, n);
        for (uint32_t k = 0; k < mo->ntargets; k++) {
            if (w[k] == 0.0f)
                continue;
            const float *dp = mo->dpos + ((size_t)k * m->nvertices + v) * 3;
            const float *dn = mo->dnorm + ((size_t)k * m->nvertices + v) * 3;
            for (int c = 0; c < 3; c++) {
                out->position[c] += w[k] * dp[c];
                n[c] += w[k] * dn[c];
            }
        }
        if (sm_vec3_norm(n) > 1e-20f) {
            sm_vec3_normalize(n);
            sm_vec3_copy(n, out->normal);
        }
    }
    mesh_compute_bounds(m);
}

/* Two passes over the vertices' influences: each joint's aabb, then the radius. */
bool scene_anim_skin_spheres(const mesh *m, anim_skin *k)
{
    sm_vec3 *lo = malloc(k->njoints * sizeof *lo), *hi = malloc(k->njoints * sizeof *hi);
    if (!lo || !hi) {
        free(lo);
        free(hi);
        return false;
    }
    for (uint32_t j = 0; j < k->njoints; j++)
        for (int i = 0; i < 3; i++) {
            lo[j][i] = INFINITY;
            hi[j][i] = -INFINITY;
        }
    for (uint32_t v = 0; v < m->nvertices; v++)
        for (int q = 0; q < 4; q++) {
            if (!(m->weights[v][q] > 0.0f))
                continue;
            uint32_t j = m->joints[v][q] - k->first;   /* < njoints: load_skin's */
            const float *p = m->vertices[v].position;
            for (int i = 0; i < 3; i++) {
                lo[j][i] = fminf(lo[j][i], p[i]);
                hi[j][i] = fmaxf(hi[j][i], p[i]);
            }
        }
    sm_vec4 *s = k->bind_sphere;
    for (uint32_t j = 0; j < k->njoints; j++) {
        bool any = lo[j][0] <= hi[j][0];
        for (int i = 0; i < 3; i++)
            s[j][i] = any ? 0.5f * (lo[j][i] + hi[j][i]) : 0.0f;
        s[j][3] = any ? 0.0f : -1.0f;
    }
    for (uint32_t v = 0; v < m->nvertices; v++)
        for (int q = 0; q < 4; q++) {
            if (!(m->weights[v][q] > 0.0f))
                continue;
            uint32_t j = m->joints[v][q] - k->first;
            const float *p = m->vertices[v].position;
            sm_vec3 d = {p[0] - s[j][0], p[1] - s[j][1], p[2] - s[j][2]};
            s[j][3] = fmaxf(s[j][3], sm_vec3_norm(d));
        }
    free(lo);
    free(hi);
    return true;
}

/* Skin k's joint matrices into the palette, and its mesh's bounds: the joints' bind
 * spheres carried by their matrices (centre by the matrix, radius by its stretch) into
 * k->posed_sphere, the aabb about them all and the sphere about the aabb's centre
 * holding them all. */
static void pose_skin(scene_anim *a, anim_skin *k, mesh *m)
{
    if (m && m->deforms)   /* morphed this frame: its spheres from the frame's shape (out
                            * of memory: the last frame's) */
        scene_anim_skin_spheres(m, k);
    sm_vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t j = 0; j < k->njoints; j++) {
        sm_mat4 *out = &a->joints[k->first + j];
        if (k->node[j] >= 0)
            sm_mat4_mul(a->world[k->node[j]], k->offset[j], *out);
        else   /* no node: the vertex where it is bound, under the file's placement */
            sm_mat4_copy(a->root, *out);
        const float *bs = k->bind_sphere[j];
        float *ps = k->posed_sphere[j];
        if (!m || bs[3] < 0.0f)
            continue;
        sm_vec3 c = {bs[0], bs[1], bs[2]};
        sm_mat4_mulv3(*out, c, 1.0f, ps);
        ps[3] = bs[3] * sm_mat4_stretch(*out);
        for (int i = 0; i < 3; i++) {
            lo[i] = fminf(lo[i], ps[i] - ps[3]);
            hi[i] = fmaxf(hi[i], ps[i] + ps[3]);
        }
    }
    if (!m || !(lo[0] <= hi[0]))
        return;   /* no joint moves a vertex (file_skin.c gives every vertex one) */
    sm_vec3 centre;
    for (int i = 0; i < 3; i++)
        centre[i] = 0.5f * (lo[i] + hi[i]);
    float radius = 0.0f;
    for (uint32_t j = 0; j < k->njoints; j++) {
        const float *ps = k->posed_sphere[j];
        if (k->bind_sphere[j][3] < 0.0f)
            continue;
        sm_vec3 d;
        sm_vec3_sub(ps, centre, d);
        radius = fmaxf(radius, sm_vec3_norm(d) + ps[3]);
    }
    sm_vec3_copy(lo, m->aabb[0]);
    sm_vec3_copy(hi, m->aabb[1]);
    m->sphere[0] = centre[0];
    m->sphere[1] = centre[1];
    m->sphere[2] = centre[2];
    m->sphere[3] = radius;
}

void scene_anim_pose(scene_anim *a, mesh *meshes, double t)
{
    if (!a)
        return;
    double d = a->duration > 0.0 ? a->duration : 1.0;
    double lt = fmod(t, d);
    if (lt < 0.0)
        lt += d;
    float ft = (float)lt;
    for (uint32_t i = 0; meshes && i < a->nmorphs; i++) {
        anim_morph *mo = &a->morphs[i];
        float w[64];   /* file_anim.c keeps at most 64 targets */
        if (mo->keys.n)
            lerpn(&mo->keys, ft, mo->ntargets, w);
        else
            memcpy(w, mo->weights, mo->ntargets * sizeof *w);
        morph(mo, w, &meshes[mo->mesh]);
    }
    for (uint32_t i = 0; i < a->nnodes; i++) {
        const anim_node *n = &a->nodes[i];
        sm_mat4 local;
        if (n->channel >= 0) {
            const anim_channel *c = &a->channels[n->channel];
            float p[3] = {n->pos[0], n->pos[1], n->pos[2]};
            float s[3] = {n->scale[0], n->scale[1], n->scale[2]};
            float q[4] = {n->rot[0], n->rot[1], n->rot[2], n->rot[3]};
            if (c->pos.n)
                lerp3(&c->pos, ft, p);
            if (c->scale.n)
                lerp3(&c->scale, ft, s);
            if (c->rot.n)
                slerp(&c->rot, ft, q);
            compose(p, q, s, local);
        } else {
            sm_mat4_copy(n->local, local);
        }
        sm_mat4_mul(n->parent >= 0 ? a->world[n->parent] : a->root, local, a->world[i]);
    }
    for (uint32_t i = 0; i < a->nskins; i++)
        pose_skin(a, &a->skins[i], meshes ? &meshes[a->skins[i].mesh] : NULL);
}

static void keys_free(anim_keys *k)
{
    free(k->t);
    free(k->v);
}

void scene_anim_free(scene_anim *a)
{
    if (!a)
        return;
    for (uint32_t i = 0; i < a->nmorphs; i++) {
        anim_morph *mo = &a->morphs[i];
        free(mo->base);
        free(mo->dpos);
        free(mo->dnorm);
        free(mo->weights);
        keys_free(&mo->keys);
    }
    free(a->morphs);
    for (uint32_t i = 0; i < a->nskins; i++) {
        free(a->skins[i].node);
        free(a->skins[i].offset);
        free(a->skins[i].bind_sphere);
        free(a->skins[i].posed_sphere);
    }
    free(a->skins);
    free(a->joints);
    for (uint32_t i = 0; i < a->nchannels; i++) {
        keys_free(&a->channels[i].pos);
        keys_free(&a->channels[i].rot);
        keys_free(&a->channels[i].scale);
    }
    free(a->channels);
    free(a->nodes);
    free(a->world);
    free(a);
}
