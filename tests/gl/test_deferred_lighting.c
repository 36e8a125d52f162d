/* deferred-lighting (the light pre-pass, renderers/deferred/deferred_lighting.c) in a debug
 * context: the passes of a frame in order and their draw calls against the formula of
 * its header in every light-volume mode (the two geometry passes draw exactly the visible
 * opaque objects each, the light passes what deferred's do), two frames running; the
 * material pass (depth EQUAL) passing no more samples than the G-buffer pass; the plan
 * (no ambient or compose pass and why, the material programs per map variant, the
 * normal + shininess G-buffer and the light buffer in the format asked for); the 8-bit
 * light buffer clamping a light above 1 (darker, finite, never brighter beyond its
 * rounding); the keys it does not read (separate specular, the sky mask, the G-buffer
 * preset) leaving its image alone; at msaa 4 deferred's edge pass and classes in its light
 * passes and its material pass per sample (gl-agreement compares its image); an unknown
 * light buffer format refused. With deferred_lighting.lights: tiled, one dispatch instead
 * of the light passes (its plan, draws, grid counters, no depth copy), its light buffer
 * against the volumes' (16-bit within rounding, 8-bit clamped alike), at msaa 4 the same
 * edge pixels as the volumes' edge pass, a bad tiles.size refused. Any GL error fails. Exits 77 (skip) when no EGL display can be created at all. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "renderers/deferred/deferred.h"
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

enum { W = 128, H = 96 };

static gl_context *ctx;
static const renderer_impl *IMPL;   /* the registry's deferred-lighting */

enum { NMODES = 6 };
static const light_volume_mode MODES[NMODES] = {
    LIGHT_VOLUMES_FULLSCREEN, LIGHT_VOLUMES_VOLUME, LIGHT_VOLUMES_STENCIL,
    LIGHT_VOLUMES_STENCIL_TWO_PASS, LIGHT_VOLUMES_HULL, LIGHT_VOLUMES_SCISSOR};

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

static const float EYE[3] = {0.0f, 12.0f, 28.0f}, TARGET[3] = {0.0f, 1.0f, 0.0f};

/* scene `name` with exactly these lights, all active, posed at t = 0 and seen from EYE. */
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
    scene_update(s, 0.0);
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3_copy(EYE, s->cam.eye);
    sm_vec3_copy(TARGET, s->cam.target);
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
    return s;
}

/* "shapes" with a light of each type, two point lights in view and one behind the camera
 * (culled). */
static scene *shapes_every_type(void)
{
    const float sp[3] = {10.0f, 9.0f, 0.0f}, st[3] = {10.0f, 0.0f, 0.0f};
    scene_light lights[] = {
        directional(-0.3f, -1.0f, -0.2f, 0.5f, 0.5f, 0.45f),
        point(-10.0f, 3.0f, -10.0f, 7.0f, 1.0f, 0.8f, 0.6f),
        point(0.0f, 4.0f, 10.0f, 8.0f, 0.5f, 0.7f, 1.0f),
        point(0.0f, 4.0f, 400.0f, 8.0f, 1.0f, 1.0f, 1.0f),   /* behind the camera: culled */
        spot(sp, st, 14.0f, 30.0f),
    };
    scene *s = build("shapes", lights, 5);
    return s;
}

// >>the renderer

static renderer_options options(light_volume_mode mode, lpp_light_buffer_format lb)
{
    const gl_info *i = gl_context_info(ctx);
    renderer_options o = {.width = W, .height = H, .queries = true,
                          .timer_query = i->timer_query,
                          .pipeline_statistics = i->pipeline_statistics,
                          .max_uniform_block_size = i->max_uniform_block_size,
                          .light_volumes = mode, .lpp_light_buffer = lb};
    renderer_options_complete(&o);   /* the renderer's own create is called: no renderer_create */
    return o;
}

