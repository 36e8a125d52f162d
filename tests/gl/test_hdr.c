/* renderer_read_hdr (renderers/renderer.h) in a debug context (any GL error fails; 77 when
 * no EGL display): forward-mpml, forward-spml and deferred on "shapes" at 64x48 read back
 * a finite, non-negative accumulation, and the RGBA8 output is round(clamp(hdr) x 255)
 * within 1 (hdr row 0 is the bottom); reading disturbs nothing; a wrong size or an
 * unprepared renderer is refused; null has no float target. RGBA16F overflow (64 lights
 * of colour 1e5 at one point): the count is the non-finite values read, the output 255
 * there. hdr: rgba32f (issue 13): every renderer renders into a GL_RGBA32F target that its
 * plan says is 16 bytes a pixel, within 2/255 of RGBA16F. Fog (seed 000 4.5.12): each
 * covered pixel is L f + C (1 - f), f = exp(-density z) with z unprojected from the depth
 * read back, the sky unchanged, and the image changed by a lot; the deferred renderers
 * draw exactly one more draw (their "fog" pass), the forward ones the same draws. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/deferred/deferred.h"
#include "renderers/forward/forward_common.h"
#include "renderers/renderer.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 64, H = 48, BRIGHT_LIGHTS = 64 };

static gl_context *ctx;

typedef struct config {
    const char *kind;
    bool separate_specular;
} config;

static const config CONFIGS[] = {
    {"forward-mpml", false},
    {"forward-spml", false},
    {"deferred", false},
    {"deferred", true},
};
enum { NCONFIGS = sizeof CONFIGS / sizeof CONFIGS[0] };

// >>scenes

static scene_light point(float x, float y, float z, float radius, float c)
{
    return (scene_light){.type = LIGHT_POINT, .position = {x, y, z}, .color = {c, c, c},
                         .direction = {0.0f, -1.0f, 0.0f}, .radius = radius,
                         .attenuation = ATTENUATION_LINEAR_RANGE};
}

/* "shapes" with exactly these lights, all active, the grid seen from the side and above. */
static scene *build(const scene_light *lights, uint32_t n)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build("shapes", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("scene shapes: %s", err);
    s->lights = calloc(n, sizeof *s->lights);
    assert_non_null(s->lights);
    memcpy(s->lights, lights, n * sizeof *lights);
    s->nlights_total = n;
    s->count = (light_count){.start = n, .max = n};
    scene_update(s, 0.0);
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    s->cam.eye[0] = 0.0f, s->cam.eye[1] = 12.0f, s->cam.eye[2] = 28.0f;
    s->cam.target[0] = 0.0f, s->cam.target[1] = 1.0f, s->cam.target[2] = 0.0f;
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
    return s;
}

static scene *build_few(void)
{
    const scene_light l[] = {
        point(-6.0f, 4.0f, 2.0f, 14.0f, 0.9f),
        point(5.0f, 3.0f, -2.0f, 12.0f, 0.7f),
        point(0.0f, 6.0f, 6.0f, 16.0f, 0.6f),
    };
    return build(l, sizeof l / sizeof l[0]);
}

static scene *build_bright(float color)
{
    scene_light l[BRIGHT_LIGHTS];
    for (int i = 0; i < BRIGHT_LIGHTS; i++)
        l[i] = point(0.0f, 2.5f, 2.0f, 20.0f, color);
    return build(l, BRIGHT_LIGHTS);
}

// >>renderers

static renderer *make(const config *c, const scene *s)
{
    char err[512] = "";
    const gl_info *i = gl_context_info(ctx);
    renderer_options o = {.width = W, .height = H, .queries = true,
                          .timer_query = i->timer_query,
                          .pipeline_statistics = i->pipeline_statistics,
                          .max_uniform_block_size = i->max_uniform_block_size,
                          .separate_specular = c->separate_specular};
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    renderer *r = test_renderer_create(c->kind, &o, err, sizeof err);
    if (!r)
        fail_msg("%s: create: %s", c->kind, err);
    if (s && !renderer_prepare(r, s, err, sizeof err))
        fail_msg("%s: prepare: %s", c->kind, err);
    return r;
}

