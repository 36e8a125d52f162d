/* MSAA (issue 12, the manifest's `msaa`; renderers/frame/base.h), any GL error failing:
 * a sample count the context cannot do refused before anything renders, the message
 * naming key, value and limits; forward-spml and forward-mpml at msaa 4 into
 * multisampled targets (4x the bytes) with the pass "msaa-resolve" (a blit), agreeing
 * within RMSE 1/255 and max 4/255, and differing from the single-sampled image on the
 * edges only; deferred at msaa 4 (reference G-buffer) against forward-spml within RMSE
 * 1/255 (under 1 % of pixels off by more than 1/255) in every light-volume mode, also
 * with the sky mask, separate specular and fog; per-sample shading exactly on the edge
 * pixels of a box face against the sky, counted on the CPU from the projected rectangle
 * and the sample positions: the edge pass finds them, and P + 3 E samples are shaded;
 * tiled-deferred at msaa 4 (one dispatch with a per-tile edge list, Lauritzen 2010) by the
 * same bounds, finding the same edge pixels and shading P + 3 E samples. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/frame/base.h"
#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/target.h"
#include "renderers/renderer.h"
#include "common/image_io.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

enum { W = 64, H = 48 };
#define RMSE_MAX (1.0 / 255.0)
#define MAX_ABS_MAX (4.0 / 255.0)

static gl_context *ctx;

static light_volume_mode g_mode = LIGHT_VOLUMES_STENCIL;
static bool g_sky_stencil, g_separate_specular;
static gbuffer_position g_position = GBUFFER_POSITION_PRESET;
static float g_fog;
static aa_mode g_aa = AA_NONE;
static bool g_clustered_deferred;

static renderer_options options(int msaa)
{
    const gl_info *gi = gl_context_info(ctx);
    return (renderer_options){
        .width = W, .height = H, .queries = true,
        .timer_query = gi->timer_query, .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size,
        .gbuffer = GBUFFER_REFERENCE, .msaa = msaa, .light_volumes = g_mode,
        .sky_stencil = g_sky_stencil, .gbuffer_position = g_position, .separate_specular = g_separate_specular,
        .fog_density = g_fog, .fog_color = {0.55f, 0.6f, 0.7f}, .aa = g_aa,
        .clustered_deferred = g_clustered_deferred,
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

/* The shapes scene at t = 0 with two point lights (and with `more`, a spot and a
 * directional light). */
static scene *build_lit(bool more)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build("shapes", &lp, W, H, err, sizeof err);
    if (!s) {
        print_error("scene: %s\n", err);
        return NULL;
    }
    s->lights = calloc(4, sizeof *s->lights);
    s->lights[0] = (scene_light){.type = LIGHT_POINT, .position = {2.0f, 3.0f, 2.0f},
                                 .color = {1.0f, 0.8f, 0.6f}, .radius = 12.0f,
                                 .attenuation = ATTENUATION_LINEAR_RANGE};
    s->lights[1] = (scene_light){.type = LIGHT_POINT, .position = {-3.0f, 2.0f, -1.0f},
                                 .color = {0.4f, 0.6f, 1.0f}, .radius = 10.0f,
                                 .attenuation = ATTENUATION_LINEAR_RANGE};
    uint32_t n = 2;
    if (more) {
        scene_light sp = {.type = LIGHT_SPOT, .position = {0.0f, 8.0f, 4.0f},
                          .direction = {0.0f, -1.0f, -0.3f}, .color = {1.0f, 0.9f, 0.7f},
                          .radius = 20.0f, .spot_angle = sm_deg2rad(30.0f),
                          .spot_exponent = 4.0f, .attenuation = ATTENUATION_LINEAR_RANGE};
        sm_vec3_normalize(sp.direction);
        scene_light dir = {.type = LIGHT_DIRECTIONAL, .direction = {0.3f, -1.0f, 0.2f},
                           .color = {0.3f, 0.3f, 0.25f}, .radius = 1.0f};
        sm_vec3_normalize(dir.direction);
        s->lights[n++] = sp;
        s->lights[n++] = dir;
    }
    s->nlights_total = n;
    s->count = (light_count){.start = n, .max = n};
    scene_update(s, 0.0);
    return s;
}

