/* The tiled renderers (issue 10: forward-plus, clustered, tiled-deferred) against forward-spml with
 * its lights in a storage buffer: images within RMSE 1/255 and max 4/255 on the 8-bit output, with 4,096
 * lights, with shadows on and off, and a tile whose list is longer than any fixed
 * per-tile budget could be; the exact passes, draws, dispatches and tiles; the
 * overflow policy (a list that does not fit fails the frame, naming the tile and its
 * count; nothing is truncated silently); the cull pass pruned without point or spot
 * lights. Debug contexts: any GL error fails. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "renderers/frame/shading.h"
#include "common/image_io.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

/* Not multiples of 16: the last column and row of tiles are partial. */
enum { W = 100, H = 60 };
#define RMSE_MAX (1.0 / 255.0)
#define MAX_ABS_MAX (4.0 / 255.0)

static gl_context *ctx;

static const char *const KINDS[] = {"forward-plus", "clustered", "tiled-deferred"};
enum { NKINDS = 3 };

typedef struct shot {
    image img;
    frame_stats fs;
    pass_plan plan;
    size_t ngrid;              /* renderer_light_grid's cells */
    uint32_t grid_max;         /* their longest list */
    double grid_sum;           /* their lengths summed */
    gbuffer_traffic traffic;   /* renderer_traffic: the bandwidth model's bytes */
} shot;

static renderer_options options(void)
{
    const gl_info *gi = gl_context_info(ctx);
    renderer_options o = {
        .width = W, .height = H, .queries = true,
        .timer_query = gi->timer_query, .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size,
        .gbuffer = GBUFFER_REFERENCE, .light_buffer = LIGHT_BUFFER_STORAGE,
    };
    return o;
}

/* One frame of s with `kind` and options o: the output, the frame's stats (after
 * collect), the plan and the light grid; with counts, a copy of the grid's lengths
 * (malloc'd, the caller frees it). */
