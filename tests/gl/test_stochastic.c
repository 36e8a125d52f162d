/* Stochastic light culling (issue 37 item 4, lights.culling: stochastic; Tokuyoshi and
 * Harada 2016) on forward-plus, clustered, tiled-deferred, deferred-lighting with tiled
 * lists and zbin (both shadings), 32x32 "shapes" with 96 dim point lights of range 60 (every light reaches
 * every pixel when exact): at an error that cuts most of them the mean of 16 seeds' HDR
 * images lies within 1/255 RMSE of the exact image (unbiased), each seed's differs from
 * it, the same seed twice gives the same image bit for bit, and light evaluations a
 * pixel and lights a tile are strictly fewer than exact's (and on "glass", forward-plus's
 * translucent pass, at a third of the error); an error of 1e-30 gives the
 * exact image and counters exactly; the range solved for each attenuation model; 0 and
 * 65536 lights, a light on a surface, errors 1e-30 and 1, msaa 4: no GL error, nothing
 * non-finite. Debug contexts: any GL error fails. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/image_io.h"
#include "renderers/frame/shading.h"
#include "renderers/frame/stochastic.h"
#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "results/image_ref.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

enum { W = 32, H = 32, NLIGHTS = 96, SEEDS = 16 };
#define ERROR_CUT 0.1f   /* cuts most ranges */

static gl_context *ctx;

typedef struct design {
    const char *kind;
    bool lpp_tiled;   /* deferred-lighting with deferred_lighting.lights: tiled */
    bool zbin_deferred;   /* zbin with zbin.shading: deferred */
} design;
static const design DESIGNS[] = {{"forward-plus", false, false}, {"clustered", false, false},
                                 {"tiled-deferred", false, false},
                                 {"deferred-lighting", true, false}, {"zbin", false, false},
                                 {"zbin", false, true}};
enum { NDESIGNS = 6 };

static renderer_options options(const design *d, float culling_error)
{
    const gl_info *gi = gl_context_info(ctx);
    renderer_options o = {
        .width = W, .height = H, .queries = false,
        .max_uniform_block_size = gi->max_uniform_block_size,
        .gbuffer = GBUFFER_REFERENCE, .lpp_tiled = d->lpp_tiled,
        .zbin_deferred = d->zbin_deferred,
        .culling_error = culling_error,
    };
    return o;
}

/* Scene `name` at t = 0 with n point lights (a fixed LCG: positions over the floor, dim
 * colours) of the given range and attenuation; "shapes" seen from (0, 12, 28), "glass"
 * (translucent panes) from its own camera. */
static scene *build(const char *name, uint32_t n, float range, attenuation_kind att)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build(name, &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("%s: %s", name, err);
    s->lights = calloc(n ? n : 1, sizeof *s->lights);
    assert_non_null(s->lights);
    uint32_t x = 12345u;
    for (uint32_t i = 0; i < n; i++) {
        float u[5];
        for (int k = 0; k < 5; k++) {
            x = x * 1664525u + 1013904223u;
            u[k] = (float)(x >> 8) / 16777216.0f;
        }
        s->lights[i] = (scene_light){.type = LIGHT_POINT,
                                     .position = {u[0] * 24.0f - 12.0f, 0.5f + u[1] * 4.0f,
                                                  u[2] * 24.0f - 12.0f},
                                     .color = {0.02f + 0.02f * u[3], 0.03f, 0.02f * u[4]},
                                     .radius = range, .attenuation = att,
                                     .att_a = 1.0f, .att_b = 0.5f, .att_c = 1.0f};
    }
    s->nlights_total = n;
    s->count = (light_count){.start = n, .max = n};
    scene_update(s, 0.0);
    if (strcmp(name, "shapes") != 0)
        return s;
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    const float eye[3] = {0.0f, 12.0f, 28.0f}, target[3] = {0.0f, 1.0f, 0.0f};
    sm_vec3_copy(eye, s->cam.eye);
    sm_vec3_copy(target, s->cam.target);
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
    return s;
}