static scene *build(void)
{
    return build_lit(false);
}

/* One frame of s by kind at msaa; the output read back, the frame's stats and plan. */
static bool render(const char *kind, int msaa, scene *s, image *out, frame_stats *fs,
                   pass_plan *plan)
{
    char err[512];
    renderer_options o = options(msaa);
    renderer *r = test_renderer_create(kind, &o, err, sizeof err);
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
                                        "forward-plus", "tiled-deferred", "deferred-lighting"};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        renderer_options o = options(over);
        renderer *r = test_renderer_create(kinds[k], &o, err, sizeof err);
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
    /* the display resolve draws into the single-sampled output: one sample a pixel */
    assert_true(fs.pass[fs.npasses - 1].single_sampled);
    assert_true(fs.pass[fs.npasses - 1].samples_shaded == (double)W * H);
    const pass_stats *shade = find_pass(&fs, "shade");
    assert_non_null(shade);
    const double shaded4 = shade->samples_shaded;
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
    /* forward shades once a pixel at any msaa: the samples shaded of msaa 4 (samples / 4)
     * are msaa 1's, give or take the edge pixels two triangles share */
    shade = find_pass(&fs, "shade");
    assert_non_null(shade);
    print_message("forward-spml shade: %.1f samples shaded at msaa 4, %.1f at 1\n", shaded4,
                  shade->samples_shaded);
    assert_true(fabs(shaded4 - shade->samples_shaded) < 0.1 * shade->samples_shaded);
    assert_true(image_compare(&spml, &single, &e, err, sizeof err));
    print_message("msaa 4 vs 1: %.4f of the pixels differ by > 1/255\n", e.frac_over_1_255);
    assert_true(e.frac_over_1_255 > 0.0);
    assert_true(e.frac_over_1_255 < 0.3);
    image_free(&spml);
    image_free(&mpml);
    image_free(&single);
    scene_destroy(s);
}

/* msaa 4 with aa: edge: the edge blur runs on the averaged samples (msaa-resolve, then
 * edge-aa: one draw into a single-sampled "hdr.aa", its depth a one-sample-a-pixel blit
 * of the multisampled one, normals rebuilt from it in every renderer), then the
 * resolve; deferred and forward-spml agree as they do without it, and the blur changes
 * the image along edges only. */
static void test_edge_aa_after_msaa(void **state)
{
    (void)state;
    if (context_limit() < 4)
        skip();
    scene *s = build();
    assert_non_null(s);
    image plain = {0}, spml = {0}, def = {0};
    frame_stats fs;
    pass_plan plan;
    assert_true(render("forward-spml", 4, s, &plain, &fs, NULL));
    g_aa = AA_EDGE;
    for (int k = 0; k < 2; k++) {
        assert_true(render(k ? "deferred" : "forward-spml", 4, s, k ? &def : &spml, &fs, &plan));
        assert_true(fs.npasses >= 3);
        assert_string_equal(fs.pass[fs.npasses - 3].name, "msaa-resolve");
        assert_string_equal(fs.pass[fs.npasses - 2].name, "edge-aa");
        assert_string_equal(fs.pass[fs.npasses - 1].name, "resolve");
        assert_int_equal(fs.pass[fs.npasses - 2].draw_calls, 1);
        assert_true(fs.pass[fs.npasses - 2].samples_shaded == (double)W * H);   /* hdr.aa */
        const pass_plan_entry *e = plan_pass(&plan, "edge-aa");
        assert_non_null(e);
        assert_true(e->run);
        assert_non_null(strstr(e->reason, "depth-rebuilt"));
        bool single = false;
        for (size_t t = 0; t < plan.ntargets; t++)
            if (strcmp(plan.target[t].name, "hdr.aa") == 0)
                single = strchr(plan.target[t].format, 'x') == NULL;
        assert_true(single);   /* the display reads it with a sampler2D */
    }
    g_aa = AA_NONE;
    image_error e;
    char err[256];
    assert_true(image_compare(&spml, &def, &e, err, sizeof err));
    print_message("msaa 4 + edge AA, deferred vs forward-spml: rmse %.3f/255\n", e.rmse * 255);
    assert_true(e.rmse < RMSE_MAX);
    assert_true(image_compare(&plain, &spml, &e, err, sizeof err));
    print_message("msaa 4, edge AA vs none: %.4f of the pixels differ by > 1/255\n",
                  e.frac_over_1_255);
    assert_true(e.frac_over_1_255 > 0.0 && e.frac_over_1_255 < 0.3);
    image_free(&plain);
    image_free(&spml);
    image_free(&def);
    scene_destroy(s);
}

