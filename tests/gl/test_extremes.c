/* Extreme inputs (issue 5), in a debug context (77 when no EGL display): each case renders
 * one frame of "shapes" (64x48 unless it says) with lights and camera set by hand in
 * deferred (curtis and reference G-buffers, stencil volumes; fullscreen where volumes
 * matter), forward-mpml, forward-spml (uniform block and storage buffer), forward-plus,
 * clustered, tiled-deferred, deferred-lighting (stencil, fullscreen, tiled lists),
 * visibility and zbin (forward and deferred), and ends with no GL error, no non-finite value in the accumulation and a
 * readable output, or with a clear message before anything renders. Cases: 0, 1, 4096 and
 * 65536 lights (forward-spml's uniform block refused at prepare, naming
 * GL_MAX_UNIFORM_BLOCK_SIZE); radius 1e-4 and 1e5; a light on a surface with 1/d^2; the
 * camera inside 50 point lights; volumes cut by the near and far planes; specular exponent
 * 0 and 10000; 1x1, the largest size the context allows (null renderer: 2 GB) and one
 * beyond (refused, limit named); far 1e6 with near 0.01; RGBA16F overflow (reported or
 * clamped, never NaN, output 255); grazing angles; zero-length normals and tangents. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "renderers/forward/forward_common.h"
#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "renderers/frame/shading.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 64, H = 48 };

static gl_context *ctx;
static int ctx_w, ctx_h;

// >>configurations

typedef struct config {
    const char *name;
    const char *kind;
    gbuffer_preset gbuffer;
    light_volume_mode mode;
    bool volumes_only;         /* only where light volumes matter (fullscreen mode) */
    light_buffer_kind light_buffer;   /* forward-spml */
    bool lpp_tiled;            /* deferred-lighting: deferred_lighting.lights: tiled */
} config;

static const config CONFIGS[] = {
    {"deferred curtis stencil", "deferred", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL, false,
     LIGHT_BUFFER_UNIFORM, false},
    {"deferred reference stencil", "deferred", GBUFFER_REFERENCE, LIGHT_VOLUMES_STENCIL, false,
     LIGHT_BUFFER_UNIFORM, false},
    {"deferred curtis fullscreen", "deferred", GBUFFER_CURTIS, LIGHT_VOLUMES_FULLSCREEN, true,
     LIGHT_BUFFER_UNIFORM, false},
    {"deferred reference fullscreen", "deferred", GBUFFER_REFERENCE, LIGHT_VOLUMES_FULLSCREEN,
     true, LIGHT_BUFFER_UNIFORM, false},
    {"forward-mpml", "forward-mpml", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL, false,
     LIGHT_BUFFER_UNIFORM, false},
    {"forward-spml", "forward-spml", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL, false,
     LIGHT_BUFFER_UNIFORM, false},
    {"forward-spml storage", "forward-spml", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL, false,
     LIGHT_BUFFER_STORAGE, false},
    {"forward-plus", "forward-plus", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL, false,
     LIGHT_BUFFER_UNIFORM, false},
    {"clustered", "clustered", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL, false,
     LIGHT_BUFFER_UNIFORM, false},
    {"tiled-deferred", "tiled-deferred", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL, false,
     LIGHT_BUFFER_UNIFORM, false},
    {"deferred-lighting stencil", "deferred-lighting", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL,
     false, LIGHT_BUFFER_UNIFORM, false},
    {"deferred-lighting fullscreen", "deferred-lighting", GBUFFER_CURTIS,
     LIGHT_VOLUMES_FULLSCREEN, true, LIGHT_BUFFER_UNIFORM, false},
    {"deferred-lighting tiled", "deferred-lighting", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL,
     false, LIGHT_BUFFER_UNIFORM, true},
    {"visibility", "visibility", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL, false,
     LIGHT_BUFFER_UNIFORM, false},
    {"zbin", "zbin", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL, false, LIGHT_BUFFER_UNIFORM, false},
    {"zbin deferred", "zbin", GBUFFER_CURTIS, LIGHT_VOLUMES_STENCIL, false,
     LIGHT_BUFFER_UNIFORM, false},   /* zbin.shading: deferred (make) */
};
enum { SPML_UNIFORM = 5 };   /* CONFIGS' forward-spml with its uniform block */
enum { NCONFIGS = sizeof CONFIGS / sizeof CONFIGS[0] };

// >>contexts