/* One frame's outputs: the HDR floats, the 8-bit image, the counters. */
typedef struct shot {
    float hdr[W * H * 4];
    image img;
    frame_stats fs;
    size_t nonfinite;
} shot;

static renderer *make(const design *d, const renderer_options *o, scene *s)
{
    char err[512];
    renderer *r = test_renderer_create(d->kind, o, err, sizeof err);
    if (!r || !renderer_prepare(r, s, err, sizeof err))
        fail_msg("%s: %s", d->kind, err);
    return r;
}

static void draw(renderer *r, const char *what, scene *s, shot *out)
{
    char err[512];
    memset(&out->fs, 0, sizeof out->fs);
    renderer_draw(r, s, &out->fs);
    gl.Finish();
    renderer_collect(r, &out->fs);
    out->nonfinite = 0;
    assert_true(renderer_read_hdr(r, out->hdr, W, H, &out->nonfinite));
    out->img = (image){.width = W, .height = H, .channels = 4, .type = IMAGE_U8,
                       .pixels = malloc((size_t)W * H * 4)};
    assert_true(gl_context_read_rgba8(ctx, out->img.pixels, err, sizeof err));
    gl_context_poll_errors(ctx, what);
    assert_int_equal(gl_context_error_count(ctx), 0);
    assert_int_equal(out->nonfinite, 0);
}

static double rmse(const image *a, const image *b)
{
    image_error e;
    char err[256];
    assert_true(image_compare(a, b, &e, err, sizeof err));
    assert_int_equal(e.nonfinite, 0);
    return e.rmse;
}

/* The attenuation lighting.inc gives packed light l at distance d, in double. */
static double attenuation(const gpu_light *l, double d)
{
    double r = l->v[0][3], d2 = d * d;
    switch ((int)l->v[3][1]) {
    case ATTENUATION_INVERSE_SQUARE:
        return 1.0 / fmax(d2, 1e-4);
    case ATTENUATION_LINEAR_RANGE:
        return fmax(0.0, 1.0 - d / r);
    case ATTENUATION_QUADRATIC:
        return 1.0 / fmax(l->v[4][0] * d2 + l->v[4][1] * d + l->v[4][2], 1e-6);
    default: {
        double q = d2 / (r * r), w = fmin(fmax(1.0 - q * q, 0.0), 1.0);
        return w * w / fmax(d2, 1e-4);
    }
    }
}

/* The range where each model's attenuation meets the threshold; the range itself when it
 * never falls that far, 0 when it never rises that high; the stream in [2^-24, 1], the
 * same for the same seed and time, another for another. */
static void test_solve(void **state)
{
    (void)state;
    sm_mat4 view;
    sm_mat4_identity(view);
    for (int a = 0; a < 4; a++) {
        scene_light sl = {.type = LIGHT_POINT, .color = {1, 1, 1}, .radius = 20.0f,
                          .attenuation = (attenuation_kind)a, .att_a = 0.25f, .att_b = 0.5f,
                          .att_c = 1.0f};
        gpu_light l;
        shading_pack_light(&sl, view, &l);
        static const double T[] = {1e-12, 1e-3, 1e-2, 0.1, 0.5, 0.9};
        for (size_t k = 0; k < sizeof T / sizeof T[0]; k++) {
            double d = stochastic_solve(&l, T[k]);
            assert_true(d >= 0.0 && d <= 20.0);
            if (d > 0.0 && d < 20.0)
                assert_true(fabs(attenuation(&l, d) - T[k]) <= 1e-6 * T[k] + 1e-15);
            else if (d == 20.0)
                assert_true(attenuation(&l, 20.0 * (1.0 - 1e-9)) >= T[k]);
        }
        assert_true(stochastic_solve(&l, 1e7) == 0.0);
    }
    uint64_t s1 = stochastic_stream(1337u, 0.5), s2 = stochastic_stream(1338u, 0.5);
    assert_true(s1 == stochastic_stream(1337u, 0.5));
    assert_true(s1 != s2 && s1 != stochastic_stream(1337u, 0.75));
    double mean = 0.0;
    for (uint32_t i = 0; i < 4096; i++) {
        double xi = stochastic_xi(s1, i);
        assert_true(xi >= 1.0 / 16777216.0 && xi <= 1.0);
        mean += xi / 4096.0;
    }
    assert_true(fabs(mean - 0.5) < 0.02);
}

