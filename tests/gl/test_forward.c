/* The forward renderers (renderers/forward/forward_mpml.c, forward_spml.c, forward_common.c)
 * in a debug context on scenes set up here: draw calls against the formulas of their
 * headers (with and without illumination sets), program and texture changes against
 * the state buckets of the frontend's order, the pass plan, forward-mpml and
 * forward-spml agreeing on the image (RGBA8: max difference <= 2/255, RMSE < 1/255)
 * with 1, 16 and 64 point lights and with spot and directional lights, no non-finite
 * value in the HDR target, and forward-spml's light limit (refused in prepare with
 * its message beyond it, working at it). Any GL error fails. Exits 77 (skip) when no
 * EGL display can be created at all.
 *
 * The formulas are computed from a frontend of the test's own over the same scene,
 * not from the renderers' counts. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "renderers/forward/forward_common.h"
#include "renderers/frame/frontend.h"
#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern const renderer_impl renderer_forward_mpml_impl;
extern const renderer_impl renderer_forward_spml_impl;

#define MPML (&renderer_forward_mpml_impl)
#define SPML (&renderer_forward_spml_impl)

enum { W = 128, H = 96, MAX_CASE_LIGHTS = 64 };

static gl_context *ctx;

// >>scenes

static scene_light point(float x, float y, float z, float radius, float r, float g, float b)
{
    return (scene_light){.type = LIGHT_POINT, .position = {x, y, z}, .color = {r, g, b},
                         .direction = {0.0f, -1.0f, 0.0f}, .radius = radius,
                         .attenuation = ATTENUATION_LINEAR_RANGE};
}

static scene_light spot(float x, float y, float z, float dx, float dy, float dz, float radius,
                        float angle_deg)
{
    scene_light l = {.type = LIGHT_SPOT, .position = {x, y, z}, .direction = {dx, dy, dz},
                     .color = {1.0f, 0.9f, 0.7f}, .radius = radius,
                     .spot_angle = sm_deg2rad(angle_deg), .spot_exponent = 4.0f,
                     .attenuation = ATTENUATION_INVERSE_SQUARE};
    sm_vec3_normalize(l.direction);
    sm_vec3_scale(l.color, 40.0f, l.color);   /* 1/d^2 at ~6 units */
    return l;
}

static scene_light directional(float dx, float dy, float dz, float r, float g, float b)
{
    scene_light l = {.type = LIGHT_DIRECTIONAL, .direction = {dx, dy, dz}, .color = {r, g, b}};
    sm_vec3_normalize(l.direction);
    return l;
}

/* Poses s at t = 0 from its orbit, then looks from eye at target instead. */
static void look(scene *s, const float eye[3], const float target[3])
{
    scene_update(s, 0.0);
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3_copy(eye, s->cam.eye);
    sm_vec3_copy(target, s->cam.target);
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
}

/* The camera of most cases: the grid of objects from the side and above (all ten
 * objects in view), and a close one that sees only part of the grid. */
static const float EYE[3] = {0.0f, 12.0f, 28.0f}, TARGET[3] = {0.0f, 1.0f, 0.0f};
static const float NEAR_EYE[3] = {-6.0f, 5.0f, 16.0f}, NEAR_TARGET[3] = {-8.0f, 1.0f, 0.0f};

/* scene `name` with exactly these lights, all active. */
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
    look(s, EYE, TARGET);
    return s;
}

/* "shapes" with n random point lights placed as a run places them (seed 1337, MSVC
 * rand, colour <= 0.3, squared distance attenuation: seed 003). */
static scene *build_random(uint32_t n, float radius)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_RANDOM, .seed = 1337, .rng = RNG_MSVC,
                       .count = {.start = n, .max = n}, .radius = radius, .color_max = 0.3f};
    scene *s = scene_build("shapes", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("scene shapes with %u lights: %s", n, err);
    look(s, EYE, TARGET);
    return s;
}

// >>renderers

typedef struct fwd {
    const renderer_impl *impl;
    void *self;
} fwd;

static renderer_options options(bool sets)
{
    const gl_info *i = gl_context_info(ctx);
    renderer_options o = {.width = W, .height = H, .queries = true,
                          .timer_query = i->timer_query,
                          .pipeline_statistics = i->pipeline_statistics,
                          .max_uniform_block_size = i->max_uniform_block_size,
                          .no_illumination_sets = !sets};
    renderer_options_complete(&o);   /* the renderers' own create is called: no renderer_create */
    return o;
}