static bool use_context(int w, int h, char *err, size_t errlen)
{
    if (ctx && ctx_w == w && ctx_h == h)
        return true;
    gl_context_destroy(ctx);
    ctx = NULL;
    gl_context_desc d = {.backend = GL_BACKEND_EGL, .device = -1, .debug = true,
                         .width = w, .height = h};
    ctx = gl_context_create(&d, err, errlen);
    ctx_w = ctx ? w : 0;
    ctx_h = ctx ? h : 0;
    return ctx != NULL;
}

static void need_context(int w, int h)
{
    char err[512];
    if (!use_context(w, h, err, sizeof err))
        fail_msg("context %dx%d: %s", w, h, err);
}

// >>scenes

static scene_light point(float x, float y, float z, float radius, float c,
                         attenuation_kind att)
{
    return (scene_light){.type = LIGHT_POINT, .position = {x, y, z}, .color = {c, c, c},
                         .direction = {0.0f, -1.0f, 0.0f}, .radius = radius,
                         .attenuation = att};
}

typedef struct view {
    sm_vec3 eye, target;
    float znear, zfar;         /* 0: the scene's */
} view;

/* The grid seen from the side and above (test_agreement.c's camera). */
static const view SIDE = {{0.0f, 12.0f, 28.0f}, {0.0f, 1.0f, 0.0f}, 0.0f, 0.0f};

/* "shapes" posed at t = 0 with exactly these n lights (copied), all active. */
static scene *build(const scene_light *lights, uint32_t n, const view *v, int w, int h)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build("shapes", &lp, w, h, err, sizeof err);
    if (!s)
        fail_msg("scene shapes: %s", err);
    s->lights = calloc(n ? n : 1, sizeof *s->lights);
    assert_non_null(s->lights);
    if (n)
        memcpy(s->lights, lights, n * sizeof *lights);
    s->nlights_total = n;
    s->count = (light_count){.start = n, .max = n};
    if (v->znear > 0.0f)
        s->znear = v->znear;
    if (v->zfar > 0.0f)
        s->zfar = v->zfar;
    scene_update(s, 0.0);
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3_copy(v->eye, s->cam.eye);
    sm_vec3_copy(v->target, s->cam.target);
    s->cam.znear = s->znear;
    s->cam.zfar = s->zfar;
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)w / (float)h, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
    return s;
}

// >>rendering

typedef struct result {
    size_t nonfinite;          /* renderer_read_hdr's count */
    size_t nan;                /* NaN values among them */
    size_t inf;
    size_t lit;                /* pixels whose rgb differs from `base` by more than 1e-3 */
    double sum;                /* sum of finite rgb values */
    uint32_t lights_drawn;     /* frame_stats.lights_drawn */
    float *hdr;                /* w x h x 4, bottom-up; owned by the caller */
    uint8_t *out;              /* w x h x 4, top-down */
} result;

static void result_free(result *r)
{
    free(r->hdr);
    free(r->out);
    *r = (result){0};
}

static renderer *make(const config *c, int w, int h, char *err, size_t errlen)
{
    const gl_info *i = gl_context_info(ctx);
    renderer_options o = {.width = w, .height = h, .queries = true,
                          .timer_query = i->timer_query,
                          .pipeline_statistics = i->pipeline_statistics,
                          .max_uniform_block_size = i->max_uniform_block_size,
                          .gbuffer = c->gbuffer, .light_volumes = c->mode,
                          .light_buffer = c->light_buffer, .lpp_tiled = c->lpp_tiled,
                          .zbin_deferred = strcmp(c->name, "zbin deferred") == 0};
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    return test_renderer_create(c->kind, &o, err, errlen);
}

/* One frame of s with c at the context's size. Asserts no GL error, a readable float
 * accumulation and RGBA8 output; counts what the accumulation holds. base (may be
 * NULL): hdr of the same view without lights, for `lit`. */
