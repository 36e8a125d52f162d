/* The state cache's feedback-loop check (renderers/gl/state.h): in a debug context it is
 * on, and a draw or a dispatch whose program samples a texture that is attached to the
 * bound draw framebuffer (a colour attachment, or the depth-stencil target as deferred's
 * position from depth did) is counted and raised as a GL error whose message names the
 * pass, the program, the sampler and unit, the texture, the framebuffer and the
 * attachment; sampling another texture, the same one with another framebuffer bound, or
 * with the check off, is not. Then every renderer of the registry, and deferred in every
 * light-volume mode and G-buffer position source (with the sky mask and separate
 * specular), tiled-deferred and clustered deferred shading in every position source,
 * and every renderer with fog and the RGBA32F light target, draws frames with shadow-casting spot and directional lights without a single loop
 * (no GL error). Exits 77 (skip) when no EGL display can be created at all. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/state.h"
#include "renderers/gl/target.h"
#include "renderers/renderer.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

enum { W = 96, H = 64 };

static gl_context *ctx;

static void assert_contains(const char *haystack, const char *needle)
{
    if (!haystack || !strstr(haystack, needle))
        fail_msg("expected \"%s\" in:\n%s", needle, haystack ? haystack : "(no message)");
}

static GLuint get_program(gl_program_cache *pc, const gl_program_desc *d)
{
    char err[4096];
    GLuint prog = 0;
    if (gl_program_get(pc, d, &prog, err, sizeof err) != GLP_OK)
        fail_msg("gl_program_get: %s", err);
    return prog;
}

static void make_target(gl_target *t, const char *name, gl_format f)
{
    char err[256];
    if (!gl_target_create(t, &(gl_target_desc){.name = name, .format = f, .width = 4,
                                               .height = 4},
                          err, sizeof err))
        fail_msg("%s", err);
}

/* GL errors since the last call (each loop the check finds is one). */
static uint64_t new_errors(uint64_t *seen)
{
    gl_context_poll_errors(ctx, "feedback test");
    uint64_t now = gl_context_error_count(ctx), d = now - *seen;
    *seen = now;
    return d;
}

// >>the check fires

