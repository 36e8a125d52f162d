/* A file's node animation (scenes/scene_anim.h), posed by hand-made channels: a node
 * translated and turned between two keys takes the interpolated pose at the midpoint
 * (the translation linear, the rotation spherical: 45 degrees halfway to 90, not the
 * linear blend's shorter matrix), its child composes it with its own transform, the
 * animation loops over its duration, a channel holds its first key before it and its
 * last after it, a node without a channel keeps its own matrix, and the root placement
 * sits above every node. Morph targets: a mesh's vertices are its own plus the weighted
 * offsets (weights interpolated between keys, the defaults without keys), the normals
 * normalised, the bounds recomputed. Skins: every joint's matrix is its node's posed world
 * times its inverse bind matrix (a joint without a node: the root placement alone), and
 * the skinned mesh's bounds hold every vertex skinned on the CPU at several times.
 * Exact to 1e-5. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/scene_anim.h"

static float *floats(const float *v, size_t n)
{
    float *p = malloc(n * sizeof *p);
    assert_non_null(p);
    memcpy(p, v, n * sizeof *p);
    return p;
}

/* Node 0: keys at 1 s and 3 s, translation (0,0,0) -> (2,0,0), rotation identity -> 90
 * degrees about y; node 1, its child, at (0, 0, 1) of it, still; node 2, a root of its
 * own, its matrix a translation by (0, 5, 0). Duration 4 s; the root placement scales
 * by 2. */
static scene_anim *make(void)
{
    scene_anim *a = calloc(1, sizeof *a);
    assert_non_null(a);
    a->nnodes = 3;
    a->nodes = calloc(3, sizeof *a->nodes);
    a->world = calloc(3, sizeof *a->world);
    a->channels = calloc(1, sizeof *a->channels);
    assert_non_null(a->nodes);
    assert_non_null(a->world);
    assert_non_null(a->channels);
    const float id_q[4] = {0, 0, 0, 1};
    for (int i = 0; i < 3; i++) {
        anim_node *n = &a->nodes[i];
        n->parent = i == 1 ? 0 : -1;
        n->channel = -1;
        sm_vec3_make(0, 0, 0, n->pos);
        sm_vec3_make(1, 1, 1, n->scale);
        memcpy(n->rot, id_q, sizeof id_q);
        sm_mat4_identity(n->local);
    }
    a->nodes[1].pos[2] = 1.0f;
    a->nodes[1].local[3][2] = 1.0f;
    a->nodes[2].pos[1] = 5.0f;
    a->nodes[2].local[3][1] = 5.0f;
    a->nodes[0].channel = 0;
    a->nchannels = 1;
    anim_channel *c = &a->channels[0];
    const float t[2] = {1, 3}, p[6] = {0, 0, 0, 2, 0, 0};
    const float s = sinf(0.25f * 3.14159265f), q[8] = {0, 0, 0, 1, 0, s, 0, s};
    c->pos = (anim_keys){2, floats(t, 2), floats(p, 6)};
    c->rot = (anim_keys){2, floats(t, 2), floats(q, 8)};
    a->duration = 4.0;
    sm_mat4_identity(a->root);
    for (int k = 0; k < 3; k++)
        a->root[k][k] = 2.0f;
    return a;
}

/* Column c's first three rows of node i's world matrix. */
static void expect_col(const scene_anim *a, int i, int c, float x, float y, float z)
{
    assert_float_equal(a->world[i][c][0], x, 1e-5);
    assert_float_equal(a->world[i][c][1], y, 1e-5);
    assert_float_equal(a->world[i][c][2], z, 1e-5);
}

static void test_midpoint(void **state)
{
    (void)state;
    scene_anim *a = make();
    scene_anim_pose(a, NULL, 2.0);   /* halfway: (1, 0, 0), 45 degrees about y */
    const float h = sqrtf(0.5f);
    expect_col(a, 0, 3, 2.0f, 0.0f, 0.0f);          /* root x 2 */
    expect_col(a, 0, 0, 2.0f * h, 0.0f, -2.0f * h); /* x axis turned about y */
    expect_col(a, 0, 2, 2.0f * h, 0.0f, 2.0f * h);
    /* the child: its (0, 0, 1) in the parent's turned frame */
    expect_col(a, 1, 3, 2.0f * (1.0f + h), 0.0f, 2.0f * h);
    /* the still root node: its own matrix under the placement */
    expect_col(a, 2, 3, 0.0f, 10.0f, 0.0f);
    expect_col(a, 2, 0, 2.0f, 0.0f, 0.0f);
    scene_anim_free(a);
}

