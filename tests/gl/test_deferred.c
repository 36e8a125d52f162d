/* The deferred renderer (renderers/deferred/deferred.c) in a debug context, on scenes set
 * up here, against formulas from a frontend of the test's own (docs/notes/deferred.md):
 * draw calls per pass in every light-volume mode; the pixels the light passes shade
 * (GL_SAMPLES_PASSED) ordered stencil <= volume <= hull <= scissor < fullscreen, the
 * scissor's exactly its rectangle, seed 000 5.5's floating spot; fragment invocations
 * exactly W x H full screen (llvmpipe counts every 4x4 block a triangle covers, rejected
 * ones too); a floating light shading no pixel; the four modes' images within 1/255 with
 * the camera outside, inside a point or spot volume, and volumes cut by the near and far
 * planes; every preset and field override finite and close to the reference G-buffer;
 * separate specular and the state cache's force mode leaving the image alone; the sky
 * mask (seed 001 19.7.2) in every mode: the image within 1/255, each full-screen draw's
 * samples lower by exactly the sky's pixels; pruned passes, programs and attachments
 * (renderer_describe); gbuffer_bytes; the layouts. Any GL error fails; exits 77 (skip)
 * when no EGL display can be created. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "renderers/deferred/deferred.h"
#include "renderers/frame/frontend.h"
#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/state.h"
#include "renderers/renderer.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern const renderer_impl renderer_deferred_impl;
#define IMPL (&renderer_deferred_impl)

enum { W = 128, H = 96 };

static gl_context *ctx;

enum { NMODES = 6 };
static const light_volume_mode MODES[NMODES] = {
    LIGHT_VOLUMES_FULLSCREEN, LIGHT_VOLUMES_VOLUME, LIGHT_VOLUMES_STENCIL,
    LIGHT_VOLUMES_STENCIL_TWO_PASS, LIGHT_VOLUMES_HULL, LIGHT_VOLUMES_SCISSOR};
static const char *const MODE_NAMES[NMODES] = {"fullscreen", "volume", "stencil",
                                               "stencil-two-pass", "hull", "scissor"};

static const gbuffer_preset PRESETS[5] = {GBUFFER_FAT, GBUFFER_CURTIS, GBUFFER_COMPACT,
                                          GBUFFER_SPHEREMAP, GBUFFER_REFERENCE};

// >>scenes

static scene_light point(float x, float y, float z, float radius, float r, float g, float b)
{
    return (scene_light){.type = LIGHT_POINT, .position = {x, y, z}, .color = {r, g, b},
                         .direction = {0.0f, -1.0f, 0.0f}, .radius = radius,
                         .attenuation = ATTENUATION_LINEAR_RANGE};
}

static scene_light spot(const float pos[3], const float target[3], float radius, float angle_deg)
{
    scene_light l = {.type = LIGHT_SPOT, .position = {pos[0], pos[1], pos[2]},
                     .color = {0.9f, 0.8f, 0.6f}, .radius = radius,
                     .spot_angle = sm_deg2rad(angle_deg), .spot_exponent = 2.0f,
                     .attenuation = ATTENUATION_LINEAR_RANGE};
    sm_vec3_sub(target, pos, l.direction);
    sm_vec3_normalize(l.direction);
    return l;
}

static scene_light directional(float dx, float dy, float dz, float r, float g, float b)
{
    scene_light l = {.type = LIGHT_DIRECTIONAL, .direction = {dx, dy, dz}, .color = {r, g, b}};
    sm_vec3_normalize(l.direction);
    return l;
}

/* Poses s at t = 0, then looks from eye at target with the given clip planes (0: the
 * scene's). */
static void look(scene *s, const float eye[3], const float target[3], float znear, float zfar)
{
    scene_update(s, 0.0);
    if (znear > 0.0f)
        s->znear = znear;
    if (zfar > 0.0f)
        s->zfar = zfar;
    s->cam.znear = s->znear;
    s->cam.zfar = s->zfar;
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3_copy(eye, s->cam.eye);
    sm_vec3_copy(target, s->cam.target);
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
}

static const float EYE[3] = {0.0f, 12.0f, 28.0f}, TARGET[3] = {0.0f, 1.0f, 0.0f};

/* scene `name` with exactly these lights, all active, seen from EYE. */
static scene *build(const char *name, const scene_light *lights, uint32_t n)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build(name, &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("scene %s: %s", name, err);
    s->lights = calloc(n ? n : 1, sizeof *s->lights);
    assert_non_null(s->lights);
    if (n)
        memcpy(s->lights, lights, n * sizeof *lights);
    s->nlights_total = n;
    s->count = (light_count){.start = n, .max = n};
    look(s, EYE, TARGET, 0.0f, 0.0f);
    return s;
}

// >>the renderer

static renderer_options options(light_volume_mode mode, gbuffer_preset preset)
{
    const gl_info *i = gl_context_info(ctx);
    renderer_options o = {.width = W, .height = H, .queries = true,
                          .timer_query = i->timer_query,
                          .pipeline_statistics = i->pipeline_statistics,
                          .max_uniform_block_size = i->max_uniform_block_size,
                          .gbuffer = preset, .light_volumes = mode};
    renderer_options_complete(&o);   /* the renderer's own create is called: no renderer_create */
    return o;
}

static void *make(const scene *s, const renderer_options *o)
{
    char err[4096] = "";
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    void *self = IMPL->create(o, err, sizeof err);
    if (!self)
        fail_msg("deferred create: %s", err);
    if (!IMPL->prepare(self, s, err, sizeof err))
        fail_msg("deferred prepare: %s", err);
    return self;
}

static void frame(void *self, const scene *s, frame_stats *fs)
{
    memset(fs, 0, sizeof *fs);
    IMPL->draw(self, s, fs);
    gl.Finish();
    renderer_impl_collect(IMPL, self, fs);
    assert_int_equal(gl_context_poll_errors(ctx, "deferred frame"), 0);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static uint8_t *render(const scene *s, const renderer_options *o)
{
    void *self = make(s, o);
    frame_stats fs;
    frame(self, s, &fs);
    frame(self, s, &fs);   /* a second frame: the cache starts from unknown state again */
    uint8_t *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    char err[256];
    assert_true(gl_context_read_rgba8(ctx, px, err, sizeof err));
    IMPL->destroy(self);
    return px;
}

static int max_diff(const uint8_t *a, const uint8_t *b, size_t *where)
{
    int m = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++) {
        int d = abs((int)a[i] - (int)b[i]);
        if (d > m) {
            m = d;
            if (where)
                *where = i / 4;
        }
    }
    return m;
}

static size_t count_different(const uint8_t *a, const uint8_t *b, int threshold)
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        for (int c = 0; c < 3; c++)
            if (abs((int)a[4 * i + c] - (int)b[4 * i + c]) > threshold) {
                n++;
                break;
            }
    return n;
}

static double rmse(const uint8_t *a, const uint8_t *b)
{
    double sum = 0.0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        for (int c = 0; c < 3; c++) {
            double d = ((double)a[4 * i + c] - (double)b[4 * i + c]) / 255.0;
            sum += d * d;
        }
    return sqrt(sum / ((double)W * H * 3));
}

/* Visible objects and lights of each type, from a frontend of our own. */
typedef struct visible {
    uint32_t objects, lights[3];
} visible;

static visible count_visible(const scene *s)
{
    frontend fe;
    memset(&fe, 0, sizeof fe);
    char err[256];
    if (!frontend_init(&fe, s, err, sizeof err))
        fail_msg("frontend_init: %s", err);
    frontend_build(&fe, s);
    visible v = {.objects = fe.nvisible};
    for (uint32_t k = 0; k < fe.nlights; k++)
        v.lights[s->lights[fe.lights[k]].type]++;
    frontend_free(&fe);
    return v;
}

// >>draw calls