static void frame(renderer *r, const scene *s)
{
    frame_stats fs;
    renderer_draw(r, s, &fs);
    gl.Finish();
    renderer_collect(r, &fs);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static uint8_t *read_output(void)
{
    uint8_t *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    char err[256];
    if (!gl_context_read_rgba8(ctx, px, err, sizeof err))
        fail_msg("read back: %s", err);
    return px;
}

static float *alloc_hdr(void)
{
    float *v = malloc((size_t)W * H * 4 * sizeof *v);
    assert_non_null(v);
    return v;
}

/* The 8-bit value resolve writes for v: clamp to [0, 1], x 255, rounded. */
static int expect8(float v)
{
    float c = v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
    return (int)lroundf(c * 255.0f);
}

// >>tests

static void check_normal(const config *c)
{
    scene *s = build_few();
    renderer *r = make(c, s);
    frame(r, s);
    uint8_t *out = read_output();
    float *hdr = alloc_hdr();
    size_t nonfinite = 12345;
    assert_true(renderer_read_hdr(r, hdr, W, H, &nonfinite));
    assert_int_equal(gl_context_error_count(ctx), 0);
    assert_int_equal(nonfinite, 0);

    int worst = 0;
    size_t lit = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float *h = &hdr[((size_t)(H - 1 - y) * W + (size_t)x) * 4];   /* bottom-up */
            const uint8_t *o = &out[((size_t)y * W + (size_t)x) * 4];                /* top-down */
            for (int k = 0; k < 3; k++) {
                if (!isfinite(h[k]) || h[k] < 0.0f)
                    fail_msg("%s%s: hdr (%d, %d)[%d] = %g", c->kind,
                             c->separate_specular ? " separate" : "", x, y, k, (double)h[k]);
                int d = abs((int)o[k] - expect8(h[k]));
                if (d > worst)
                    worst = d;
                if (d > 1)
                    fail_msg("%s%s: pixel (%d, %d)[%d]: output %d, hdr %g -> %d", c->kind,
                             c->separate_specular ? " separate" : "", x, y, k, o[k],
                             (double)h[k], expect8(h[k]));
                lit += h[k] > 0.0f;
            }
            assert_int_equal(o[3], 255);   /* resolve writes alpha 1 whatever hdr holds */
        }
    assert_true(lit > (size_t)W * H / 4);   /* the picture is not black */
    print_message("%s%s: max |output - round(clamp(hdr) x 255)| = %d\n", c->kind,
                  c->separate_specular ? " (separate specular)" : "", worst);

    /* Reading disturbed nothing: the next frame draws the same output. */
    frame(r, s);
    uint8_t *again = read_output();
    assert_memory_equal(out, again, (size_t)W * H * 4);

    /* A wrong size: refused, nothing written, count 0. */
    float sentinel[4] = {-7.0f, -7.0f, -7.0f, -7.0f};
    nonfinite = 99;
    assert_false(renderer_read_hdr(r, sentinel, 1, 1, &nonfinite));
    assert_int_equal(nonfinite, 0);
    assert_true(sentinel[0] == -7.0f && sentinel[3] == -7.0f);
    assert_false(renderer_read_hdr(r, hdr, W + 1, H, &nonfinite));
    assert_false(renderer_read_hdr(r, hdr, W, H - 1, &nonfinite));
    assert_false(renderer_read_hdr(r, hdr, 0, 0, &nonfinite));
    assert_true(renderer_read_hdr(r, hdr, W, H, NULL));   /* the count is optional */

    assert_int_equal(gl_context_error_count(ctx), 0);
    free(again);
    free(hdr);
    free(out);
    renderer_destroy(r);
    gl_context_poll_errors(ctx, "hdr test");
    assert_int_equal(gl_context_error_count(ctx), 0);
    scene_destroy(s);
}

static void test_hdr_matches_output(void **state)
{
    (void)state;
    for (size_t i = 0; i < NCONFIGS; i++)
        check_normal(&CONFIGS[i]);
}