static void test_hold_and_loop(void **state)
{
    (void)state;
    scene_anim *a = make();
    scene_anim_pose(a, NULL, 0.5);   /* before the first key: the first */
    expect_col(a, 0, 3, 0.0f, 0.0f, 0.0f);
    expect_col(a, 0, 0, 2.0f, 0.0f, 0.0f);
    scene_anim_pose(a, NULL, 3.5);   /* after the last: the last, 90 degrees */
    expect_col(a, 0, 3, 4.0f, 0.0f, 0.0f);
    expect_col(a, 0, 0, 0.0f, 0.0f, -2.0f);
    scene_anim_pose(a, NULL, 6.0);   /* 6 s is 2 s into the second loop */
    const float h = sqrtf(0.5f);
    expect_col(a, 0, 3, 2.0f, 0.0f, 0.0f);
    expect_col(a, 0, 0, 2.0f * h, 0.0f, -2.0f * h);
    scene_anim_free(a);
    scene_anim_free(NULL);
}

/* A two-vertex mesh, one target moving vertex 1 by (0, 2, 0) and turning its normal
 * from +z towards +x; weights 0 at 0 s and 1 at 2 s. */
static void test_morph(void **state)
{
    (void)state;
    mesh m = {0};
    m.nvertices = 2;
    m.vertices = calloc(2, sizeof *m.vertices);
    assert_non_null(m.vertices);
    for (int v = 0; v < 2; v++) {
        m.vertices[v].position[0] = (float)v;
        m.vertices[v].normal[2] = 1.0f;
    }
    scene_anim *a = calloc(1, sizeof *a);
    assert_non_null(a);
    a->duration = 4.0;
    a->morphs = calloc(1, sizeof *a->morphs);
    assert_non_null(a->morphs);
    a->nmorphs = 1;
    anim_morph *mo = &a->morphs[0];
    mo->ntargets = 1;
    mo->base = malloc(2 * sizeof *mo->base);
    assert_non_null(mo->base);
    memcpy(mo->base, m.vertices, 2 * sizeof *mo->base);
    const float dp[6] = {0, 0, 0, 0, 2, 0}, dn[6] = {0, 0, 0, 1, 0, -1}, w0[1] = {0.25f};
    mo->dpos = floats(dp, 6);
    mo->dnorm = floats(dn, 6);
    mo->weights = floats(w0, 1);
    scene_anim_pose(a, &m, 1.0);   /* no keys: the default 0.25 */
    assert_float_equal(m.vertices[1].position[1], 0.5f, 1e-5);
    assert_float_equal(m.vertices[0].position[1], 0.0f, 1e-5);
    const float t[2] = {0, 2}, w[2] = {0, 1};
    mo->keys = (anim_keys){2, floats(t, 2), floats(w, 2)};
    scene_anim_pose(a, &m, 1.0);   /* weight 0.5: (1, 1, 0), normal (0.5, 0, 0.5) normalised */
    assert_float_equal(m.vertices[1].position[0], 1.0f, 1e-5);
    assert_float_equal(m.vertices[1].position[1], 1.0f, 1e-5);
    assert_float_equal(m.vertices[1].normal[0], sqrtf(0.5f), 1e-5);
    assert_float_equal(m.vertices[1].normal[2], sqrtf(0.5f), 1e-5);
    assert_float_equal(m.aabb[1][1], 1.0f, 1e-5);   /* bounds follow */
    scene_anim_pose(a, &m, 3.0);   /* after the last key: weight 1, normal +x */
    assert_float_equal(m.vertices[1].position[1], 2.0f, 1e-5);
    assert_float_equal(m.vertices[1].normal[0], 1.0f, 1e-5);
    assert_float_equal(m.vertices[1].normal[2], 0.0f, 1e-5);
    scene_anim_free(a);
    mesh_free(&m);
}

/* p skinned by the palette: the weighted sum of its joints' images. */
static void skin_point(const scene_anim *a, const mesh *m, uint32_t v, sm_vec3 out)
{
    sm_vec3 p = {m->vertices[v].position[0], m->vertices[v].position[1],
                 m->vertices[v].position[2]};
    out[0] = out[1] = out[2] = 0.0f;
    for (int q = 0; q < 4; q++) {
        sm_vec3 t;
        sm_mat4_mulv3(a->joints[m->joints[v][q]], p, 1.0f, t);
        for (int k = 0; k < 3; k++)
            out[k] += m->weights[v][q] * t[k];
    }
}

/* make()'s nodes; a mesh (scene mesh 1 of 2) of three vertices on x: (0, 0, 0) on joint 1
 * (node 0), (1, 0, 0) on joint 2 (node 1, bound at (0, 0, 1): its inverse bind matrix
 * moves by -1 in z), (0.5, 0, 0) half on each; joint 0 (palette index 0, a first skin's
 * place) has no node. */