static void check_formula(const scene *s, light_volume_mode mode, bool separate)
{
    renderer_options o = options(mode, GBUFFER_CURTIS);
    o.separate_specular = separate;
    void *self = make(s, &o);
    visible v = count_visible(s);
    const uint64_t per_light = mode == LIGHT_VOLUMES_STENCIL            ? 2
                               : mode == LIGHT_VOLUMES_STENCIL_TWO_PASS ? 3
                                                                        : 1;
    for (int f = 0; f < 2; f++) {
        frame_stats fs;
        frame(self, s, &fs);
        /* the passes in order, only those that run */
        const char *want[8];
        size_t n = 0;
        want[n++] = "gbuffer";
        want[n++] = "ambient";
        bool types[3] = {false, false, false};
        for (uint32_t i = 0; i < s->nlights_total; i++)
            types[s->lights[i].type] = true;
        if (types[LIGHT_DIRECTIONAL])
            want[n++] = "directional";
        if (types[LIGHT_POINT])
            want[n++] = "point";
        if (types[LIGHT_SPOT])
            want[n++] = "spot";
        if (separate)
            want[n++] = "compose";
        if (s->sky)
            want[n++] = "sky";
        want[n++] = "resolve";
        assert_int_equal(fs.npasses, n);
        for (size_t i = 0; i < n; i++)
            assert_string_equal(fs.pass[i].name, want[i]);

        uint64_t total = 0;
        for (size_t i = 0; i < fs.npasses; i++)
            total += fs.pass[i].draw_calls;
        assert_int_equal(find_pass(&fs, "gbuffer")->draw_calls, v.objects);
        assert_int_equal(find_pass(&fs, "ambient")->draw_calls, 1);
        if (types[LIGHT_DIRECTIONAL])
            assert_int_equal(find_pass(&fs, "directional")->draw_calls,
                             v.lights[LIGHT_DIRECTIONAL]);
        if (types[LIGHT_POINT])
            assert_int_equal(find_pass(&fs, "point")->draw_calls,
                             per_light * v.lights[LIGHT_POINT]);
        if (types[LIGHT_SPOT])
            assert_int_equal(find_pass(&fs, "spot")->draw_calls, per_light * v.lights[LIGHT_SPOT]);
        if (separate)
            assert_int_equal(find_pass(&fs, "compose")->draw_calls, 1);
        if (s->sky)
            assert_int_equal(find_pass(&fs, "sky")->draw_calls, 1);
        assert_int_equal(find_pass(&fs, "resolve")->draw_calls, 1);
        /* the header's formula as a whole */
        uint64_t formula = v.objects + 1 + v.lights[LIGHT_DIRECTIONAL] +
                           per_light * (v.lights[LIGHT_POINT] + v.lights[LIGHT_SPOT]) +
                           (separate ? 1 : 0) + (s->sky ? 1 : 0) + 1;
        assert_int_equal(total, formula);
        assert_int_equal(fs.lights_drawn, v.lights[0] + v.lights[1] + v.lights[2]);
        assert_int_equal(deferred_last_shade_draws(self, LIGHT_POINT), v.lights[LIGHT_POINT]);
        assert_int_equal(deferred_last_mark_draws(self, LIGHT_SPOT),
                         (per_light - 1) * v.lights[LIGHT_SPOT]);
    }
    IMPL->destroy(self);
}

static void test_draw_calls(void **state)
{
    (void)state;
    const float sp[3] = {10.0f, 9.0f, 0.0f}, st[3] = {10.0f, 0.0f, 0.0f};
    scene_light lights[] = {
        directional(-0.3f, -1.0f, -0.2f, 0.5f, 0.5f, 0.45f),
        point(-10.0f, 3.0f, -10.0f, 7.0f, 1.0f, 0.8f, 0.6f),
        point(0.0f, 4.0f, 10.0f, 8.0f, 0.5f, 0.7f, 1.0f),
        point(0.0f, 4.0f, 400.0f, 8.0f, 1.0f, 1.0f, 1.0f),   /* behind the camera: culled */
        spot(sp, st, 14.0f, 30.0f),
    };
    scene *s = build("shapes", lights, 5);
    visible v = count_visible(s);
    assert_int_equal(v.lights[LIGHT_POINT], 2);   /* the far one is culled */
    for (int m = 0; m < NMODES; m++) {
        check_formula(s, MODES[m], false);
        check_formula(s, MODES[m], true);
    }
    /* The counts do not depend on where the camera is: inside a volume too. */
    const float in_eye[3] = {0.0f, 4.0f, 12.0f};
    look(s, in_eye, TARGET, 0.0f, 0.0f);
    for (int m = 0; m < NMODES; m++)
        check_formula(s, MODES[m], false);
    scene_destroy(s);

    /* "empty": no objects, no sky, point lights only */
    scene_light pl[] = {point(0.0f, 5.0f, 0.0f, 20.0f, 1.0f, 1.0f, 1.0f)};
    s = build("empty", pl, 1);
    for (int m = 0; m < NMODES; m++)
        check_formula(s, MODES[m], false);
    scene_destroy(s);
}

// >>fragments

/* The light pass's fragment-shader invocations (pipeline statistics, NAN without
 * them) and the samples its shade draws lit (pass_stats.samples: GL_SAMPLES_PASSED
 * outside the stencil marks). */
typedef struct light_work {
    double invocations;
    uint64_t shaded;
    double scissor_pixels;   /* passes.csv's scissor_pixels of the pass (NAN: not scissor) */
} light_work;

static light_work light_fragments(const scene *s, light_volume_mode mode, int type)
{
    renderer_options o = options(mode, GBUFFER_REFERENCE);
    void *self = make(s, &o);
    frame_stats fs;
    frame(self, s, &fs);
    frame(self, s, &fs);
    const pass_stats *p = find_pass(&fs, type == LIGHT_POINT ? "point" : "spot");
    assert_non_null(p);
    /* samples: GL_SAMPLES_PASSED of the shade draws, the stencil marks left out */
    assert_false(isnan(p->samples));
    light_work w = {.invocations = p->fragments, .shaded = (uint64_t)p->samples,
                    .scissor_pixels = p->scissor_pixels};
    if (mode == LIGHT_VOLUMES_SCISSOR)
        assert_false(isnan(p->scissor_pixels));
    else
        assert_true(isnan(p->scissor_pixels));
    IMPL->destroy(self);
    return w;
}

static void test_fragment_order(void **state)
{
    (void)state;
    const float sp[3] = {-10.0f, 8.0f, -10.0f}, st[3] = {-10.0f, 0.0f, -10.0f};
    scene_light lights[] = {point(10.0f, 2.0f, 0.0f, 5.0f, 1.0f, 0.8f, 0.6f),
                            spot(sp, st, 12.0f, 25.0f)};
    scene *s = build("shapes", lights, 2);
    static const int types[2] = {LIGHT_POINT, LIGHT_SPOT};
    const bool stats = gl_context_info(ctx)->pipeline_statistics;
    for (int p = 0; p < 2; p++) {
        light_work w[NMODES];
        for (int m = 0; m < NMODES; m++)
            w[m] = light_fragments(s, MODES[m], types[p]);
        print_message("%s: shaded samples hull %llu scissor %llu (rectangle %.0f)\n",
                      types[p] == LIGHT_POINT ? "point" : "spot",
                      (unsigned long long)w[4].shaded, (unsigned long long)w[5].shaded,
                      w[5].scissor_pixels);
        /* the hull shades every pixel its back faces cover: at least what the volume's
         * depth test lets through, fewer than the screen; the scissor's full-screen
         * triangle shades exactly its rectangle, which holds the hull's projection */
        assert_true(w[4].shaded >= w[1].shaded);
        assert_true(w[4].shaded < w[0].shaded);
        assert_true(w[5].shaded == (uint64_t)w[5].scissor_pixels);
        assert_true(w[5].shaded >= w[4].shaded);
        assert_true(w[5].shaded < w[0].shaded);
        print_message("%s: shaded samples fullscreen %llu volume %llu stencil %llu "
                      "stencil-two-pass %llu; invocations %.0f %.0f %.0f %.0f\n",
                      types[p] == LIGHT_POINT ? "point" : "spot",
                      (unsigned long long)w[0].shaded, (unsigned long long)w[1].shaded,
                      (unsigned long long)w[2].shaded, (unsigned long long)w[3].shaded,
                      w[0].invocations, w[1].invocations, w[2].invocations, w[3].invocations);
        /* what the shade draws light: stencil <= volume < fullscreen (every pixel) */
        assert_int_equal(w[0].shaded, (uint64_t)W * H);
        assert_true(w[2].shaded <= w[1].shaded);
        assert_true(w[3].shaded <= w[1].shaded);
        assert_int_equal(w[2].shaded, w[3].shaded);   /* both stencil modes mark alike */
        assert_true(w[1].shaded < w[0].shaded);
        assert_true(w[2].shaded > 0);                 /* the light does reach surfaces */
        if (stats) {
            /* The full-screen pass is exactly W x H invocations (unclipped triangle); a
             * volume covers fewer. */
            assert_true(w[0].invocations == (double)W * H);
            assert_true(w[1].invocations < w[0].invocations);
        } else {
            assert_true(isnan(w[0].invocations));
        }
    }
    scene_destroy(s);
}

