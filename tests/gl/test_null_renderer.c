/* The null renderer (renderers/null.c) through the registry (renderer.h) and the
 * per-pass queries it uses (renderers/gl/query.h), in a debug context. Exits 77
 * (skip) when no EGL display can be created at all. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "renderers/gl/context.h"
#include "tests/gl/gl_test.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/query.h"
#include "renderers/renderer.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 32, H = 24, FRAMES = 6 };

/* null.c's clear colour, (0.2, 0.4, 0.6, 1.0) as RGBA8. */
static const uint8_t NULL_CLEAR[4] = {51, 102, 153, 255};



static int setup(void **state)
{
    char err[512] = "";
    gl_context_desc desc = {.backend = GL_BACKEND_EGL, .device = -1, .debug = true,
                            .width = W, .height = H};
    gl_context *ctx = gl_context_create(&desc, err, sizeof err);
    if (!ctx) {
        print_error("gl_context_create: %s\n", err);
        return -1;
    }
    *state = ctx;
    return 0;
}

static int teardown(void **state)
{
    gl_context_destroy(*state);
    return 0;
}

static renderer_options options(const gl_context *ctx, bool queries)
{
    const gl_info *i = gl_context_info(ctx);
    return (renderer_options){.width = W, .height = H, .queries = queries,
                              .timer_query = i->timer_query,
                              .pipeline_statistics = i->pipeline_statistics};
}

static renderer *create_null(const renderer_options *opts)
{
    char err[256] = "";
    renderer *r = test_renderer_create("null", opts, err, sizeof err);
    if (!r)
        fail_msg("test_renderer_create(\"null\"): %s", err);
    assert_true(renderer_prepare(r, NULL, err, sizeof err));
    return r;
}

static void clear_output(gl_context *ctx, float v)
{
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    gl.ClearColor(v, v, v, v);
    gl.Clear(GL_COLOR_BUFFER_BIT);
}

static void assert_output_is(gl_context *ctx, const uint8_t want[4])
{
    uint8_t *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    char err[256] = "";
    assert_true(gl_context_read_rgba8(ctx, px, err, sizeof err));
    for (size_t i = 0; i < (size_t)W * H; i++)
        if (memcmp(px + 4 * i, want, 4) != 0)
            fail_msg("pixel %zu is %u,%u,%u,%u, expected %u,%u,%u,%u", i, px[4 * i],
                     px[4 * i + 1], px[4 * i + 2], px[4 * i + 3], want[0], want[1], want[2],
                     want[3]);
    free(px);
}