/* msaa 4: deferred in every light-volume mode agrees with forward-spml */
static void test_deferred_agrees_msaa4(void **state)
{
    (void)state;
    if (context_limit() < 4)
        skip();
    scene *s = build_lit(true);
    assert_non_null(s);
    static const struct {
        light_volume_mode mode;
        bool sky, sep;
        float fog;
    } cases[] = {
        {LIGHT_VOLUMES_STENCIL, false, false, 0.0f},
        {LIGHT_VOLUMES_STENCIL_TWO_PASS, false, false, 0.0f},
        {LIGHT_VOLUMES_VOLUME, false, false, 0.0f},
        {LIGHT_VOLUMES_FULLSCREEN, false, false, 0.0f},
        {LIGHT_VOLUMES_HULL, false, false, 0.0f},
        {LIGHT_VOLUMES_SCISSOR, false, false, 0.0f},
        {LIGHT_VOLUMES_STENCIL, true, false, 0.0f},
        {LIGHT_VOLUMES_STENCIL_TWO_PASS, true, true, 0.0f},
        {LIGHT_VOLUMES_FULLSCREEN, true, false, 0.03f},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        g_mode = cases[k].mode;
        g_sky_stencil = cases[k].sky;
        g_separate_specular = cases[k].sep;
        g_fog = cases[k].fog;
        image fwd = {0}, def = {0};
        frame_stats fs;
        pass_plan plan;
        assert_true(render("forward-spml", 4, s, &fwd, &fs, NULL));
        assert_true(render("deferred", 4, s, &def, &fs, &plan));
        assert_non_null(find_pass(&fs, "edges"));
        assert_non_null(find_pass(&fs, "msaa-resolve"));
        assert_true(fs.edge_fraction > 0.0 && fs.edge_fraction < 0.5);
        assert_true(fs.total.per_sample_samples > 0.0);
        image_error e;
        char err[256];
        assert_true(image_compare(&fwd, &def, &e, err, sizeof err));
        print_message("msaa 4 deferred (%d, sky %d, sep %d, fog %g) vs forward-spml: rmse "
                      "%.3f/255, max %.0f/255, edges %.4f\n", (int)g_mode, cases[k].sky,
                      cases[k].sep, (double)g_fog, e.rmse * 255, e.max_abs * 255,
                      fs.edge_fraction);
        /* the bound is the RMSE; the few pixels beyond 1/255 (at most 0.5 % here,
         * up to 16/255) are edges where a light volume's per-sample stencil and the
         * per-pixel shading of near-equal samples differ from forward's shading */
        assert_true(e.rmse < RMSE_MAX);
        assert_true(e.frac_over_1_255 < 0.01);
        assert_int_equal(e.nonfinite, 0);
        image_free(&fwd);
        image_free(&def);
    }
    g_mode = LIGHT_VOLUMES_STENCIL;
    g_sky_stencil = g_separate_specular = false;
    g_fog = 0.0f;
    scene_destroy(s);
}

/* One face of the shapes scene's box (object 3, half size 1.5 at (10, 2.2, -10)), alone,
 * seen head-on from d in front: an axis-aligned rectangle of constant depth and normal
 * against the sky, its sides 1.5 f / d = 10.5 pixels from the centre (32, 24). */
static scene *build_box_face(void)
{
    scene *s = build_lit(true);
    if (!s)
        return NULL;
    s->objects[0] = s->objects[3];
    s->nobjects = 1;
    const float f = (H / 2.0f) / tanf(s->fovy / 2.0f);   /* pixels per unit at depth 1 */
    const float d = 1.5f * f / 10.5f;
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3_make(10.0f, 2.2f, -8.5f + d, s->cam.eye);
    sm_vec3_make(10.0f, 2.2f, -10.0f, s->cam.target);
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
    return s;
}