static void test_skin(void **state)
{
    (void)state;
    scene_anim *a = make();
    mesh meshes[2] = {{0}, {0}};
    mesh *m = &meshes[1];
    m->nvertices = 3;
    m->vertices = calloc(3, sizeof *m->vertices);
    m->joints = calloc(3, sizeof *m->joints);
    m->weights = calloc(3, sizeof *m->weights);
    assert_non_null(m->vertices);
    assert_non_null(m->joints);
    assert_non_null(m->weights);
    const float x[3] = {0.0f, 1.0f, 0.5f};
    for (int v = 0; v < 3; v++) {
        m->vertices[v].position[0] = x[v];
        m->joints[v][0] = v == 1 ? 2 : 1;
        m->joints[v][1] = 2;
        m->joints[v][2] = m->joints[v][3] = 1;
        m->weights[v][0] = v == 2 ? 0.5f : 1.0f;
        m->weights[v][1] = v == 2 ? 0.5f : 0.0f;
    }
    a->njoints = 3;
    a->joints = calloc(3, sizeof *a->joints);
    a->skins = calloc(1, sizeof *a->skins);
    assert_non_null(a->joints);
    assert_non_null(a->skins);
    a->nskins = 1;
    anim_skin *k = &a->skins[0];
    *k = (anim_skin){.mesh = 1, .first = 0, .njoints = 3};
    k->node = calloc(3, sizeof *k->node);
    k->offset = calloc(3, sizeof *k->offset);
    k->bind_sphere = calloc(3, sizeof *k->bind_sphere);
    k->posed_sphere = calloc(3, sizeof *k->posed_sphere);
    assert_non_null(k->node);
    assert_non_null(k->offset);
    assert_non_null(k->bind_sphere);
    assert_non_null(k->posed_sphere);
    k->node[0] = -1;
    k->node[1] = 0;
    k->node[2] = 1;
    for (int j = 0; j < 3; j++)
        sm_mat4_identity(k->offset[j]);
    k->offset[2][3][2] = -1.0f;
    /* joint 0 moves nothing, joint 1 x in [0, 0.5], joint 2 x in [0.5, 1] */
    const float spheres[3][4] = {{0, 0, 0, -1}, {0.25f, 0, 0, 0.25f}, {0.75f, 0, 0, 0.25f}};
    assert_true(scene_anim_skin_spheres(m, k));
    for (int j = 0; j < 3; j++)
        for (int c = 0; c < 4; c++)
            assert_float_equal(k->bind_sphere[j][c], spheres[j][c], 1e-6);
    const double times[4] = {0.0, 1.5, 2.0, 3.0};
    for (int i = 0; i < 4; i++) {
        scene_anim_pose(a, meshes, times[i]);
        for (int j = 1; j < 3; j++) {   /* world x offset */
            sm_mat4 want;
            sm_mat4_mul(a->world[k->node[j]], k->offset[j], want);
            for (int c = 0; c < 16; c++)
                assert_float_equal(a->joints[j][c / 4][c % 4], want[c / 4][c % 4], 1e-6);
        }
        for (int c = 0; c < 16; c++)   /* no node: the placement */
            assert_float_equal(a->joints[0][c / 4][c % 4], a->root[c / 4][c % 4], 0.0);
        for (uint32_t v = 0; v < 3; v++) {
            sm_vec3 p, d;
            skin_point(a, m, v, p);
            for (int c = 0; c < 3; c++) {
                assert_true(p[c] >= m->aabb[0][c] - 1e-5f && p[c] <= m->aabb[1][c] + 1e-5f);
                d[c] = p[c] - m->sphere[c];
            }
            assert_true(sm_vec3_norm(d) <= m->sphere[3] + 1e-5f);
        }
    }
    /* at 0 s (node 0 still at its first key): vertex 1 on node 1 at (0, 0, 1) under the
     * root's scale 2, moved back by its inverse bind matrix: (2, 0, 0); vertex 0: (0, 0, 0) */
    scene_anim_pose(a, meshes, 0.0);
    sm_vec3 p;
    skin_point(a, m, 1, p);
    assert_float_equal(p[0], 2.0f, 1e-5);
    assert_float_equal(p[2], 0.0f, 1e-5);
    skin_point(a, m, 0, p);
    assert_float_equal(p[0], 0.0f, 1e-5);
    assert_float_equal(m->sphere[3] > 0.0f, 1.0f, 0.0);
    scene_anim_free(a);
    mesh_free(&meshes[0]);
    mesh_free(&meshes[1]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_midpoint),
        cmocka_unit_test(test_hold_and_loop),
        cmocka_unit_test(test_morph),
        cmocka_unit_test(test_skin),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
