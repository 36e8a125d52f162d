/* File scenes, >>skins: the file's skinned meshes (assimp's aiMesh.mBones: a bone names
 * its joint's node, its mOffsetMatrix is the joint's inverse bind matrix, its weights say
 * which vertices it moves) as the scene's skins (scenes/scene_anim.h), which
 * scene_anim_pose poses and every renderer blends in its vertex stage.
 *
 * Per vertex the 4 largest influences are kept (glTF's JOINTS_0 / WEIGHTS_0; a file's
 * JOINTS_1 beyond them is dropped, which file_not_rendered lists) and renormalised to sum
 * to 1. Untrusted weights: one that is not finite or not above 0, or of a vertex the mesh
 * does not have, counts as none; a vertex left with no influence follows its mesh's first
 * joint wholly (a documented fallback: never a zero or NaN blend). A joint's inverse bind
 * matrix that is not finite refuses the file; a bone whose node is not in the tree leaves
 * its vertices where they are bound (scene_anim.h). */
#include "scenes/file/file_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <assimp/scene.h>

#include "scenes/scene_anim.h"

/* Influence (joint j, weight w) into a vertex's 4 largest, slots by weight, first come
 * first kept among equals. */
static void keep_largest(uint16_t joints[4], float weights[4], uint16_t j, float w)
{
    int low = 0;
    for (int k = 1; k < 4; k++)
        if (weights[k] < weights[low])
            low = k;
    if (w > weights[low]) {
        weights[low] = w;
        joints[low] = j;
    }
}

/* A vertex's weights summing to 1 (scaled by the largest first, so that no sum of finite
 * weights overflows); none: its mesh's first joint (palette index first). Every slot's
 * joint is one of the skin's after it. */
static void normalise(uint16_t joints[4], float weights[4], uint16_t first)
{
    float most = fmaxf(fmaxf(weights[0], weights[1]), fmaxf(weights[2], weights[3]));
    if (!(most > 0.0f)) {
        joints[0] = first;
        weights[0] = 1.0f;
        return;
    }
    float sum = 0.0f;
    for (int k = 0; k < 4; k++)
        sum += weights[k] / most;
    for (int k = 0; k < 4; k++) {
        weights[k] = weights[k] / most / sum;
        if (!(weights[k] > 0.0f))   /* an empty slot names a joint of the skin too */
            joints[k] = first;
    }
}

unsigned file_skin_over4(const struct aiMesh *am)
{
    if (!am->mNumBones || !am->mNumVertices)
        return 0;
    unsigned char *n = calloc(am->mNumVertices, 1);
    if (!n)
        return 0;
    unsigned over = 0;
    for (unsigned b = 0; b < am->mNumBones; b++)
        for (unsigned i = 0; i < am->mBones[b]->mNumWeights; i++) {
            const struct aiVertexWeight *vw = &am->mBones[b]->mWeights[i];
            if (vw->mVertexId < am->mNumVertices && vw->mWeight > 0.0f &&
                isfinite(vw->mWeight) && n[vw->mVertexId] < 5)
                over += ++n[vw->mVertexId] == 5;
        }
    free(n);
    return over;
}

/* File mesh am's skin as skin k of a, its vertices' joints and weights into scene mesh m.
 * False (b failed) out of memory or for an inverse bind matrix that is not finite. */