/* A point light high above everything, its volume in front of the floor as the
 * camera sees it (camera outside): no surface is in it, and the stencil modes shade
 * nothing. */
static void test_floating_light(void **state)
{
    (void)state;
    scene_light lights[] = {point(0.0f, 20.0f, 8.0f, 3.0f, 1.0f, 1.0f, 1.0f)};
    scene *s = build("shapes", lights, 1);
    const float eye[3] = {0.0f, 30.0f, 30.0f}, target[3] = {0.0f, 0.0f, 0.0f};
    look(s, eye, target, 0.0f, 0.0f);
    assert_int_equal(count_visible(s).lights[LIGHT_POINT], 1);
    light_work st = light_fragments(s, LIGHT_VOLUMES_STENCIL, LIGHT_POINT);
    light_work s2 = light_fragments(s, LIGHT_VOLUMES_STENCIL_TWO_PASS, LIGHT_POINT);
    light_work fv = light_fragments(s, LIGHT_VOLUMES_VOLUME, LIGHT_POINT);
    light_work ff = light_fragments(s, LIGHT_VOLUMES_FULLSCREEN, LIGHT_POINT);
    light_work fh = light_fragments(s, LIGHT_VOLUMES_HULL, LIGHT_POINT);
    light_work fs = light_fragments(s, LIGHT_VOLUMES_SCISSOR, LIGHT_POINT);
    print_message("floating light: shaded samples hull %llu scissor %llu (rectangle %.0f)\n",
                  (unsigned long long)fh.shaded, (unsigned long long)fs.shaded,
                  fs.scissor_pixels);
    /* seed 000 4.5.8's baseline shades the whole hull where the stencil shades nothing */
    assert_true(fh.shaded >= 10u * (st.shaded + 1u));
    assert_true(fs.shaded == (uint64_t)fs.scissor_pixels && fs.shaded >= fh.shaded);
    print_message("floating light: shaded samples stencil %llu stencil-two-pass %llu volume "
                  "%llu fullscreen %llu; invocations %.0f %.0f %.0f %.0f\n",
                  (unsigned long long)st.shaded, (unsigned long long)s2.shaded,
                  (unsigned long long)fv.shaded, (unsigned long long)ff.shaded, st.invocations,
                  s2.invocations, fv.invocations, ff.invocations);
    assert_int_equal(st.shaded, 0);
    assert_int_equal(s2.shaded, 0);
    assert_int_equal(ff.shaded, (uint64_t)W * H);
    if (gl_context_info(ctx)->pipeline_statistics)
        assert_true(fv.invocations > 0.0);   /* the volume is on screen */
    scene_destroy(s);
}

/* Seed 000 5.5's floating spot (the catalog's floating-spot, its lights, the eye of
 * its hold 1): the volume covers most of the screen and lights nothing. Both stencil
 * modes shade exactly no sample (their marks are not counted); the hull, the paper's
 * baseline, shades every pixel it covers: more than half the screen. */