static void *make(const scene *s, const renderer_options *o)
{
    char err[4096] = "";
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    void *self = IMPL->create(o, err, sizeof err);
    if (!self)
        fail_msg("deferred-lighting create: %s", err);
    if (!IMPL->prepare(self, s, err, sizeof err))
        fail_msg("deferred-lighting prepare: %s", err);
    return self;
}

static void frame(void *self, const scene *s, frame_stats *fs)
{
    memset(fs, 0, sizeof *fs);
    IMPL->draw(self, s, fs);
    gl.Finish();
    renderer_impl_collect(IMPL, self, fs);
    assert_int_equal(gl_context_poll_errors(ctx, "deferred-lighting frame"), 0);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

/* Two frames of s (the second from the state the first left) read back: the output
 * (RGBA8) and, when hdr is not NULL, the light target as floats (W x H x 4). */
static uint8_t *render(const scene *s, const renderer_options *o, float *hdr)
{
    void *self = make(s, o);
    frame_stats fs;
    frame(self, s, &fs);
    frame(self, s, &fs);
    uint8_t *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    char err[256];
    assert_true(gl_context_read_rgba8(ctx, px, err, sizeof err));
    if (hdr)
        assert_true(IMPL->read_hdr(self, hdr, W, H));
    IMPL->destroy(self);
    return px;
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

static void check_formula(const scene *s, light_volume_mode mode)
{
    renderer_options o = options(mode, LPP_LIGHT_BUFFER_RGBA16F);
    void *self = make(s, &o);
    visible v = count_visible(s);
    /* deferred's light draws: the stencil modes' marks before each shading draw */
    const uint64_t per_light = mode == LIGHT_VOLUMES_STENCIL            ? 2
                               : mode == LIGHT_VOLUMES_STENCIL_TWO_PASS ? 3
                                                                        : 1;
    bool types[3] = {false, false, false};
    for (uint32_t i = 0; i < s->nlights_total; i++)
        types[s->lights[i].type] = true;
    for (int f = 0; f < 2; f++) {
        frame_stats fs;
        frame(self, s, &fs);
        const char *want[8];
        size_t n = 0;
        want[n++] = "gbuffer";
        if (types[LIGHT_DIRECTIONAL])
            want[n++] = "directional";
        if (types[LIGHT_POINT])
            want[n++] = "point";
        if (types[LIGHT_SPOT])
            want[n++] = "spot";
        want[n++] = "material";
        if (s->sky)
            want[n++] = "sky";
        want[n++] = "resolve";
        assert_int_equal(fs.npasses, n);
        for (size_t i = 0; i < n; i++)
            assert_string_equal(fs.pass[i].name, want[i]);

        /* the two geometry passes: each visible opaque object once in each */
        const pass_stats *gb = find_pass(&fs, "gbuffer"), *mat = find_pass(&fs, "material");
        assert_int_equal(gb->draw_calls, v.objects);
        assert_int_equal(mat->draw_calls, v.objects);
        assert_int_equal(gb->draw_calls + mat->draw_calls, 2 * (uint64_t)v.objects);
        if (types[LIGHT_DIRECTIONAL])
            assert_int_equal(find_pass(&fs, "directional")->draw_calls,
                             v.lights[LIGHT_DIRECTIONAL]);
        if (types[LIGHT_POINT])
            assert_int_equal(find_pass(&fs, "point")->draw_calls,
                             per_light * v.lights[LIGHT_POINT]);
        if (types[LIGHT_SPOT])
            assert_int_equal(find_pass(&fs, "spot")->draw_calls,
                             per_light * v.lights[LIGHT_SPOT]);
        if (s->sky)
            assert_int_equal(find_pass(&fs, "sky")->draw_calls, 1);
        assert_int_equal(find_pass(&fs, "resolve")->draw_calls, 1);
        uint64_t total = 0;
        for (size_t i = 0; i < fs.npasses; i++)
            total += fs.pass[i].draw_calls;
        uint64_t formula = 2 * (uint64_t)v.objects + v.lights[LIGHT_DIRECTIONAL] +
                           per_light * (v.lights[LIGHT_POINT] + v.lights[LIGHT_SPOT]) +
                           (s->sky ? 1 : 0) + 1;
        assert_int_equal(total, formula);
        assert_int_equal(fs.lights_drawn, v.lights[0] + v.lights[1] + v.lights[2]);
        assert_int_equal(deferred_last_shade_draws(self, LIGHT_POINT), v.lights[LIGHT_POINT]);
        assert_int_equal(deferred_last_mark_draws(self, LIGHT_SPOT),
                         (per_light - 1) * v.lights[LIGHT_SPOT]);
        /* depth EQUAL against the G-buffer pass's depth: only the fragments that ended up
         * visible pass, never more than the G-buffer pass let through (its overdraw) */
        if (!isnan(gb->samples) && !isnan(mat->samples)) {
            assert_true(mat->samples <= gb->samples);
            assert_true(v.objects == 0 ? mat->samples == 0.0 : mat->samples > 0.0);
        }
    }
    IMPL->destroy(self);
}

static void test_draw_calls(void **state)
{
    (void)state;
    scene *s = shapes_every_type();
    visible v = count_visible(s);
    assert_int_equal(v.lights[LIGHT_POINT], 2);
    assert_true(v.objects > 0);
    for (int m = 0; m < NMODES; m++)
        check_formula(s, MODES[m]);
    scene_destroy(s);

    /* no light at all: the material pass clears the light buffer itself */
    s = build("shapes", NULL, 0);
    check_formula(s, LIGHT_VOLUMES_STENCIL);
    scene_destroy(s);

    /* "empty": no objects, no sky: both geometry passes draw nothing */
    scene_light pl[] = {point(0.0f, 5.0f, 0.0f, 20.0f, 1.0f, 1.0f, 1.0f)};
    s = build("empty", pl, 1);
    for (int m = 0; m < NMODES; m++)
        check_formula(s, MODES[m]);
    scene_destroy(s);
}

// >>the plan

static size_t programs_named(const pass_plan *p, const char *prefix)
{
    size_t n = 0;
    for (size_t i = 0; i < p->nprograms; i++)
        n += strncmp(p->program[i], prefix, strlen(prefix)) == 0;
    return n;
}

static const target_plan_entry *target_named(const pass_plan *p, const char *name)
{
    for (size_t i = 0; i < p->ntargets; i++)
        if (strcmp(p->target[i].name, name) == 0)
            return &p->target[i];
    return NULL;
}

static void test_plan(void **state)
{
    (void)state;
    scene_light lights[] = {point(0.0f, 4.0f, 10.0f, 9.0f, 1.0f, 1.0f, 1.0f)};
    scene *s = build("shapes", lights, 1);
    static const struct {
        lpp_light_buffer_format f;
        const char *name;
        uint64_t bpp;
    } formats[] = {{LPP_LIGHT_BUFFER_RGBA16F, "rgba16f", 8}, {LPP_LIGHT_BUFFER_RGBA8, "rgba8", 4}};
    for (size_t k = 0; k < 2; k++) {
        renderer_options o = options(LIGHT_VOLUMES_STENCIL, formats[k].f);
        void *self = make(s, &o);
        pass_plan p;
        IMPL->describe(self, &p);
        const pass_plan_entry *e = plan_pass(&p, "ambient");
        assert_non_null(e);
        assert_false(e->run);
        assert_string_equal(e->reason, "ambient and emissive are the material pass's");
        assert_false(plan_pass(&p, "compose")->run);
        assert_false(plan_pass(&p, "spot")->run);
        assert_false(plan_pass(&p, "directional")->run);
        assert_true(plan_pass(&p, "point")->run);
        assert_true(plan_pass(&p, "material")->run);
        assert_non_null(strstr(plan_pass(&p, "material")->reason, formats[k].name));
        assert_int_equal(programs_named(&p, "deferred_ambient"), 0);
        assert_int_equal(programs_named(&p, "deferred_compose"), 0);
        assert_int_equal(programs_named(&p, "deferred_point"), 1);
        /* shapes' materials: plain, diffuse, diffuse + gloss, diffuse + normal + emissive */
        assert_int_equal(programs_named(&p, "deferred_gbuffer"), 4);
        assert_int_equal(programs_named(&p, "deferred_lighting_material"), 4);
        /* Engel's minimal G-buffer: normal and shininess in one RGBA16F, position from
         * depth (its copy sampled) */
        const target_plan_entry *g = target_named(&p, "gbuffer.normal+shininess");
        assert_non_null(g);
        assert_string_equal(g->format, "rgba16f");
        assert_int_equal(p.gbuffer_bytes, (uint64_t)W * H * 8);
        assert_non_null(target_named(&p, "depth.sampled"));
        for (int t = 0; t < 2; t++) {
            const target_plan_entry *lb =
                target_named(&p, t ? "lightbuffer.specular" : "lightbuffer.diffuse");
            assert_non_null(lb);
            assert_string_equal(lb->format, formats[k].name);
            assert_int_equal(lb->bytes, (uint64_t)W * H * formats[k].bpp);
        }
        const target_plan_entry *light = target_named(&p, "light");
        assert_non_null(light);
        assert_string_equal(light->format, "rgba16f");   /* the run's hdr, not the buffer's */
        IMPL->destroy(self);
    }
    scene_destroy(s);
}

// >>the light buffer's format

static void test_rgba8_clamps(void **state)
{
    (void)state;
    /* a light of colour 4 close over the scene: incoming x N.L well above 1 */
    scene_light lights[] = {point(0.0f, 5.0f, 4.0f, 30.0f, 4.0f, 4.0f, 4.0f)};
    scene *s = build("shapes", lights, 1);
    float *h16 = malloc(sizeof(float) * W * H * 4), *h8 = malloc(sizeof(float) * W * H * 4);
    assert_non_null(h16);
    assert_non_null(h8);
    renderer_options o16 = options(LIGHT_VOLUMES_STENCIL, LPP_LIGHT_BUFFER_RGBA16F);
    renderer_options o8 = options(LIGHT_VOLUMES_STENCIL, LPP_LIGHT_BUFFER_RGBA8);
    uint8_t *p16 = render(s, &o16, h16), *p8 = render(s, &o8, h8);
    size_t darker = 0, brighter = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++) {
        assert_true(isfinite(h16[i]) && isfinite(h8[i]));
        if (i % 4 == 3)
            continue;
        /* 8 bits round the light by at most 1/510, times a diffuse and a gloss <= 1 each */
        if (h8[i] > h16[i] + 2.0f / 510.0f + 1e-3f * h16[i])
            brighter++;
        if (h8[i] < h16[i] - 0.05f)
            darker++;
    }
    print_message("rgba8 light buffer: %zu channels darker by > 0.05, %zu brighter\n", darker,
                  brighter);
    assert_int_equal(brighter, 0);
    assert_true(darker > 100);   /* the clamp shows as image error */
    size_t diff = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++)
        diff += p16[i] != p8[i];
    assert_true(diff > 0);
    free(p16);
    free(p8);
    free(h16);
    free(h8);
    scene_destroy(s);
}