/* The edge pixels of the rectangle [x0, x1] x [y0, y1] (pixels) under the context's
 * 4x sample positions: some sample inside, some outside. */
static int count_edge_pixels(float x0, float x1, float y0, float y1)
{
    gl_target t;
    gl_framebuffer fb;
    char err[256];
    assert_true(gl_target_create(&t, &(gl_target_desc){.name = "probe",
                                                       .format = GLT_FORMAT_RGBA8,
                                                       .width = 4, .height = 4, .samples = 4},
                                 err, sizeof err));
    assert_true(gl_framebuffer_create(&fb, &(gl_framebuffer_desc){.name = "probe",
                                                                  .color = {&t}},
                                      err, sizeof err));
    GLint prev = 0;
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &prev);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fb.fbo);
    float pos[4][2];
    for (int i = 0; i < 4; i++)
        gl.GetMultisamplefv(GL_SAMPLE_POSITION, (GLuint)i, pos[i]);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)prev);
    gl_framebuffer_destroy(&fb);
    gl_target_destroy(&t);
    int edges = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int in = 0;
            for (int i = 0; i < 4; i++) {
                float sx = (float)x + pos[i][0], sy = (float)y + pos[i][1];
                in += sx > x0 && sx < x1 && sy > y0 && sy < y1;
            }
            edges += in > 0 && in < 4;
        }
    return edges;
}

static void test_per_sample_exactly_on_edges(void **state)
{
    (void)state;
    if (context_limit() < 4)
        skip();
    scene *s = build_box_face();
    assert_non_null(s);
    const int edges = count_edge_pixels(21.5f, 42.5f, 13.5f, 34.5f);
    print_message("box face: %d edge pixels of %d\n", edges, W * H);
    assert_true(edges > 0);
    /* position stored (the reference preset) and rebuilt from the multisampled depth */
    static const light_volume_mode modes[] = {LIGHT_VOLUMES_STENCIL, LIGHT_VOLUMES_FULLSCREEN,
                                              LIGHT_VOLUMES_VOLUME};
    for (size_t m = 0; m < 2 * sizeof modes / sizeof modes[0]; m++) {
        g_mode = modes[m % 3];
        g_position = m < 3 ? GBUFFER_POSITION_PRESET : GBUFFER_POSITION_DEPTH;
        image img = {0};
        frame_stats fs;
        assert_true(render("deferred", 4, s, &img, &fs, NULL));
        image_free(&img);
        const double P = (double)W * H;
        const pass_stats *ep = find_pass(&fs, "edges");
        assert_non_null(ep);
        assert_true(ep->samples == 4.0 * edges);           /* N per edge pixel */
        assert_true(fs.edge_fraction == edges / P);
        static const char *const full[] = {"ambient", "directional"};
        for (size_t k = 0; k < 2; k++) {
            const pass_stats *p = find_pass(&fs, full[k]);
            assert_non_null(p);
            if (p->samples != 4.0 * P || p->per_sample_samples != 4.0 * edges)
                print_error("%s: samples %.0f (want %.0f), per sample %.0f (want %d)\n",
                            full[k], p->samples, 4.0 * P, p->per_sample_samples, 4 * edges);
            assert_true(p->samples == 4.0 * P);            /* every sample, once */
            assert_true(p->per_sample_samples == 4.0 * edges);
            assert_true(p->samples_shaded == (P - edges) + 4.0 * edges);
            assert_int_equal(p->draw_calls, k == 0 ? 2 : 2);   /* edge draw + pixel draw */
        }
    }
    g_mode = LIGHT_VOLUMES_STENCIL;
    g_position = GBUFFER_POSITION_PRESET;
    scene_destroy(s);
}

/* msaa 4: tiled-deferred's compute path (and clustered's with clustered.shading: deferred,
 * the same shader with its depth slices) agrees with forward-spml, in one dispatch, and
 * classifies the pixels as deferred's edge pass does (the same rule, edge_rule.inc);
 * msaa 2 (llvmpipe gives 4) renders and finds the same edges too */