static void test_floating_spot(void **state)
{
    (void)state;
    char err[256];
    light_params lp = {.placement = PLACEMENT_SCENE, .radius = 1.0f,
                       .count = {.start = LIGHT_COUNT_ALL, .max = LIGHT_COUNT_ALL}};
    scene *s = scene_build("floating-spot", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("floating-spot: %s", err);
    assert_int_equal(s->nlights_total, 1);
    scene_update(s, 0.0);
    const float eye[3] = {0.0f, 3.3f, 1.8f}, target[3] = {0.0f, 3.2f, 0.0f};
    look(s, eye, target, 0.0f, 0.0f);
    assert_int_equal(count_visible(s).lights[LIGHT_SPOT], 1);
    light_work st = light_fragments(s, LIGHT_VOLUMES_STENCIL, LIGHT_SPOT);
    light_work s2 = light_fragments(s, LIGHT_VOLUMES_STENCIL_TWO_PASS, LIGHT_SPOT);
    light_work hu = light_fragments(s, LIGHT_VOLUMES_HULL, LIGHT_SPOT);
    light_work sc = light_fragments(s, LIGHT_VOLUMES_SCISSOR, LIGHT_SPOT);
    print_message("floating-spot: samples stencil %llu stencil-two-pass %llu hull %llu "
                  "scissor %llu (of %d)\n", (unsigned long long)st.shaded,
                  (unsigned long long)s2.shaded, (unsigned long long)hu.shaded,
                  (unsigned long long)sc.shaded, W * H);
    assert_int_equal(st.shaded, 0);
    assert_int_equal(s2.shaded, 0);
    assert_true(hu.shaded > (uint64_t)W * H / 2);
    assert_true(hu.shaded >= 10u * (st.shaded + 1u));
    assert_true(sc.shaded == (uint64_t)sc.scissor_pixels && sc.shaded >= hu.shaded);
    scene_destroy(s);
}

// >>the scissor rectangle

/* A point light straight ahead of the camera: its volume's box (+-1.05 x 1.1 x radius
 * about the light, deferred_scissor_rect) projects to a square whose half side in NDC
 * is proj[0][0] b / (d - b) (x) and proj[1][1] b / (d - b) (y), b the box's half side,
 * d the light's distance: the near face is the widest. The rectangle is the whole
 * pixels that holds, its area what the pass reports and what it shades. */
static void test_scissor_rect(void **state)
{
    (void)state;
    const float d = 20.0f, radius = 3.0f;
    scene_light lights[] = {point(0.0f, 2.0f, -d, radius, 1.0f, 1.0f, 1.0f)};
    scene *s = build("shapes", lights, 1);
    const float eye[3] = {0.0f, 2.0f, 0.0f}, target[3] = {0.0f, 2.0f, -1.0f};
    look(s, eye, target, 0.0f, 0.0f);
    double b = 1.05 * 1.1 * radius;
    double ax = s->proj[0][0] * b / (d - b), ay = s->proj[1][1] * b / (d - b);
    int x0 = (int)floor(W / 2.0 * (1.0 - ax)), x1 = (int)ceil(W / 2.0 * (1.0 + ax));
    int y0 = (int)floor(H / 2.0 * (1.0 - ay)), y1 = (int)ceil(H / 2.0 * (1.0 + ay));
    int rect[4];
    int64_t area = deferred_scissor_rect(s, 0, W, H, rect);
    print_message("scissor rectangle (%d, %d) %dx%d, expected (%d, %d) %dx%d\n", rect[0],
                  rect[1], rect[2], rect[3], x0, y0, x1 - x0, y1 - y0);
    assert_int_equal(rect[0], x0);
    assert_int_equal(rect[1], y0);
    assert_int_equal(rect[2], x1 - x0);
    assert_int_equal(rect[3], y1 - y0);
    assert_int_equal(area, (int64_t)(x1 - x0) * (y1 - y0));
    light_work w = light_fragments(s, LIGHT_VOLUMES_SCISSOR, LIGHT_POINT);
    assert_true(w.scissor_pixels == (double)area);
    assert_int_equal(w.shaded, (uint64_t)area);
    /* behind the camera: nothing; reaching the eye's plane: the whole screen */
    s->lights[0].position[2] = 30.0f;
    assert_int_equal(deferred_scissor_rect(s, 0, W, H, rect), 0);
    s->lights[0].position[2] = -2.0f;
    assert_int_equal(deferred_scissor_rect(s, 0, W, H, rect), (int64_t)W * H);
    scene_destroy(s);
}

// >>images

typedef enum where_kind { CAMERA_OUTSIDE, CAMERA_INSIDE, NEAR_CUTS, FAR_CUTS } where_kind;

typedef struct image_case {
    const char *what;
    where_kind where;
    scene_light light;
    float eye[3], target[3];
    float znear, zfar;
} image_case;

static void check_modes_agree(const image_case *c)
{
    scene *s = build("shapes", &c->light, 1);
    look(s, c->eye, c->target, c->znear, c->zfar);
    visible v = count_visible(s);
    assert_int_equal(v.lights[LIGHT_POINT] + v.lights[LIGHT_SPOT], 1);
    /* The case is what it says: where the eye and the clip planes are against the
     * volume as drawn (a point light's mesh lies between 1.1 and 1.1 x 1.0389 radii). */
    const scene_light *l = &c->light;
    sm_vec3 d;
    sm_vec3_sub(c->eye, l->position, d);
    float dist = sm_vec3_norm(d);
    float lo = 1.1f * l->radius, hi = 1.1f * 1.0389f * l->radius;
    sm_vec3 pv;
    sm_mat4_mulv3(s->view, l->position, 1.0f, pv);
    switch (c->where) {
    case CAMERA_OUTSIDE:
        assert_true(dist > hi && -pv[2] - hi > s->znear && -pv[2] + hi < s->zfar);
        break;
    case CAMERA_INSIDE:
        if (l->type == LIGHT_POINT) {
            assert_true(dist < lo);
        } else {
            /* inside the spot's cone of height radius (which its volume holds) */
            float h = -sm_vec3_dot(d, l->direction);
            assert_true(h < 0.0f && -h < l->radius);
            assert_true(-h / dist > cosf(l->spot_angle));
        }
        break;
    case NEAR_CUTS:
        assert_true(dist > hi && -pv[2] - lo < s->znear);
        break;
    case FAR_CUTS:
        assert_true(dist > hi && -pv[2] + lo > s->zfar && -pv[2] < s->zfar);
        break;
    }
    uint8_t *img[NMODES];
    for (int m = 0; m < NMODES; m++) {
        renderer_options o = options(MODES[m], GBUFFER_REFERENCE);
        img[m] = render(s, &o);
    }
    /* The light must matter: without it the image differs in many pixels. */
    s->nlights_active = 0;
    renderer_options o = options(LIGHT_VOLUMES_FULLSCREEN, GBUFFER_REFERENCE);
    uint8_t *dark = render(s, &o);
    size_t lit = count_different(img[0], dark, 2);
    print_message("%s: %zu pixels lit\n", c->what, lit);
    assert_true(lit > (size_t)W * H / 50);
    for (int m = 1; m < NMODES; m++) {
        size_t at = 0;
        int diff = max_diff(img[0], img[m], &at);
        if (diff > 1)
            fail_msg("%s: %s differs from fullscreen by %d/255 at pixel (%zu, %zu)", c->what,
                     MODE_NAMES[m], diff, at % W, at / W);
        /* hull and scissor against stencil too (seed 000 5.5 compares them) */
        diff = m >= 4 ? max_diff(img[2], img[m], &at) : 0;
        if (diff > 1)
            fail_msg("%s: %s differs from stencil by %d/255 at pixel (%zu, %zu)", c->what,
                     MODE_NAMES[m], diff, at % W, at / W);
    }
    for (int m = 0; m < NMODES; m++)
        free(img[m]);
    free(dark);
    scene_destroy(s);
}

static void test_modes_agree(void **state)
{
    (void)state;
    /* A point light's drawn volume reaches 1.1 x 1.0389 x its radius from it. */
    const float k = 1.1f * 1.0389f;
    image_case cases[5];
    memset(cases, 0, sizeof cases);
    /* outside: a light on the grid, seen from afar */
    cases[0] = (image_case){.what = "camera outside", .where = CAMERA_OUTSIDE,
                            .light = point(0.0f, 3.0f, 0.0f, 9.0f, 1.0f, 0.8f, 0.6f),
                            .eye = {0.0f, 12.0f, 28.0f}, .target = {0.0f, 1.0f, 0.0f}};
    /* inside a point volume */
    cases[1] = (image_case){.what = "camera inside a point volume", .where = CAMERA_INSIDE,
                            .light = point(0.0f, 4.0f, 14.0f, 12.0f, 1.0f, 0.9f, 0.7f),
                            .eye = {0.0f, 5.0f, 18.0f}, .target = {0.0f, 1.0f, 0.0f}};
    /* inside a spot volume: the spot just behind the eye, looking where the eye looks */
    {
        const float sp[3] = {0.0f, 9.0f, 24.0f}, st[3] = {0.0f, 0.0f, 0.0f};
        cases[2] = (image_case){.what = "camera inside a spot volume", .where = CAMERA_INSIDE,
                                .light = spot(sp, st, 45.0f, 30.0f),
                                .eye = {0.0f, 8.6f, 23.0f}, .target = {0.0f, 0.0f, 0.0f}};
    }
    /* the near plane cuts a point volume, the eye outside it: the volume's surface is
     * 1 unit from the eye, the near plane 2 units */
    {
        const float eye[3] = {0.0f, 3.0f, 20.0f}, target[3] = {0.0f, 0.0f, 0.0f};
        float dir[3];
        sm_vec3_sub(target, eye, dir);
        sm_vec3_normalize(dir);
        const float r = 4.0f, dist = r * k + 1.0f;
        cases[3] = (image_case){.what = "near plane cuts a point volume", .where = NEAR_CUTS,
                                .light = point(eye[0] + dir[0] * dist, eye[1] + dir[1] * dist,
                                               eye[2] + dir[2] * dist, r, 1.0f, 0.9f, 0.8f),
                                .eye = {eye[0], eye[1], eye[2]},
                                .target = {target[0], target[1], target[2]},
                                .znear = 2.0f};
    }
    /* the far plane (30) cuts a point volume lying on the floor 28 away */
    cases[4] = (image_case){.what = "far plane cuts a point volume", .where = FAR_CUTS,
                            .light = point(-5.0f, 1.5f, -6.0f, 10.0f, 1.0f, 1.0f, 1.0f),
                            .eye = {-5.0f, 3.0f, 20.0f}, .target = {-5.0f, 1.0f, -8.0f},
                            .zfar = 30.0f};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        check_modes_agree(&cases[i]);
}

// >>presets

typedef struct preset_case {
    gbuffer_preset preset;
    gbuffer_position position;
    gbuffer_normal normal;
    double max_rmse;           /* against the reference G-buffer's image */
} preset_case;

static void check_hdr_finite(void *self, const char *what)
{
    const gl_target *t = deferred_hdr_target(self);
    assert_non_null(t);
    assert_int_equal(t->format, GLT_FORMAT_RGBA16F);
    size_t n = (size_t)W * H * 4;
    float *buf = malloc(n * sizeof *buf);
    assert_non_null(buf);
    gl.GetTextureImage(t->texture, 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * sizeof *buf), buf);
    size_t bad = 0;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(buf[i]))
            bad++;
    if (bad)
        fail_msg("%s: %zu non-finite values in the HDR target", what, bad);
    free(buf);
}

static void test_presets(void **state)
{
    (void)state;
    const float sp[3] = {10.0f, 9.0f, -10.0f}, st[3] = {10.0f, 0.0f, -10.0f};
    scene_light lights[] = {
        directional(-0.3f, -1.0f, -0.2f, 0.4f, 0.4f, 0.35f),
        point(-10.0f, 3.0f, -10.0f, 8.0f, 1.0f, 0.8f, 0.6f),
        point(0.0f, 4.0f, 10.0f, 9.0f, 0.5f, 0.7f, 1.0f),
        point(10.0f, 3.0f, 0.0f, 7.0f, 0.8f, 1.0f, 0.6f),
        spot(sp, st, 14.0f, 30.0f),
    };
    scene *s = build("shapes", lights, 5);
    renderer_options ro = options(LIGHT_VOLUMES_STENCIL, GBUFFER_REFERENCE);
    uint8_t *ref = render(s, &ro);
    static const preset_case cases[] = {
        {GBUFFER_REFERENCE, 0, 0, 0.0},
        {GBUFFER_FAT, 0, 0, 0.03},
        {GBUFFER_CURTIS, 0, 0, 0.03},
        {GBUFFER_COMPACT, 0, 0, 0.03},
        {GBUFFER_SPHEREMAP, 0, 0, 0.03},
        {GBUFFER_FAT, GBUFFER_POSITION_DEPTH, GBUFFER_NORMAL_FLOAT32, 0.03},
        {GBUFFER_CURTIS, GBUFFER_POSITION_STORED32, GBUFFER_NORMAL_UNORM10, 0.03},
        {GBUFFER_COMPACT, GBUFFER_POSITION_DEPTH, GBUFFER_NORMAL_SPHEREMAP16, 0.03},
        {GBUFFER_SPHEREMAP, GBUFFER_POSITION_STORED16, GBUFFER_NORMAL_FLOAT16, 0.03},
        {GBUFFER_REFERENCE, GBUFFER_POSITION_DEPTH, GBUFFER_NORMAL_SPHEREMAP8, 0.03},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const preset_case *c = &cases[i];
        renderer_options o = options(LIGHT_VOLUMES_STENCIL, c->preset);
        o.gbuffer_position = c->position;
        o.gbuffer_normal = c->normal;
        void *self = make(s, &o);
        frame_stats fs;
        frame(self, s, &fs);
        frame(self, s, &fs);
        char what[64];
        snprintf(what, sizeof what, "%s (position %d, normal %d)",
                 deferred_preset_name(c->preset), (int)c->position, (int)c->normal);
        check_hdr_finite(self, what);
        uint8_t *px = malloc((size_t)W * H * 4);
        assert_non_null(px);
        char err[256];
        assert_true(gl_context_read_rgba8(ctx, px, err, sizeof err));
        double e = rmse(px, ref);
        print_message("%s: RMSE %.5f against the reference G-buffer\n", what, e);
        assert_true(e <= c->max_rmse);
        free(px);
        IMPL->destroy(self);
    }
    free(ref);
    scene_destroy(s);
}