static void test_frames_with_queries(void **state)
{
    gl_context *ctx = *state;
    const gl_info *info = gl_context_info(ctx);
    renderer_options opts = options(ctx, true);
    renderer *r = create_null(&opts);

    for (int f = 0; f < FRAMES; f++) {
        clear_output(ctx, 0.0f);
        frame_stats fs;
        renderer_draw(r, NULL, &fs);
        gl.Finish();
        renderer_collect(r, &fs);

        assert_int_equal(fs.npasses, 1);
        const pass_stats *p = &fs.pass[0];
        assert_string_equal(p->name, "clear");
        assert_int_equal(p->draw_calls, 0);
        assert_int_equal(p->state_changes, 0);
        assert_int_equal(fs.lights_drawn, 0);
        assert_true(isfinite(p->cpu_us) && p->cpu_us >= 0.0);
        if (info->pipeline_statistics) {
            /* A clear runs no fragment shader and submits no primitive. */
            assert_true(p->fragments == 0.0);
            assert_true(p->primitives == 0.0);
        } else {
            assert_true(isnan(p->fragments) && isnan(p->primitives));
        }
        if (info->timer_query)
            assert_true(isfinite(p->gpu_us) && p->gpu_us >= 0.0);
        else
            assert_true(isnan(p->gpu_us));
        assert_int_equal(fs.total.draw_calls, 0);
        assert_int_equal(fs.total.state_changes, 0);
        assert_true(fs.total.cpu_us == p->cpu_us);
        if (info->pipeline_statistics)
            assert_true(fs.total.fragments == 0.0);

        assert_output_is(ctx, NULL_CLEAR);
    }
    renderer_destroy(r);
    assert_int_equal(gl_context_poll_errors(ctx, "null renderer frames"), 0);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static void test_frames_without_queries(void **state)
{
    gl_context *ctx = *state;
    renderer_options opts = options(ctx, false);
    renderer *r = create_null(&opts);
    for (int f = 0; f < 3; f++) {
        frame_stats fs;
        renderer_draw(r, NULL, &fs);
        gl.Finish();
        renderer_collect(r, &fs);
        assert_int_equal(fs.npasses, 1);
        assert_true(isnan(fs.pass[0].gpu_us));
        assert_true(isnan(fs.pass[0].fragments));
        assert_true(isnan(fs.pass[0].primitives));
        assert_true(isnan(fs.total.gpu_us));   /* no partial sum passes for a measurement */
        assert_int_equal(fs.pass[0].draw_calls, 0);
        assert_output_is(ctx, NULL_CLEAR);
    }
    renderer_destroy(r);
    renderer_destroy(NULL);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

/* The renderer draws into the framebuffer bound when it was created, whatever is
 * bound when it draws. */
static void test_draws_into_framebuffer_of_creation(void **state)
{
    gl_context *ctx = *state;
    clear_output(ctx, 0.0f);
    renderer_options opts = options(ctx, true);
    renderer *r = create_null(&opts);

    GLuint rb, fbo;
    gl.GenRenderbuffers(1, &rb);
    gl.BindRenderbuffer(GL_RENDERBUFFER, rb);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, W, H);
    gl.GenFramebuffers(1, &fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    assert_int_equal(gl.CheckFramebufferStatus(GL_FRAMEBUFFER), GL_FRAMEBUFFER_COMPLETE);
    gl.ClearColor(0, 0, 0, 0);
    gl.Clear(GL_COLOR_BUFFER_BIT);

    frame_stats fs;
    renderer_draw(r, NULL, &fs);
    gl.Finish();
    renderer_collect(r, &fs);
    assert_output_is(ctx, NULL_CLEAR);

    uint8_t px[4] = {1, 1, 1, 1};
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    gl.ReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    static const uint8_t zero[4] = {0, 0, 0, 0};
    assert_memory_equal(px, zero, 4);

    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    gl.DeleteFramebuffers(1, &fbo);
    gl.DeleteRenderbuffers(1, &rb);
    renderer_destroy(r);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static void test_describe(void **state)
{
    gl_context *ctx = *state;
    renderer_options opts = options(ctx, true);
    renderer *r = create_null(&opts);
    pass_plan plan;
    memset(&plan, 0xFF, sizeof plan);
    renderer_describe(r, &plan);
    assert_int_equal(plan.npasses, 1);
    assert_string_equal(plan.pass[0].name, "clear");
    assert_true(plan.pass[0].run);
    assert_string_equal(plan.pass[0].reason, "clears the output framebuffer");
    assert_int_equal(plan.nprograms, 0);
    assert_int_equal(plan.ntargets, 0);
    assert_int_equal(plan.gbuffer_bytes, 0);
    assert_int_equal(plan.target_bytes, 0);
    renderer_destroy(r);

    const renderer_impl *impl = renderer_kind_find("null");
    assert_non_null(impl);
    assert_string_equal(impl->name, "null");
    assert_true(impl->description && impl->description[0]);
}

/* query.c on its own: passes not measured in a frame, kinds not asked for and
 * misuse all give NAN (or nothing), never a GL error. */
static void test_pass_queries(void **state)
{
    gl_context *ctx = *state;
    const gl_info *info = gl_context_info(ctx);
    assert_null(gl_pass_queries_create(0, true, true));
    assert_null(gl_pass_queries_create(RENDERER_MAX_PASSES + 1, true, true));
    gl_pass_queries_destroy(NULL);

    gl_pass_queries *q = gl_pass_queries_create(3, info->timer_query, false);
    assert_non_null(q);
    for (int f = 0; f < 2 * GL_PASS_QUERIES_FRAMES + 1; f++) {
        frame_stats fs;
        memset(&fs, 0, sizeof fs);
        fs.npasses = 3;
        gl_pass_queries_begin(q, 0);
        gl.Clear(GL_COLOR_BUFFER_BIT);
        gl_pass_queries_end(q);
        /* pass 1 does not run this frame */
        gl_pass_queries_begin(q, 2);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        gl_pass_queries_end(q);
        gl.Finish();
        gl_pass_queries_collect(q, &fs);
        if (info->timer_query) {
            assert_true(isfinite(fs.pass[0].gpu_us) && fs.pass[0].gpu_us >= 0.0);
            assert_true(isfinite(fs.pass[2].gpu_us) && fs.pass[2].gpu_us >= 0.0);
        }
        assert_true(isnan(fs.pass[1].gpu_us));
        for (size_t p = 0; p < 3; p++)   /* stats not asked for */
            assert_true(isnan(fs.pass[p].fragments) && isnan(fs.pass[p].primitives));
        assert_true(fs.pass[3].gpu_us == 0.0);   /* beyond npasses: untouched */
    }
    gl_pass_queries_destroy(q);
    assert_int_equal(gl_context_poll_errors(ctx, "pass queries"), 0);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

int main(void)
{
    GL_TEST_SKIP_WITHOUT_EGL();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frames_with_queries),
        cmocka_unit_test(test_frames_without_queries),
        cmocka_unit_test(test_draws_into_framebuffer_of_creation),
        cmocka_unit_test(test_describe),
        cmocka_unit_test(test_pass_queries),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
