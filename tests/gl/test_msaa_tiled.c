/* MSAA (issue 12) in the tiled forward renderers, forward-plus and clustered
 * (renderers/forward_plus.c): at msaa 4 each agrees with forward-spml at msaa 4 (its
 * lights from storage) within RMSE 1/255 and max 4/255 on the 8-bit output, on the
 * agreement cases (tests/gl/test_agreement.c's lights and cameras, at a smaller size
 * whose last tiles are partial), with no non-finite value in the HDR target; small
 * lights that reach only what lies at the far end of a tile's depth range (behind a
 * sphere's rim, beyond the floor's far edge: samples off the pixel centres, and the
 * extrapolated centres of partly covered pixels) are lit the same, at msaa 2, 4 and 8
 * (where the context allows them); the draws and dispatches are those of msaa 1, plus
 * the pass msaa-resolve (clustered with clustered.shading: deferred at msaa 4:
 * tests/gl/test_msaa.c).
 * Debug contexts: any GL error fails. */
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
#include "common/image_io.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

/* Not multiples of 16: the last column and row of tiles are partial. */
enum { W = 100, H = 60 };
#define RMSE_MAX (1.0 / 255.0)
#define MAX_ABS_MAX (4.0 / 255.0)

static gl_context *ctx;

static const char *const KINDS[] = {"forward-plus", "clustered"};
enum { NKINDS = 2 };

typedef struct shot {
    image img;
    frame_stats fs;
    pass_plan plan;
} shot;

static int context_limit(void)
{
    GLint ms = 0, mc = 0, md = 0;
    gl.GetIntegerv(GL_MAX_SAMPLES, &ms);
    gl.GetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &mc);
    gl.GetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &md);
    int l = ms < mc ? ms : mc;
    return l < md ? l : md;
}

static renderer_options options(int msaa)
{
    const gl_info *gi = gl_context_info(ctx);
    return (renderer_options){
        .width = W, .height = H, .queries = true,
        .timer_query = gi->timer_query, .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size,
        .gbuffer = GBUFFER_REFERENCE, .light_buffer = LIGHT_BUFFER_STORAGE, .msaa = msaa,
    };
}

/* One frame of s by kind at msaa: the output, the frame's stats (after collect) and
 * the plan; fails on a GL error or a non-finite HDR value. */
static void render(const char *kind, int msaa, scene *s, shot *out)
{
    char err[512];
    memset(out, 0, sizeof *out);
    renderer_options o = options(msaa);
    renderer *r = test_renderer_create(kind, &o, err, sizeof err);
    if (!r || !renderer_prepare(r, s, err, sizeof err))
        fail_msg("%s msaa %d: %s", kind, msaa, err);
    renderer_draw(r, s, &out->fs);
    gl.Finish();
    renderer_collect(r, &out->fs);
    renderer_describe(r, &out->plan);
    float *hdr = malloc((size_t)W * H * 4 * sizeof *hdr);
    size_t nonfinite = 1;
    assert_true(renderer_read_hdr(r, hdr, W, H, &nonfinite));
    assert_int_equal(nonfinite, 0);
    free(hdr);
    out->img = (image){.width = W, .height = H, .channels = 4, .type = IMAGE_U8,
                       .pixels = malloc((size_t)W * H * 4)};
    assert_true(gl_context_read_rgba8(ctx, out->img.pixels, err, sizeof err));
    renderer_destroy(r);
    gl_context_poll_errors(ctx, kind);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static void expect_agree(const char *what, const image *a, const image *b)
{
    gl_test_expect_agree(what, a, b, RMSE_MAX, MAX_ABS_MAX, false);
}

/* "shapes" at t = 0 with exactly these lights, seen from eye towards target. */
static scene *shapes(const scene_light *lights, uint32_t n, const float eye[3],
                     const float target[3])
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
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3_copy(eye, s->cam.eye);
    sm_vec3_copy(target, s->cam.target);
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
    return s;
}

static const float EYE[3] = {0.0f, 12.0f, 28.0f}, TARGET[3] = {0.0f, 1.0f, 0.0f};

static scene_light point(float x, float y, float z, float radius, float r, float g, float b)
{
    return (scene_light){.type = LIGHT_POINT, .position = {x, y, z}, .color = {r, g, b},
                         .radius = radius, .attenuation = ATTENUATION_LINEAR_RANGE};
}