/* Separate diffuse and specular accumulation (seed 001) gives the same image. */
static void test_separate_specular(void **state)
{
    (void)state;
    scene_light lights[] = {directional(0.2f, -1.0f, -0.4f, 0.5f, 0.5f, 0.5f),
                            point(0.0f, 4.0f, 10.0f, 9.0f, 1.0f, 1.0f, 1.0f)};
    scene *s = build("shapes", lights, 2);
    renderer_options o = options(LIGHT_VOLUMES_VOLUME, GBUFFER_REFERENCE);
    uint8_t *a = render(s, &o);
    o.separate_specular = true;
    uint8_t *b = render(s, &o);
    assert_true(max_diff(a, b, NULL) <= 1);
    void *self = make(s, &o);
    pass_plan plan;
    IMPL->describe(self, &plan);
    bool diffuse = false, specular = false;
    for (size_t i = 0; i < plan.ntargets; i++) {
        diffuse |= strcmp(plan.target[i].name, "light.diffuse") == 0;
        specular |= strcmp(plan.target[i].name, "light.specular") == 0;
    }
    assert_true(diffuse && specular);
    IMPL->destroy(self);
    free(a);
    free(b);
    scene_destroy(s);
}

// >>the sky mask (deferred.sky_stencil, seed 001 section 19.7.2)

typedef struct sky_result {
    frame_stats fs;
    uint8_t *px;
    float *depth;   /* the depth target after the frame, row 0 at the bottom */
} sky_result;

static sky_result sky_render(const scene *s, const renderer_options *o)
{
    sky_result r;
    void *self = make(s, o);
    frame(self, s, &r.fs);
    frame(self, s, &r.fs);
    r.px = malloc((size_t)W * H * 4);
    r.depth = malloc((size_t)W * H * sizeof(float));
    assert_non_null(r.px);
    assert_non_null(r.depth);
    char err[256];
    assert_true(gl_context_read_rgba8(ctx, r.px, err, sizeof err));
    const gl_target *d = deferred_depth_target(self);
    assert_non_null(d);
    gl.GetTextureImage(d->texture, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                       (GLsizei)((size_t)W * H * sizeof(float)), r.depth);
    assert_int_equal(gl_context_poll_errors(ctx, "depth read-back"), 0);
    IMPL->destroy(self);
    return r;
}

static int64_t samples_of(const frame_stats *fs, const char *pass)
{
    const pass_stats *p = find_pass(fs, pass);
    if (!p)
        fail_msg("no pass %s", pass);
    assert_true(isfinite(p->samples) && p->samples >= 0.0);
    return (int64_t)p->samples;
}

/* Pixels at depth 1 (no surface: the sky) in the rectangle {x, y, w, h} of window
 * coordinates, from the depth read back: counted without the stencil. */
static int64_t sky_in(const float *depth, const int rect[4])
{
    int64_t n = 0;
    for (int y = rect[1]; y < rect[1] + rect[3]; y++)
        for (int x = rect[0]; x < rect[0] + rect[2]; x++)
            n += depth[(size_t)y * W + (size_t)x] == 1.0f;
    return n;
}

/* The sky pixels in the scissor rectangles of the visible lights of type t. */
static int64_t sky_in_scissors(const scene *s, int t, const float *depth)
{
    frontend fe;
    memset(&fe, 0, sizeof fe);
    char err[256];
    if (!frontend_init(&fe, s, err, sizeof err))
        fail_msg("frontend_init: %s", err);
    frontend_build(&fe, s);
    int64_t n = 0;
    for (uint32_t k = 0; k < fe.nlights; k++) {
        if ((int)s->lights[fe.lights[k]].type != t)
            continue;
        int rect[4];
        deferred_scissor_rect(s, fe.lights[k], W, H, rect);
        n += sky_in(depth, rect);
    }
    frontend_free(&fe);
    return n;
}

/* With the mask, the same image within 1/255, and every full-screen draw shades exactly
 * the sky's pixels fewer samples; the other passes shade what they did. */
static void check_sky_stencil(const scene *s, light_volume_mode mode, bool separate)
{
    renderer_options o = options(mode, GBUFFER_CURTIS);
    o.separate_specular = separate;
    sky_result off = sky_render(s, &o);
    o.sky_stencil = true;
    sky_result on = sky_render(s, &o);
    const int screen[4] = {0, 0, W, H};
    const int64_t sky = sky_in(off.depth, screen);
    assert_memory_equal(off.depth, on.depth, (size_t)W * H * sizeof(float));
    const visible v = count_visible(s);
    const int64_t d = v.lights[LIGHT_DIRECTIONAL], np = v.lights[LIGHT_POINT],
                  ns = v.lights[LIGHT_SPOT];
    size_t where = 0;
    int diff = max_diff(off.px, on.px, &where);
    print_message("sky mask, %s%s%s: %lld sky pixels of %d; ambient samples %lld -> %lld, "
                  "point %lld -> %lld, spot %lld -> %lld; image max difference %d/255\n",
                  MODE_NAMES[mode == LIGHT_VOLUMES_FULLSCREEN ? 0
                             : mode == LIGHT_VOLUMES_VOLUME ? 1
                             : mode == LIGHT_VOLUMES_STENCIL ? 2
                             : mode == LIGHT_VOLUMES_STENCIL_TWO_PASS ? 3
                             : mode == LIGHT_VOLUMES_HULL ? 4 : 5],
                  separate ? ", separate specular" : "", s->sky ? "" : ", no sky pass",
                  (long long)sky, W * H, (long long)samples_of(&off.fs, "ambient"),
                  (long long)samples_of(&on.fs, "ambient"),
                  (long long)samples_of(&off.fs, "point"), (long long)samples_of(&on.fs, "point"),
                  (long long)samples_of(&off.fs, "spot"), (long long)samples_of(&on.fs, "spot"),
                  diff);
    assert_true(sky > W * H / 8 && sky < W * H * 7 / 8);   /* the case has both */
    assert_true(d > 0 && np > 0 && ns > 0);
    assert_true(diff <= 1);
    assert_int_equal(off.fs.npasses, on.fs.npasses);
    for (size_t i = 0; i < off.fs.npasses; i++) {
        assert_string_equal(off.fs.pass[i].name, on.fs.pass[i].name);
        assert_int_equal(off.fs.pass[i].draw_calls, on.fs.pass[i].draw_calls);
    }
    assert_int_equal(samples_of(&on.fs, "gbuffer"), samples_of(&off.fs, "gbuffer"));
    /* full screen: every pixel without the mask, all but the sky's with it */
    assert_int_equal(samples_of(&off.fs, "ambient"), (int64_t)W * H);
    assert_int_equal(samples_of(&off.fs, "ambient") - samples_of(&on.fs, "ambient"), sky);
    assert_int_equal(samples_of(&off.fs, "directional") - samples_of(&on.fs, "directional"),
                     d * sky);
    int64_t point_less = 0, spot_less = 0;   /* what the mask saves the point and spot passes */
    if (mode == LIGHT_VOLUMES_FULLSCREEN) {
        point_less = np * sky;
        spot_less = ns * sky;
    } else if (mode == LIGHT_VOLUMES_SCISSOR) {
        point_less = sky_in_scissors(s, LIGHT_POINT, off.depth);
        spot_less = sky_in_scissors(s, LIGHT_SPOT, off.depth);
        assert_true(point_less > 0);   /* the point light's rectangle reaches the sky */
    }
    assert_int_equal(samples_of(&off.fs, "point") - samples_of(&on.fs, "point"), point_less);
    assert_int_equal(samples_of(&off.fs, "spot") - samples_of(&on.fs, "spot"), spot_less);
    if (separate)
        assert_int_equal(samples_of(&off.fs, "compose") - samples_of(&on.fs, "compose"), sky);
    if (s->sky) {
        /* the sky pass draws exactly the unmarked pixels, mask or not */
        assert_int_equal(samples_of(&off.fs, "sky"), sky);
        assert_int_equal(samples_of(&on.fs, "sky"), sky);
    }
    free(off.px);
    free(off.depth);
    free(on.px);
    free(on.depth);
}