static void test_unprepared(void **state)
{
    (void)state;
    float v[4] = {0};
    size_t nonfinite = 5;
    for (size_t i = 0; i < NCONFIGS; i++) {
        renderer *r = make(&CONFIGS[i], NULL);
        assert_false(renderer_read_hdr(r, v, W, H, &nonfinite));
        assert_int_equal(nonfinite, 0);
        renderer_destroy(r);
    }
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static void test_null_has_none(void **state)
{
    (void)state;
    scene *s = build_few();
    renderer *r = make(&(config){"null", false}, s);
    frame(r, s);
    float *hdr = alloc_hdr();
    hdr[0] = -3.0f;
    size_t nonfinite = 77;
    assert_false(renderer_read_hdr(r, hdr, W, H, &nonfinite));
    assert_int_equal(nonfinite, 0);
    assert_true(hdr[0] == -3.0f);
    assert_null(renderer_kind_find("null")->read_hdr);
    free(hdr);
    renderer_destroy(r);
    assert_int_equal(gl_context_error_count(ctx), 0);
    scene_destroy(s);
}

/* 64 lights of one colour at one point, far beyond RGBA16F's 65504. The count must be
 * what the read gives; every channel value is >= 0 and not NaN (all light is
 * positive); the output is 255 where the accumulation is >= 1 or +Inf. Returns the Inf
 * count. What llvmpipe does (the test prints it): a finite value beyond 65504 written
 * or blended into RGBA16F saturates at 65504 (no Inf, count 0); an fp32 +Inf from
 * the shader (forward-spml sums 64 x 3e38 in the fragment shader) is stored as +Inf.
 * A GPU may store +Inf for the first case too; both pass. */
static size_t check_bright(const config *c, float color)
{
    scene *s = build_bright(color);
    renderer *r = make(c, s);
    frame(r, s);
    uint8_t *out = read_output();
    float *hdr = alloc_hdr();
    size_t nonfinite = 12345;
    assert_true(renderer_read_hdr(r, hdr, W, H, &nonfinite));
    assert_int_equal(gl_context_error_count(ctx), 0);

    size_t inf = 0, nan = 0, neg = 0, saturated = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float *h = &hdr[((size_t)(H - 1 - y) * W + (size_t)x) * 4];   /* bottom-up */
            const uint8_t *o = &out[((size_t)y * W + (size_t)x) * 4];                /* top-down */
            for (int k = 0; k < 4; k++) {
                inf += isinf(h[k]) ? 1u : 0u;
                nan += isnan(h[k]) ? 1u : 0u;
                if (k == 3 || isnan(h[k]))
                    continue;
                neg += h[k] < 0.0f;
                saturated += h[k] >= 65504.0f;   /* +Inf included */
                if (abs((int)o[k] - expect8(h[k])) > (h[k] >= 1.0f ? 0 : 1))
                    fail_msg("%s: pixel (%d, %d)[%d]: hdr %g, output %d", c->kind, x, y, k,
                             (double)h[k], o[k]);
            }
            assert_int_equal(o[3], 255);
        }
    print_message("%s%s, 64 lights x %g: %zu non-finite (%zu +-Inf, %zu NaN), %zu channel "
                  "values at 65504 or beyond\n",
                  c->kind, c->separate_specular ? " (separate specular)" : "", (double)color,
                  nonfinite, inf, nan, saturated);
    assert_int_equal(nonfinite, inf + nan);
    assert_int_equal(nan, 0);
    assert_int_equal(neg, 0);
    assert_true(saturated > 0);   /* it did overflow: 65504 or +Inf */
    free(hdr);
    free(out);
    renderer_destroy(r);
    gl_context_poll_errors(ctx, "hdr test");
    assert_int_equal(gl_context_error_count(ctx), 0);
    scene_destroy(s);
    return inf;
}