// >>what it does not read

static void test_unread_keys(void **state)
{
    (void)state;
    const float sp[3] = {10.0f, 9.0f, 0.0f}, st[3] = {10.0f, 0.0f, 0.0f};
    scene_light lights[] = {directional(-0.3f, -1.0f, -0.2f, 0.5f, 0.5f, 0.45f),
                            point(-10.0f, 3.0f, -10.0f, 7.0f, 1.0f, 0.8f, 0.6f),
                            spot(sp, st, 14.0f, 30.0f)};
    scene *s = build("shapes", lights, 3);
    renderer_options o = options(LIGHT_VOLUMES_STENCIL, LPP_LIGHT_BUFFER_RGBA16F);
    uint8_t *base = render(s, &o, NULL);
    renderer_options other = o;
    other.separate_specular = true;
    other.sky_stencil = true;
    other.gbuffer = GBUFFER_FAT;
    other.gbuffer_normal = GBUFFER_NORMAL_SPHEREMAP8;
    uint8_t *img = render(s, &other, NULL);
    assert_memory_equal(base, img, (size_t)W * H * 4);
    free(base);
    free(img);
    scene_destroy(s);
}

/* msaa 4: deferred's edge pass and classes in the light passes (a shading draw per class),
 * the material pass per sample everywhere; an unknown light buffer format is refused. */