extern const renderer_impl renderer_tiled_deferred_impl;

static void test_sky_stencil(void **state)
{
    (void)state;
    const float sp[3] = {-10.0f, 8.0f, -10.0f}, st[3] = {-10.0f, 0.0f, -10.0f};
    scene_light lights[] = {directional(0.2f, -1.0f, -0.4f, 0.4f, 0.4f, 0.4f),
                            point(10.0f, 2.0f, 0.0f, 8.0f, 1.0f, 0.8f, 0.6f),
                            point(-10.0f, 3.0f, 10.0f, 6.0f, 0.5f, 0.6f, 1.0f),
                            spot(sp, st, 12.0f, 25.0f)};
    scene *s = build("shapes", lights, 4);
    /* eye level with the horizon: the floor below, the sky above, the objects between */
    const float eye[3] = {0.0f, 3.0f, 28.0f}, target[3] = {0.0f, 3.0f, 0.0f};
    look(s, eye, target, 0.0f, 0.0f);
    assert_true(s->sky);
    for (int m = 0; m < NMODES; m++)
        check_sky_stencil(s, MODES[m], false);
    check_sky_stencil(s, LIGHT_VOLUMES_SCISSOR, true);
    /* no sky pass: the light target is cleared where the ambient pass no longer writes */
    s->sky = false;
    check_sky_stencil(s, LIGHT_VOLUMES_FULLSCREEN, true);
    check_sky_stencil(s, LIGHT_VOLUMES_STENCIL_TWO_PASS, false);
    check_sky_stencil(s, LIGHT_VOLUMES_STENCIL, false);
    /* tiled-deferred shades in a compute dispatch: no stencil test to mask it */
    renderer_options o = options(LIGHT_VOLUMES_STENCIL, GBUFFER_CURTIS);
    o.sky_stencil = true;
    char err[512] = "";
    assert_null(renderer_tiled_deferred_impl.create(&o, err, sizeof err));
    assert_non_null(strstr(err, "tiled-deferred: deferred.sky_stencil:"));
    scene_destroy(s);
}

/* With the state cache forcing every set, nothing changes: no state is changed behind
 * the cache's back (depth clamp is outside the cache and switched back each pass). */
static void test_force(void **state)
{
    (void)state;
    const float sp[3] = {10.0f, 9.0f, -10.0f}, st[3] = {10.0f, 0.0f, -10.0f};
    scene_light lights[] = {directional(-0.3f, -1.0f, -0.2f, 0.4f, 0.4f, 0.35f),
                            point(0.0f, 4.0f, 10.0f, 9.0f, 0.5f, 0.7f, 1.0f),
                            spot(sp, st, 14.0f, 30.0f)};
    scene *s = build("shapes", lights, 3);
    for (int m = 0; m < NMODES; m++) {
        renderer_options o = options(MODES[m], GBUFFER_SPHEREMAP);
        o.separate_specular = m == 1;
        uint8_t *a = render(s, &o);
        void *self = make(s, &o);
        gl_state_set_force(deferred_state_cache(self), true);
        frame_stats fs;
        frame(self, s, &fs);
        frame(self, s, &fs);
        uint8_t *b = malloc((size_t)W * H * 4);
        assert_non_null(b);
        char err[256];
        assert_true(gl_context_read_rgba8(ctx, b, err, sizeof err));
        assert_int_equal(max_diff(a, b, NULL), 0);
        IMPL->destroy(self);
        free(a);
        free(b);
    }
    scene_destroy(s);
}

// >>pruning and describe

static const pass_plan_entry *plan_pass_or_fail(const pass_plan *p, const char *name)
{
    for (size_t i = 0; i < p->npasses; i++)
        if (strcmp(p->pass[i].name, name) == 0)
            return &p->pass[i];
    fail_msg("no pass %s in the plan", name);
    return NULL;
}

static size_t programs_named(const pass_plan *p, const char *prefix)
{
    size_t n = 0, len = strlen(prefix);
    for (size_t i = 0; i < p->nprograms; i++)
        if (strncmp(p->program[i], prefix, len) == 0 &&
            (p->program[i][len] == '\0' || p->program[i][len] == '+'))
            n++;
    return n;
}

static size_t targets_containing(const pass_plan *p, const char *word)
{
    size_t n = 0;
    for (size_t i = 0; i < p->ntargets; i++)
        if (strstr(p->target[i].name, word))
            n++;
    return n;
}

/* gbuffer_bytes: the G-buffer's attachments, and the layout's bytes per pixel. */
static void check_bytes(void *self, const pass_plan *p)
{
    uint64_t gb = 0, all = 0;
    size_t ngb = 0;
    for (size_t i = 0; i < p->ntargets; i++) {
        const target_plan_entry *t = &p->target[i];
        assert_int_equal(t->width, W);
        assert_int_equal(t->height, H);
        all += t->bytes;
        if (strncmp(t->name, "gbuffer.", 8) == 0) {
            gb += t->bytes;
            ngb++;
        }
    }
    const deferred_layout *l = deferred_gbuffer_layout(self);
    assert_non_null(l);
    assert_int_equal(ngb, (size_t)l->nattachments);
    assert_int_equal(p->gbuffer_bytes, gb);
    assert_int_equal(p->gbuffer_bytes, (uint64_t)W * H * deferred_layout_bytes_per_pixel(l));
    assert_int_equal(p->target_bytes, all);
    for (int k = 0; k < l->nattachments; k++) {
        const gl_target *t = deferred_gbuffer_target(self, k);
        assert_non_null(t);
        assert_string_equal(t->name, l->att[k].name);
        assert_int_equal(t->format, l->att[k].format);
    }
    assert_null(deferred_gbuffer_target(self, l->nattachments));
}