static void test_overflow(void **state)
{
    (void)state;
    for (size_t i = 0; i < NCONFIGS; i++)
        check_bright(&CONFIGS[i], 1e5f);
    /* forward-spml sums every light in the fragment shader in fp32: 64 x 3e38 is +Inf
     * there, and +Inf is what the target holds, which the count must see. */
    assert_true(check_bright(&CONFIGS[1], 3e38f) > 0);
}

// >>hdr: rgba32f, fog

static renderer_options options32(const char *kind, hdr_format hdr, float fog)
{
    const gl_info *i = gl_context_info(ctx);
    renderer_options o = {.width = W, .height = H, .queries = true,
                          .timer_query = i->timer_query,
                          .pipeline_statistics = i->pipeline_statistics,
                          .max_uniform_block_size = i->max_uniform_block_size,
                          .gbuffer = GBUFFER_REFERENCE, .hdr = hdr, .fog_density = fog,
                          .fog_color = {0.6f, 0.5f, 0.4f}};
    (void)kind;
    renderer_options_complete(&o);   /* some are made through their implementations */
    return o;
}

/* The frame render32 drew last. */
static frame_stats last_fs;

/* One frame of kind (clustered: clustered_deferred as given) into out (RGBA8, top row
 * first) and hdr (floats, bottom row first); the plan into plan, the frame's stats into
 * last_fs. */
