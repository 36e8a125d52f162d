/* File scenes, >>animation: the first animation's node channels as the scene's node
 * animation (scenes/scene_anim.h), which scene_update plays, with the meshes' morph
 * targets and skins (file_skin.c). */
#include "scenes/file/file_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <assimp/anim.h>
#include <assimp/cimport.h>
#include <assimp/scene.h>

#include "scenes/scene_anim.h"

typedef struct node_table {
    const struct aiNode **node;
    int32_t *parent;
    uint32_t n, cap;
    bool oom;
} node_table;

/* The tree in walk's order (file_assimp.c: pre-order, FILE_MAX_NODE_DEPTH levels). */
static void collect(node_table *t, const struct aiNode *n, int32_t parent, unsigned depth)
{
    if (t->oom)
        return;
    if (t->n == t->cap) {
        uint32_t cap = t->cap ? 2 * t->cap : 64;
        const struct aiNode **nn = realloc(t->node, cap * sizeof *nn);
        if (nn)
            t->node = nn;
        int32_t *np = realloc(t->parent, cap * sizeof *np);
        if (np)
            t->parent = np;
        if (!nn || !np) {
            t->oom = true;
            return;
        }
        t->cap = cap;
    }
    uint32_t self = t->n++;
    t->node[self] = n;
    t->parent[self] = parent;
    if (depth + 1 < FILE_MAX_NODE_DEPTH)
        for (unsigned i = 0; i < n->mNumChildren; i++)
            collect(t, n->mChildren[i], (int32_t)self, depth + 1);
}

static const node_table *g_sort_table;   /* qsort's comparison has no context */

static int by_name(const void *a, const void *b)
{
    const struct aiNode *x = g_sort_table->node[*(const uint32_t *)a];
    const struct aiNode *y = g_sort_table->node[*(const uint32_t *)b];
    return strcmp(x->mName.data, y->mName.data);
}