static void test_pruning(void **state)
{
    (void)state;
    /* point lights only: no spot or directional pass, program or draw */
    scene_light lights[] = {point(0.0f, 4.0f, 10.0f, 9.0f, 1.0f, 1.0f, 1.0f),
                            point(-10.0f, 3.0f, -10.0f, 8.0f, 1.0f, 0.8f, 0.6f)};
    scene *s = build("shapes", lights, 2);
    for (int m = 0; m < NMODES; m++) {
        renderer_options o = options(MODES[m], GBUFFER_CURTIS);
        void *self = make(s, &o);
        pass_plan p;
        memset(&p, 0xff, sizeof p);
        IMPL->describe(self, &p);
        const pass_plan_entry *e = plan_pass_or_fail(&p, "spot");
        assert_false(e->run);
        assert_string_equal(e->reason, "no spot light in the scene");
        e = plan_pass_or_fail(&p, "directional");
        assert_false(e->run);
        assert_string_equal(e->reason, "no directional light in the scene");
        assert_true(plan_pass_or_fail(&p, "point")->run);
        assert_true(plan_pass_or_fail(&p, "gbuffer")->run);
        assert_true(plan_pass_or_fail(&p, "ambient")->run);
        assert_true(plan_pass_or_fail(&p, "sky")->run);
        assert_true(plan_pass_or_fail(&p, "resolve")->run);
        assert_false(plan_pass_or_fail(&p, "compose")->run);
        assert_false(plan_pass_or_fail(&p, "shadows")->run);
        assert_string_equal(plan_pass_or_fail(&p, "shadows")->reason, "no light casts shadows");
        assert_string_equal(p.pass[0].name, "shadows");
        assert_string_equal(p.pass[1].name, "gbuffer");
        assert_int_equal(programs_named(&p, "deferred_spot"), 0);
        assert_int_equal(programs_named(&p, "deferred_directional"), 0);
        assert_int_equal(programs_named(&p, "deferred_point"), 1);
        assert_int_equal(programs_named(&p, "deferred_ambient"), 1);
        assert_int_equal(programs_named(&p, "deferred_compose"), 0);
        /* shapes' materials: plain, diffuse, diffuse + gloss, diffuse + normal + emissive */
        assert_int_equal(programs_named(&p, "deferred_gbuffer"), 4);
        bool stencil = MODES[m] == LIGHT_VOLUMES_STENCIL || MODES[m] == LIGHT_VOLUMES_STENCIL_TWO_PASS;
        assert_int_equal(programs_named(&p, "deferred_stencil_mark"), stencil ? 1 : 0);
        check_bytes(self, &p);
        frame_stats fs;
        frame(self, s, &fs);
        assert_null(find_pass(&fs, "spot"));
        assert_null(find_pass(&fs, "directional"));
        assert_non_null(find_pass(&fs, "point"));
        IMPL->destroy(self);
    }

    /* emissive and gloss: with them every preset has their channels ... */
    for (int i = 0; i < 5; i++) {
        renderer_options o = options(LIGHT_VOLUMES_STENCIL, PRESETS[i]);
        void *self = make(s, &o);
        pass_plan p;
        IMPL->describe(self, &p);
        assert_int_equal(targets_containing(&p, "emissive"), 1);
        assert_int_equal(targets_containing(&p, "gloss"), 1);
        assert_int_equal(targets_containing(&p, "shininess"), 1);
        check_bytes(self, &p);
        IMPL->destroy(self);
    }
    /* ... without an emissive material, no emissive channel; without specular, no
     * gloss or shininess channel; where a preset gives them an attachment of their
     * own, that attachment is not allocated */
    for (uint32_t i = 0; i < s->nmaterials; i++) {
        sm_vec3_zero(s->materials[i].emissive);
        s->materials[i].specular = 0.0f;
        s->materials[i].gloss_map = -1;
    }
    static const int natt[5] = {3, 2, 4, 3, 3};   /* fat curtis compact spheremap reference */
    static const unsigned bpp[5] = {24, 16, 12, 14, 48};
    for (int i = 0; i < 5; i++) {
        renderer_options o = options(LIGHT_VOLUMES_STENCIL, PRESETS[i]);
        void *self = make(s, &o);
        pass_plan p;
        IMPL->describe(self, &p);
        assert_int_equal(targets_containing(&p, "emissive"), 0);
        assert_int_equal(targets_containing(&p, "gloss"), 0);
        assert_int_equal(targets_containing(&p, "shininess"), 0);
        const deferred_layout *l = deferred_gbuffer_layout(self);
        assert_int_equal(l->nattachments, natt[i]);
        assert_int_equal(deferred_layout_bytes_per_pixel(l), bpp[i]);
        assert_false(l->has[DEFERRED_SLOT_EMISSIVE]);
        assert_false(l->has[DEFERRED_SLOT_GLOSS]);
        assert_string_equal(plan_pass_or_fail(&p, "ambient")->reason,
                            "ambient x diffuse, full screen (no material is emissive)");
        check_bytes(self, &p);
        frame_stats fs;
        frame(self, s, &fs);
        check_hdr_finite(self, deferred_preset_name(PRESETS[i]));
        IMPL->destroy(self);
    }
    scene_destroy(s);

    /* no sky, no objects */
    scene_light dl[] = {directional(0.0f, -1.0f, 0.0f, 1.0f, 1.0f, 1.0f)};
    s = build("empty", dl, 1);
    renderer_options o = options(LIGHT_VOLUMES_STENCIL, GBUFFER_FAT);
    void *self = make(s, &o);
    pass_plan p;
    IMPL->describe(self, &p);
    assert_false(plan_pass_or_fail(&p, "sky")->run);
    assert_string_equal(plan_pass_or_fail(&p, "sky")->reason, "the scene has no sky");
    assert_false(plan_pass_or_fail(&p, "point")->run);
    assert_false(plan_pass_or_fail(&p, "spot")->run);
    assert_true(plan_pass_or_fail(&p, "directional")->run);
    assert_int_equal(programs_named(&p, "deferred_gbuffer"), 0);
    assert_int_equal(programs_named(&p, "deferred_stencil_mark"), 0);
    frame_stats fs;
    frame(self, s, &fs);
    assert_null(find_pass(&fs, "sky"));
    IMPL->destroy(self);
    scene_destroy(s);
}

// >>layouts (no GL)

typedef struct att_want {
    const char *name;
    gl_format format;
} att_want;

static void check_layout(gbuffer_preset preset, gbuffer_position pos, gbuffer_normal nrm,
                         deferred_needs needs, const att_want *want, int n,
                         deferred_position_source source, deferred_normal_encoding enc)
{
    renderer_options o = {.gbuffer = preset, .gbuffer_position = pos, .gbuffer_normal = nrm};
    deferred_layout l;
    char err[256] = "";
    assert_true(deferred_layout_build(&o, needs, &l, err, sizeof err));
    if (l.nattachments != n) {
        for (int i = 0; i < l.nattachments; i++)
            print_message("  %s %s\n", l.att[i].name, gl_format_name(l.att[i].format));
        fail_msg("%s: %d attachments, expected %d", deferred_preset_name(preset),
                 l.nattachments, n);
    }
    for (int i = 0; i < n; i++) {
        assert_string_equal(l.att[i].name, want[i].name);
        assert_string_equal(gl_format_name(l.att[i].format), gl_format_name(want[i].format));
    }
    assert_int_equal(l.position, source);
    assert_int_equal(l.normal, enc);
}