static result render(const config *c, const scene *s, const float *base)
{
    int w = ctx_w, h = ctx_h;
    char err[512] = "";
    renderer *r = make(c, w, h, err, sizeof err);
    if (!r)
        fail_msg("%s: create: %s", c->name, err);
    if (!renderer_prepare(r, s, err, sizeof err))
        fail_msg("%s: prepare (%u lights): %s", c->name, s->nlights_total, err);
    frame_stats fs;
    renderer_draw(r, s, &fs);
    gl.Finish();
    renderer_collect(r, &fs);
    gl_context_poll_errors(ctx, c->name);
    if (gl_context_error_count(ctx) != 0)
        fail_msg("%s: GL errors in the frame", c->name);

    size_t npx = (size_t)w * (size_t)h;
    result res = {.hdr = malloc(npx * 4 * sizeof(float)), .out = malloc(npx * 4),
                  .lights_drawn = fs.lights_drawn};
    assert_non_null(res.hdr);
    assert_non_null(res.out);
    if (!renderer_read_hdr(r, res.hdr, w, h, &res.nonfinite))
        fail_msg("%s: renderer_read_hdr refused %dx%d", c->name, w, h);
    if (!gl_context_read_rgba8(ctx, res.out, err, sizeof err))
        fail_msg("%s: read back: %s", c->name, err);
    renderer_destroy(r);
    gl_context_poll_errors(ctx, c->name);
    if (gl_context_error_count(ctx) != 0)
        fail_msg("%s: GL errors reading back", c->name);

    for (size_t p = 0; p < npx; p++) {
        bool lit = false;
        for (int k = 0; k < 4; k++) {
            float v = res.hdr[p * 4 + (size_t)k];
            res.nan += isnan(v) ? 1u : 0u;
            res.inf += isinf(v) ? 1u : 0u;
            if (k == 3 || !isfinite(v))
                continue;
            res.sum += v;
            if (base && fabsf(v - base[p * 4 + (size_t)k]) > 1e-3f)
                lit = true;
        }
        res.lit += lit;
        assert_int_equal(res.out[p * 4 + 3], 255);
    }
    assert_int_equal(res.nonfinite, res.nan + res.inf);
    return res;
}

/* The usual expectation: finite everywhere. */
static result render_finite(const config *c, const scene *s, const char *what,
                            const float *base)
{
    result res = render(c, s, base);
    if (res.nonfinite)
        fail_msg("%s, %s: %zu non-finite values in the light accumulation (%zu NaN)", what,
                 c->name, res.nonfinite, res.nan);
    return res;
}

/* Every configuration (fullscreen ones only when `volumes`) renders s finite. */
static void all_finite(const scene *s, const char *what, bool volumes)
{
    for (size_t i = 0; i < NCONFIGS; i++) {
        if (CONFIGS[i].volumes_only && !volumes)
            continue;
        result r = render_finite(&CONFIGS[i], s, what, NULL);
        result_free(&r);
    }
}

// >>light counts

static void test_zero_lights(void **state)
{
    (void)state;
    need_context(W, H);
    scene *s = build(NULL, 0, &SIDE, W, H);
    for (size_t i = 0; i < NCONFIGS; i++) {
        result r = render_finite(&CONFIGS[i], s, "0 lights", NULL);
        assert_true(r.sum > 0.0);   /* ambient, emissive and sky still show */
        result_free(&r);
    }
    scene_destroy(s);
}

static void test_one_light(void **state)
{
    (void)state;
    need_context(W, H);
    scene_light l = point(0.0f, 6.0f, 4.0f, 14.0f, 1.0f, ATTENUATION_LINEAR_RANGE);
    scene *s = build(&l, 1, &SIDE, W, H);
    scene *dark = build(NULL, 0, &SIDE, W, H);
    for (size_t i = 0; i < NCONFIGS; i++) {
        result b = render_finite(&CONFIGS[i], dark, "1 light (base)", NULL);
        result r = render_finite(&CONFIGS[i], s, "1 light", b.hdr);
        assert_true(r.lit > (size_t)W * H / 20);
        result_free(&r);
        result_free(&b);
    }
    scene_destroy(dark);
    scene_destroy(s);
}

/* n dim point lights of radius 1.5 on a grid over the light bounds (deterministic). */
static scene_light *many_lights(uint32_t n)
{
    scene_light *l = calloc(n, sizeof *l);
    assert_non_null(l);
    uint32_t side = (uint32_t)ceil(sqrt((double)n));
    for (uint32_t i = 0; i < n; i++) {
        float x = -20.0f + 40.0f * ((float)(i % side) + 0.5f) / (float)side;
        float z = -20.0f + 40.0f * ((float)(i / side) + 0.5f) / (float)side;
        float y = 0.5f + 3.0f * (float)((i * 7u) % 11u) / 10.0f;
        l[i] = point(x, y, z, 1.5f, 0.05f, ATTENUATION_LINEAR_RANGE);
    }
    return l;
}