static fwd make(const renderer_impl *impl, const scene *s, bool sets)
{
    char err[512] = "";
    renderer_options o = options(sets);
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    fwd f = {impl, impl->create(&o, err, sizeof err)};
    if (!f.self)
        fail_msg("%s: create: %s", impl->name, err);
    if (!impl->prepare(f.self, s, err, sizeof err))
        fail_msg("%s: prepare: %s", impl->name, err);
    return f;
}

static void drop(fwd *f)
{
    f->impl->destroy(f->self);
    f->self = NULL;
    gl_context_poll_errors(ctx, "forward test");
    assert_int_equal(gl_context_error_count(ctx), 0);
}

/* One frame as renderer.c runs it: zeroed stats, draw, sync, collect. */
static void frame(fwd *f, const scene *s, frame_stats *fs)
{
    memset(fs, 0, sizeof *fs);
    f->impl->draw(f->self, s, fs);
    gl.Finish();
    renderer_impl_collect(f->impl, f->self, fs);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static size_t pass_index(const frame_stats *fs, const char *name)
{
    for (size_t i = 0; i < fs->npasses; i++)
        if (strcmp(fs->pass[i].name, name) == 0)
            return i;
    fail_msg("no pass %s", name);
    return 0;
}

static void assert_pass_names(const frame_stats *fs, const char *const *names)
{
    size_t n = 0;
    while (names[n])
        n++;
    assert_int_equal(fs->npasses, n);
    for (size_t i = 0; i < n; i++)
        assert_string_equal(fs->pass[i].name, names[i]);
}

/* The frontend the formulas are computed from. */
static void frontend_of(const scene *s, frontend *fe)
{
    char err[256] = "";
    memset(fe, 0, sizeof *fe);
    if (!frontend_init(fe, s, err, sizeof err))
        fail_msg("frontend_init: %s", err);
    frontend_build(fe, s);
}

static uint32_t illum_size(const frontend *fe, uint32_t k)
{
    return fe->illum_start[k + 1] - fe->illum_start[k];
}

// >>pixels

static uint8_t *read_output(void)
{
    uint8_t *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    char err[256];
    if (!gl_context_read_rgba8(ctx, px, err, sizeof err))
        fail_msg("read back: %s", err);
    return px;
}

/* Non-finite values in the HDR target of the last frame. */
static size_t hdr_nonfinite(const fwd *f)
{
    const gl_target *t = forward_hdr_target(f->self);
    assert_non_null(t);
    assert_int_equal(t->format, GLT_FORMAT_RGBA16F);
    size_t n = (size_t)t->width * (size_t)t->height * 4, bad = 0;
    float *v = malloc(n * sizeof *v);
    assert_non_null(v);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.GetTextureImage(t->texture, 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * sizeof *v), v);
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            bad++;
    free(v);
    return bad;
}

typedef struct diff {
    int max;                  /* in 1/255 */
    double rmse;              /* in [0, 1] */
    size_t differing;         /* pixels with any channel different */
} diff;

static diff compare(const uint8_t *a, const uint8_t *b)
{
    diff d = {0, 0.0, 0};
    double sum = 0.0;
    for (size_t p = 0; p < (size_t)W * H; p++) {
        bool differs = false;
        for (int c = 0; c < 4; c++) {
            int e = abs((int)a[4 * p + c] - (int)b[4 * p + c]);
            if (e > d.max)
                d.max = e;
            sum += (double)e * e;
            differs |= e != 0;
        }
        d.differing += differs;
    }
    d.rmse = sqrt(sum / ((double)W * H * 4)) / 255.0;
    return d;
}

/* Renders one frame of s with impl and returns the output (and checks the HDR target). */
static uint8_t *render(const renderer_impl *impl, const scene *s, bool sets)
{
    fwd f = make(impl, s, sets);
    frame_stats fs;
    frame(&f, s, &fs);
    assert_int_equal(hdr_nonfinite(&f), 0);
    uint8_t *px = read_output();
    drop(&f);
    return px;
}

/* forward-mpml (with and without illumination sets) and forward-spml agree on s, and
 * its lights change the image. */