static scene_light spot(float x, float y, float z, float dx, float dy, float dz, float radius,
                        float angle_deg)
{
    scene_light l = {.type = LIGHT_SPOT, .position = {x, y, z}, .direction = {dx, dy, dz},
                     .color = {1.0f, 0.9f, 0.7f}, .radius = radius,
                     .spot_angle = sm_deg2rad(angle_deg), .spot_exponent = 4.0f,
                     .attenuation = ATTENUATION_LINEAR_RANGE};
    sm_vec3_normalize(l.direction);
    return l;
}

/* s at msaa: each tiled renderer against forward-spml (storage); the reference's
 * image into *ref when not NULL. */
static void expect_case(const char *name, scene *s, int msaa, image *ref)
{
    shot spml, t;
    render("forward-spml", msaa, s, &spml);
    for (size_t k = 0; k < NKINDS; k++) {
        render(KINDS[k], msaa, s, &t);
        assert_non_null(find_pass(&t.fs, "msaa-resolve"));
        char what[160];
        snprintf(what, sizeof what, "%s, msaa %d: %s vs forward-spml", name, msaa, KINDS[k]);
        expect_agree(what, &t.img, &spml.img);
        image_free(&t.img);
    }
    if (ref)
        *ref = spml.img;
    else
        image_free(&spml.img);
}

/* test_agreement.c's light cases at msaa 4 */
static void test_agreement_cases(void **state)
{
    (void)state;
    if (context_limit() < 4)
        skip();
    struct {
        const char *name;
        float eye[3], target[3];
        uint32_t n;
        scene_light l[16];
    } cases[] = {
        {"one point light", {0, 12, 28}, {0, 1, 0}, 1, {point(0, 6, 4, 14, 1.0f, 0.9f, 0.8f)}},
        {"one spot light", {0, 12, 28}, {0, 1, 0}, 1, {spot(0, 10, 0, 0.2f, -1, 0.1f, 20, 30)}},
        {"one directional light", {0, 12, 28}, {0, 1, 0}, 1, {{0}}},
        {"16 point lights", {0, 12, 28}, {0, 1, 0}, 16, {{0}}},
        {"camera inside a point volume", {0, 12, 28}, {0, 1, 0}, 1,
         {point(0, 11, 25, 30, 1.0f, 1.0f, 1.0f)}},
        {"volume cut by the near plane", {0.0f, 3.0f, 12.0f}, {0, 0, 0}, 1,
         {point(0, 1.0f, 9.6f, 3.0f, 1.0f, 0.8f, 0.6f)}},
    };
    cases[2].l[0] = (scene_light){.type = LIGHT_DIRECTIONAL, .direction = {-0.4f, -1.0f, -0.3f},
                                  .color = {0.8f, 0.8f, 0.7f}};
    sm_vec3_normalize(cases[2].l[0].direction);
    for (int i = 0; i < 16; i++) {
        float x = (float)(i % 4) * 8.0f - 12.0f, z = (float)(i / 4) * 8.0f - 12.0f;
        cases[3].l[i] = point(x, 3.0f + (float)(i % 3), z, 7.0f, 0.2f + 0.05f * (float)(i % 5),
                              0.3f, 0.5f - 0.02f * (float)i);
    }
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        scene *s = shapes(cases[c].l, cases[c].n, cases[c].eye, cases[c].target);
        expect_case(cases[c].name, s, 4, NULL);
        scene_destroy(s);
    }
}

/* Lights that reach only what is at the far end of a tile's depth range, seen
 * against the sky: (1) the sphere at (0, 2.2, 10) (radius 2) seen level from (0, 2.2,
 * 24), a small light just behind its right rim (the tangent points of the eye's rays
 * are 4/14 towards the eye, 1.98 beside the centre); (2) the floor seen at a grazing
 * angle from 1 above it, a light just beyond its far edge (z = -40), reaching only
 * its last half unit, a fraction of a pixel row whose samples (and the extrapolated
 * centres of its partly covered pixels) lie deeper than most of the row. Each must be
 * lit as forward-spml lights it, at msaa 2, 4 and 8 (as far as the context allows). */