/* An error of 1e-30 cuts nothing and weights nothing: the exact image and counters,
 * bit for bit. */
static void test_tiny_error_is_exact(void **state)
{
    (void)state;
    scene *s = build("shapes", NLIGHTS, 60.0f, ATTENUATION_INVERSE_SQUARE);
    for (int k = 0; k < NDESIGNS; k++) {
        static shot exact, tiny;
        renderer_options o = options(&DESIGNS[k], 0.0f);
        renderer *r = make(&DESIGNS[k], &o, s);
        draw(r, DESIGNS[k].kind, s, &exact);
        renderer_destroy(r);
        o.culling_error = 1e-30f;
        r = make(&DESIGNS[k], &o, s);
        draw(r, DESIGNS[k].kind, s, &tiny);
        renderer_destroy(r);
        assert_memory_equal(exact.img.pixels, tiny.img.pixels, (size_t)W * H * 4);
        assert_memory_equal(exact.hdr, tiny.hdr, sizeof exact.hdr);
        assert_true(exact.fs.light_evals_per_pixel == tiny.fs.light_evals_per_pixel);
        assert_true(exact.fs.grid_lights_mean == tiny.fs.grid_lights_mean);
        assert_true(exact.fs.grid_lights_max == tiny.fs.grid_lights_max);
        assert_int_equal(exact.fs.total.draw_calls, tiny.fs.total.draw_calls);
        assert_int_equal(exact.fs.total.dispatches, tiny.fs.total.dispatches);
        image_free(&exact.img);
        image_free(&tiny.img);
    }
    scene_destroy(s);
}

/* The mean of 16 seeds' HDR images, displayed, within 1/255 RMSE of the exact one; each
 * seed's image off the exact one; a seed drawn twice the same bit for bit; fewer
 * evaluations a pixel and lights a tile than exact, each seed. */
static void unbiased(const char *name, int ndesigns, float error)
{
    scene *s = build(name, NLIGHTS, 60.0f, ATTENUATION_INVERSE_SQUARE);
    static shot exact, one, again;
    static double mean[W * H * 4];
    static uint8_t shown[W * H * 4], shown_exact[W * H * 4];
    for (int k = 0; k < ndesigns; k++) {
        const design *d = &DESIGNS[k];
        renderer_options o = options(d, 0.0f);
        renderer *r = make(d, &o, s);
        draw(r, d->kind, s, &exact);
        renderer_destroy(r);
        o.culling_error = error;
        r = make(d, &o, s);
        memset(mean, 0, sizeof mean);
        double evals = 0.0, tile = 0.0, least = 1.0, single = 0.0;
        for (uint32_t seed = 1; seed <= SEEDS; seed++) {
            s->lights_seed = seed;
            draw(r, d->kind, s, &one);
            for (size_t i = 0; i < (size_t)W * H * 4; i++)
                mean[i] += one.hdr[i] / SEEDS;
            double e = rmse(&one.img, &exact.img);
            least = fmin(least, e);
            single += e / SEEDS;
            assert_true(e > 0.0);   /* really stochastic */
            assert_true(one.fs.light_evals_per_pixel < exact.fs.light_evals_per_pixel);
            assert_true(one.fs.grid_lights_mean < exact.fs.grid_lights_mean);
            evals += one.fs.light_evals_per_pixel / SEEDS;
            tile += one.fs.grid_lights_mean / SEEDS;
            if (seed == 3) {   /* the same seed again: the same image */
                draw(r, d->kind, s, &again);
                assert_memory_equal(one.img.pixels, again.img.pixels, (size_t)W * H * 4);
                assert_memory_equal(one.hdr, again.hdr, sizeof one.hdr);
                image_free(&again.img);
            }
            image_free(&one.img);
        }
        renderer_destroy(r);
        float meanf[W * H * 4];
        for (size_t i = 0; i < (size_t)W * H * 4; i++)
            meanf[i] = (float)mean[i];
        image_display_rgba8(meanf, W, H, false, 1.0f, false, shown);
        image_display_rgba8(exact.hdr, W, H, false, 1.0f, false, shown_exact);
        image a = {.width = W, .height = H, .channels = 4, .type = IMAGE_U8, .pixels = shown};
        image b = {.width = W, .height = H, .channels = 4, .type = IMAGE_U8,
                   .pixels = shown_exact};
        double e = rmse(&a, &b);
        print_message("%s, %s%s: error %.3g: evaluations a pixel %.2f (exact %.2f), lights a "
                      "tile %.2f (exact %.2f); a seed's RMSE %.2f/255 (>= %.2f), 16 seeds' "
                      "mean's %.3f/255\n",
                      name, d->kind, d->zbin_deferred ? " deferred" : "", (double)error, evals, exact.fs.light_evals_per_pixel, tile,
                      exact.fs.grid_lights_mean, single * 255, least * 255, e * 255);
        assert_true(exact.fs.light_evals_per_pixel > 0.9 * NLIGHTS);   /* exact: every light */
        assert_true(evals < 0.5 * exact.fs.light_evals_per_pixel);     /* most cut */
        assert_true(e < 1.0 / 255.0);
        assert_true(e < single);   /* the mean converges on the exact image */
        image_free(&exact.img);
    }
    scene_destroy(s);
}

