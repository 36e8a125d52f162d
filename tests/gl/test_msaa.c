/* MSAA (issue 12, the manifest's `msaa`; renderers/base.h): the refusal of a sample
 * count the context cannot do (on the limits of a test, and on the context's own,
 * before anything renders, with the message naming the key, the value and the
 * limits); forward-spml and forward-mpml at msaa 4 draw into multisampled targets
 * (4x the bytes), run the pass "msaa-resolve" (a blit: no draw, no sample shaded)
 * before the display resolve, and agree with each other within RMSE 1/255 and max
 * 4/255 on the 8-bit output; the 4-sample image differs from the single-sampled one
 * only on a small fraction of the pixels (the edges). Any GL error fails. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/base.h"
#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "results/image_io.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

enum { W = 64, H = 48 };
#define RMSE_MAX (1.0 / 255.0)
#define MAX_ABS_MAX (4.0 / 255.0)

static gl_context *ctx;

static renderer_options options(int msaa)
{
    const gl_info *gi = gl_context_info(ctx);
    return (renderer_options){
        .width = W, .height = H, .queries = true,
        .timer_query = gi->timer_query, .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size,
        .gbuffer = GBUFFER_REFERENCE, .msaa = msaa,
    };
}

static int context_limit(void)
{
    GLint ms = 0, mc = 0, md = 0;
    gl.GetIntegerv(GL_MAX_SAMPLES, &ms);
    gl.GetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &mc);
    gl.GetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &md);
    int l = ms < mc ? ms : mc;
    return l < md ? l : md;
}

/* The shapes scene at t = 0 with two point lights. */
static scene *build(void)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build("shapes", &lp, W, H, err, sizeof err);
    if (!s) {
        print_error("scene: %s\n", err);
        return NULL;
    }
    s->lights = calloc(2, sizeof *s->lights);
    s->lights[0] = (scene_light){.type = LIGHT_POINT, .position = {2.0f, 3.0f, 2.0f},
                                 .color = {1.0f, 0.8f, 0.6f}, .radius = 12.0f,
                                 .attenuation = ATTENUATION_LINEAR_RANGE};
    s->lights[1] = (scene_light){.type = LIGHT_POINT, .position = {-3.0f, 2.0f, -1.0f},
                                 .color = {0.4f, 0.6f, 1.0f}, .radius = 10.0f,
                                 .attenuation = ATTENUATION_LINEAR_RANGE};
    s->nlights_total = 2;
    s->count = (light_count){.start = 2, .max = 2};
    scene_update(s, 0.0);
    return s;
}

/* One frame of s by kind at msaa; the output read back, the frame's stats and plan. */
static bool render(const char *kind, int msaa, scene *s, image *out, frame_stats *fs,
                   pass_plan *plan)
{
    char err[512];
    renderer_options o = options(msaa);
    renderer *r = renderer_create(kind, &o, err, sizeof err);
    if (!r || !renderer_prepare(r, s, err, sizeof err)) {
        print_error("%s: %s\n", kind, err);
        renderer_destroy(r);
        return false;
    }
    renderer_draw(r, s, fs);
    gl.Finish();
    renderer_collect(r, fs);
    if (plan)
        renderer_describe(r, plan);
    out->width = W;
    out->height = H;
    out->channels = 4;
    out->type = IMAGE_U8;
    out->pixels = malloc((size_t)W * H * 4);
    bool ok = gl_context_read_rgba8(ctx, out->pixels, err, sizeof err);
    renderer_destroy(r);
    gl_context_poll_errors(ctx, kind);
    return ok && gl_context_error_count(ctx) == 0;
}

static void test_refusal_on_given_limits(void **state)
{
    (void)state;
    char err[256] = "";
    assert_true(renderer_base_msaa_check("forward-spml", 1, 1, 1, 1, err, sizeof err));
    assert_true(renderer_base_msaa_check("forward-spml", 4, 4, 8, 4, err, sizeof err));
    assert_false(renderer_base_msaa_check("forward-spml", 4, 8, 2, 8, err, sizeof err));
    assert_string_equal(err, "forward-spml: msaa 4: this context allows at most 2 samples "
                             "(GL_MAX_SAMPLES 8, GL_MAX_COLOR_TEXTURE_SAMPLES 2, "
                             "GL_MAX_DEPTH_TEXTURE_SAMPLES 8)");
    assert_false(renderer_base_msaa_check("deferred", 8, 32, 32, 4, err, sizeof err));
    assert_non_null(strstr(err, "deferred: msaa 8: this context allows at most 4 samples"));
    assert_false(renderer_base_msaa_check("deferred", 3, 32, 32, 32, err, sizeof err));
    assert_string_equal(err, "deferred: msaa 3: expected 1, 2, 4 or 8 samples");
}

