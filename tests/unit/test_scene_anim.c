/* A file's node animation (scenes/scene_anim.h), posed by hand-made channels: a node
 * translated and turned between two keys takes the interpolated pose at the midpoint
 * (the translation linear, the rotation spherical: 45 degrees halfway to 90, not the
 * linear blend's shorter matrix), its child composes it with its own transform, the
 * animation loops over its duration, a channel holds its first key before it and its
 * last after it, a node without a channel keeps its own matrix, and the root placement
 * sits above every node. Morph targets: a mesh's vertices are its own plus the weighted
 * offsets (weights interpolated between keys, the defaults without keys), the normals
 * normalised, the bounds recomputed. Exact to 1e-5. */
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_midpoint),
        cmocka_unit_test(test_hold_and_loop),
        cmocka_unit_test(test_morph),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
