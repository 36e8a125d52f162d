/* renderer_read_hdr (renderers/renderer.h) in a debug context: for forward-mpml,
 * forward-spml and deferred (also with separate_specular) on "shapes" with a few point
 * lights at 64x48, the float light accumulation reads back, is finite and >= 0, and the
 * RGBA8 output is round(clamp(hdr) x 255) at every pixel within 1 (hdr row 0 is the
 * bottom, the output's the top); reading it disturbs nothing (the next frame's output
 * is the same); a wrong size or an unprepared renderer is refused with nothing read;
 * null has no float target (false, count 0). Lights bright enough to overflow RGBA16F
 * (64 lights of colour 1e5 at one point): the count is the number of non-finite values
 * the read gives, and the output saturates at 255 where the accumulation is +Inf.
 * Any GL error fails. Exits 77 (skip) when no EGL display can be created at all. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
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
    renderer *r = renderer_create(c->kind, &o, err, sizeof err);
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
        printf("skip: %s\n", why);
        return 77;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hdr_matches_output),
        cmocka_unit_test(test_unprepared),
        cmocka_unit_test(test_null_has_none),
        cmocka_unit_test(test_overflow),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