/* forward-spml refuses n lights beyond its uniform block at prepare, naming the limit. */
static void expect_spml_refuses(const scene *s, uint32_t n)
{
    const gl_info *gi = gl_context_info(ctx);
    uint32_t cap = forward_spml_max_lights(gi->max_uniform_block_size);
    assert_true(n > cap);
    char want[256], err[512] = "";
    snprintf(want, sizeof want,
             "forward-spml: %u lights requested, this context allows at most %u "
             "(GL_MAX_UNIFORM_BLOCK_SIZE %d / %zu bytes; forward.light_buffer: storage has "
             "no such limit)",
             n, cap, gi->max_uniform_block_size, sizeof(gpu_light));
    renderer *r = make(&CONFIGS[SPML_UNIFORM], ctx_w, ctx_h, err, sizeof err);
    assert_non_null(r);
    assert_false(renderer_prepare(r, s, err, sizeof err));
    if (strcmp(err, want) != 0)
        fail_msg("forward-spml with %u lights: message\n  '%s'\nexpected\n  '%s'", n, err,
                 want);
    renderer_destroy(r);
    gl_context_poll_errors(ctx, "forward-spml refusal");
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static void many(uint32_t n, bool no_mpml)
{
    enum { MW = 32, MH = 24 };
    need_context(MW, MH);
    scene_light *l = many_lights(n);
    scene *s = build(l, n, &SIDE, MW, MH);
    free(l);
    char what[64];
    snprintf(what, sizeof what, "%u lights", n);
    for (size_t i = 0; i < NCONFIGS; i++) {
        const config *c = &CONFIGS[i];
        if (c == &CONFIGS[SPML_UNIFORM]) {
            expect_spml_refuses(s, n);
            continue;
        }
        if (c->volumes_only || (no_mpml && strcmp(c->kind, "forward-mpml") == 0))
            continue;
        result r = render_finite(c, s, what, NULL);
        print_message("%u lights, %s: %u drawn\n", n, c->name, r.lights_drawn);
        assert_true(r.lights_drawn > n / 8);   /* the frame really drew many of them */
        result_free(&r);
    }
    scene_destroy(s);
}

static void test_4096_lights(void **state)
{
    (void)state;
    many(4096, false);
}

/* forward-mpml draws the lit objects once per light: 65536 passes are left out for
 * time (forward-mpml at 4096 covers its path); deferred, forward-spml with its
 * storage buffer, forward-plus, clustered and tiled-deferred render them. */
static void test_65536_lights(void **state)
{
    (void)state;
    many(65536, true);
}

// >>light radius and position

static void test_radius_tiny(void **state)
{
    (void)state;
    need_context(W, H);
    scene_light l[3] = {
        point(0.0f, 3.0f, 4.0f, 1e-4f, 1.0f, ATTENUATION_LINEAR_RANGE),
        point(0.0f, 1e-5f, 6.0f, 1e-4f, 1.0f, ATTENUATION_INVERSE_SQUARE),   /* by the floor */
        point(-10.0f, 4.2f, -10.0f, 1e-4f, 1.0f, ATTENUATION_INVERSE_SQUARE), /* on the sphere */
    };
    scene *s = build(l, 3, &SIDE, W, H);
    scene *dark = build(NULL, 0, &SIDE, W, H);
    for (size_t i = 0; i < NCONFIGS; i++) {
        result b = render_finite(&CONFIGS[i], dark, "radius 1e-4 (base)", NULL);
        result r = render_finite(&CONFIGS[i], s, "radius 1e-4", b.hdr);
        if (r.lit > 1)
            fail_msg("radius 1e-4, %s: %zu pixels lit", CONFIGS[i].name, r.lit);
        result_free(&r);
        result_free(&b);
    }
    scene_destroy(dark);
    scene_destroy(s);
}

static void test_radius_huge(void **state)
{
    (void)state;
    need_context(W, H);
    scene_light l = point(0.0f, 10.0f, 0.0f, 1e5f, 0.5f, ATTENUATION_LINEAR_RANGE);
    scene *s = build(&l, 1, &SIDE, W, H);
    scene *dark = build(NULL, 0, &SIDE, W, H);
    size_t first = 0;
    for (size_t i = 0; i < NCONFIGS; i++) {
        result b = render_finite(&CONFIGS[i], dark, "radius 1e5 (base)", NULL);
        result r = render_finite(&CONFIGS[i], s, "radius 1e5", b.hdr);
        print_message("radius 1e5, %s: %zu of %d pixels lit\n", CONFIGS[i].name, r.lit, W * H);
        assert_true(r.lit > (size_t)W * H / 2);
        if (i == 0)
            first = r.lit;
        /* every renderer lights the same pixels (within a few, on edges) */
        assert_true(r.lit + 8 >= first && first + 8 >= r.lit);
        result_free(&r);
        result_free(&b);
    }
    scene_destroy(dark);
    scene_destroy(s);
}

/* 1/d^2 with d = 0: lights exactly on the floor's top (y = 0) and on the top of the
 * sphere at (-10, 2.2, -10), radius 2. Bright but finite. */
static void test_light_on_surface(void **state)
{
    (void)state;
    need_context(W, H);
    scene_light l[3] = {
        point(0.0f, 0.0f, 5.0f, 20.0f, 1.0f, ATTENUATION_INVERSE_SQUARE),
        point(-10.0f, 4.2f, -10.0f, 20.0f, 1.0f, ATTENUATION_INVERSE_SQUARE),
        point(10.0f, 0.0f, 0.0f, 20.0f, 1.0f, ATTENUATION_QUADRATIC),
    };
    l[2].att_a = 1.0f;   /* 1 / (d^2): c = 0 too */
    scene *s = build(l, 3, &SIDE, W, H);
    all_finite(s, "light on a surface", true);
    view close = {{0.0f, 3.0f, 9.0f}, {0.0f, 0.0f, 5.0f}, 0.0f, 0.0f};
    scene *s2 = build(l, 3, &close, W, H);
    all_finite(s2, "light on a surface, close up", true);
    scene_destroy(s2);
    scene_destroy(s);
}

// >>volumes and the camera

/* 50 point lights of radius 10 about the eye, all containing it. */
static void test_camera_inside_many(void **state)
{
    (void)state;
    need_context(W, H);
    view v = {{0.0f, 4.0f, 18.0f}, {0.0f, 1.0f, 0.0f}, 0.0f, 0.0f};
    scene_light l[50];
    for (int i = 0; i < 50; i++) {
        float a = (float)i * 0.7f;
        float rr = 0.2f + 0.1f * (float)(i % 7);
        l[i] = point(v.eye[0] + rr * cosf(a), v.eye[1] + 0.3f * sinf(1.3f * a),
                     v.eye[2] + rr * sinf(a), 10.0f + (float)(i % 5), 0.03f,
                     ATTENUATION_LINEAR_RANGE);
    }
    scene *s = build(l, 50, &v, W, H);
    scene *dark = build(NULL, 0, &v, W, H);
    for (size_t i = 0; i < NCONFIGS; i++) {
        result b = render_finite(&CONFIGS[i], dark, "camera inside 50 volumes (base)", NULL);
        result r = render_finite(&CONFIGS[i], s, "camera inside 50 volumes", b.hdr);
        assert_true(r.lit > (size_t)W * H / 4);   /* volumes seen from inside still light */
        result_free(&r);
        result_free(&b);
    }
    scene_destroy(dark);
    scene_destroy(s);
}

/* A volume whose near side lies between the eye and the near plane (cut by it, the eye
 * outside), one cut by the far plane at 40, and one straddling both at near 0.01. */
static void test_volumes_cut(void **state)
{
    (void)state;
    need_context(W, H);
    view v = {{0.0f, 3.0f, 20.0f}, {0.0f, 1.0f, 0.0f}, 0.5f, 40.0f};
    sm_vec3 dir;
    sm_vec3_sub(v.target, v.eye, dir);
    sm_vec3_normalize(dir);
    float r_near = 3.0f, r_far = 8.0f;
    float dn = r_near + 0.25f;   /* nearest point 0.25 from the eye, inside the near plane */
    float df = 40.0f;            /* centre on the far plane */
    scene_light l[2] = {
        point(v.eye[0] + dir[0] * dn, v.eye[1] + dir[1] * dn, v.eye[2] + dir[2] * dn, r_near,
              1.0f, ATTENUATION_LINEAR_RANGE),
        point(v.eye[0] + dir[0] * df, v.eye[1] + dir[1] * df, v.eye[2] + dir[2] * df, r_far,
              1.0f, ATTENUATION_LINEAR_RANGE),
    };
    scene *s = build(l, 2, &v, W, H);
    all_finite(s, "volumes cut by near and far", true);
    scene_destroy(s);
}

static void test_far_1e6(void **state)
{
    (void)state;
    need_context(W, H);
    view v = SIDE;
    v.znear = 0.01f;
    v.zfar = 1e6f;
    scene_light l[2] = {
        point(0.0f, 6.0f, 4.0f, 14.0f, 1.0f, ATTENUATION_LINEAR_RANGE),
        point(0.0f, 6.0f, -5e5f, 6e5f, 1.0f, ATTENUATION_LINEAR_RANGE),   /* to the far plane */
    };
    scene *s = build(l, 2, &v, W, H);
    all_finite(s, "near 0.01 far 1e6", true);
    scene_destroy(s);
}

// >>materials

static void shininess(float n)
{
    need_context(W, H);
    scene_light l[2] = {
        point(0.0f, 6.0f, 4.0f, 14.0f, 1.0f, ATTENUATION_LINEAR_RANGE),
        point(-5.0f, 3.0f, 8.0f, 12.0f, 0.8f, ATTENUATION_INVERSE_SQUARE),
    };
    scene *s = build(l, 2, &SIDE, W, H);
    for (uint32_t i = 0; i < s->nmaterials; i++)
        s->materials[i].shininess = n;
    char what[64];
    snprintf(what, sizeof what, "specular exponent %g", (double)n);
    all_finite(s, what, false);
    scene_destroy(s);
}

static void test_shininess_0(void **state)
{
    (void)state;
    shininess(0.0f);
}

static void test_shininess_10000(void **state)
{
    (void)state;
    shininess(10000.0f);
}

// >>overflow

/* 64 lights of colour 1e5 at one point: beyond RGBA16F's 65504. Clamped (65504) or
 * reported (+Inf, counted by renderer_read_hdr), never NaN; the 8-bit output is 255
 * wherever the accumulation saturated. */
static void test_overflow(void **state)
{
    (void)state;
    need_context(W, H);
    scene_light l[64];
    for (int i = 0; i < 64; i++)
        l[i] = point(0.0f, 2.5f, 2.0f, 20.0f, 1e5f, ATTENUATION_LINEAR_RANGE);
    scene *s = build(l, 64, &SIDE, W, H);
    for (size_t i = 0; i < NCONFIGS; i++) {
        result r = render(&CONFIGS[i], s, NULL);
        size_t saturated = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                const float *hp = &r.hdr[((size_t)(H - 1 - y) * W + (size_t)x) * 4];
                const uint8_t *o = &r.out[((size_t)y * W + (size_t)x) * 4];
                for (int k = 0; k < 3; k++) {
                    if (isnan(hp[k]))
                        fail_msg("overflow, %s: NaN at (%d, %d)[%d]", CONFIGS[i].name, x, y, k);
                    if (hp[k] >= 1.0f) {
                        saturated += hp[k] >= 65504.0f;
                        if (o[k] != 255)
                            fail_msg("overflow, %s: (%d, %d)[%d]: hdr %g, output %d",
                                     CONFIGS[i].name, x, y, k, (double)hp[k], o[k]);
                    }
                }
            }
        print_message("overflow, %s: %zu non-finite reported (%zu Inf), %zu channels >= "
                      "65504\n",
                      CONFIGS[i].name, r.nonfinite, r.inf, saturated);
        assert_int_equal(r.nan, 0);
        assert_true(saturated > 0);
        result_free(&r);
    }
    scene_destroy(s);
}