static void test_check_fires(void **state)
{
    (void)state;
    uint64_t seen = 0;
    new_errors(&seen);
    gl_state *s = gl_state_create();
    assert_non_null(s);
    assert_true(gl_state_feedback_check(s));   /* a debug context */
    gl_program_cache *pc = gl_program_cache_create();
    GLuint draw = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                     .fragment = "test_color.frag",
                                                     .defines = {"SAMPLE"}});
    GLuint plain = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                      .fragment = "test_color.frag"});
    GLuint compute = get_program(pc, &(gl_program_desc){.compute = "test_sample.comp"});
    gl_target a, b, depth;
    make_target(&a, "feedback.a", GLT_FORMAT_RGBA8);
    make_target(&b, "feedback.b", GLT_FORMAT_RGBA8);
    make_target(&depth, "feedback.depth", GLT_FORMAT_DEPTH24_STENCIL8);
    gl_framebuffer fa, fb;
    char err[512];
    assert_true(gl_framebuffer_create(&fa, &(gl_framebuffer_desc){.name = "fb.a",
                                                                  .color = {&a},
                                                                  .depth_stencil = &depth},
                                      err, sizeof err));
    assert_true(gl_framebuffer_create(&fb, &(gl_framebuffer_desc){.name = "fb.b",
                                                                  .color = {&b}},
                                      err, sizeof err));
    GLuint out = 0;
    gl.CreateBuffers(1, &out);
    gl.NamedBufferStorage(out, 16, NULL, 0);

    gl_state_begin_pass(s, "loops");
    gl_state_framebuffer(s, fa.fbo);
    gl_state_depth(s, NULL);   /* writes off: still a loop (GL 4.5 section 9.3) */
    gl_state_program(s, draw);
    /* another texture: fine */
    gl_state_texture(s, 0, b.texture);
    gl_state_draw_fullscreen(s, 4, 4, false);
    assert_int_equal(gl_state_feedback_loops(s), 0);
    assert_int_equal(new_errors(&seen), 0);
    assert_string_equal(gl_state_feedback_message(s), "");
    /* the colour attachment itself */
    gl_state_texture(s, 0, a.texture);
    gl_state_draw_fullscreen(s, 4, 4, false);
    assert_int_equal(gl_state_feedback_loops(s), 1);
    assert_int_equal(new_errors(&seen), 1);
    const char *m = gl_state_feedback_message(s);
    print_message("%s\n", m);
    assert_contains(m, "feedback loop in pass loops: draw of program test_color+SAMPLE");
    assert_contains(m, "samples texture feedback.a (sampler t_input, unit 0)");
    assert_contains(m, "attached to the draw framebuffer fb.a (colour 0)");
    assert_contains(m, "GL 4.5 section 9.3");
    /* the depth-stencil target, depth test and writes off (deferred's old position from
     * depth) */
    gl_state_texture(s, 0, depth.texture);
    gl_state_draw_fullscreen(s, 4, 4, false);
    assert_int_equal(gl_state_feedback_loops(s), 2);
    assert_int_equal(new_errors(&seen), 1);
    assert_contains(gl_state_feedback_message(s),
                    "samples texture feedback.depth (sampler t_input, unit 0) while it is "
                    "attached to the draw framebuffer fb.a (depth)");
    /* the texture bound but not sampled by the program: fine */
    gl_state_program(s, plain);
    gl_state_draw_fullscreen(s, 4, 4, false);
    assert_int_equal(gl_state_feedback_loops(s), 2);
    /* a dispatch that samples it while fb.a is bound */
    gl_state_storage_buffer(s, 0, out);
    gl_state_program(s, compute);
    gl_state_dispatch(s, 1, 1, 1);
    assert_int_equal(gl_state_feedback_loops(s), 3);
    assert_int_equal(new_errors(&seen), 1);
    assert_contains(gl_state_feedback_message(s),
                    "dispatch of program test_sample samples texture feedback.depth");
    /* ... and with another framebuffer bound: fine */
    gl_state_framebuffer(s, fb.fbo);
    gl_state_dispatch(s, 1, 1, 1);
    gl_state_texture(s, 0, a.texture);
    gl_state_program(s, draw);
    gl_state_draw_fullscreen(s, 4, 4, false);   /* samples a, draws into b */
    assert_int_equal(gl_state_feedback_loops(s), 3);
    assert_int_equal(new_errors(&seen), 0);
    /* the check off: not looked for */
    gl_state_framebuffer(s, fa.fbo);
    gl_state_set_feedback_check(s, false);
    gl_state_draw_fullscreen(s, 4, 4, false);
    assert_int_equal(gl_state_feedback_loops(s), 3);
    assert_int_equal(new_errors(&seen), 0);
    gl_state_end_pass(s, NULL);

    gl_state_texture(s, 0, 0);
    gl_state_storage_buffer(s, 0, 0);
    gl.DeleteBuffers(1, &out);
    gl_framebuffer_destroy(&fa);
    gl_framebuffer_destroy(&fb);
    gl_target_destroy(&a);
    gl_target_destroy(&b);
    gl_target_destroy(&depth);
    gl_program_cache_destroy(pc);
    gl_state_destroy(s);
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    assert_int_equal(new_errors(&seen), 0);
}

// >>no renderer loops

static scene *build_scene(void)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build("shapes", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("scene: %s", err);
    scene_light l[4] = {
        {.type = LIGHT_POINT, .position = {10.0f, 2.0f, 0.0f}, .color = {1.0f, 0.8f, 0.6f},
         .direction = {0.0f, -1.0f, 0.0f}, .radius = 8.0f,
         .attenuation = ATTENUATION_LINEAR_RANGE},
        {.type = LIGHT_SPOT, .position = {-10.0f, 9.0f, -10.0f}, .direction = {0.0f, -1.0f, 0.0f},
         .color = {0.9f, 0.8f, 0.6f}, .radius = 14.0f, .spot_angle = 0.5f, .spot_exponent = 2.0f,
         .attenuation = ATTENUATION_LINEAR_RANGE, .shadows = true},
        {.type = LIGHT_DIRECTIONAL, .direction = {0.3f, -0.9f, -0.3f}, .color = {0.3f, 0.3f, 0.3f},
         .shadows = true},
        {.type = LIGHT_POINT, .position = {-10.0f, 2.0f, 10.0f}, .color = {0.5f, 0.6f, 1.0f},
         .direction = {0.0f, -1.0f, 0.0f}, .radius = 6.0f,
         .attenuation = ATTENUATION_LINEAR_RANGE},
    };
    s->lights = calloc(4, sizeof *s->lights);
    assert_non_null(s->lights);
    memcpy(s->lights, l, sizeof l);
    s->nlights_total = 4;
    s->count = (light_count){.start = 4, .max = 4};
    scene_update(s, 0.0);
    return s;
}