static void expect_agreement(const char *what, scene *s)
{
    uint8_t *spml = render(SPML, s, true);
    uint8_t *mpml = render(MPML, s, true);
    uint8_t *brute = render(MPML, s, false);
    diff d = compare(mpml, spml);
    if (d.max > 2 || d.rmse >= 1.0 / 255.0)
        print_error("%s: forward-mpml vs forward-spml: max %d/255, rmse %.3f/255, %zu pixels "
                    "differ\n", what, d.max, d.rmse * 255.0, d.differing);
    assert_true(d.max <= 2);
    assert_true(d.rmse < 1.0 / 255.0);
    /* illumination sets leave out only objects the light cannot reach: the same image */
    diff b = compare(mpml, brute);
    if (b.max != 0)
        print_error("%s: forward-mpml with and without illumination sets: max %d/255\n", what,
                    b.max);
    assert_int_equal(b.max, 0);

    /* the lights light something: without them the image is different */
    uint32_t n = s->nlights_active;
    s->nlights_active = 0;
    s->count.start = s->count.max = 0;
    uint8_t *dark = render(SPML, s, true);
    s->count.start = s->count.max = n;
    s->nlights_active = n;
    diff lit = compare(spml, dark);
    if (lit.differing < (size_t)W * H / 100)
        print_error("%s: the lights change only %zu pixels\n", what, lit.differing);
    assert_true(lit.differing >= (size_t)W * H / 100);
    free(dark);
    free(brute);
    free(mpml);
    free(spml);
}

// >>state buckets

/* Program and texture changes the state cache must count for objects[0..n) drawn in
 * order after `program` (an id of the simulation: kind * 64 + type * 16 + variant)
 * and the four texture units `unit` (scene texture indices; -2 unknown). */
typedef struct bucket_sim {
    int program;
    int unit[4];
    uint64_t program_changes, texture_changes;
} bucket_sim;

static void sim_reset(bucket_sim *b)
{
    b->program = -1;
    for (int u = 0; u < 4; u++)
        b->unit[u] = -2;
    b->program_changes = b->texture_changes = 0;
}

static void sim_draw(bucket_sim *b, const scene *s, uint32_t object, int program_kind)
{
    const scene_material *m = &s->materials[s->objects[object].material];
    int program = program_kind + (int)forward_material_variant(m);
    if (program != b->program) {
        b->program = program;
        b->program_changes++;
    }
    const int maps[4] = {m->diffuse_map, m->gloss_map, m->normal_map, m->emissive_map};
    for (int u = 0; u < 4; u++)
        if (maps[u] >= 0 && maps[u] != b->unit[u]) {
            b->unit[u] = maps[u];
            b->texture_changes++;
        }
}

// >>tests: draw calls

static void check_mpml_draws(scene *s, bool sets, int frames)
{
    fwd f = make(MPML, s, sets);
    for (int k = 0; k < frames; k++) {
        if (k > 0)
            scene_update(s, 3.0 * k);   /* the orbit: other views, other sets */
        frontend fe;
        frontend_of(s, &fe);
        frame_stats fs;
        frame(&f, s, &fs);
        static const char *const names[] = {"base", "lights", "sky", "resolve", NULL};
        assert_pass_names(&fs, names);
        uint64_t lights = 0;
        uint32_t lit = 0;
        for (uint32_t l = 0; l < fe.nlights; l++) {
            uint32_t n = sets ? illum_size(&fe, l) : fe.nvisible;
            lights += n;
            lit += n > 0;
        }
        /* draws = V + sum over visible lights of |I(l)| (V each without sets) + sky + resolve */
        assert_int_equal(fs.pass[0].draw_calls, fe.nvisible);
        assert_int_equal(fs.pass[1].draw_calls, lights);
        assert_int_equal(fs.pass[2].draw_calls, 1);
        assert_int_equal(fs.pass[3].draw_calls, 1);
        assert_int_equal(total_draws(&fs), fe.nvisible + lights + 2);
        assert_int_equal(fs.lights_drawn, lit);
        if (!sets)
            assert_int_equal(fs.pass[1].draw_calls, (uint64_t)fe.nvisible * fe.nlights);
        frontend_free(&fe);
    }
    drop(&f);
}

static scene_light sixteen[16];

static void make_sixteen(void)
{
    for (int i = 0; i < 16; i++) {
        float x = (float)(i % 4) * 8.0f - 12.0f, z = (float)(i / 4) * 8.0f - 12.0f;
        sixteen[i] = point(x, 3.0f + (float)(i % 3), z, 7.0f, 0.2f + 0.05f * (float)(i % 5),
                           0.3f, 0.5f - 0.02f * (float)i);
    }
}