static void test_layouts(void **state)
{
    (void)state;
    const deferred_needs all = {.gloss = true, .emissive = true}, none = {0};
    const gl_format F16 = GLT_FORMAT_RGBA16F, F32 = GLT_FORMAT_RGBA32F;
    check_layout(GBUFFER_FAT, 0, 0, all,
                 (att_want[]){{"gbuffer.position+shininess", F16},
                              {"gbuffer.normal+emissive", F16},
                              {"gbuffer.diffuse+gloss", F16}},
                 3, DEFERRED_POSITION_STORED, DEFERRED_NORMAL_XYZ_FLOAT);
    check_layout(GBUFFER_CURTIS, 0, 0, all,
                 (att_want[]){{"gbuffer.normal+depth", F16},
                              {"gbuffer.diffuse+gloss", F16},
                              {"gbuffer.shininess", F16},
                              {"gbuffer.emissive", F16}},
                 4, DEFERRED_POSITION_LINEAR_DEPTH, DEFERRED_NORMAL_XYZ_FLOAT);
    /* seed 002's 96 bits */
    check_layout(GBUFFER_COMPACT, 0, 0, none,
                 (att_want[]){{"gbuffer.position.xy", GLT_FORMAT_RG16F},
                              {"gbuffer.position.z", GLT_FORMAT_R16F},
                              {"gbuffer.diffuse+normal.z", GLT_FORMAT_RGBA8},
                              {"gbuffer.normal.xy", GLT_FORMAT_RG8}},
                 4, DEFERRED_POSITION_STORED, DEFERRED_NORMAL_XYZ_UNORM);
    check_layout(GBUFFER_COMPACT, 0, 0, all,
                 (att_want[]){{"gbuffer.position.xy", GLT_FORMAT_RG16F},
                              {"gbuffer.position.z", GLT_FORMAT_R16F},
                              {"gbuffer.diffuse+normal.z", GLT_FORMAT_RGBA8},
                              {"gbuffer.normal.xy", GLT_FORMAT_RG8},
                              {"gbuffer.gloss+shininess", GLT_FORMAT_RG8},
                              {"gbuffer.emissive", GLT_FORMAT_RGBA8}},
                 6, DEFERRED_POSITION_STORED, DEFERRED_NORMAL_XYZ_UNORM);
    check_layout(GBUFFER_SPHEREMAP, 0, 0, all,
                 (att_want[]){{"gbuffer.normal", GLT_FORMAT_RG8},
                              {"gbuffer.depth+gloss+shininess", F16},
                              {"gbuffer.diffuse", GLT_FORMAT_RGBA8},
                              {"gbuffer.emissive", GLT_FORMAT_RGBA8}},
                 4, DEFERRED_POSITION_LINEAR_DEPTH, DEFERRED_NORMAL_SPHEREMAP);
    check_layout(GBUFFER_REFERENCE, 0, 0, all,
                 (att_want[]){{"gbuffer.position+shininess", F32},
                              {"gbuffer.normal+gloss", F32},
                              {"gbuffer.diffuse", F32},
                              {"gbuffer.emissive", F32}},
                 4, DEFERRED_POSITION_STORED, DEFERRED_NORMAL_XYZ_FLOAT);
    /* overrides: the field moves to an attachment of its own; what it leaves behind
     * is packed into the narrowest format of its kind */
    check_layout(GBUFFER_FAT, GBUFFER_POSITION_DEPTH, 0, all,
                 (att_want[]){{"gbuffer.shininess", GLT_FORMAT_R16F},
                              {"gbuffer.normal+emissive", F16},
                              {"gbuffer.diffuse+gloss", F16}},
                 3, DEFERRED_POSITION_DEPTH_BUFFER, DEFERRED_NORMAL_XYZ_FLOAT);
    check_layout(GBUFFER_FAT, GBUFFER_POSITION_STORED16, GBUFFER_NORMAL_FLOAT16, all,
                 (att_want[]){{"gbuffer.position+shininess", F16},
                              {"gbuffer.normal+emissive", F16},
                              {"gbuffer.diffuse+gloss", F16}},
                 3, DEFERRED_POSITION_STORED, DEFERRED_NORMAL_XYZ_FLOAT);   /* = the preset */
    check_layout(GBUFFER_CURTIS, GBUFFER_POSITION_STORED32, GBUFFER_NORMAL_UNORM10, none,
                 (att_want[]){{"gbuffer.diffuse", F16},
                              {"gbuffer.position", F32},
                              {"gbuffer.normal", GLT_FORMAT_RGB10A2}},
                 3, DEFERRED_POSITION_STORED, DEFERRED_NORMAL_XYZ_UNORM);
    check_layout(GBUFFER_REFERENCE, 0, GBUFFER_NORMAL_SPHEREMAP8, all,
                 (att_want[]){{"gbuffer.position+shininess", F32},
                              {"gbuffer.gloss", GLT_FORMAT_R32F},
                              {"gbuffer.diffuse", F32},
                              {"gbuffer.emissive", F32},
                              {"gbuffer.normal", GLT_FORMAT_RG8}},
                 5, DEFERRED_POSITION_STORED, DEFERRED_NORMAL_SPHEREMAP);
    check_layout(GBUFFER_COMPACT, 0, GBUFFER_NORMAL_FLOAT16, none,
                 (att_want[]){{"gbuffer.position.xy", GLT_FORMAT_RG16F},
                              {"gbuffer.position.z", GLT_FORMAT_R16F},
                              {"gbuffer.diffuse", GLT_FORMAT_RGBA8},
                              {"gbuffer.normal", F16}},
                 4, DEFERRED_POSITION_STORED, DEFERRED_NORMAL_XYZ_FLOAT);
    check_layout(GBUFFER_SPHEREMAP, GBUFFER_POSITION_DEPTH, GBUFFER_NORMAL_SPHEREMAP16, all,
                 (att_want[]){{"gbuffer.gloss+shininess", GLT_FORMAT_RG16F},
                              {"gbuffer.diffuse", GLT_FORMAT_RGBA8},
                              {"gbuffer.emissive", GLT_FORMAT_RGBA8},
                              {"gbuffer.normal", GLT_FORMAT_RG16F}},
                 4, DEFERRED_POSITION_DEPTH_BUFFER, DEFERRED_NORMAL_SPHEREMAP);

    /* issue 25, the metallic-roughness model: gloss and shininess are named for what
     * they hold; an occlusion map's slot takes the first channel a preset leaves free,
     * else a target of its own; deferred-lighting's pre-pass G-buffer gains F0 */
    const deferred_needs pbr = {.gloss = true, .emissive = true, .pbr = true,
                                .occlusion = true};
    check_layout(GBUFFER_CURTIS, 0, 0, pbr,
                 (att_want[]){{"gbuffer.normal+depth", F16},
                              {"gbuffer.diffuse+metal", F16},
                              {"gbuffer.rough+ao", F16},
                              {"gbuffer.emissive", F16}},
                 4, DEFERRED_POSITION_LINEAR_DEPTH, DEFERRED_NORMAL_XYZ_FLOAT);
    check_layout(GBUFFER_FAT, 0, 0, pbr,
                 (att_want[]){{"gbuffer.position+rough", F16},
                              {"gbuffer.normal+emissive", F16},
                              {"gbuffer.diffuse+metal", F16},
                              {"gbuffer.ao", GLT_FORMAT_R16F}},
                 4, DEFERRED_POSITION_STORED, DEFERRED_NORMAL_XYZ_FLOAT);
    check_layout(GBUFFER_SPHEREMAP, 0, 0, pbr,
                 (att_want[]){{"gbuffer.normal", GLT_FORMAT_RG8},
                              {"gbuffer.depth+metal+rough+ao", F16},
                              {"gbuffer.diffuse", GLT_FORMAT_RGBA8},
                              {"gbuffer.emissive", GLT_FORMAT_RGBA8}},
                 4, DEFERRED_POSITION_LINEAR_DEPTH, DEFERRED_NORMAL_SPHEREMAP);
    check_layout(GBUFFER_COMPACT, 0, 0, pbr,
                 (att_want[]){{"gbuffer.position.xy", GLT_FORMAT_RG16F},
                              {"gbuffer.position.z", GLT_FORMAT_R16F},
                              {"gbuffer.diffuse+normal.z", GLT_FORMAT_RGBA8},
                              {"gbuffer.normal.xy", GLT_FORMAT_RG8},
                              {"gbuffer.metal+rough", GLT_FORMAT_RG8},
                              {"gbuffer.emissive+ao", GLT_FORMAT_RGBA8}},
                 6, DEFERRED_POSITION_STORED, DEFERRED_NORMAL_XYZ_UNORM);
    {
        deferred_layout lp;
        deferred_layout_defs defs;
        deferred_layout_light_prepass(pbr, &lp);
        assert_int_equal(lp.nattachments, 2);
        assert_string_equal(lp.att[0].name, "gbuffer.normal+rough");
        assert_string_equal(lp.att[1].name, "gbuffer.f0");
        assert_string_equal(gl_format_name(lp.att[1].format), "rgba16f");
        deferred_layout_defines(&lp, &defs);
        bool f0 = false, unorm = false;
        for (int i = 0; i < defs.n; i++) {
            f0 |= strcmp(defs.text[i], "GB_F0 gb1.xyz") == 0;
            unorm |= strstr(defs.text[i], "UNORM") != NULL;
        }
        assert_true(f0);
        assert_false(unorm);   /* roughness stored as it is, never as n / 255 */
    }

    /* bad values are refused, in create too */
    char err[256] = "";
    deferred_layout l;
    renderer_options bad = {.gbuffer = (gbuffer_preset)99};
    assert_false(deferred_layout_build(&bad, all, &l, err, sizeof err));
    assert_string_equal(err, "deferred: unknown G-buffer preset 99");
    bad = (renderer_options){.gbuffer = GBUFFER_CURTIS, .gbuffer_normal = (gbuffer_normal)42};
    assert_false(deferred_layout_build(&bad, all, &l, err, sizeof err));
    assert_string_equal(err, "deferred: unknown G-buffer normal 42");
    bad = options((light_volume_mode)7, GBUFFER_CURTIS);
    assert_null(IMPL->create(&bad, err, sizeof err));
    assert_string_equal(err, "deferred: unknown light volume mode 7");
    IMPL->destroy(NULL);
    assert_string_equal(deferred_preset_name(GBUFFER_SPHEREMAP), "spheremap");
    assert_string_equal(deferred_slot_name(DEFERRED_SLOT_NORMAL_Z), "normal.z");
}

int main(void)
{
    GL_TEST_SKIP_WITHOUT_EGL();
    char err[512] = "";
    gl_context_desc desc = {.backend = GL_BACKEND_EGL, .device = -1, .debug = true,
                            .width = W, .height = H};
    ctx = gl_context_create(&desc, err, sizeof err);
    if (!ctx) {
        printf("gl_context_create: %s\n", err);
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_draw_calls),
        cmocka_unit_test(test_fragment_order),
        cmocka_unit_test(test_floating_light),
        cmocka_unit_test(test_scissor_rect),
        cmocka_unit_test(test_floating_spot),
        cmocka_unit_test(test_modes_agree),
        cmocka_unit_test(test_presets),
        cmocka_unit_test(test_separate_specular),
        cmocka_unit_test(test_sky_stencil),
        cmocka_unit_test(test_force),
        cmocka_unit_test(test_pruning),
        cmocka_unit_test(test_layouts),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    gl_context_destroy(ctx);
    return rc;
}