static void render32(const char *kind, bool clustered_deferred, hdr_format fmt, float fog,
                     const scene *s, uint8_t **out, float **hdr, pass_plan *plan)
{
    char err[512] = "";
    renderer_options o = options32(kind, fmt, fog);
    o.clustered_deferred = clustered_deferred;
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    renderer *r = test_renderer_create(kind, &o, err, sizeof err);
    if (!r || !renderer_prepare(r, s, err, sizeof err))
        fail_msg("%s (%s, fog %g): %s", kind, fmt == HDR_RGBA32F ? "rgba32f" : "rgba16f",
                 (double)fog, err);
    renderer_draw(r, s, &last_fs);
    gl.Finish();
    renderer_collect(r, &last_fs);
    assert_int_equal(gl_context_error_count(ctx), 0);
    *out = read_output();
    *hdr = alloc_hdr();
    size_t nonfinite = 1;
    assert_true(renderer_read_hdr(r, *hdr, W, H, &nonfinite));
    assert_int_equal(nonfinite, 0);
    if (plan)
        renderer_describe(r, plan);
    renderer_destroy(r);
    gl_context_poll_errors(ctx, kind);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static void test_rgba32f_every_renderer(void **state)
{
    (void)state;
    scene *s = build_few();
    size_t kinds = 0;
    uint64_t draws_without_fog = 0;
    for (size_t i = 0; i < renderer_kind_count() + 1; i++) {
        /* every registered renderer, then clustered once more with deferred shading */
        bool again = i == renderer_kind_count();
        const renderer_impl *k = again ? renderer_kind_find("clustered") : renderer_kind_at(i);
        /* the design that serves the object (clustered: forward, or deferred again) */
        const renderer_impl *design =
            k->variant ? k->variant(&(renderer_options){.clustered_deferred = again}) : k;
        if (!design->read_hdr)
            continue;   /* null: no float target */
        kinds++;
        for (int fogged = 0; fogged < 2; fogged++) {
            float fog = fogged ? 0.03f : 0.0f;
            uint8_t *out16, *out32;
            float *hdr16, *hdr32;
            pass_plan p16, p32;
            render32(k->name, again, HDR_RGBA16F, fog, s, &out16, &hdr16, &p16);
            render32(k->name, again, HDR_RGBA32F, fog, s, &out32, &hdr32, &p32);
            /* the passes: deferred shading adds one pass of one full-screen draw (every
             * pixel shaded once), forward fogs in its shaders and draws what it did */
            bool deferred = again || strcmp(k->name, "deferred") == 0 ||
                            strcmp(k->name, "tiled-deferred") == 0 ||
                            strcmp(k->name, "deferred-lighting") == 0;
            const pass_stats *fp = find_pass(&last_fs, "fog");
            if (!fogged) {
                draws_without_fog = total_draws(&last_fs);
                assert_null(fp);
            } else if (deferred) {
                assert_non_null(fp);
                assert_int_equal(fp->draw_calls, 1);
                if (!isnan(fp->samples))
                    assert_true(fp->samples == (double)W * H);
                assert_int_equal(total_draws(&last_fs), draws_without_fog + 1);
            } else {
                assert_null(fp);
                assert_int_equal(total_draws(&last_fs), draws_without_fog);
            }
            /* the plan: the light target in the format asked for, 16 bytes a pixel */
            const char *target = strcmp(p32.target[0].name, "hdr") == 0 ? "hdr" : "light";
            bool found = false;
            for (size_t t = 0; t < p32.ntargets; t++)
                if (strcmp(p32.target[t].name, target) == 0) {
                    assert_string_equal(p32.target[t].format, "rgba32f");
                    assert_int_equal(p32.target[t].bytes, (uint64_t)W * H * 16);
                    assert_string_equal(p16.target[t].format, "rgba16f");
                    found = true;
                }
            if (!found)
                fail_msg("%s: no %s target in the plan", k->name, target);
            const pass_plan_entry *f16 = plan_pass(&p16, "fog");
            assert_non_null(f16);
            assert_true(f16->run == (fogged != 0));
            /* the same image whatever the precision */
            int worst = 0;
            for (size_t q = 0; q < (size_t)W * H * 4; q++) {
                int d = abs((int)out16[q] - (int)out32[q]);
                worst = d > worst ? d : worst;
            }
            print_message("%s%s%s: rgba32f vs rgba16f output: max %d/255\n", k->name,
                          again ? " (deferred)" : "", fogged ? ", fog" : "", worst);
            assert_true(worst <= 2);
            free(out16);
            free(out32);
            free(hdr16);
            free(hdr32);
        }
    }
    /* every registered renderer but null, and clustered twice */
    assert_int_equal(kinds, renderer_kind_count());
    scene_destroy(s);
}

static GLint internal_format(GLuint texture)
{
    GLint f = 0;
    gl.GetTextureLevelParameteriv(texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &f);
    return f;
}

/* What GL itself says the light target is: forward-mpml's, deferred's and
 * tiled-deferred's, made through their implementations (the accessors take self). */
static void test_rgba32f_internal_format(void **state)
{
    (void)state;
    scene *s = build_few();
    static const char *const kinds[] = {"forward-mpml", "deferred", "tiled-deferred"};
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++)
        for (int f = 0; f < 2; f++) {
            char err[512] = "";
            const renderer_impl *k = renderer_kind_find(kinds[i]);
            renderer_options o = options32(kinds[i], f ? HDR_RGBA32F : HDR_RGBA16F, 0.0f);
            gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
            void *self = k->create(&o, err, sizeof err);
            if (!self || !k->prepare(self, s, err, sizeof err))
                fail_msg("%s: %s", kinds[i], err);
            frame_stats fs;
            k->draw(self, s, &fs);
            gl.Finish();
            renderer_impl_collect(k, self, &fs);
            const gl_target *t = i == 0 ? forward_hdr_target(self) : deferred_hdr_target(self);
            assert_non_null(t);
            assert_int_equal(internal_format(t->texture), f ? GL_RGBA32F : GL_RGBA16F);
            k->destroy(self);
            assert_int_equal(gl_context_error_count(ctx), 0);
        }
    scene_destroy(s);
}