static void test_mpml_draw_calls(void **state)
{
    (void)state;
    make_sixteen();
    scene *s = build("shapes", sixteen, 16);
    /* the case means something: sets smaller than V, some lights lighting nothing */
    frontend fe;
    frontend_of(s, &fe);
    assert_int_equal(fe.nvisible, s->nobjects);
    assert_int_equal(fe.nlights, 16);
    uint32_t total = fe.illum_start[fe.nlights];
    assert_true(total > 0 && total < fe.nvisible * fe.nlights);
    frontend_free(&fe);

    check_mpml_draws(s, true, 3);
    look(s, NEAR_EYE, NEAR_TARGET);
    frontend_of(s, &fe);
    assert_true(fe.nvisible > 0 && fe.nvisible < s->nobjects);   /* culled objects */
    frontend_free(&fe);
    check_mpml_draws(s, true, 1);
    scene_destroy(s);
}

static void test_mpml_draw_calls_without_sets(void **state)
{
    (void)state;
    make_sixteen();
    scene *s = build("shapes", sixteen, 16);
    check_mpml_draws(s, false, 3);
    scene_destroy(s);
}

/* A light in view whose range reaches no visible object: no draw with sets, V without.
 * (The floor's bounding sphere has a radius of 57: the light floats beyond it.) */
static void test_mpml_light_reaching_nothing(void **state)
{
    (void)state;
    scene_light lights[2] = {point(0, 6, 4, 14, 1.0f, 0.9f, 0.8f),
                             point(0, 14, -70, 3.0f, 1.0f, 1.0f, 1.0f)};   /* in the air */
    scene *s = build("shapes", lights, 2);
    frontend fe;
    frontend_of(s, &fe);
    assert_int_equal(fe.nlights, 2);            /* visible: it is not culled ... */
    assert_int_equal(illum_size(&fe, 1), 0);    /* ... but lights no object */
    uint32_t first = illum_size(&fe, 0);
    assert_true(first > 0);

    for (int with_sets = 1; with_sets >= 0; with_sets--) {
        fwd f = make(MPML, s, with_sets);
        frame_stats both, one;
        frame(&f, s, &both);
        s->nlights_total = 1;   /* the same scene without the floating light */
        s->count.start = s->count.max = 1;
        scene_update(s, 0.0);
        look(s, EYE, TARGET);
        frame(&f, s, &one);
        s->nlights_total = 2;
        s->count.start = s->count.max = 2;
        look(s, EYE, TARGET);
        uint64_t lights_both = both.pass[pass_index(&both, "lights")].draw_calls;
        uint64_t lights_one = one.pass[pass_index(&one, "lights")].draw_calls;
        if (with_sets) {
            assert_int_equal(lights_both, first);
            assert_int_equal(lights_one, first);
            assert_int_equal(total_draws(&both), total_draws(&one));
            assert_int_equal(both.lights_drawn, 1);
        } else {
            assert_int_equal(lights_both, 2 * (uint64_t)fe.nvisible);
            assert_int_equal(lights_one, fe.nvisible);
            assert_int_equal(both.lights_drawn, 2);
        }
        drop(&f);
    }
    frontend_free(&fe);
    scene_destroy(s);
}

static void test_spml_draw_calls(void **state)
{
    (void)state;
    make_sixteen();
    scene *s = build("shapes", sixteen, 16);
    fwd f = make(SPML, s, true);
    for (int k = 0; k < 3; k++) {
        if (k == 1)
            look(s, NEAR_EYE, NEAR_TARGET);
        if (k == 2)
            scene_update(s, 7.0);
        frontend fe;
        frontend_of(s, &fe);
        frame_stats fs;
        frame(&f, s, &fs);
        static const char *const names[] = {"shade", "sky", "resolve", NULL};
        assert_pass_names(&fs, names);
        /* draws = V + sky + resolve */
        assert_int_equal(fs.pass[0].draw_calls, fe.nvisible);
        assert_int_equal(total_draws(&fs), fe.nvisible + 2);
        assert_int_equal(fs.lights_drawn, fe.nlights);
        frontend_free(&fe);
    }
    drop(&f);
    scene_destroy(s);
}