/* The node named name (the first in walk's order of equal names), or -1. */
static int32_t find(const node_table *t, const uint32_t *sorted, const char *name)
{
    uint32_t lo = 0, hi = t->n;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (strcmp(t->node[sorted[mid]]->mName.data, name) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < t->n && strcmp(t->node[sorted[lo]]->mName.data, name) == 0 ? (int32_t)sorted[lo]
                                                                         : -1;
}

typedef struct lookup_ctx {
    const node_table *t;
    const uint32_t *sorted;
} lookup_ctx;

static int32_t lookup(const void *ctx, const char *name)
{
    const lookup_ctx *c = ctx;
    return find(c->t, c->sorted, name);
}

/* n keys of `width` floats from assimp's keys (times in ticks), checked: finite, times
 * ascending. False with a message. */
static bool copy_keys(scene_builder *b, const char *path, const char *node, anim_keys *k,
                      unsigned n, double tps, const struct aiVectorKey *vk,
                      const struct aiQuatKey *qk)
{
    if (!n)
        return true;
    unsigned width = qk ? 4 : 3;
    k->t = malloc(n * sizeof *k->t);
    k->v = malloc((size_t)n * width * sizeof *k->v);
    if (!k->t || !k->v)
        return sb_fail(b, "%s: out of memory for %u animation keys", path, n);
    for (unsigned i = 0; i < n; i++) {
        double t = (qk ? qk[i].mTime : vk[i].mTime) / tps;
        float *v = k->v + (size_t)i * width;
        if (qk) {
            v[0] = qk[i].mValue.x;
            v[1] = qk[i].mValue.y;
            v[2] = qk[i].mValue.z;
            v[3] = qk[i].mValue.w;
        } else {
            v[0] = vk[i].mValue.x;
            v[1] = vk[i].mValue.y;
            v[2] = vk[i].mValue.z;
        }
        bool finite = isfinite(t);
        for (unsigned c = 0; c < width; c++)
            finite = finite && isfinite(v[c]);
        if (!finite)
            return sb_fail(b, "%s: the animation of node '%s' has a key that is not finite",
                           path, node);
        if (i > 0 && t < k->t[i - 1])
            return sb_fail(b, "%s: the animation of node '%s' has key times that go back "
                           "(%g after %g s)", path, node, t, (double)k->t[i - 1]);
        k->t[i] = (float)t;
    }
    if (qk)   /* unit quaternions (a zero one: no rotation) */
        for (unsigned i = 0; i < n; i++) {
            float *q = k->v + 4 * (size_t)i;
            float len = sqrtf(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
            for (int c = 0; c < 4; c++)
                q[c] = len > 0.0f ? q[c] / len : (c == 3 ? 1.0f : 0.0f);
        }
    k->n = n;
    return true;
}

/* The node's own transform as translation, rotation and scale, and as its matrix. */
static void node_trs(const struct aiNode *n, anim_node *an)
{
    struct aiVector3D s, p;
    struct aiQuaternion q;
    aiDecomposeMatrix(&n->mTransformation, &s, &q, &p);
    sm_vec3_make(p.x, p.y, p.z, an->pos);
    sm_vec3_make(s.x, s.y, s.z, an->scale);
    an->rot[0] = q.x;
    an->rot[1] = q.y;
    an->rot[2] = q.z;
    an->rot[3] = q.w;
    file_matrix_from_ai(&n->mTransformation, an->local);
}

/* Morph target k of file mesh am as offsets from its own vertices (a value that is not
 * finite: no offset). */
static void target_offsets(const struct aiMesh *am, unsigned k, float *dpos, float *dnorm)
{
    const struct aiAnimMesh *t = am->mAnimMeshes[k];
    for (unsigned v = 0; v < am->mNumVertices; v++) {
        float *p = dpos + 3 * (size_t)v, *n = dnorm + 3 * (size_t)v;
        p[0] = p[1] = p[2] = n[0] = n[1] = n[2] = 0.0f;
        if (t->mVertices && v < t->mNumVertices && file_finite3(&t->mVertices[v])) {
            p[0] = t->mVertices[v].x - am->mVertices[v].x;
            p[1] = t->mVertices[v].y - am->mVertices[v].y;
            p[2] = t->mVertices[v].z - am->mVertices[v].z;
        }
        if (t->mNormals && am->mNormals && v < t->mNumVertices &&
            file_finite3(&t->mNormals[v]) && file_finite3(&am->mNormals[v])) {
            n[0] = t->mNormals[v].x - am->mNormals[v].x;
            n[1] = t->mNormals[v].y - am->mNormals[v].y;
            n[2] = t->mNormals[v].z - am->mNormals[v].z;
        }
        for (int c = 0; c < 3; c++) {
            p[c] = isfinite(p[c]) ? p[c] : 0.0f;
            n[c] = isfinite(n[c]) ? n[c] : 0.0f;
        }
    }
}

/* The morphs of the file's meshes with targets (scene mesh mesh_index[i] of file mesh i),
 * their default weights. False (b failed) out of memory or beyond 64 targets. */
static bool load_morphs(scene_builder *b, const char *path, const struct aiScene *ai,
                        const uint32_t *mesh_index, scene_anim *a)
{
    unsigned n = 0;
    for (unsigned i = 0; i < ai->mNumMeshes; i++)
        n += ai->mMeshes[i]->mNumAnimMeshes > 0;
    if (!n)
        return true;
    a->morphs = calloc(n, sizeof *a->morphs);
    if (!a->morphs)
        return sb_fail(b, "%s: out of memory for %u morphed meshes", path, n);
    for (unsigned i = 0; i < ai->mNumMeshes; i++) {
        const struct aiMesh *am = ai->mMeshes[i];
        unsigned k = am->mNumAnimMeshes;
        if (!k)
            continue;
        if (k > 64)
            return sb_fail(b, "%s: mesh %u has %u morph targets; at most 64 are drawn", path,
                           i, k);
        mesh *m = &b->s->meshes[mesh_index[i]];
        anim_morph *mo = &a->morphs[a->nmorphs++];
        mo->mesh = mesh_index[i];
        mo->ntargets = k;
        size_t nv = m->nvertices ? m->nvertices : 1;
        mo->base = malloc(nv * sizeof *mo->base);
        mo->dpos = malloc(k * nv * 3 * sizeof *mo->dpos);
        mo->dnorm = malloc(k * nv * 3 * sizeof *mo->dnorm);
        mo->weights = malloc(k * sizeof *mo->weights);
        if (!mo->base || !mo->dpos || !mo->dnorm || !mo->weights)
            return sb_fail(b, "%s: out of memory for mesh %u's %u morph targets", path, i, k);
        memcpy(mo->base, m->vertices, m->nvertices * sizeof *mo->base);
        for (unsigned t = 0; t < k; t++) {
            target_offsets(am, t, mo->dpos + (size_t)t * nv * 3, mo->dnorm + (size_t)t * nv * 3);
            float w = am->mAnimMeshes[t]->mWeight;
            mo->weights[t] = isfinite(w) ? w : 0.0f;
        }
        m->deforms = true;
    }
    return true;
}

/* The first animation's weights for the morphs of the meshes its morph channels' nodes
 * draw (a channel names its node). False (b failed) for keys that are not finite or go
 * back in time, or out of memory. */
static bool load_weights(scene_builder *b, const char *path, const struct aiScene *ai,
                         const node_table *t, const uint32_t *sorted, double tps,
                         const uint32_t *mesh_index, scene_anim *a, double *last)
{
    const struct aiAnimation *an = ai->mAnimations[0];
    for (unsigned c = 0; c < an->mNumMorphMeshChannels; c++) {
        const struct aiMeshMorphAnim *mm = an->mMorphMeshChannels[c];
        int32_t node = find(t, sorted, mm->mName.data);
        if (node < 0 || !mm->mNumKeys)
            continue;
        const struct aiNode *nd = t->node[node];
        for (unsigned j = 0; j < nd->mNumMeshes; j++) {
            anim_morph *mo = NULL;
            for (uint32_t i = 0; i < a->nmorphs && nd->mMeshes[j] < ai->mNumMeshes; i++)
                if (a->morphs[i].mesh == mesh_index[nd->mMeshes[j]])
                    mo = &a->morphs[i];
            if (!mo || mo->keys.n)
                continue;
            anim_keys *k = &mo->keys;
            k->t = malloc(mm->mNumKeys * sizeof *k->t);
            k->v = calloc((size_t)mm->mNumKeys * mo->ntargets, sizeof *k->v);
            if (!k->t || !k->v)
                return sb_fail(b, "%s: out of memory for %u morph keys", path, mm->mNumKeys);
            for (unsigned i = 0; i < mm->mNumKeys; i++) {
                const struct aiMeshMorphKey *key = &mm->mKeys[i];
                double tt = key->mTime / tps;
                if (!isfinite(tt))
                    return sb_fail(b, "%s: the morph animation of node '%s' has a key time "
                                   "that is not finite", path, mm->mName.data);
                if (i > 0 && tt < k->t[i - 1])
                    return sb_fail(b, "%s: the morph animation of node '%s' has key times that "
                                   "go back (%g after %g s)", path, mm->mName.data, tt,
                                   (double)k->t[i - 1]);
                k->t[i] = (float)tt;
                for (unsigned q = 0; q < key->mNumValuesAndWeights; q++) {
                    double w = key->mWeights[q];
                    if (key->mValues[q] < mo->ntargets)
                        k->v[(size_t)i * mo->ntargets + key->mValues[q]] =
                            isfinite(w) ? (float)w : 0.0f;
                }
            }
            k->n = mm->mNumKeys;
            *last = fmax(*last, k->t[k->n - 1]);
        }
    }
    return true;
}

bool file_anim_load(scene_builder *b, const char *path, const struct aiScene *ai,
                    const uint32_t *mesh_index, const sm_mat4 root, bool **moves)
{
    *moves = NULL;
    bool deformed = false;   /* morph targets or a skin: posed even when nothing moves */
    for (unsigned i = 0; i < ai->mNumMeshes; i++)
        deformed |= ai->mMeshes[i]->mNumAnimMeshes > 0 || ai->mMeshes[i]->mNumBones > 0;
    const struct aiAnimation *an = ai->mNumAnimations ? ai->mAnimations[0] : NULL;
    if (!deformed && (!an || !an->mNumChannels))
        return true;
    node_table t = {0};
    collect(&t, ai->mRootNode, -1, 0);
    uint32_t *sorted = t.oom ? NULL : malloc((t.n ? t.n : 1) * sizeof *sorted);
    scene_anim *a = calloc(1, sizeof *a);
    bool ok = false;
    if (!sorted || !a)
        goto oom;
    for (uint32_t i = 0; i < t.n; i++)
        sorted[i] = i;
    g_sort_table = &t;
    qsort(sorted, t.n, sizeof *sorted, by_name);
    a->nodes = calloc(t.n ? t.n : 1, sizeof *a->nodes);
    a->world = calloc(t.n ? t.n : 1, sizeof *a->world);
    a->channels = calloc(an && an->mNumChannels ? an->mNumChannels : 1, sizeof *a->channels);
    *moves = calloc(t.n ? t.n : 1, sizeof **moves);
    if (!a->nodes || !a->world || !a->channels || !*moves)
        goto oom;
    a->nnodes = t.n;
    for (uint32_t i = 0; i < t.n; i++) {
        a->nodes[i].parent = t.parent[i];
        a->nodes[i].channel = -1;
        node_trs(t.node[i], &a->nodes[i]);
    }
    double tps = an && an->mTicksPerSecond > 0.0 && isfinite(an->mTicksPerSecond)
                     ? an->mTicksPerSecond : 25.0;   /* assimp's convention for 0 */
    double last = 0.0;
    for (unsigned c = 0; an && c < an->mNumChannels; c++) {
        const struct aiNodeAnim *na = an->mChannels[c];
        int32_t node = find(&t, sorted, na->mNodeName.data);
        if (node < 0 || a->nodes[node].channel >= 0)
            continue;   /* a channel of no node drawn (beyond the depth cap), or repeated */
        anim_channel *ch = &a->channels[a->nchannels];
        ch->node = (uint32_t)node;
        if (!copy_keys(b, path, na->mNodeName.data, &ch->pos, na->mNumPositionKeys, tps,
                       na->mPositionKeys, NULL) ||
            !copy_keys(b, path, na->mNodeName.data, &ch->rot, na->mNumRotationKeys, tps,
                       NULL, na->mRotationKeys) ||
            !copy_keys(b, path, na->mNodeName.data, &ch->scale, na->mNumScalingKeys, tps,
                       na->mScalingKeys, NULL)) {
            a->nchannels++;   /* freed with the rest */
            goto out;
        }
        a->nodes[node].channel = (int32_t)a->nchannels++;
        const anim_keys *k[3] = {&ch->pos, &ch->rot, &ch->scale};
        for (int i = 0; i < 3; i++)
            if (k[i]->n)
                last = fmax(last, k[i]->t[k[i]->n - 1]);
    }
    lookup_ctx lc = {&t, sorted};
    if (!load_morphs(b, path, ai, mesh_index, a) ||
        !file_skin_load(b, path, ai, mesh_index, lookup, &lc, a) ||
        (an && !load_weights(b, path, ai, &t, sorted, tps, mesh_index, a, &last)))
        goto out;
    double d = an ? an->mDuration / tps : 0.0;
    a->duration = isfinite(d) && d > 0.0 ? d : last > 0.0 ? last : 1.0;
    sm_mat4_copy(root, a->root);
    bool any = a->nmorphs > 0 || a->nskins > 0;
    for (uint32_t i = 0; i < t.n; i++) {
        int32_t p = a->nodes[i].parent;
        (*moves)[i] = a->nodes[i].channel >= 0 || (p >= 0 && (*moves)[p]);
        any |= (*moves)[i];
    }
    if (any) {
        b->s->anim = a;
        a = NULL;
    }
    ok = true;
    goto out;
oom:
    sb_fail(b, "%s: out of memory for the animation of %u nodes", path, t.n);
out:
    scene_anim_free(a);
    free(sorted);
    free(t.node);
    free(t.parent);
    if (!ok) {
        free(*moves);
        *moves = NULL;
    }
    return ok;
}