// >>geometry and views

/* The eye 0.01 above the floor (its top is y = 0) looking along it. */
static void test_grazing(void **state)
{
    (void)state;
    need_context(W, H);
    scene_light l[2] = {
        point(0.0f, 3.0f, 10.0f, 30.0f, 1.0f, ATTENUATION_LINEAR_RANGE),
        point(3.0f, 0.05f, 15.0f, 10.0f, 1.0f, ATTENUATION_INVERSE_SQUARE),   /* grazing light */
    };
    view v = {{0.0f, 0.01f, 30.0f}, {0.0f, 0.01f, -30.0f}, 0.0f, 0.0f};
    scene *s = build(l, 2, &v, W, H);
    all_finite(s, "grazing view", true);
    view v2 = {{0.0f, 1e-4f, 25.0f}, {0.0f, 0.0f, -30.0f}, 0.01f, 0.0f};
    scene *s2 = build(l, 2, &v2, W, H);
    all_finite(s2, "grazing view, eye 1e-4 above the floor", true);
    scene_destroy(s2);
    scene_destroy(s);
}

/* Every 5th vertex of every mesh gets a zero normal and a zero tangent (w = 0 too),
 * before renderer_prepare uploads them. */
static void test_degenerate_frames(void **state)
{
    (void)state;
    need_context(W, H);
    scene_light l[3] = {
        point(0.0f, 6.0f, 4.0f, 20.0f, 1.0f, ATTENUATION_LINEAR_RANGE),
        point(0.0f, 5.0f, 0.0f, 14.0f, 1.0f, ATTENUATION_INVERSE_SQUARE),
        point(-10.0f, 5.0f, 10.0f, 14.0f, 1.0f, ATTENUATION_LINEAR_RANGE),
    };
    scene *s = build(l, 3, &SIDE, W, H);
    size_t zeroed = 0;
    for (uint32_t m = 0; m < s->nmeshes; m++)
        for (uint32_t v = 0; v < s->meshes[m].nvertices; v += 5) {
            mesh_vertex *mv = &s->meshes[m].vertices[v];
            memset(mv->normal, 0, sizeof mv->normal);
            memset(mv->tangent, 0, sizeof mv->tangent);
            zeroed++;
        }
    assert_true(zeroed > 100);
    all_finite(s, "zero normals and tangents", false);
    /* all of them */
    for (uint32_t m = 0; m < s->nmeshes; m++)
        for (uint32_t v = 0; v < s->meshes[m].nvertices; v++) {
            mesh_vertex *mv = &s->meshes[m].vertices[v];
            memset(mv->normal, 0, sizeof mv->normal);
            memset(mv->tangent, 0, sizeof mv->tangent);
        }
    all_finite(s, "every normal and tangent zero", false);
    scene_destroy(s);
}