static void test_light_at_the_silhouette(void **state)
{
    (void)state;
    int limit = context_limit();
    if (limit < 2)
        skip();
    static const struct {
        const char *name;
        float eye[3], target[3], light[3], radius;
    } cases[] = {
        {"a light behind the sphere's rim", {0, 2.2f, 24}, {0, 2.2f, 10}, {2.35f, 2.2f, 9.7f},
         0.9f},
        {"a light beyond the floor's far edge", {5, 1, -25}, {5, 1, -40}, {5, 0.3f, -40.5f},
         1.0f},
    };
    static const int counts[] = {2, 4, 8};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        scene_light l = point(cases[c].light[0], cases[c].light[1], cases[c].light[2],
                              cases[c].radius, 4.0f, 4.0f, 4.0f);
        scene *s = shapes(&l, 1, cases[c].eye, cases[c].target);
        for (size_t i = 0; i < 3; i++) {
            if (counts[i] > limit)
                continue;
            image lit = {0};
            expect_case(cases[c].name, s, counts[i], &lit);
            /* the light really lights something: the same view without it differs */
            s->nlights_active = 0;
            s->count.start = s->count.max = 0;
            shot dark;
            render("forward-spml", counts[i], s, &dark);
            s->nlights_active = 1;
            s->count.start = s->count.max = 1;
            image_error e;
            char err[256];
            assert_true(image_compare(&lit, &dark.img, &e, err, sizeof err));
            print_message("%s, msaa %d: it changes %.4f of the pixels, max %.0f/255\n",
                          cases[c].name, counts[i], e.frac_over_1_255, e.max_abs * 255);
            assert_true(e.frac_over_1_255 > 0.0);
            assert_true(e.max_abs >= 16.0 / 255.0);
            image_free(&lit);
            image_free(&dark.img);
        }
        scene_destroy(s);
    }
}

/* Sixteen point lights: at msaa 4 the same draws per pass and the same one dispatch
 * as at msaa 1, the same grid; the passes those of msaa 1 with msaa-resolve before
 * the resolve; the cull reads the 4-sample depth. */
static void test_counts_at_msaa4(void **state)
{
    (void)state;
    if (context_limit() < 4)
        skip();
    scene_light l[16];
    for (int i = 0; i < 16; i++)
        l[i] = point((float)(i % 4) * 8.0f - 12.0f, 3.0f, (float)(i / 4) * 8.0f - 12.0f, 7.0f,
                     0.4f, 0.4f, 0.4f);
    scene *s = shapes(l, 16, EYE, TARGET);
    for (size_t k = 0; k < NKINDS; k++) {
        shot one, four;
        render(KINDS[k], 1, s, &one);
        render(KINDS[k], 4, s, &four);
        assert_null(find_pass(&one.fs, "msaa-resolve"));
        assert_int_equal(one.fs.total.dispatches, 1);
        assert_int_equal(four.fs.total.dispatches, one.fs.total.dispatches);
        assert_int_equal(find_pass(&four.fs, "cull")->dispatches, 1);
        assert_int_equal(total_draws(&four.fs), total_draws(&one.fs));
        assert_int_equal(four.fs.npasses, one.fs.npasses + 1);
        for (size_t p = 0, q = 0; p < four.fs.npasses; p++) {
            if (strcmp(four.fs.pass[p].name, "msaa-resolve") == 0) {
                assert_int_equal(four.fs.pass[p].draw_calls, 0);
                assert_int_equal(four.fs.pass[p].dispatches, 0);
                assert_string_equal(four.fs.pass[p + 1].name, "resolve");
                continue;
            }
            assert_string_equal(four.fs.pass[p].name, one.fs.pass[q].name);
            assert_int_equal(four.fs.pass[p].draw_calls, one.fs.pass[q].draw_calls);
            assert_int_equal(four.fs.pass[p].dispatches, one.fs.pass[q].dispatches);
            q++;
        }
        assert_int_equal(four.fs.grid_cells, one.fs.grid_cells);
        assert_non_null(plan_pass(&four.plan, "msaa-resolve"));
        assert_string_equal(four.plan.target[0].format, "rgba16f x4");
        assert_string_equal(four.plan.target[1].format, "depth24-stencil8 x4");
        /* the lists are those of every sample's depth: about msaa 1's (a list left
         * empty would be hidden by forward_tiled.frag's fallback in the image); a
         * little longer, as the samples widen a tile's depth range and so its box */
        print_message("%s: msaa 1 vs 4: %.3f vs %.3f light evaluations per pixel\n", KINDS[k],
                      one.fs.light_evals_per_pixel, four.fs.light_evals_per_pixel);
        assert_true(four.fs.light_evals_per_pixel > 0.9 * one.fs.light_evals_per_pixel);
        assert_true(four.fs.light_evals_per_pixel < 1.25 * one.fs.light_evals_per_pixel);
        image_free(&one.img);
        image_free(&four.img);
    }
    scene_destroy(s);
}

GL_TEST_MAIN(ctx, W, H,
             cmocka_unit_test(test_agreement_cases),
             cmocka_unit_test(test_light_at_the_silhouette),
             cmocka_unit_test(test_counts_at_msaa4))