static bool load_skin(scene_builder *b, const char *path, const struct aiMesh *am, mesh *m,
                      file_node_lookup lookup, const void *ctx, scene_anim *a, anim_skin *k)
{
    k->first = a->njoints;
    k->njoints = am->mNumBones;
    k->node = malloc(k->njoints * sizeof *k->node);
    k->offset = malloc(k->njoints * sizeof *k->offset);
    k->bind_sphere = malloc(k->njoints * sizeof *k->bind_sphere);
    k->posed_sphere = malloc(k->njoints * sizeof *k->posed_sphere);
    m->joints = calloc(m->nvertices ? m->nvertices : 1, sizeof *m->joints);
    m->weights = calloc(m->nvertices ? m->nvertices : 1, sizeof *m->weights);
    if (!k->node || !k->offset || !k->bind_sphere || !k->posed_sphere || !m->joints ||
        !m->weights)
        return sb_fail(b, "%s: out of memory for a skin of %u joints", path, k->njoints);
    for (uint32_t j = 0; j < k->njoints; j++) {
        const struct aiBone *bone = am->mBones[j];
        file_matrix_from_ai(&bone->mOffsetMatrix, k->offset[j]);
        for (int c = 0; c < 16; c++)
            if (!isfinite(k->offset[j][c / 4][c % 4]))
                return sb_fail(b, "%s: the inverse bind matrix of joint '%s' is not finite",
                               path, bone->mName.data);
        k->node[j] = lookup(ctx, bone->mName.data);
        for (unsigned i = 0; i < bone->mNumWeights; i++) {
            const struct aiVertexWeight *vw = &bone->mWeights[i];
            if (vw->mVertexId < m->nvertices && isfinite(vw->mWeight) && vw->mWeight > 0.0f)
                keep_largest(m->joints[vw->mVertexId], m->weights[vw->mVertexId],
                             (uint16_t)(k->first + j), vw->mWeight);
        }
    }
    for (uint32_t v = 0; v < m->nvertices; v++)
        normalise(m->joints[v], m->weights[v], (uint16_t)k->first);
    if (!scene_anim_skin_spheres(m, k))
        return sb_fail(b, "%s: out of memory for a skin of %u joints", path, k->njoints);
    a->njoints += k->njoints;
    return true;
}

bool file_skin_load(scene_builder *b, const char *path, const struct aiScene *ai,
                    const uint32_t *mesh_index, file_node_lookup lookup, const void *ctx,
                    scene_anim *a)
{
    unsigned n = 0;
    uint64_t joints = 0;
    for (unsigned i = 0; i < ai->mNumMeshes; i++) {
        n += ai->mMeshes[i]->mNumBones > 0;
        joints += ai->mMeshes[i]->mNumBones;
    }
    if (!n)
        return true;
    if (joints > SCENE_ANIM_MAX_JOINTS)
        return sb_fail(b, "%s: its skins have %llu joints in all; at most %u are drawn", path,
                       (unsigned long long)joints, SCENE_ANIM_MAX_JOINTS);
    a->skins = calloc(n, sizeof *a->skins);
    a->joints = calloc(joints, sizeof *a->joints);
    if (!a->skins || !a->joints)
        return sb_fail(b, "%s: out of memory for %u skins", path, n);
    for (unsigned i = 0; i < ai->mNumMeshes; i++) {
        const struct aiMesh *am = ai->mMeshes[i];
        if (!am->mNumBones)
            continue;
        anim_skin *k = &a->skins[a->nskins++];
        k->mesh = mesh_index[i];
        if (!load_skin(b, path, am, &b->s->meshes[k->mesh], lookup, ctx, a, k))
            return false;
    }
    return true;
}

void file_skin_bounds(scene *s, sm_vec3 lo, sm_vec3 hi)
{
    if (!s->anim || !s->anim->nskins)
        return;
    scene_anim_pose(s->anim, s->meshes, 0.0);
    /* the vertices skinned here, once: the joints' spheres (the frames' culling bounds)
     * are looser than a framing wants */
    for (uint32_t i = 0; i < s->anim->nskins; i++) {
        const mesh *m = &s->meshes[s->anim->skins[i].mesh];
        for (uint32_t v = 0; v < m->nvertices; v++) {
            sm_vec3 p = {0.0f, 0.0f, 0.0f};
            for (int q = 0; q < 4; q++) {
                sm_vec3 t;
                sm_mat4_mulv3(s->anim->joints[m->joints[v][q]], m->vertices[v].position, 1.0f,
                              t);
                for (int k = 0; k < 3; k++)
                    p[k] += m->weights[v][q] * t[k];
            }
            for (int k = 0; k < 3; k++) {
                lo[k] = fminf(lo[k], p[k]);
                hi[k] = fmaxf(hi[k], p[k]);
            }
        }
    }
}