// >>resolutions

static void test_resolution_1x1(void **state)
{
    (void)state;
    need_context(1, 1);
    scene_light l = point(0.0f, 6.0f, 4.0f, 40.0f, 1.0f, ATTENUATION_LINEAR_RANGE);
    scene *s = build(&l, 1, &SIDE, 1, 1);
    all_finite(s, "1x1", true);
    scene_destroy(s);
}

static bool has(const char *text, const char *part)
{
    return strstr(text, part) != NULL;
}

/* The largest square the context renders: its renderbuffer, texture and viewport
 * limits' least. */
static int size_limit(const gl_info *gi)
{
    int max = gi->max_renderbuffer_size;
    if (gi->max_texture_size < max)
        max = gi->max_texture_size;
    if (gi->max_viewport_dims[0] < max)
        max = gi->max_viewport_dims[0];
    if (gi->max_viewport_dims[1] < max)
        max = gi->max_viewport_dims[1];
    return max;
}

/* Beyond the limit: refused with the limit named. At the limit: the null renderer
 * (an RGBA8 and a depth-stencil renderbuffer of max x max: 2 GB on llvmpipe at 16384),
 * skipped with a printed reason if the context cannot be had for memory. The forward
 * and deferred renderers at max x 1 and 1 x max. */
static void test_resolution_limits(void **state)
{
    (void)state;
    need_context(W, H);
    const gl_info *gi = gl_context_info(ctx);
    int max = size_limit(gi);
    int rb = gi->max_renderbuffer_size;
    print_message("limits: renderbuffer %d, texture %d, viewport %dx%d\n", rb,
                  gi->max_texture_size, gi->max_viewport_dims[0], gi->max_viewport_dims[1]);

    char err[512] = "", want[64];
    gl_context_destroy(ctx);
    ctx = NULL;
    ctx_w = ctx_h = 0;
    gl_context_desc d = {.backend = GL_BACKEND_EGL, .device = -1, .debug = true,
                         .width = rb + 1, .height = 1};
    gl_context *bad = gl_context_create(&d, err, sizeof err);
    assert_null(bad);
    print_message("%dx1: %s\n", rb + 1, err);
    snprintf(want, sizeof want, "resolution %dx1 exceeds this context's limit of ", rb + 1);
    assert_true(has(err, want));
    d.width = 1;
    d.height = rb + 1;
    bad = gl_context_create(&d, err, sizeof err);
    assert_null(bad);
    snprintf(want, sizeof want, "resolution 1x%d exceeds this context's limit of ", rb + 1);
    assert_true(has(err, want));

    /* max x 1 and 1 x max with every renderer */
    scene_light l = point(0.0f, 6.0f, 4.0f, 40.0f, 1.0f, ATTENUATION_LINEAR_RANGE);
    const int sizes[2][2] = {{max, 1}, {1, max}};
    for (int k = 0; k < 2; k++) {
        need_context(sizes[k][0], sizes[k][1]);
        scene *s = build(&l, 1, &SIDE, sizes[k][0], sizes[k][1]);
        char what[64];
        snprintf(what, sizeof what, "%dx%d", sizes[k][0], sizes[k][1]);
        all_finite(s, what, false);
        scene_destroy(s);
    }

    /* max x max: the null renderer only */
    if (getenv("SHADESWEEP_EXTREMES_NO_HUGE")) {
        print_message("skip: %dx%d (SHADESWEEP_EXTREMES_NO_HUGE is set)\n", max, max);
    } else if (!use_context(max, max, err, sizeof err)) {
        print_message("skip: a %dx%d context could not be created: %s\n", max, max, err);
    } else {
        scene *s = build(&l, 1, &SIDE, max, max);
        renderer_options o = {.width = max, .height = max};
        renderer *r = test_renderer_create("null", &o, err, sizeof err);
        if (!r)
            fail_msg("null at %dx%d: %s", max, max, err);
        if (!renderer_prepare(r, s, err, sizeof err))
            fail_msg("null at %dx%d: prepare: %s", max, max, err);
        frame_stats fs;
        renderer_draw(r, s, &fs);
        gl.Finish();
        renderer_collect(r, &fs);
        uint8_t px[4] = {1, 2, 3, 4};
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, gl_context_framebuffer(ctx));
        gl.ReadPixels(max - 1, max - 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
        gl_context_poll_errors(ctx, "null at the limit");
        assert_int_equal(gl_context_error_count(ctx), 0);
        print_message("%dx%d null: corner pixel %d %d %d %d\n", max, max, px[0], px[1], px[2],
                      px[3]);
        renderer_destroy(r);
        scene_destroy(s);
    }
    gl_context_destroy(ctx);
    ctx = NULL;
    ctx_w = ctx_h = 0;
    need_context(W, H);
}