static void run_one(const char *kind, renderer_options o, const scene *s)
{
    char err[4096] = "";
    const gl_info *gi = gl_context_info(ctx);
    o.width = W;
    o.height = H;
    o.queries = true;
    o.timer_query = gi->timer_query;
    o.pipeline_statistics = gi->pipeline_statistics;
    o.max_uniform_block_size = gi->max_uniform_block_size;
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    gl_context_poll_errors(ctx, "before");
    const uint64_t before = gl_context_error_count(ctx);   /* test_check_fires' own */
    renderer *r = test_renderer_create(kind, &o, err, sizeof err);
    if (!r || !renderer_prepare(r, s, err, sizeof err))
        fail_msg("%s: %s", kind, err);
    for (int f = 0; f < 2; f++) {
        frame_stats fs;
        memset(&fs, 0, sizeof fs);
        renderer_draw(r, s, &fs);
        gl.Finish();
        renderer_collect(r, &fs);
    }
    renderer_destroy(r);
    gl_context_poll_errors(ctx, kind);
    if (gl_context_error_count(ctx) != before)
        fail_msg("%s (light volumes %d, position %d, sky mask %d): GL errors (above)", kind,
                 (int)o.light_volumes, (int)o.gbuffer_position, (int)o.sky_stencil);
}

static void test_renderers_have_no_loop(void **state)
{
    (void)state;
    gl_state *probe = gl_state_create();
    assert_true(gl_state_feedback_check(probe));   /* the renderers' caches check too */
    gl_state_destroy(probe);
    scene *s = build_scene();
    static const gbuffer_position POS[4] = {GBUFFER_POSITION_PRESET, GBUFFER_POSITION_STORED16,
                                            GBUFFER_POSITION_STORED32, GBUFFER_POSITION_DEPTH};
    /* every renderer as it comes */
    for (size_t i = 0; i < renderer_kind_count(); i++)
        run_one(renderer_kind_at(i)->name, (renderer_options){0}, s);
    run_one("clustered", (renderer_options){.clustered_deferred = true}, s);
    /* deferred: every mode with position from depth, the sky mask and separate specular */
    for (int m = LIGHT_VOLUMES_STENCIL; m <= (int)LIGHT_VOLUMES_SCISSOR; m++)
        run_one("deferred",
                (renderer_options){.light_volumes = (light_volume_mode)m,
                                   .gbuffer_position = GBUFFER_POSITION_DEPTH,
                                   .sky_stencil = true,
                                   .separate_specular = m == LIGHT_VOLUMES_FULLSCREEN},
                s);
    /* fog (it samples depth too) and the 32-bit light target, every renderer */
    for (size_t i = 0; i < renderer_kind_count(); i++)
        run_one(renderer_kind_at(i)->name,
                (renderer_options){.fog_density = 0.02f, .hdr = HDR_RGBA32F,
                                   .gbuffer_position = GBUFFER_POSITION_DEPTH},
                s);
    /* every position source in the deferred family */
    for (int p = 0; p < 4; p++) {
        run_one("deferred", (renderer_options){.gbuffer_position = POS[p]}, s);
        run_one("tiled-deferred", (renderer_options){.gbuffer_position = POS[p]}, s);
        run_one("clustered", (renderer_options){.gbuffer_position = POS[p],
                                                .clustered_deferred = true},
                s);
    }
    scene_destroy(s);
}

int main(void)
{
    GL_TEST_SKIP_WITHOUT_EGL();
    ctx = gl_test_context(W, H);
    if (!ctx)
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_check_fires),
        cmocka_unit_test(test_renderers_have_no_loop),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    gl_context_destroy(ctx);
    return rc;
}