/* A scene without sky, lights or objects: base (or shade) and resolve only. */
static void test_empty_scene(void **state)
{
    (void)state;
    scene *s = build("empty", NULL, 0);
    assert_false(s->sky);
    const renderer_impl *impls[] = {MPML, SPML};
    for (int i = 0; i < 2; i++) {
        fwd f = make(impls[i], s, true);
        frame_stats fs;
        frame(&f, s, &fs);
        static const char *const mpml_names[] = {"base", "resolve", NULL};
        static const char *const spml_names[] = {"shade", "resolve", NULL};
        assert_pass_names(&fs, i == 0 ? mpml_names : spml_names);
        assert_int_equal(total_draws(&fs), 1);
        assert_int_equal(fs.lights_drawn, 0);
        uint8_t *px = read_output();
        static const uint8_t black[4] = {0, 0, 0, 255};
        for (size_t p = 0; p < (size_t)W * H; p++)
            assert_memory_equal(px + 4 * p, black, 4);
        free(px);
        pass_plan plan;
        memset(&plan, 0, sizeof plan);
        f.impl->describe(f.self, &plan);
        bool sky_skipped = false, lights_skipped = false;
        for (size_t k = 0; k < plan.npasses; k++) {
            if (strcmp(plan.pass[k].name, "sky") == 0) {
                assert_false(plan.pass[k].run);
                assert_string_equal(plan.pass[k].reason, "skipped, the scene has no sky");
                sky_skipped = true;
            }
            if (strcmp(plan.pass[k].name, "lights") == 0) {
                assert_false(plan.pass[k].run);
                assert_string_equal(plan.pass[k].reason, "skipped, the scene has no lights");
                lights_skipped = true;
            }
        }
        assert_true(sky_skipped);
        assert_true(lights_skipped == (i == 0));
        drop(&f);
    }
    scene_destroy(s);
}

// >>tests: state changes

static void test_state_buckets(void **state)
{
    (void)state;
    make_sixteen();
    scene_light lights[18];
    memcpy(lights, sixteen, sizeof sixteen);
    lights[16] = spot(0, 10, 0, 0.2f, -1, 0.1f, 20, 30);
    lights[17] = directional(-0.4f, -1.0f, -0.3f, 0.3f, 0.3f, 0.25f);
    scene *s = build("shapes", lights, 18);
    frontend fe;
    frontend_of(s, &fe);

    /* The frontend's order is the state buckets: each diffuse map in one run. */
    for (uint32_t i = 1; i < fe.nvisible; i++)
        assert_true(frontend_sort_key(s, fe.visible[i - 1]) <=
                    frontend_sort_key(s, fe.visible[i]));

    for (int sets = 1; sets >= 0; sets--) {
        fwd f = make(MPML, s, sets);
        frame_stats fs;
        for (int k = 0; k < 2; k++) {   /* every frame counts alike */
            frame(&f, s, &fs);
            bucket_sim b;
            sim_reset(&b);
            for (uint32_t i = 0; i < fe.nvisible; i++)
                sim_draw(&b, s, fe.visible[i], 0);
            const gls_counts *base = forward_last_pass_counts(f.self, 0);
            assert_non_null(base);
            assert_int_equal(base->category[GLS_CAT_PROGRAM], b.program_changes);
            assert_int_equal(base->category[GLS_CAT_TEXTURE], b.texture_changes);
            assert_int_equal(base->category[GLS_CAT_FRAMEBUFFER], 1);
            assert_int_equal(base->draw_calls, fe.nvisible);

            b.program_changes = b.texture_changes = 0;
            for (uint32_t l = 0; l < fe.nlights; l++) {
                const scene_light *light = &s->lights[fe.lights[l]];
                const uint32_t *objs = sets ? fe.illum + fe.illum_start[l] : fe.visible;
                uint32_t n = sets ? illum_size(&fe, l) : fe.nvisible;
                for (uint32_t i = 0; i < n; i++)
                    sim_draw(&b, s, objs[i], 64 + 16 * (int)light->type);
            }
            const gls_counts *lp = forward_last_pass_counts(f.self, 1);
            assert_non_null(lp);
            assert_int_equal(lp->category[GLS_CAT_PROGRAM], b.program_changes);
            assert_int_equal(lp->category[GLS_CAT_TEXTURE], b.texture_changes);
            /* the light passes share one state: blending on and depth EQUAL, set once */
            assert_int_equal(lp->category[GLS_CAT_FRAMEBUFFER], 0);
            assert_int_equal(lp->category[GLS_CAT_BLEND], 1);
            assert_int_equal(lp->category[GLS_CAT_DEPTH], 1);
            assert_int_equal(lp->category[GLS_CAT_STENCIL], 0);
            assert_int_equal(lp->category[GLS_CAT_CULL], 0);
            assert_int_equal(lp->state_changes, b.program_changes + b.texture_changes + 2);
            assert_int_equal(fs.pass[1].state_changes, lp->state_changes);
            assert_null(forward_last_pass_counts(f.self, 4));
        }
        drop(&f);
    }

    /* forward-spml: one pass in bucket order */
    fwd f = make(SPML, s, true);
    frame_stats fs;
    frame(&f, s, &fs);
    bucket_sim b;
    sim_reset(&b);
    for (uint32_t i = 0; i < fe.nvisible; i++)
        sim_draw(&b, s, fe.visible[i], 0);
    const gls_counts *shade = forward_last_pass_counts(f.self, 0);
    assert_int_equal(shade->category[GLS_CAT_PROGRAM], b.program_changes);
    assert_int_equal(shade->category[GLS_CAT_TEXTURE], b.texture_changes);
    /* shapes: 4 materials of 4 variants, 3 diffuse maps, one gloss, normal and
     * emissive map: bucket order binds each map once */
    assert_int_equal(b.program_changes, 4);
    assert_int_equal(b.texture_changes, 6);
    drop(&f);
    frontend_free(&fe);
    scene_destroy(s);
}