static void test_unbiased(void **state)
{
    (void)state;
    unbiased("shapes", NDESIGNS, ERROR_CUT);
    /* forward-plus's translucent pass over its translucent lists: brighter there (the
     * panes close to the camera), so a smaller error for the same noise */
    unbiased("glass", 1, 0.3f * ERROR_CUT);
}

/* A light on the floor (inverse-square: 1e4 at d = 0) among 64, each attenuation model,
 * errors 1e-30, ERROR_CUT and 1 (the key's largest), msaa 4 once; 0 lights and 65536
 * lights of range 3 at error 1: no GL error, nothing non-finite (draw's asserts). */
static void test_extremes(void **state)
{
    (void)state;
    static shot out;
    static const float errors[] = {1e-30f, ERROR_CUT, 1.0f};
    for (int a = 0; a < 4; a++) {
        scene *s = build("shapes", 64u, 60.0f, (attenuation_kind)a);
        s->lights[0].position[0] = s->lights[0].position[2] = 0.0f;   /* on the floor */
        s->lights[0].position[1] = 0.0f;
        s->lights[0].color[0] = 0.6f;
        for (int k = 0; k < NDESIGNS; k++)
            for (size_t e = 0; e < 3; e++) {
                renderer_options o = options(&DESIGNS[k], errors[e]);
                o.msaa = a == 1 && e == 1 ? 4 : 1;
                renderer *r = make(&DESIGNS[k], &o, s);
                s->lights_seed = (uint32_t)e;
                draw(r, DESIGNS[k].kind, s, &out);
                renderer_destroy(r);
                image_free(&out.img);
            }
        scene_destroy(s);
    }
    for (int n = 0; n < 2; n++) {
        scene *s = build("shapes", n ? 65536u : 0u, 3.0f, ATTENUATION_INVERSE_SQUARE);
        for (int k = 0; k < NDESIGNS; k++) {
            renderer_options o = options(&DESIGNS[k], 1.0f);
            renderer *r = make(&DESIGNS[k], &o, s);
            draw(r, DESIGNS[k].kind, s, &out);
            renderer_destroy(r);
            image_free(&out.img);
        }
        scene_destroy(s);
    }
}

GL_TEST_MAIN(ctx, W, H, cmocka_unit_test(test_solve), cmocka_unit_test(test_tiny_error_is_exact),
             cmocka_unit_test(test_unbiased), cmocka_unit_test(test_extremes))