/* Past the context's own limit: renderer_create refuses, nothing is drawn. */
static void test_refusal_on_the_context(void **state)
{
    (void)state;
    int limit = context_limit();
    print_message("context: at most %d samples\n", limit);
    int over = limit < 8 ? (limit < 4 ? (limit < 2 ? 2 : 4) : 8) : 16;
    char err[512] = "";
    static const char *const kinds[] = {"forward-spml", "forward-mpml", "deferred",
                                        "forward-plus"};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        renderer_options o = options(over);
        renderer *r = renderer_create(kinds[k], &o, err, sizeof err);
        assert_null(r);
        char want[64];
        snprintf(want, sizeof want, "%s: msaa %d: ", kinds[k], over);
        if (strncmp(err, want, strlen(want)) != 0)
            print_error("%s\n", err);
        assert_int_equal(strncmp(err, want, strlen(want)), 0);
        if (over <= 8 && strcmp(kinds[k], "forward-spml") == 0)
            assert_non_null(strstr(err, "GL_MAX_SAMPLES"));
    }
    gl_context_poll_errors(ctx, "refusal");
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static void test_forward_msaa4(void **state)
{
    (void)state;
    if (context_limit() < 4)
        skip();
    scene *s = build();
    assert_non_null(s);
    image spml = {0}, mpml = {0}, single = {0};
    frame_stats fs;
    pass_plan plan;
    assert_true(render("forward-spml", 4, s, &spml, &fs, &plan));
    const pass_stats *p = find_pass(&fs, "msaa-resolve");
    assert_non_null(p);
    assert_int_equal(p->draw_calls, 0);
    assert_true(p->samples == 0.0);
    assert_string_equal(fs.pass[fs.npasses - 2].name, "msaa-resolve");
    assert_string_equal(fs.pass[fs.npasses - 1].name, "resolve");
    assert_non_null(plan_pass(&plan, "msaa-resolve"));
    assert_int_equal(plan.ntargets, 3);
    assert_string_equal(plan.target[0].format, "rgba16f x4");
    assert_int_equal(plan.target[0].bytes, (uint64_t)W * H * 8 * 4);
    assert_string_equal(plan.target[1].format, "depth24-stencil8 x4");
    assert_int_equal(plan.target[1].bytes, (uint64_t)W * H * 4 * 4);
    assert_string_equal(plan.target[2].name, "hdr.resolved");
    assert_int_equal(plan.target[2].bytes, (uint64_t)W * H * 8);

    assert_true(render("forward-mpml", 4, s, &mpml, &fs, NULL));
    assert_non_null(find_pass(&fs, "msaa-resolve"));
    image_error e;
    char err[256];
    assert_true(image_compare(&spml, &mpml, &e, err, sizeof err));
    print_message("msaa 4 forward-mpml vs forward-spml: rmse %.3f/255, max %.0f/255\n",
                  e.rmse * 255, e.max_abs * 255);
    assert_true(e.rmse < RMSE_MAX);
    assert_true(e.max_abs <= MAX_ABS_MAX);

    /* against single-sampled: the same picture, different only along edges */
    assert_true(render("forward-spml", 1, s, &single, &fs, &plan));
    assert_null(find_pass(&fs, "msaa-resolve"));
    assert_null(plan_pass(&plan, "msaa-resolve"));
    assert_true(image_compare(&spml, &single, &e, err, sizeof err));
    print_message("msaa 4 vs 1: %.4f of the pixels differ by > 1/255\n", e.frac_over_1_255);
    assert_true(e.frac_over_1_255 > 0.0);
    assert_true(e.frac_over_1_255 < 0.3);
    image_free(&spml);
    image_free(&mpml);
    image_free(&single);
    scene_destroy(s);
}

static int setup(void **state)
{
    (void)state;
    ctx = gl_test_context(W, H);
    return ctx ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    gl_context_destroy(ctx);
    return 0;
}

int main(void)
{
    char why[256];
    if (!egl_display_available(why, sizeof why)) {
        fprintf(stderr, "SKIP: %s\n", why);
        return 77;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refusal_on_given_limits),
        cmocka_unit_test(test_refusal_on_the_context),
        cmocka_unit_test(test_forward_msaa4),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