// >>tests: the plan

static bool has_program(const pass_plan *p, const char *name)
{
    for (size_t i = 0; i < p->nprograms; i++)
        if (strcmp(p->program[i], name) == 0)
            return true;
    return false;
}

static void test_describe(void **state)
{
    (void)state;
    make_sixteen();
    scene *s = build("shapes", sixteen, 16);
    fwd f = make(MPML, s, true);
    pass_plan p;
    memset(&p, 0, sizeof p);
    f.impl->describe(f.self, &p);
    assert_int_equal(p.npasses, 7);
    static const char *const names[] = {"base", "lights", "fog", "sky", "translucent",
                                        "edge-aa", "resolve"};
    for (size_t i = 0; i < 7; i++) {
        assert_string_equal(p.pass[i].name, names[i]);
        /* fog off, nothing translucent, aa: none: skipped */
        assert_true(p.pass[i].run == (i != 2 && i != 4 && i != 5));
        assert_true(p.pass[i].reason[0] != '\0');
    }
    assert_string_equal(p.pass[4].reason, "skipped: no translucent materials");
    /* 4 material variants x (base + point lights), then the sky and the resolve */
    assert_int_equal(p.nprograms, 10);
    assert_true(has_program(&p, "forward_base"));
    assert_true(has_program(&p, "forward_base+DIFFUSE_MAP"));
    assert_true(has_program(&p, "forward_base+DIFFUSE_MAP+GLOSS_MAP"));
    assert_true(has_program(&p, "forward_base+DIFFUSE_MAP+EMISSIVE_MAP+NORMAL_MAP"));
    assert_true(has_program(&p, "forward_point+DIFFUSE_MAP+LIGHT_TYPE=LIGHT_POINT"));
    assert_true(has_program(&p, "forward_point+LIGHT_TYPE=LIGHT_POINT"));
    assert_false(has_program(&p, "forward_spot+LIGHT_TYPE=LIGHT_SPOT"));
    assert_int_equal(p.ntargets, 2);
    assert_string_equal(p.target[0].name, "hdr");
    assert_string_equal(p.target[0].format, "rgba16f");
    assert_int_equal(p.target[0].bytes, (uint64_t)W * H * 8);
    assert_string_equal(p.target[1].name, "depth");
    assert_int_equal(p.target_bytes, (uint64_t)W * H * 12);
    assert_int_equal(p.gbuffer_bytes, 0);
    drop(&f);

    /* spots and directional lights: their light programs, and no others */
    scene_light lights[2] = {spot(0, 10, 0, 0.2f, -1, 0.1f, 20, 30),
                             directional(-0.4f, -1.0f, -0.3f, 0.8f, 0.8f, 0.7f)};
    scene *s2 = build("shapes", lights, 2);
    f = make(MPML, s2, false);
    memset(&p, 0, sizeof p);
    f.impl->describe(f.self, &p);
    assert_int_equal(p.nprograms, 4 + 8 + 2);
    assert_true(has_program(&p, "forward_spot+LIGHT_TYPE=LIGHT_SPOT"));
    assert_true(has_program(&p, "forward_directional+DIFFUSE_MAP+LIGHT_TYPE=LIGHT_DIRECTIONAL"));
    assert_false(has_program(&p, "forward_point+LIGHT_TYPE=LIGHT_POINT"));
    assert_non_null(strstr(p.pass[1].reason, "illumination sets off"));
    drop(&f);

    f = make(SPML, s, true);
    memset(&p, 0, sizeof p);
    f.impl->describe(f.self, &p);
    assert_int_equal(p.npasses, 6);   /* shade fog sky translucent edge-aa resolve */
    assert_string_equal(p.pass[0].name, "shade");
    assert_string_equal(p.pass[1].name, "fog");
    assert_false(p.pass[1].run);
    assert_int_equal(p.nprograms, 4 + 2);
    assert_true(has_program(&p, "forward_spml+MAX_LIGHTS=16"));
    assert_true(has_program(&p, "forward_spml+DIFFUSE_MAP+EMISSIVE_MAP+MAX_LIGHTS=16+NORMAL_MAP"));
    assert_int_equal(p.gbuffer_bytes, 0);
    assert_int_equal(p.target_bytes, (uint64_t)W * H * 12);
    drop(&f);
    scene_destroy(s2);
    scene_destroy(s);
}