/* The depth buffer of forward-spml's frame (bottom row first) as view-space z. */
static double *view_depth(const scene *s, float density)
{
    char err[512] = "";
    const renderer_impl *k = renderer_kind_find("forward-spml");
    renderer_options o = options32("forward-spml", HDR_RGBA32F, density);
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    void *self = k->create(&o, err, sizeof err);
    if (!self || !k->prepare(self, s, err, sizeof err))
        fail_msg("forward-spml: %s", err);
    frame_stats fs;
    k->draw(self, s, &fs);
    gl.Finish();
    renderer_impl_collect(k, self, &fs);
    const gl_target *t = forward_depth_target(self);
    float *d = malloc((size_t)W * H * sizeof *d);
    double *z = malloc((size_t)W * H * sizeof *z);
    assert_true(d && z);
    gl.GetTextureImage(t->texture, 0, GL_DEPTH_COMPONENT, GL_FLOAT, (GLsizei)(W * H * sizeof *d),
                       d);
    k->destroy(self);
    assert_int_equal(gl_context_error_count(ctx), 0);
    /* clip z = P22 z + P32, w = -z: ndc = 2 d - 1 = (P22 z + P32) / -z */
    double p22 = s->proj[2][2], p32 = s->proj[3][2];
    for (size_t i = 0; i < (size_t)W * H; i++)
        z[i] = d[i] >= 1.0f ? NAN : -p32 / (2.0 * d[i] - 1.0 + p22);
    free(d);
    return z;
}

static void test_fog_formula(void **state)
{
    (void)state;
    scene *s = build_few();
    const float density = 0.04f, colour[3] = {0.6f, 0.5f, 0.4f};
    double *z = view_depth(s, density);
    static const struct {
        const char *kind;
        bool clustered_deferred;
    } kinds[] = {{"forward-spml", false}, {"forward-mpml", false}, {"forward-plus", false},
                 {"deferred", false},     {"tiled-deferred", false}, {"clustered", true},
                 {"deferred-lighting", false}};
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
        uint8_t *out0, *out1;
        float *clear, *fogged;
        render32(kinds[i].kind, kinds[i].clustered_deferred, HDR_RGBA32F, 0.0f, s, &out0, &clear,
                 NULL);
        render32(kinds[i].kind, kinds[i].clustered_deferred, HDR_RGBA32F, density, s, &out1,
                 &fogged, NULL);
        size_t covered = 0, sky = 0;
        double worst = 0, change = 0, fmin = 1, fmax = 0;
        for (size_t p = 0; p < (size_t)W * H; p++)
            for (int c = 0; c < 3; c++) {
                double l = clear[4 * p + c], lf = fogged[4 * p + c];
                if (isnan(z[p])) {   /* no surface: the sky, unchanged */
                    if (lf != l)
                        fail_msg("%s: sky pixel %zu[%d]: %g without fog, %g with", kinds[i].kind,
                                 p, c, l, lf);
                    sky += c == 0;
                    continue;
                }
                double f = exp(density * z[p]);   /* z < 0 in front of the eye */
                double want = l * f + colour[c] * (1.0 - f);
                double e = fabs(lf - want);
                if (e > 1e-4 + 1e-4 * fabs(want))   /* measured: about 1.5e-6 */
                    fail_msg("%s: pixel (%zu, %zu)[%d] at z %g: %g without fog, %g with, "
                             "formula %g (f %g)", kinds[i].kind, p % W, p / W, c, z[p], l, lf,
                             want, f);
                worst = e > worst ? e : worst;
                change += fabs(lf - l);
                covered += c == 0;
                fmin = f < fmin ? f : fmin;
                fmax = f > fmax ? f : fmax;
            }
        print_message("%s: fog f in [%.3f, %.3f] over %zu pixels (%zu sky): max |hdr - formula| "
                      "%.2e, mean change %.3f\n", kinds[i].kind, fmin, fmax, covered, sky,
                      worst, change / (3.0 * (double)covered));
        assert_true(covered > (size_t)W * H / 2);
        assert_true(sky > 0);
        assert_true(change / (3.0 * (double)covered) > 0.05);   /* fog changes the image */
        free(out0);
        free(out1);
        free(clear);
        free(fogged);
    }
    free(z);
    scene_destroy(s);
}

GL_TEST_MAIN(ctx, W, H,
             cmocka_unit_test(test_hdr_matches_output),
             cmocka_unit_test(test_unprepared),
             cmocka_unit_test(test_null_has_none),
             cmocka_unit_test(test_overflow),
             cmocka_unit_test(test_rgba32f_every_renderer),
             cmocka_unit_test(test_rgba32f_internal_format),
             cmocka_unit_test(test_fog_formula))
