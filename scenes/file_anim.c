/* File scenes, >>animation: the first animation's node channels as the scene's node
 * animation (scenes/scene_anim.h), which scene_update plays. */
#include "scenes/file_internal.h"

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

bool file_anim_load(scene_builder *b, const char *path, const struct aiScene *ai,
                    const sm_mat4 root, bool **moves)
{
    *moves = NULL;
    if (!ai->mNumAnimations || !ai->mAnimations[0]->mNumChannels)
        return true;
    const struct aiAnimation *an = ai->mAnimations[0];
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
    a->channels = calloc(an->mNumChannels, sizeof *a->channels);
    *moves = calloc(t.n ? t.n : 1, sizeof **moves);
    if (!a->nodes || !a->world || !a->channels || !*moves)
        goto oom;
    a->nnodes = t.n;
    for (uint32_t i = 0; i < t.n; i++) {
        a->nodes[i].parent = t.parent[i];
        a->nodes[i].channel = -1;
        node_trs(t.node[i], &a->nodes[i]);
    }
    double tps = an->mTicksPerSecond > 0.0 && isfinite(an->mTicksPerSecond)
                     ? an->mTicksPerSecond : 25.0;   /* assimp's convention for 0 */
    double last = 0.0;
    for (unsigned c = 0; c < an->mNumChannels; c++) {
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
    double d = an->mDuration / tps;
    a->duration = isfinite(d) && d > 0.0 ? d : last > 0.0 ? last : 1.0;
    sm_mat4_copy(root, a->root);
    bool any = false;
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