// >>tests: images

static void test_agree_one_point(void **state)
{
    (void)state;
    scene_light l = point(0, 6, 4, 14, 1.0f, 0.9f, 0.8f);
    scene *s = build("shapes", &l, 1);
    expect_agreement("one point light", s);
    scene_destroy(s);
}

static void test_agree_sixteen_points(void **state)
{
    (void)state;
    make_sixteen();
    scene *s = build("shapes", sixteen, 16);
    expect_agreement("16 point lights", s);
    look(s, NEAR_EYE, NEAR_TARGET);
    expect_agreement("16 point lights, close", s);
    scene_destroy(s);
}

static void test_agree_sixty_four_points(void **state)
{
    (void)state;
    scene *s = build_random(64, 8.0f);
    expect_agreement("64 random point lights", s);
    scene_update(s, 11.0);   /* the orbit */
    expect_agreement("64 random point lights, orbiting", s);
    /* brighter and overlapping more: many additive passes on each pixel, so that the
     * RGBA16F rounding of each blend adds up as far as it can */
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        s->lights[i].attenuation = ATTENUATION_LINEAR_RANGE;
        s->lights[i].radius = 14.0f;
        sm_vec3_scale(s->lights[i].color, 1.5f, s->lights[i].color);
    }
    look(s, EYE, TARGET);
    expect_agreement("64 bright overlapping point lights", s);
    scene_destroy(s);
}

static void test_agree_spot_and_directional(void **state)
{
    (void)state;
    scene_light l = spot(0, 10, 0, 0.2f, -1, 0.1f, 20, 30);
    scene *s = build("shapes", &l, 1);
    expect_agreement("one spot light", s);
    scene_destroy(s);

    l = directional(-0.4f, -1.0f, -0.3f, 0.8f, 0.8f, 0.7f);
    s = build("shapes", &l, 1);
    expect_agreement("one directional light", s);
    scene_destroy(s);

    scene_light mix[4] = {spot(-6, 9, 3, 0.3f, -1, -0.2f, 18, 25),
                          directional(0.5f, -1.0f, 0.2f, 0.25f, 0.22f, 0.2f),
                          point(5, 4, -3, 9, 0.6f, 0.4f, 0.3f),
                          spot(8, 6, 8, -0.5f, -1, -0.5f, 16, 40)};
    s = build("shapes", mix, 4);
    expect_agreement("spots, a directional and a point light", s);
    scene_destroy(s);
}

// >>tests: forward-spml's light limit

static void test_spml_limit(void **state)
{
    (void)state;
    const gl_info *gi = gl_context_info(ctx);
    uint32_t cap = forward_spml_max_lights(gi->max_uniform_block_size);
    assert_int_equal(cap, (uint32_t)gi->max_uniform_block_size / 80u);
    assert_true(cap >= 16384u / 80u);   /* GL's minimum GL_MAX_UNIFORM_BLOCK_SIZE */
    assert_int_equal(forward_spml_max_lights(0), 0);
    assert_int_equal(forward_spml_max_lights(-1), 0);
    assert_int_equal(forward_spml_max_lights(65536), 819);

    const uint32_t too_many[] = {cap + 1, 65536};
    for (size_t i = 0; i < 2; i++) {
        scene *s = build_random(too_many[i], 8.0f);
        char err[512] = "", want[512];
        renderer_options o = options(true);
        void *self = SPML->create(&o, err, sizeof err);
        assert_non_null(self);
        assert_false(SPML->prepare(self, s, err, sizeof err));
        snprintf(want, sizeof want,
                 "forward-spml: %u lights requested, this context allows at most %u "
                 "(GL_MAX_UNIFORM_BLOCK_SIZE %d / 80 bytes; forward.light_buffer: storage "
                 "has no such limit)",
                 too_many[i], cap, gi->max_uniform_block_size);
        assert_string_equal(err, want);
        SPML->destroy(self);
        assert_int_equal(gl_context_error_count(ctx), 0);
        scene_destroy(s);
    }

    /* exactly at the limit: works, with the array as large as the block allows */
    scene *s = build_random(cap, 8.0f);
    fwd f = make(SPML, s, true);
    pass_plan p;
    memset(&p, 0, sizeof p);
    f.impl->describe(f.self, &p);
    char want[64];
    snprintf(want, sizeof want, "forward_spml+MAX_LIGHTS=%u", cap);
    assert_true(has_program(&p, want));
    for (int k = 0; k < 2; k++) {
        frontend fe;
        frontend_of(s, &fe);
        frame_stats fs;
        frame(&f, s, &fs);
        assert_true(fe.nlights > cap / 2);   /* most of them are in view */
        assert_int_equal(fs.lights_drawn, fe.nlights);
        assert_int_equal(total_draws(&fs), fe.nvisible + 2);
        assert_int_equal(hdr_nonfinite(&f), 0);
        frontend_free(&fe);
        scene_update(s, 5.0);
    }
    drop(&f);
    scene_destroy(s);
}