static void test_tiled_deferred_agrees_msaa4(void **state)
{
    (void)state;
    if (context_limit() < 4)
        skip();
    scene *s = build_lit(true);
    assert_non_null(s);
    image fwd = {0}, def = {0};
    frame_stats fs;
    assert_true(render("forward-spml", 4, s, &fwd, &fs, NULL));
    assert_true(render("deferred", 4, s, &def, &fs, NULL));
    const double deferred_edges = fs.edge_fraction;
    image_free(&def);
    for (int k = 0; k < 3; k++) {
        const char *kind = k == 1 ? "clustered" : "tiled-deferred";
        const int msaa = k == 2 ? 2 : 4;
        g_clustered_deferred = k == 1;
        image til = {0};
        pass_plan plan;
        assert_true(render(kind, msaa, s, &til, &fs, &plan));
        g_clustered_deferred = false;
        assert_int_equal(fs.total.dispatches, 1);
        assert_null(find_pass(&fs, "edges"));
        assert_non_null(find_pass(&fs, "msaa-resolve"));
        const pass_plan_entry *pe = plan_pass(&plan, "edges");
        assert_non_null(pe);
        assert_false(pe->run);
        print_message("%s msaa %d: edges %.4f (deferred msaa 4: %.4f)\n", kind, msaa,
                      fs.edge_fraction, deferred_edges);
        assert_true(fs.edge_fraction > 0.0 && fs.edge_fraction < 0.5);
        if (fs.msaa == 4)
            assert_true(fs.edge_fraction == deferred_edges);
        const pass_stats *p = find_pass(&fs, "tiled");
        assert_non_null(p);
        const double P = (double)W * H, E = fs.edge_fraction * P;
        assert_true(p->samples_shaded == P + (fs.msaa - 1) * E);
        image_error e;
        char err[256];
        assert_true(image_compare(&fwd, &til, &e, err, sizeof err));
        print_message("%s msaa %d vs forward-spml msaa 4: rmse %.3f/255, max %.0f/255, %.4f "
                      "of the pixels > 1/255\n", kind, msaa, e.rmse * 255, e.max_abs * 255,
                      e.frac_over_1_255);
        assert_int_equal(e.nonfinite, 0);
        if (fs.msaa == 4) {
            assert_true(e.rmse < RMSE_MAX);
            assert_true(e.frac_over_1_255 < 0.01);
        }
        image_free(&til);
    }
    image_free(&fwd);
    scene_destroy(s);
}

/* The box face: tiled-deferred's edge list holds exactly the counted edge pixels (position
 * stored and from depth), and its dispatch shades P + 3 E samples */
static void test_tiled_deferred_exact_edges(void **state)
{
    (void)state;
    if (context_limit() < 4)
        skip();
    scene *s = build_box_face();
    assert_non_null(s);
    const int edges = count_edge_pixels(21.5f, 42.5f, 13.5f, 34.5f);
    assert_true(edges > 0);
    for (int m = 0; m < 2; m++) {
        g_position = m == 0 ? GBUFFER_POSITION_PRESET : GBUFFER_POSITION_DEPTH;
        image img = {0};
        frame_stats fs;
        assert_true(render("tiled-deferred", 4, s, &img, &fs, NULL));
        image_free(&img);
        const double P = (double)W * H;
        if (fs.edge_fraction != edges / P)
            print_error("position %d: %.0f edge pixels, want %d\n", m, fs.edge_fraction * P,
                        edges);
        assert_true(fs.edge_fraction == edges / P);
        const pass_stats *p = find_pass(&fs, "tiled");
        assert_non_null(p);
        assert_int_equal(p->dispatches, 1);
        assert_true(p->per_sample_samples == 4.0 * edges);
        assert_true(p->samples_shaded == (P - edges) + 4.0 * edges);
    }
    g_position = GBUFFER_POSITION_PRESET;
    scene_destroy(s);
}

GL_TEST_MAIN(ctx, W, H,
             cmocka_unit_test(test_refusal_on_given_limits),
             cmocka_unit_test(test_refusal_on_the_context),
             cmocka_unit_test(test_forward_msaa4),
             cmocka_unit_test(test_edge_aa_after_msaa),
             cmocka_unit_test(test_deferred_agrees_msaa4),
             cmocka_unit_test(test_per_sample_exactly_on_edges),
             cmocka_unit_test(test_tiled_deferred_agrees_msaa4),
             cmocka_unit_test(test_tiled_deferred_exact_edges))