static void test_msaa(void **state)
{
    (void)state;
    scene_light lights[] = {point(0.0f, 4.0f, 10.0f, 9.0f, 1.0f, 1.0f, 1.0f),
                            point(-10.0f, 3.0f, -10.0f, 8.0f, 1.0f, 0.8f, 0.6f)};
    scene *s = build("shapes", lights, 2);
    visible v = count_visible(s);
    renderer_options o = options(LIGHT_VOLUMES_STENCIL, LPP_LIGHT_BUFFER_RGBA16F);
    o.msaa = 4;
    void *self = make(s, &o);
    pass_plan p;
    IMPL->describe(self, &p);
    assert_true(plan_pass(&p, "edges")->run);
    assert_true(plan_pass(&p, "msaa-resolve")->run);
    const target_plan_entry *lb = target_named(&p, "lightbuffer.diffuse");
    assert_non_null(lb);
    assert_int_equal(lb->bytes, (uint64_t)W * H * 8 * 4);   /* 4 samples of RGBA16F */
    for (int f = 0; f < 2; f++) {
        frame_stats fs;
        frame(self, s, &fs);
        static const char *const want[] = {"gbuffer", "edges", "point", "material", "sky",
                                           "msaa-resolve", "resolve"};
        assert_int_equal(fs.npasses, sizeof want / sizeof want[0]);
        for (size_t i = 0; i < fs.npasses; i++)
            assert_string_equal(fs.pass[i].name, want[i]);
        assert_int_equal(find_pass(&fs, "gbuffer")->draw_calls, v.objects);
        assert_int_equal(find_pass(&fs, "material")->draw_calls, v.objects);
        /* per light: one mark, then a shading draw for the edge samples and one for the
         * other pixels */
        assert_int_equal(find_pass(&fs, "point")->draw_calls, 3 * v.lights[LIGHT_POINT]);
        assert_int_equal(deferred_last_shade_draws(self, LIGHT_POINT),
                         2 * v.lights[LIGHT_POINT]);
        const pass_stats *mat = find_pass(&fs, "material");
        if (!isnan(mat->samples)) {   /* every sample it passes is shaded on its own */
            assert_true(mat->samples > 0.0);
            assert_true(mat->per_sample_samples == mat->samples);
        }
        assert_true(fs.edge_fraction > 0.0 && fs.edge_fraction < 1.0);
    }
    float *hdr = malloc(sizeof(float) * W * H * 4);
    assert_non_null(hdr);
    assert_true(IMPL->read_hdr(self, hdr, W, H));
    for (size_t i = 0; i < (size_t)W * H * 4; i++)
        assert_true(isfinite(hdr[i]));
    free(hdr);
    IMPL->destroy(self);

    char err[512] = "";
    o.msaa = 1;
    o.lpp_light_buffer = (lpp_light_buffer_format)7;
    assert_null(renderer_create("deferred-lighting", &o, err, sizeof err));
    assert_string_equal(err, "deferred-lighting: unknown light buffer format 7");
    scene_destroy(s);
}