// >>tests: queries and misuse

static void test_queries_and_misuse(void **state)
{
    (void)state;
    const gl_info *gi = gl_context_info(ctx);
    make_sixteen();
    scene *s = build("shapes", sixteen, 16);
    fwd f = make(MPML, s, true);
    frame_stats fs;
    for (int k = 0; k < 4; k++)
        frame(&f, s, &fs);
    for (size_t i = 0; i < fs.npasses; i++) {
        if (gi->pipeline_statistics) {
            assert_true(isfinite(fs.pass[i].fragments));
            assert_true(isfinite(fs.pass[i].primitives));
        }
        assert_true(isfinite(fs.pass[i].cpu_us) && fs.pass[i].cpu_us >= 0.0);
    }
    if (gi->pipeline_statistics) {
        /* the resolve shades every output pixel once */
        assert_true(find_pass(&fs, "resolve")->fragments == (double)W * H);
        assert_true(find_pass(&fs, "lights")->fragments > 0.0);
    }
    drop(&f);

    /* without queries: NAN measurements, the same counts */
    renderer_options o = options(true);
    o.queries = false;
    char err[512] = "";
    void *self = MPML->create(&o, err, sizeof err);
    assert_non_null(self);
    /* a scene posed for another size is refused */
    scene *other = build_random(1, 8.0f);
    other->width = W * 2;
    assert_false(MPML->prepare(self, other, err, sizeof err));
    assert_non_null(strstr(err, "forward-mpml: the scene is posed for"));
    other->width = W;
    scene_destroy(other);
    assert_false(MPML->prepare(self, NULL, err, sizeof err));
    assert_true(MPML->prepare(self, s, err, sizeof err));
    frame_stats nq;
    memset(&nq, 0, sizeof nq);
    MPML->draw(self, s, &nq);
    gl.Finish();
    renderer_impl_collect(MPML, self, &nq);
    for (size_t i = 0; i < nq.npasses; i++) {
        assert_true(isnan(nq.pass[i].gpu_us) && isnan(nq.pass[i].fragments));
        assert_int_equal(nq.pass[i].draw_calls, fs.pass[i].draw_calls);
        assert_int_equal(nq.pass[i].state_changes, fs.pass[i].state_changes);
    }
    /* prepare twice: the second replaces the first */
    assert_true(MPML->prepare(self, s, err, sizeof err));
    MPML->draw(self, s, &nq);
    gl.Finish();
    renderer_impl_collect(MPML, self, &nq);
    assert_int_equal(total_draws(&nq), total_draws(&fs));
    MPML->destroy(self);
    MPML->destroy(NULL);
    SPML->destroy(NULL);
    assert_int_equal(gl_context_error_count(ctx), 0);
    scene_destroy(s);
}

GL_TEST_MAIN(ctx, W, H,
             cmocka_unit_test(test_mpml_draw_calls),
             cmocka_unit_test(test_mpml_draw_calls_without_sets),
             cmocka_unit_test(test_mpml_light_reaching_nothing),
             cmocka_unit_test(test_spml_draw_calls),
             cmocka_unit_test(test_empty_scene),
             cmocka_unit_test(test_state_buckets),
             cmocka_unit_test(test_describe),
             cmocka_unit_test(test_agree_one_point),
             cmocka_unit_test(test_agree_sixteen_points),
             cmocka_unit_test(test_agree_sixty_four_points),
             cmocka_unit_test(test_agree_spot_and_directional),
             cmocka_unit_test(test_spml_limit),
             cmocka_unit_test(test_queries_and_misuse))