/* The tiled and clustered renderers at max x max (16384 x 16384 on llvmpipe: up to
 * 19 GB resident with the test's own read-back, 6 minutes on two cores), only when
 * SHADESWEEP_EXTREMES_MAX_TILED is set (never in CI; README's extremes section says when
 * it last ran): one light, finite everywhere and no GL error, or refused at prepare,
 * before anything renders, naming the limit it would exceed (clustered: a list head per
 * cluster, 16384^2 / 16^2 tiles x its slices, beyond GL_MAX_SHADER_STORAGE_BLOCK_SIZE). */
static void test_resolution_max_tiled(void **state)
{
    (void)state;
    if (!getenv("SHADESWEEP_EXTREMES_MAX_TILED")) {
        print_message("skip: the tiled renderers at the size limit "
                      "(set SHADESWEEP_EXTREMES_MAX_TILED to run them)\n");
        return;
    }
    need_context(W, H);
    const gl_info *gi = gl_context_info(ctx);
    int max = size_limit(gi);
    char err[512] = "";
    gl_context_destroy(ctx);
    ctx = NULL;
    ctx_w = ctx_h = 0;
    if (!use_context(max, max, err, sizeof err))
        fail_msg("a %dx%d context could not be created: %s", max, max, err);
    scene_light l = point(0.0f, 6.0f, 4.0f, 40.0f, 1.0f, ATTENUATION_LINEAR_RANGE);
    scene *s = build(&l, 1, &SIDE, max, max);
    static const char *const tiled[] = {"forward-plus", "clustered", "tiled-deferred",
                                        "visibility"};
    for (size_t i = 0; i < NCONFIGS; i++)
        for (size_t k = 0; k < 4; k++)
            if (strcmp(CONFIGS[i].name, tiled[k]) == 0) {
                renderer *pr = make(&CONFIGS[i], max, max, err, sizeof err);
                if (!pr)
                    fail_msg("%s: create: %s", CONFIGS[i].name, err);
                bool ok = renderer_prepare(pr, s, err, sizeof err);
                renderer_destroy(pr);
                if (!ok) {
                    print_message("%dx%d %s: refused: %s\n", max, max, CONFIGS[i].name, err);
                    assert_non_null(strstr(err, "this context allows"));
                    assert_non_null(strstr(err, "GL_MAX_SHADER_STORAGE_BLOCK_SIZE"));
                    continue;
                }
                result r = render_finite(&CONFIGS[i], s, "the size limit", NULL);
                print_message("%dx%d %s: finite, light sum %.4g\n", max, max, CONFIGS[i].name,
                              r.sum);
                assert_true(r.sum > 0.0);
                result_free(&r);
            }
    scene_destroy(s);
    gl_context_destroy(ctx);
    ctx = NULL;
    ctx_w = ctx_h = 0;
    need_context(W, H);
}

static int teardown(void **state)
{
    (void)state;
    gl_context_destroy(ctx);
    ctx = NULL;
    return 0;
}

int main(void)
{
    GL_TEST_SKIP_WITHOUT_EGL();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_zero_lights),
        cmocka_unit_test(test_one_light),
        cmocka_unit_test(test_4096_lights),
        cmocka_unit_test(test_65536_lights),
        cmocka_unit_test(test_radius_tiny),
        cmocka_unit_test(test_radius_huge),
        cmocka_unit_test(test_light_on_surface),
        cmocka_unit_test(test_camera_inside_many),
        cmocka_unit_test(test_volumes_cut),
        cmocka_unit_test(test_far_1e6),
        cmocka_unit_test(test_shininess_0),
        cmocka_unit_test(test_shininess_10000),
        cmocka_unit_test(test_overflow),
        cmocka_unit_test(test_grazing),
        cmocka_unit_test(test_degenerate_frames),
        cmocka_unit_test(test_resolution_1x1),
        cmocka_unit_test(test_resolution_limits),
        cmocka_unit_test(test_resolution_max_tiled),
    };
    return cmocka_run_group_tests(tests, NULL, teardown);
}