// >>the tiled light lists (deferred_lighting.lights: tiled)

/* The frame's draw calls (dispatches: true, its dispatches) over its passes (the impl's
 * collect does not sum them). */
static uint64_t frame_total(const frame_stats *fs, bool dispatches)
{
    uint64_t n = 0;
    for (size_t i = 0; i < fs->npasses; i++)
        n += dispatches ? fs->pass[i].dispatches : fs->pass[i].draw_calls;
    return n;
}

static void light_target(const scene *s, const renderer_options *o, float *hdr,
                         frame_stats *fs)
{
    void *self = make(s, o);
    frame(self, s, fs);
    frame(self, s, fs);
    assert_true(IMPL->read_hdr(self, hdr, W, H));
    IMPL->destroy(self);
}

/* The largest difference of two light targets' colour channels, and whether any is not
 * finite. */
static float max_diff(const float *a, const float *b)
{
    float m = 0.0f;
    for (size_t i = 0; i < (size_t)W * H * 4; i++) {
        assert_true(isfinite(a[i]) && isfinite(b[i]));
        if (i % 4 != 3 && fabsf(a[i] - b[i]) > m)
            m = fabsf(a[i] - b[i]);
    }
    return m;
}

static void test_tiled(void **state)
{
    (void)state;
    scene *s = shapes_every_type();
    visible v = count_visible(s);
    renderer_options o = options(LIGHT_VOLUMES_STENCIL, LPP_LIGHT_BUFFER_RGBA16F);
    o.lpp_tiled = true;
    void *self = make(s, &o);

    /* the plan: one dispatch, no light pass, no depth copy, the light-prepass program */
    pass_plan p;
    IMPL->describe(self, &p);
    assert_true(plan_pass(&p, "tiled")->run);
    assert_non_null(strstr(plan_pass(&p, "tiled")->reason, "8x6 tiles of 16 px"));
    assert_non_null(strstr(plan_pass(&p, "tiled")->reason, "into the light buffer"));
    static const char *const in_tiled[] = {"directional", "point", "spot"};
    for (size_t i = 0; i < 3; i++) {
        assert_false(plan_pass(&p, in_tiled[i])->run);
        assert_string_equal(plan_pass(&p, in_tiled[i])->reason, "in the tiled pass");
    }
    assert_string_equal(plan_pass(&p, "ambient")->reason,
                        "ambient and emissive are the material pass's");
    assert_true(plan_pass(&p, "material")->run);
    assert_int_equal(programs_named(&p, "tiled_light_prepass"), 1);
    assert_int_equal(programs_named(&p, "deferred_point"), 0);
    assert_int_equal(programs_named(&p, "deferred_stencil_mark"), 0);
    assert_null(target_named(&p, "depth.sampled"));
    assert_non_null(target_named(&p, "lightbuffer.specular"));

    /* the frame: gbuffer, one dispatch, material: 2 V + sky + resolve draws */
    for (int f = 0; f < 2; f++) {
        frame_stats fs;
        frame(self, s, &fs);
        static const char *const want[] = {"gbuffer", "tiled", "material", "sky", "resolve"};
        assert_int_equal(fs.npasses, 5);
        for (size_t i = 0; i < 5; i++)
            assert_string_equal(fs.pass[i].name, want[i]);
        const pass_stats *t = find_pass(&fs, "tiled");
        assert_int_equal(t->draw_calls, 0);
        assert_int_equal(t->dispatches, 1);
        assert_int_equal(frame_total(&fs, true), 1);
        assert_int_equal(find_pass(&fs, "gbuffer")->draw_calls, v.objects);
        assert_int_equal(find_pass(&fs, "material")->draw_calls, v.objects);
        assert_int_equal(frame_total(&fs, false), 2 * (uint64_t)v.objects + 2);
        assert_int_equal(fs.lights_drawn, v.lights[0] + v.lights[1] + v.lights[2]);
        /* the grid's counters: 48 tiles, the directional light in every list */
        assert_int_equal(fs.grid_cells, 48);
        assert_true(fs.grid_lights_mean >= 1.0 && fs.grid_lights_max <= 4.0);
        assert_true(fs.light_evals_per_pixel >= 1.0);
        size_t n = 0;
        assert_non_null(IMPL->light_grid(self, &n));
        assert_int_equal(n, 48);
    }
    IMPL->destroy(self);

    /* its light buffer is the volumes' (16-bit: the sums' order and rounding apart) */
    float *vol = malloc(sizeof(float) * W * H * 4), *til = malloc(sizeof(float) * W * H * 4);
    assert_non_null(vol);
    assert_non_null(til);
    frame_stats fv, ft;
    renderer_options ov = options(LIGHT_VOLUMES_STENCIL, LPP_LIGHT_BUFFER_RGBA16F);
    light_target(s, &ov, vol, &fv);
    light_target(s, &o, til, &ft);
    float d16 = max_diff(vol, til);
    /* 8 bits: the store clamps as the blending does (one rounding instead of one a light) */
    ov.lpp_light_buffer = o.lpp_light_buffer = LPP_LIGHT_BUFFER_RGBA8;
    light_target(s, &ov, vol, &fv);
    light_target(s, &o, til, &ft);
    float d8 = max_diff(vol, til);
    print_message("tiled vs volumes light target: max %.2e (rgba16f), %.2e (rgba8)\n", d16,
                  d8);
    assert_true(d16 < 2e-3f);
    assert_true(d8 < 3.0f / 255.0f);

    /* msaa 4: no edges pass, the dispatch finds the same edge pixels as it */
    ov.lpp_light_buffer = o.lpp_light_buffer = LPP_LIGHT_BUFFER_RGBA16F;
    ov.msaa = o.msaa = 4;
    light_target(s, &ov, vol, &fv);
    light_target(s, &o, til, &ft);
    assert_non_null(find_pass(&fv, "edges"));
    assert_null(find_pass(&ft, "edges"));
    assert_int_equal(frame_total(&ft, true), 1);
    print_message("msaa 4: edge fraction %.4f (volumes) %.4f (tiled), max diff %.2e\n",
                  fv.edge_fraction, ft.edge_fraction, max_diff(vol, til));
    assert_true(ft.edge_fraction > 0.0 && ft.edge_fraction < 1.0);
    assert_true(ft.edge_fraction == fv.edge_fraction);
    /* the same light but for a few pixels: where a light volume's silhouette crosses a
     * pixel, the volumes' stencil lights some of its samples; the dispatch lights them all
     * or none by the pixel's centre, as forward does (gl-agreement compares both with
     * forward-spml): at most 0.5 % of the pixels */
    size_t off = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        for (int c = 0; c < 3; c++)
            if (fabsf(vol[4 * i + c] - til[4 * i + c]) > 2e-3f) {
                off++;
                break;
            }
    print_message("msaa 4: %zu pixels off by > 2e-3\n", off);
    assert_true(off <= (size_t)W * H / 200);
    const pass_stats *t = find_pass(&ft, "tiled");
    assert_true(t->samples == (double)W * H * 4);
    assert_true(t->per_sample_samples == ft.edge_fraction * W * H * 4);
    free(vol);
    free(til);

    /* tiles.size is read (and checked) only with the tiled lists */
    char err[512] = "";
    o.msaa = 1;
    o.tile_size = 12;
    assert_null(renderer_create("deferred-lighting", &o, err, sizeof err));
    assert_non_null(strstr(err, "deferred-lighting: tiles.size"));
    o.lpp_tiled = false;
    renderer *r = renderer_create("deferred-lighting", &o, err, sizeof err);
    assert_non_null(r);
    renderer_destroy(r);
    scene_destroy(s);
}

int main(void)
{
    GL_TEST_SKIP_WITHOUT_EGL();
    IMPL = renderer_kind_find("deferred-lighting");
    if (!IMPL) {
        printf("deferred-lighting is not registered\n");
        return 1;
    }
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
        cmocka_unit_test(test_plan),
        cmocka_unit_test(test_rgba8_clamps),
        cmocka_unit_test(test_unread_keys),
        cmocka_unit_test(test_msaa),
        cmocka_unit_test(test_tiled),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    gl_context_destroy(ctx);
    return rc;
}