static void render_counts(const char *kind, const renderer_options *o, scene *s, shot *out,
                          uint32_t **counts)
{
    char err[512];
    memset(out, 0, sizeof *out);
    renderer *r = test_renderer_create(kind, o, err, sizeof err);
    if (!r || !renderer_prepare(r, s, err, sizeof err))
        fail_msg("%s: %s", kind, err);
    renderer_draw(r, s, &out->fs);
    gl.Finish();
    renderer_collect(r, &out->fs);
    renderer_describe(r, &out->plan);
    out->traffic = renderer_traffic(r, &out->fs);
    size_t n = 0;
    const uint32_t *g = renderer_light_grid(r, &n);
    for (size_t i = 0; g && i < n; i++) {
        out->grid_max = g[i] > out->grid_max ? g[i] : out->grid_max;
        out->grid_sum += g[i];
    }
    out->ngrid = n;
    if (counts) {
        *counts = malloc((n ? n : 1) * sizeof **counts);
        assert_non_null(*counts);
        if (n)
            memcpy(*counts, g, n * sizeof **counts);
    }
    out->img = (image){.width = W, .height = H, .channels = 4, .type = IMAGE_U8,
                       .pixels = malloc((size_t)W * H * 4)};
    assert_true(gl_context_read_rgba8(ctx, out->img.pixels, err, sizeof err));
    renderer_destroy(r);
    gl_context_poll_errors(ctx, kind);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static void render(const char *kind, const renderer_options *o, scene *s, shot *out)
{
    render_counts(kind, o, s, out, NULL);
}

static void expect_agree(const char *what, const image *a, const image *b)
{
    gl_test_expect_agree(what, a, b, RMSE_MAX, MAX_ABS_MAX, false);
}

static void look(scene *s, const float eye[3], const float target[3])
{
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3_copy(eye, s->cam.eye);
    sm_vec3_copy(target, s->cam.target);
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
}

/* "shapes" at t = 0 with exactly these lights, seen from (0, 12, 28). */
static scene *shapes(const scene_light *lights, uint32_t n)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build("shapes", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("shapes: %s", err);
    s->lights = calloc(n ? n : 1, sizeof *s->lights);
    memcpy(s->lights, lights, n * sizeof *s->lights);
    s->nlights_total = n;
    s->count = (light_count){.start = n, .max = n};
    scene_update(s, 0.0);
    static const float eye[3] = {0.0f, 12.0f, 28.0f}, target[3] = {0.0f, 1.0f, 0.0f};
    look(s, eye, target);
    return s;
}

static scene_light point(float x, float y, float z, float radius)
{
    scene_light l = {.type = LIGHT_POINT, .position = {x, y, z}, .color = {0.6f, 0.5f, 0.4f},
                     .radius = radius, .attenuation = ATTENUATION_LINEAR_RANGE};
    return l;
}

/* Sixteen point lights over the floor: the exact passes, draws, dispatches and tiles
 * of forward-plus at every tile size, and its image. */
static void test_counts_and_tile_sizes(void **state)
{
    (void)state;
    scene_light l[16];
    for (int i = 0; i < 16; i++)
        l[i] = point((float)(i % 4) * 8.0f - 12.0f, 3.0f, (float)(i / 4) * 8.0f - 12.0f, 7.0f);
    scene *s = shapes(l, 16);
    renderer_options o = options();
    shot ref, t;
    render("forward-spml", &o, s, &ref);
    uint32_t v = 0;
    const pass_stats *shade = find_pass(&ref.fs, "shade");
    assert_non_null(shade);
    v = (uint32_t)shade->draw_calls;   /* forward-spml: one draw per visible object */
    assert_true(v > 0);
    assert_int_equal(ref.fs.total.dispatches, 0);

    static const int sizes[] = {8, 16, 32};
    double prev_evals = 0.0;
    for (size_t k = 0; k < 3; k++) {
        o.tile_size = sizes[k];
        uint32_t tx = (uint32_t)((W + sizes[k] - 1) / sizes[k]);
        uint32_t ty = (uint32_t)((H + sizes[k] - 1) / sizes[k]);
        /* clustered: the same tiles cut into Olsson's depth slices (S_y = 24: slices
         * about as deep as wide, so many more than 24 reach the far plane); every
         * cluster's list is part of its tile's, so it evaluates no more lights per
         * pixel */
        uint32_t K = shading_cluster_slices(s, 24, NULL);
        assert_true(K > 24 && K <= 1024);
        shot cl;
        render("clustered", &o, s, &cl);
        assert_int_equal(cl.fs.total.dispatches, 1);
        assert_int_equal(find_pass(&cl.fs, "cull")->dispatches, 1);
        assert_int_equal(cl.fs.total.draw_calls, 2u * v + (s->sky ? 1u : 0u) + 1u);
        assert_int_equal(cl.fs.grid_cells, tx * ty * K);
        assert_int_equal(cl.ngrid, tx * ty * K);
        assert_int_equal(cl.fs.overflow[0], '\0');
        char what[64];
        snprintf(what, sizeof what, "clustered, %d px tiles", sizes[k]);
        expect_agree(what, &cl.img, &ref.img);
        image_free(&cl.img);

        /* tiled-deferred: the G-buffer, one dispatch for ambient and every light, the sky
         * and the resolve: V + sky + 1 draws */
        shot td;
        render("tiled-deferred", &o, s, &td);
        size_t ntd = s->sky ? 4 : 3;
        assert_int_equal(td.fs.npasses, ntd);
        assert_string_equal(td.fs.pass[0].name, "gbuffer");
        assert_string_equal(td.fs.pass[1].name, "tiled");
        assert_int_equal(td.fs.pass[0].draw_calls, v);
        assert_int_equal(td.fs.pass[1].draw_calls, 0);
        assert_int_equal(td.fs.pass[1].dispatches, 1);
        assert_int_equal(td.fs.total.draw_calls, v + (s->sky ? 1u : 0u) + 1u);
        assert_int_equal(td.fs.grid_cells, tx * ty);
        snprintf(what, sizeof what, "tiled-deferred, %d px tiles", sizes[k]);
        expect_agree(what, &td.img, &ref.img);
        image_free(&td.img);

        render("forward-plus", &o, s, &t);
        /* the same tiles, the same lists (tiled-deferred's depth is the G-buffer's) */
        print_message("%d px: mean lights a tile %.6f (tiled-deferred) %.6f (forward-plus)\n",
                      sizes[k], td.fs.grid_lights_mean, t.fs.grid_lights_mean);
        assert_true(fabs(td.fs.grid_lights_mean - t.fs.grid_lights_mean) < 1e-9);
        assert_true(cl.fs.light_evals_per_pixel <= t.fs.light_evals_per_pixel);
        /* each pixel with geometry counted in exactly one cluster, as in one tile (with
         * more slices than a small tile has invocations, a slice's count was once left
         * at what the last work group had there) */
        print_message("%d px: %u slices, %llu covered pixels\n", sizes[k], K,
                      (unsigned long long)t.fs.grid_covered);
        assert_true(t.fs.grid_covered > 0);
        assert_int_equal(cl.fs.grid_covered, t.fs.grid_covered);
        assert_int_equal(td.fs.grid_covered, t.fs.grid_covered);
        assert_true(cl.fs.grid_lights_max <= t.fs.grid_lights_max);
        const char *names[] = {"depth", "cull", "shade", "sky", "resolve"};
        size_t np = s->sky ? 5 : 4;
        assert_int_equal(t.fs.npasses, np);
        for (size_t i = 0; i < np; i++)
            assert_string_equal(t.fs.pass[i].name, i == 4 || (i == 3 && !s->sky)
                                                       ? "resolve" : names[i]);
        assert_int_equal(find_pass(&t.fs, "depth")->draw_calls, v);
        assert_int_equal(find_pass(&t.fs, "cull")->draw_calls, 0);
        assert_int_equal(find_pass(&t.fs, "cull")->dispatches, 1);
        assert_int_equal(find_pass(&t.fs, "shade")->draw_calls, v);
        assert_int_equal(t.fs.total.dispatches, 1);
        assert_int_equal(t.fs.total.draw_calls, 2u * v + (s->sky ? 1u : 0u) + 1u);
        assert_int_equal(t.fs.grid_cells, tx * ty);
        assert_int_equal(t.ngrid, tx * ty);
        assert_true(t.grid_max > 0 && t.grid_max <= 16);
        assert_true(fabs(t.fs.grid_lights_max - t.grid_max) < 1e-9);
        assert_true(fabs(t.fs.grid_lights_mean - t.grid_sum / (double)t.ngrid) < 1e-9);
        /* culling culls: fewer than all 16 lights per shaded pixel, and fewer the
         * smaller the tiles (8 px: 3.17, 16 px: 4.89, 32 px: 9.25 here) */
        assert_true(t.fs.light_evals_per_pixel > 0.0 && t.fs.light_evals_per_pixel < 12.0);
        assert_true(t.fs.light_evals_per_pixel > prev_evals);
        prev_evals = t.fs.light_evals_per_pixel;
        assert_int_equal(t.fs.overflow[0], '\0');
        snprintf(what, sizeof what, "forward-plus, %d px tiles", sizes[k]);
        expect_agree(what, &t.img, &ref.img);
        image_free(&t.img);
    }
    image_free(&ref.img);
    scene_destroy(s);
}

/* zbin.comp's dispatches for n lights (zbin.c): the blocks of 2,048 entries sorted, per
 * larger k of the bitonic sort one per step with j >= 2,048 and one merge, the bins. */
static int zbin_dispatches(uint32_t n)
{
    int count = 2;
    for (uint32_t k = 4096; k < 2 * n; k <<= 1)
        for (uint32_t j = k; j >= 2048; j >>= 1)
            count++;
    return count;
}

/* 4,096 radius-3 lights on curtis-scene3, and one tile reached by all of them: longer
 * than any per-tile budget a work group's shared memory could hold. zbin too: its sort
 * past one block (steps and a merge), its masks exactly forward-plus's lists. */
static void test_4096_lights(void **state)
{
    (void)state;
    char err[256];
    light_params lp = {.placement = PLACEMENT_RANDOM, .seed = 1337, .rng = RNG_MSVC,
                       .count = {.start = 4096, .max = 4096}, .radius = 3.0f,
                       .color_max = 0.3f};
    scene *s = scene_build("curtis-scene3", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("curtis-scene3: %s", err);
    scene_update(s, 5.0);
    renderer_options o = options();
    shot ref, t, z;
    uint32_t *cf = NULL, *cz = NULL;
    size_t nf = 0;
    render("forward-spml", &o, s, &ref);
    for (size_t k = 0; k < NKINDS; k++) {
        render_counts(KINDS[k], &o, s, &t, k == 0 ? &cf : NULL);
        nf = k == 0 ? t.ngrid : nf;
        char what[64];
        snprintf(what, sizeof what, "%s, 4096 lights", KINDS[k]);
        expect_agree(what, &t.img, &ref.img);
        assert_int_equal(t.fs.total.dispatches, 1);
        assert_true(t.fs.lights_drawn > 1000);
        image_free(&t.img);
    }
    render_counts("zbin", &o, s, &z, &cz);
    print_message("zbin, 4096 lights: %u sorted, %d sort dispatches\n", z.fs.lights_drawn,
                  zbin_dispatches(z.fs.lights_drawn));
    expect_agree("zbin, 4096 lights", &z.img, &ref.img);
    assert_true(zbin_dispatches(z.fs.lights_drawn) > 2);
    assert_int_equal(find_pass(&z.fs, "cull")->dispatches,
                     zbin_dispatches(z.fs.lights_drawn) + 1);
    assert_int_equal(z.ngrid, nf);
    for (size_t c = 0; c < nf; c++)
        if (cz[c] != cf[c])
            fail_msg("4096 lights: tile %zu: zbin %u lights, forward-plus %u", c, cz[c], cf[c]);
    free(cf);
    free(cz);
    image_free(&z.img);
    image_free(&ref.img);

    /* the uniform block cannot hold them: refused with the numbers, storage named */
    o.light_buffer = LIGHT_BUFFER_UNIFORM;
    renderer *r = test_renderer_create("forward-spml", &o, err, sizeof err);
    assert_non_null(r);
    assert_false(renderer_prepare(r, s, err, sizeof err));
    assert_non_null(strstr(err, "4096 lights requested"));
    assert_non_null(strstr(err, "forward.light_buffer: storage"));
    renderer_destroy(r);
    scene_destroy(s);

    /* 4,096 lights over the middle of the floor, every one reaching the tiles there */
    scene_light *many = calloc(4096, sizeof *many);
    for (int i = 0; i < 4096; i++) {
        many[i] = point(-2.0f + 0.001f * (float)i, 1.0f, 0.0f, 6.0f);
        many[i].color[0] = many[i].color[1] = many[i].color[2] = 0.0002f;
    }
    s = shapes(many, 4096);
    free(many);
    o = options();
    render("forward-spml", &o, s, &ref);
    for (size_t k = 0; k < NKINDS; k++) {
        render(KINDS[k], &o, s, &t);
        char what[64];
        snprintf(what, sizeof what, "%s, 4096 lights in one tile", KINDS[k]);
        expect_agree(what, &t.img, &ref.img);
        assert_true(t.fs.grid_lights_max == 4096.0);
        assert_int_equal(t.fs.overflow[0], '\0');
        image_free(&t.img);
    }
    image_free(&ref.img);
    scene_destroy(s);
}

/* An index buffer too small for a frame's lists (tiles.max_lights_per_tile 1 with 64
 * overlapping lights): the frame reports the total, the capacity and the longest
 * list, never a truncated image that passes. */
static void test_overflow_is_reported(void **state)
{
    (void)state;
    scene_light l[64];
    for (int i = 0; i < 64; i++)
        l[i] = point(0.0625f * (float)i - 2.0f, 2.0f, 0.0f, 20.0f);
    scene *s = shapes(l, 64);
    renderer_options o = options();
    o.max_lights_per_tile = 1;
    shot t;
    render("forward-plus", &o, s, &t);
    print_message("overflow: %s\n", t.fs.overflow);
    assert_non_null(strstr(t.fs.overflow, "forward-plus: the tiles' light lists need "));
    assert_non_null(strstr(t.fs.overflow, " indices, the index buffer holds 28; tile "));
    assert_non_null(strstr(t.fs.overflow, " alone needs 64"));
    image_free(&t.img);
    render("clustered", &o, s, &t);
    print_message("overflow: %s\n", t.fs.overflow);
    char want[96];
    snprintf(want, sizeof want, " indices, the index buffer holds %u; cluster ",
             28u * shading_cluster_slices(s, 24, NULL));
    assert_non_null(strstr(t.fs.overflow, "clustered: the clusters' light lists need "));
    assert_non_null(strstr(t.fs.overflow, want));
    assert_non_null(strstr(t.fs.overflow, " alone needs 64"));
    image_free(&t.img);
    scene_destroy(s);
}

/* Without point or spot lights there is nothing to cull: no cull pass, no dispatch,
 * and the plan says why; the image still agrees. */
static void test_no_cull_without_local_lights(void **state)
{
    (void)state;
    scene_light sun = {.type = LIGHT_DIRECTIONAL, .direction = {-0.4f, -1.0f, -0.3f},
                       .color = {0.8f, 0.8f, 0.7f}};
    sm_vec3_normalize(sun.direction);
    scene *s = shapes(&sun, 1);
    renderer_options o = options();
    shot ref, t;
    render("forward-spml", &o, s, &ref);
    for (size_t k = 0; k < NKINDS; k++) {
        render(KINDS[k], &o, s, &t);
        assert_null(find_pass(&t.fs, "cull"));
        assert_int_equal(t.fs.grid_cells, 0);
        assert_int_equal(t.fs.grid_pass, 0);
        if (strcmp(KINDS[k], "tiled-deferred") == 0) {
            /* its one dispatch shades too: it runs, without culling */
            assert_int_equal(t.fs.total.dispatches, 1);
            const pass_plan_entry *e = plan_pass(&t.plan, "tiled");
            assert_non_null(e);
            assert_true(e->run);
            assert_non_null(strstr(e->reason, "no point or spot light: no culling"));
        } else {
            assert_int_equal(t.fs.total.dispatches, 0);
            const pass_plan_entry *e = plan_pass(&t.plan, "cull");
            assert_non_null(e);
            assert_false(e->run);
            assert_string_equal(e->reason, "skipped, the scene has no point or spot light");
        }
        char what[64];
        snprintf(what, sizeof what, "%s, one directional light", KINDS[k]);
        expect_agree(what, &t.img, &ref.img);
        image_free(&t.img);
    }
    image_free(&ref.img);
    scene_destroy(s);
}

/* interior: a shadowing moon, omni lights and shadowing spots; with shadows on and
 * off the images agree and the shadows pass draws what forward-spml's does. */
static void test_shadows_on_and_off(void **state)
{
    (void)state;
    char err[256];
    light_params lp = {.placement = PLACEMENT_SCENE, .radius = 1.0f,
                       .count = {.start = LIGHT_COUNT_ALL, .max = LIGHT_COUNT_ALL}};
    scene *s = scene_build("interior", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("interior: %s", err);
    scene_update(s, 15.0);
    for (int off = 0; off < 2; off++) {
        renderer_options o = options();
        o.no_shadows = off;
        shot ref, t;
        render("forward-spml", &o, s, &ref);
        for (size_t k = 0; k < NKINDS; k++) {
            render(KINDS[k], &o, s, &t);
            const pass_stats *a = find_pass(&ref.fs, "shadows"), *b = find_pass(&t.fs, "shadows");
            if (off) {
                assert_null(a);
                assert_null(b);
            } else {
                assert_non_null(a);
                assert_non_null(b);
                assert_true(a->draw_calls > 0);
                assert_int_equal(a->draw_calls, b->draw_calls);
            }
            char what[64];
            snprintf(what, sizeof what, "%s, interior, shadows %s", KINDS[k], off ? "off" : "on");
            expect_agree(what, &t.img, &ref.img);
            image_free(&t.img);
        }
        image_free(&ref.img);
    }
    scene_destroy(s);
}

/* tiled-deferred reads every G-buffer preset and field override of deferred: against
 * deferred with the same G-buffer (full-screen lights) it agrees, and the plan lists
 * the light passes as done in the tiled pass. */
static void test_tiled_deferred_gbuffers(void **state)
{
    (void)state;
    scene_light l[6];
    for (int i = 0; i < 5; i++)
        l[i] = point((float)i * 6.0f - 12.0f, 3.0f, (float)(i % 2) * 6.0f - 3.0f, 9.0f);
    l[5] = (scene_light){.type = LIGHT_DIRECTIONAL, .direction = {-0.4f, -1.0f, -0.3f},
                         .color = {0.3f, 0.3f, 0.25f}};
    sm_vec3_normalize(l[5].direction);
    scene *s = shapes(l, 6);
    static const struct {
        gbuffer_preset preset;
        gbuffer_position position;
        gbuffer_normal normal;
        const char *name;
    } g[] = {
        {GBUFFER_CURTIS, 0, 0, "curtis"},
        {GBUFFER_FAT, 0, 0, "fat"},
        {GBUFFER_COMPACT, 0, 0, "compact"},
        {GBUFFER_SPHEREMAP, 0, 0, "spheremap"},
        {GBUFFER_REFERENCE, 0, 0, "reference"},
        {GBUFFER_CURTIS, GBUFFER_POSITION_DEPTH, GBUFFER_NORMAL_SPHEREMAP8,
         "curtis, position from depth, spheremap8 normals"},
        {GBUFFER_FAT, GBUFFER_POSITION_STORED32, GBUFFER_NORMAL_UNORM10,
         "fat, position float32, unorm10 normals"},
    };
    for (size_t i = 0; i < sizeof g / sizeof g[0]; i++) {
        renderer_options o = options();
        o.gbuffer = g[i].preset;
        o.gbuffer_position = g[i].position;
        o.gbuffer_normal = g[i].normal;
        o.light_volumes = LIGHT_VOLUMES_FULLSCREEN;
        shot d, t;
        render("deferred", &o, s, &d);
        render("tiled-deferred", &o, s, &t);
        assert_int_equal(t.plan.gbuffer_bytes, d.plan.gbuffer_bytes);
        const pass_plan_entry *e = plan_pass(&t.plan, "point");
        assert_non_null(e);
        assert_false(e->run);
        assert_string_equal(e->reason, "in the tiled pass");
        char what[96];
        snprintf(what, sizeof what, "tiled-deferred vs deferred, %s", g[i].name);
        expect_agree(what, &t.img, &d.img);
        image_free(&t.img);
        image_free(&d.img);
    }
    /* one target: no separate specular */
    renderer_options o = options();
    o.separate_specular = true;
    char err[256];
    assert_null(test_renderer_create("tiled-deferred", &o, err, sizeof err));
    assert_non_null(strstr(err, "tiled-deferred: deferred.separate_specular: "));
    scene_destroy(s);
}

/* clustered with clustered.shading: deferred: the G-buffer, one clustered compute
 * pass; agrees with forward-spml (16 lights, 4,096 lights, shadows on and off) and
 * with deferred on other G-buffers; the same clusters as clustered forward. */
static void test_clustered_deferred(void **state)
{
    (void)state;
    scene_light l[16];
    for (int i = 0; i < 16; i++)
        l[i] = point((float)(i % 4) * 8.0f - 12.0f, 3.0f, (float)(i / 4) * 8.0f - 12.0f, 7.0f);
    scene *s = shapes(l, 16);
    renderer_options o = options();
    shot ref, t, f;
    render("forward-spml", &o, s, &ref);
    uint32_t v = (uint32_t)find_pass(&ref.fs, "shade")->draw_calls;
    render("clustered", &o, s, &f);
    o.clustered_deferred = true;
    render("clustered", &o, s, &t);
    assert_string_equal(t.fs.pass[0].name, "gbuffer");
    assert_string_equal(t.fs.pass[1].name, "tiled");
    assert_int_equal(t.fs.pass[1].dispatches, 1);
    assert_int_equal(t.fs.total.draw_calls, v + (s->sky ? 1u : 0u) + 1u);
    uint32_t cells = ((W + 15) / 16) * ((H + 15) / 16) * shading_cluster_slices(s, 24, NULL);
    assert_int_equal(t.fs.grid_cells, cells);
    assert_int_equal(t.ngrid, cells);
    const pass_plan_entry *e = plan_pass(&t.plan, "tiled");
    assert_non_null(e);
    assert_non_null(strstr(e->reason, "clusters"));
    expect_agree("clustered deferred vs forward-spml", &t.img, &ref.img);
    expect_agree("clustered deferred vs clustered forward", &t.img, &f.img);
    image_free(&t.img);
    image_free(&f.img);
    image_free(&ref.img);
    /* the curtis G-buffer: against deferred with the same */
    o.gbuffer = GBUFFER_CURTIS;
    o.light_volumes = LIGHT_VOLUMES_FULLSCREEN;
    render("deferred", &o, s, &ref);
    render("clustered", &o, s, &t);
    expect_agree("clustered deferred vs deferred, curtis", &t.img, &ref.img);
    image_free(&t.img);
    image_free(&ref.img);
    scene_destroy(s);

    char err[256];
    light_params lp = {.placement = PLACEMENT_RANDOM, .seed = 1337, .rng = RNG_MSVC,
                       .count = {.start = 4096, .max = 4096}, .radius = 3.0f,
                       .color_max = 0.3f};
    s = scene_build("curtis-scene3", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("curtis-scene3: %s", err);
    scene_update(s, 5.0);
    o = options();
    render("forward-spml", &o, s, &ref);
    o.clustered_deferred = true;
    render("clustered", &o, s, &t);
    expect_agree("clustered deferred, 4096 lights", &t.img, &ref.img);
    image_free(&t.img);
    image_free(&ref.img);
    scene_destroy(s);

    light_params sp = {.placement = PLACEMENT_SCENE, .radius = 1.0f,
                       .count = {.start = LIGHT_COUNT_ALL, .max = LIGHT_COUNT_ALL}};
    s = scene_build("interior", &sp, W, H, err, sizeof err);
    if (!s)
        fail_msg("interior: %s", err);
    scene_update(s, 15.0);
    for (int off = 0; off < 2; off++) {
        o = options();
        o.no_shadows = off;
        render("forward-spml", &o, s, &ref);
        o.clustered_deferred = true;
        render("clustered", &o, s, &t);
        assert_true(off ? find_pass(&t.fs, "shadows") == NULL
                        : find_pass(&t.fs, "shadows") != NULL);
        expect_agree(off ? "clustered deferred, interior, shadows off"
                         : "clustered deferred, interior, shadows on", &t.img, &ref.img);
        image_free(&t.img);
        image_free(&ref.img);
    }
    scene_destroy(s);
}

/* Catalog scene `name` at 5 s with n random lights of radius 3 (seed 1337). */
static scene *radius3_scene(const char *name, uint32_t n)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_RANDOM, .seed = 1337, .rng = RNG_MSVC,
                       .count = {.start = n, .max = n}, .radius = 3.0f, .color_max = 0.3f};
    scene *s = scene_build(name, &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("%s: %s", name, err);
    scene_update(s, 5.0);
    return s;
}

/* A culling option of issue 37 (set() turns it off and on): on curtis-scene3 and
 * canyon with 2,000 radius-3 lights, each kind's list of every tile (cluster) with it
 * on is at most as long as with it off, cell by cell, and the lists are shorter in all
 * (the option does something): fewer light evaluations a pixel; the image still
 * forward-spml's, and byte for byte the option off's (msaa 1). With `pass`, the
 * option only adds that pass, of one dispatch: every list exactly as long as without. */
static void expect_lights(const char *name, void (*set)(renderer_options *, bool),
                          const char *pass)
{
    static const char *const scenes[] = {"curtis-scene3", "canyon"};
    for (size_t i = 0; i < 2; i++) {
        scene *s = radius3_scene(scenes[i], 2000);
        renderer_options o = options();
        shot ref, a, b;
        render("forward-spml", &o, s, &ref);
        for (size_t k = 0; k < NKINDS; k++) {
            uint32_t *ca = NULL, *cb = NULL;
            set(&o, false);
            render_counts(KINDS[k], &o, s, &a, &ca);
            set(&o, true);
            render_counts(KINDS[k], &o, s, &b, &cb);
            print_message("%s, %s: lights a cell %.4f (off) %.4f (%s), evaluations a "
                          "pixel %.3f %.3f\n", scenes[i], KINDS[k], a.fs.grid_lights_mean,
                          b.fs.grid_lights_mean, name, a.fs.light_evals_per_pixel,
                          b.fs.light_evals_per_pixel);
            assert_true(a.ngrid > 0);
            assert_int_equal(a.ngrid, b.ngrid);
            for (size_t c = 0; c < a.ngrid; c++)
                if (pass ? cb[c] != ca[c] : cb[c] > ca[c])
                    fail_msg("%s, %s: cell %zu: %u lights with %s, %u without",
                             scenes[i], KINDS[k], c, cb[c], name, ca[c]);
            if (pass) {
                assert_null(find_pass(&a.fs, pass));
                assert_non_null(find_pass(&b.fs, pass));
                assert_int_equal(find_pass(&b.fs, pass)->dispatches, 1);
                assert_int_equal(b.fs.npasses, a.fs.npasses + 1);
                assert_true(b.fs.light_evals_per_pixel == a.fs.light_evals_per_pixel);
            } else {
                assert_true(b.grid_sum < a.grid_sum);
                assert_true(b.fs.light_evals_per_pixel < a.fs.light_evals_per_pixel);
            }
            assert_int_equal(b.fs.grid_covered, a.fs.grid_covered);
            char what[96];
            snprintf(what, sizeof what, "%s, %s, %s", scenes[i], KINDS[k], name);
            expect_agree(what, &b.img, &ref.img);
            /* the lights dropped reach no shaded position: the same image, byte for byte */
            if (memcmp(a.img.pixels, b.img.pixels, (size_t)W * H * 4) != 0)
                fail_msg("%s: the image differs from the default's", what);
            free(ca);
            free(cb);
            image_free(&a.img);
            image_free(&b.img);
        }
        image_free(&ref.img);
        scene_destroy(s);
    }
}

static void set_mask(renderer_options *o, bool on)
{
    o->depth_mask = on;
}

static void set_prune(renderer_options *o, bool on)
{
    o->prune_samples = on;
}

static void set_levels(renderer_options *o, bool on)
{
    o->tile_levels = on ? 2 : 1;
}

/* tiles.depth_culling: mask (Harada's 2.5D culling) against minmax. */
static void test_depth_mask(void **state)
{
    (void)state;
    expect_lights("mask", set_mask, NULL);
}

/* tiles.prune: samples (HDRP's fine pruning) against bounds. */
static void test_prune_samples(void **state)
{
    (void)state;
    expect_lights("prune samples", set_prune, NULL);
}

/* tiles.levels: 2 (HDRP's and Unreal's two-level culling) against 1: the same lists, the
 * coarse pass of its own. */
static void test_two_levels(void **state)
{
    (void)state;
    expect_lights("levels 2", set_levels, "cull-coarse");
    renderer_options o = options();
    o.tile_levels = 2;
    o.tile_size = 16;
    o.coarse_size = 40;   /* not a multiple of the tile: refused at create */
    char err[256] = "";
    assert_null(test_renderer_create("forward-plus", &o, err, sizeof err));
    assert_string_equal(err, "forward-plus: tiles.coarse_size 40: expected a multiple of "
                             "tiles.size (16) up to 512");
}

/* Issue 37, zbin (Drobot 2017) beside forward-plus at the same tile size, on
 * curtis-scene3 and canyon with 300 radius-3 lights: its tiles keep exactly
 * forward-plus's lights (the same tests, as bit masks), and its light evaluations a
 * pixel (each pixel's mask bits within its depth bin) are at most forward-plus's, and
 * fewer in all; forward and deferred shading count the same; the image is
 * forward-spml's. Its light-structure bytes are reported and are exactly the sorted
 * lights + the bins + tiles x ceil(lights / 32) mask words: with 600 lights they grow
 * by the lights, and with 4096 bins instead of 1024 by 3072 words, not by bins x tiles.
 * Its cull pass is the sort's and bins' dispatches (zbin_dispatches) and the masks',
 * skipped with no local light. */
static double zbin_bytes(const shot *z, uint32_t bins)
{
    double tiles = ((W + 15) / 16) * ((H + 15) / 16), n = z->fs.lights_drawn;
    return n * sizeof(gpu_light) + 16 + bins * 4.0 + tiles * ceil(n / 32.0) * 4.0;
}

static void test_zbin_work(void **state)
{
    (void)state;
    static const char *const scenes[] = {"curtis-scene3", "canyon"};
    for (size_t i = 0; i < 2; i++) {
        double bytes[2] = {0};
        for (int pass = 0; pass < 2; pass++) {
            uint32_t nl = pass ? 600 : 300;
            scene *s = radius3_scene(scenes[i], nl);
            renderer_options o = options();
            shot ref, fp, z, zd;
            uint32_t *cf = NULL, *cz = NULL;
            render("forward-spml", &o, s, &ref);
            render_counts("forward-plus", &o, s, &fp, &cf);
            render_counts("zbin", &o, s, &z, &cz);
            print_message("%s, %u lights: evaluations a pixel: forward-plus %.3f, zbin %.3f; "
                          "light-structure bytes: forward-plus %.0f, zbin %.0f\n", scenes[i],
                          nl, fp.fs.light_evals_per_pixel, z.fs.light_evals_per_pixel,
                          fp.fs.light_struct_bytes, z.fs.light_struct_bytes);
            assert_int_equal(z.ngrid, fp.ngrid);
            for (size_t c = 0; c < z.ngrid; c++)
                if (cz[c] != cf[c])
                    fail_msg("%s: tile %zu: zbin %u lights, forward-plus %u", scenes[i], c,
                             cz[c], cf[c]);
            assert_int_equal(z.fs.grid_covered, fp.fs.grid_covered);
            assert_int_equal(find_pass(&z.fs, "cull")->dispatches,
                             zbin_dispatches(z.fs.lights_drawn) + 1);
            assert_true(z.fs.light_evals_per_pixel <= fp.fs.light_evals_per_pixel);
            assert_true(z.fs.light_evals_per_pixel < fp.fs.light_evals_per_pixel);
            assert_int_equal(z.fs.translucent_lists, 0);
            assert_true(z.fs.light_struct_bytes == zbin_bytes(&z, 1024));
            bytes[pass] = z.fs.light_struct_bytes;
            expect_agree(scenes[i], &z.img, &ref.img);
            o.zbin_deferred = true;
            render("zbin", &o, s, &zd);
            assert_true(zd.fs.light_evals_per_pixel == z.fs.light_evals_per_pixel);
            expect_agree(scenes[i], &zd.img, &ref.img);
            image_free(&zd.img);
            if (pass) {   /* 4096 bins: 3072 words more, whatever the tiles */
                o.zbin_deferred = false;
                o.zbin_bins = 4096;
                render("zbin", &o, s, &zd);
                assert_true(zd.fs.light_struct_bytes == z.fs.light_struct_bytes + 3072 * 4);
                assert_true(zd.fs.light_evals_per_pixel <= z.fs.light_evals_per_pixel);
                image_free(&zd.img);
            }
            free(cf);
            free(cz);
            image_free(&ref.img);
            image_free(&fp.img);
            image_free(&z.img);
            scene_destroy(s);
        }
        assert_true(bytes[1] > bytes[0]);
    }
    /* pass pruning: one directional light, nothing sorted or culled */
    scene_light sun = {.type = LIGHT_DIRECTIONAL, .direction = {0.0f, -1.0f, 0.0f},
                       .color = {0.8f, 0.8f, 0.7f}};
    scene *s = shapes(&sun, 1);
    renderer_options o = options();
    shot t;
    render("zbin", &o, s, &t);
    assert_null(find_pass(&t.fs, "cull"));
    assert_int_equal(t.fs.total.dispatches, 0);
    const pass_plan_entry *e = plan_pass(&t.plan, "cull");
    assert_non_null(e);
    assert_false(e->run);
    assert_string_equal(e->reason, "skipped, the scene has no point or spot light");
    image_free(&t.img);
    scene_destroy(s);
}

/* tiles.levels: 2 for zbin (forward and deferred shading, and forward with tiles.prune:
 * samples), on curtis-scene3 and canyon with 600 radius-3 lights: cull-coarse sorts the
 * lights and culls the sorted ones into big tiles (the sort's dispatches and one), the
 * tiles' masks are then one dispatch; every tile's mask holds exactly levels 1's
 * lights, the evaluations a pixel are the same, and the image is levels 1's byte for
 * byte and forward-spml's. */
static void test_zbin_two_levels(void **state)
{
    (void)state;
    static const char *const scenes[] = {"curtis-scene3", "canyon"};
    static const char *const fine[] = {"cull", "tiled", "cull"};
    for (size_t i = 0; i < 2; i++) {
        scene *s = radius3_scene(scenes[i], 600);
        renderer_options o = options();
        shot ref;
        render("forward-spml", &o, s, &ref);
        for (int v = 0; v < 3; v++) {   /* forward, deferred, forward pruned by samples */
            shot a, b;
            uint32_t *ca = NULL, *cb = NULL;
            o.zbin_deferred = v == 1;
            o.prune_samples = v == 2;
            o.tile_levels = 1;
            render_counts("zbin", &o, s, &a, &ca);
            o.tile_levels = 2;
            render_counts("zbin", &o, s, &b, &cb);
            print_message("%s, zbin %s: levels 2: evaluations a pixel %.3f (levels 1 %.3f)\n",
                          scenes[i], fine[v], b.fs.light_evals_per_pixel,
                          a.fs.light_evals_per_pixel);
            assert_true(a.ngrid > 0);
            assert_int_equal(b.ngrid, a.ngrid);
            for (size_t c = 0; c < a.ngrid; c++)
                if (cb[c] != ca[c])
                    fail_msg("%s, %d: tile %zu: %u lights at levels 2, %u at 1", scenes[i], v,
                             c, cb[c], ca[c]);
            assert_true(b.fs.light_evals_per_pixel == a.fs.light_evals_per_pixel);
            assert_int_equal(b.fs.grid_covered, a.fs.grid_covered);
            assert_null(find_pass(&a.fs, "cull-coarse"));
            assert_int_equal(find_pass(&b.fs, "cull-coarse")->dispatches,
                             zbin_dispatches(b.fs.lights_drawn) + 1);
            assert_int_equal(find_pass(&b.fs, fine[v])->dispatches, 1);
            assert_int_equal(find_pass(&a.fs, fine[v])->dispatches,
                             zbin_dispatches(a.fs.lights_drawn) + 1);
            expect_agree(scenes[i], &b.img, &ref.img);
            if (memcmp(a.img.pixels, b.img.pixels, (size_t)W * H * 4) != 0)
                fail_msg("%s, %d: the image differs from levels 1's", scenes[i], v);
            free(ca);
            free(cb);
            image_free(&a.img);
            image_free(&b.img);
        }
        image_free(&ref.img);
        scene_destroy(s);
    }
}

/* The bandwidth model's bytes (seed 002, issue 37 item 5): zbin with zbin.shading:
 * deferred reports exactly tiled-deferred's G-buffer writes and reads for the same
 * layout and scene (its G-buffer pass and one compute pass reading every pixel), at
 * two layouts; with forward shading, none (NaN: no G-buffer), as forward-plus. */
static void test_zbin_traffic(void **state)
{
    (void)state;
    scene_light l[4];
    for (int i = 0; i < 4; i++)
        l[i] = point((float)i * 8.0f - 12.0f, 3.0f, 0.0f, 9.0f);
    scene *s = shapes(l, 4);
    static const gbuffer_preset layouts[] = {GBUFFER_REFERENCE, GBUFFER_COMPACT};
    for (size_t k = 0; k < 2; k++) {
        renderer_options o = options();
        o.gbuffer = layouts[k];
        shot td, z;
        render("tiled-deferred", &o, s, &td);
        o.zbin_deferred = true;
        render("zbin", &o, s, &z);
        print_message("gbuffer %zu: write %.0f read %.0f bytes (tiled-deferred %.0f %.0f)\n", k,
                      z.traffic.write_bytes, z.traffic.read_bytes, td.traffic.write_bytes,
                      td.traffic.read_bytes);
        assert_true(td.traffic.write_bytes > 0.0 && td.traffic.read_bytes > 0.0);
        assert_true(z.traffic.write_bytes == td.traffic.write_bytes);
        assert_true(z.traffic.read_bytes == td.traffic.read_bytes);
        image_free(&td.img);
        image_free(&z.img);
        o.zbin_deferred = false;
        render("zbin", &o, s, &z);
        assert_true(isnan(z.traffic.write_bytes) && isnan(z.traffic.read_bytes));
        image_free(&z.img);
    }
    scene_destroy(s);
}

GL_TEST_MAIN(ctx, W, H,
             cmocka_unit_test(test_counts_and_tile_sizes),
             cmocka_unit_test(test_4096_lights),
             cmocka_unit_test(test_overflow_is_reported),
             cmocka_unit_test(test_no_cull_without_local_lights),
             cmocka_unit_test(test_shadows_on_and_off),
             cmocka_unit_test(test_tiled_deferred_gbuffers),
             cmocka_unit_test(test_clustered_deferred),
             cmocka_unit_test(test_depth_mask),
             cmocka_unit_test(test_prune_samples),
             cmocka_unit_test(test_two_levels),
             cmocka_unit_test(test_zbin_work),
             cmocka_unit_test(test_zbin_two_levels),
             cmocka_unit_test(test_zbin_traffic))
