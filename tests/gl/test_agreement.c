/* Image agreement across renderers (issue 3's acceptance), in a debug context (any GL
 * error fails): on "shapes" with hand-placed lights and cameras (one light of each type,
 * 16 lights, the camera inside a point and a spot volume, volumes cut by the near and far
 * planes), deferred with the `reference` G-buffer in every light-volume mode agrees with
 * forward-mpml and forward-spml within RMSE 1/255 and max 4/255 on the 8-bit output, and
 * the modes give the same image; forward-spml's storage buffer the uniform block's image;
 * the tiled renderers (issue 10) within the same bounds; with fog (issue 13) every one of
 * them still; forward-mpml with 64 lights on every pixel within 1/255 RMSE of forward-spml
 * in hdr: rgba32f (0.0048 RMSE in RGBA16F: extremes-camera.yaml's case). Issue 12: the
 * eight cases at msaa 4, deferred in all six modes within RMSE 1/255 (under 1 % of pixels
 * off by more than 1/255). deferred-lighting in every mode and by the tiled lists as
 * deferred, at msaa 1 and 4; with its 8-bit light buffer within 2/255 RMSE. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "common/image_io.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

enum { W = 160, H = 120 };
#define RMSE_MAX (1.0 / 255.0)
#define MAX_ABS_MAX (4.0 / 255.0)

static gl_context *ctx;
/* what every render_with uses beside its arguments (issue 13) */
static hdr_format g_hdr = HDR_RGBA16F;
static float g_fog_density = 0.0f;
static int g_msaa = 0;   /* issue 12: > 1, run_case compares msaa forward-spml and deferred */
static lpp_light_buffer_format g_lpp = LPP_LIGHT_BUFFER_RGBA16F;   /* deferred-lighting's */
static bool g_lpp_tiled = false;   /* deferred-lighting's lights by the tiled lists */
static bool g_depth_mask = false;  /* tiles.depth_culling: mask (issue 37) */
static bool g_prune = false;       /* tiles.prune: samples (issue 37) */
static int g_levels = 1;           /* tiles.levels (issue 37) */
static const char *const *g_scenes;   /* expect_catalog_agrees: these (NULL-ended), or all */
static bool g_double_sided = false;   /* build: every material double-sided */
static bool g_vertex_colors = false;  /* build: the sphere's mesh (1) coloured by its normals */
static bool g_uv2 = false;   /* build: the knot's mesh (2) a second uv set, 3 x its first,
                                which material 2's diffuse and gloss maps read */
static bool g_pbr = false;   /* build: shading.model pbr (issue 25) */
static bool g_env = false;   /* build: environment.light sky (issue 36) */
static gbuffer_preset g_gbuffer = GBUFFER_REFERENCE;   /* deferred's and tiled-deferred's */
static frame_stats g_last;            /* the last frame render_with drew */

typedef struct light_case {
    const char *name;
    sm_vec3 eye, target;
    float zfar;                /* 0: the scene's */
    uint32_t nlights;
    scene_light lights[16];
} light_case;

static scene_light point(float x, float y, float z, float radius, float r, float g, float b)
{
    scene_light l = {.type = LIGHT_POINT, .position = {x, y, z}, .color = {r, g, b},
                     .radius = radius, .attenuation = ATTENUATION_LINEAR_RANGE};
    return l;
}

static scene_light spot(float x, float y, float z, float dx, float dy, float dz, float radius,
                        float angle_deg)
{
    scene_light l = {.type = LIGHT_SPOT, .position = {x, y, z}, .direction = {dx, dy, dz},
                     .color = {1.0f, 0.9f, 0.7f}, .radius = radius,
                     .spot_angle = sm_deg2rad(angle_deg), .spot_exponent = 4.0f,
                     .attenuation = ATTENUATION_LINEAR_RANGE};
    sm_vec3_normalize(l.direction);
    return l;
}

/* The shapes scene posed at t = 0 with the case's lights and camera. */
static scene *build(const light_case *c)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build("shapes", &lp, W, H, err, sizeof err);
    if (!s) {
        print_error("scene: %s\n", err);
        return NULL;
    }
    s->lights = calloc(c->nlights ? c->nlights : 1, sizeof *s->lights);
    memcpy(s->lights, c->lights, c->nlights * sizeof *s->lights);
    s->nlights_total = c->nlights;
    s->count = (light_count){.start = c->nlights, .max = c->nlights};
    if (c->zfar > 0)
        s->zfar = c->zfar;
    for (uint32_t i = 0; i < s->nmaterials; i++)
        s->materials[i].double_sided = g_double_sided;
    if (g_uv2) {
        mesh *m = &s->meshes[2];
        m->uv2 = malloc(m->nvertices * sizeof *m->uv2);
        assert_non_null(m->uv2);
        for (uint32_t v = 0; v < m->nvertices; v++)
            for (int k = 0; k < 2; k++)
                m->uv2[v][k] = 3.0f * m->vertices[v].uv[k];
        s->materials[2].uv1_maps = 1u | 2u;
    }
    if (g_vertex_colors) {   /* RGB from the normal, alpha 1 */
        mesh *m = &s->meshes[1];
        m->colors = malloc(m->nvertices * sizeof *m->colors);
        assert_non_null(m->colors);
        for (uint32_t v = 0; v < m->nvertices; v++) {
            uint32_t rgba = 0xff000000u;
            for (int k = 0; k < 3; k++)
                rgba |= (uint32_t)lrintf(255.0f * (0.5f + 0.5f * m->vertices[v].normal[k]))
                        << (8 * k);
            m->colors[v] = rgba;
        }
    }
    if (g_pbr)
        assert_true(scene_set_shading(s, SHADING_PBR));
    if (g_env)
        scene_set_environment(s, ENVIRONMENT_SKY, 1.0f);
    scene_update(s, 0.0);
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3_copy(c->eye, s->cam.eye);
    sm_vec3_copy(c->target, s->cam.target);
    s->cam.zfar = s->zfar;
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
    return s;
}

/* Renders one frame of s with `kind` (forward-spml's lights from storage when
 * `storage`) and reads the output back. */
static bool render_with(const char *kind, light_volume_mode mode, bool storage, scene *s,
                        image *out)
{
    char err[512];
    const gl_info *gi = gl_context_info(ctx);
    renderer_options o = {
        .width = W, .height = H, .queries = true,
        .timer_query = gi->timer_query, .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size,
        .gbuffer = g_gbuffer, .light_volumes = mode,
        .light_buffer = storage ? LIGHT_BUFFER_STORAGE : LIGHT_BUFFER_UNIFORM,
        .hdr = g_hdr, .fog_density = g_fog_density, .fog_color = {0.55f, 0.6f, 0.7f},
        .msaa = g_msaa, .lpp_light_buffer = g_lpp, .lpp_tiled = g_lpp_tiled,
        .depth_mask = g_depth_mask, .prune_samples = g_prune,
        .tile_levels = g_levels,
    };
    if (strcmp(kind, "zbin deferred") == 0) {   /* issue 37: zbin.shading: deferred */
        kind = "zbin";
        o.zbin_deferred = true;
    }
    renderer *r = test_renderer_create(kind, &o, err, sizeof err);
    if (!r || !renderer_prepare(r, s, err, sizeof err)) {
        print_error("%s: %s\n", kind, err);
        renderer_destroy(r);
        return false;
    }
    frame_stats fs;
    renderer_draw(r, s, &fs);
    gl.Finish();
    renderer_collect(r, &fs);
    g_last = fs;
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

static bool render(const char *kind, light_volume_mode mode, scene *s, image *out)
{
    return render_with(kind, mode, false, s, out);
}

static void expect_agree(const char *what, const image *a, const image *b)
{
    gl_test_expect_agree(what, a, b, RMSE_MAX, MAX_ABS_MAX, g_fog_density > 0.0f);
}

/* The image must show something: lights that light nothing would agree trivially. */
static void expect_lit(const image *with, const image *without, const char *what)
{
    image_error e;
    char err[256];
    assert_true(image_compare(with, without, &e, err, sizeof err));
    if (e.frac_over_1_255 < 0.01)
        print_error("%s: the lights change only %.4f of the pixels\n", what, e.frac_over_1_255);
    assert_true(e.frac_over_1_255 >= 0.01);
}

/* Issue 12: at msaa g_msaa, deferred (reference G-buffer) in every light-volume mode
 * against forward-spml: RMSE < 1/255, fewer than 1 % of the pixels off by > 1/255 (the
 * edges, where per-sample stencil and forward's per-pixel shading may differ). */
static void run_case_msaa(const light_case *c)
{
    scene *s = build(c);
    assert_non_null(s);
    image ref = {0}, img = {0};
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &ref));
    static const light_volume_mode modes[] = {
        LIGHT_VOLUMES_STENCIL, LIGHT_VOLUMES_FULLSCREEN, LIGHT_VOLUMES_VOLUME,
        LIGHT_VOLUMES_STENCIL_TWO_PASS, LIGHT_VOLUMES_HULL, LIGHT_VOLUMES_SCISSOR};
    for (size_t m = 0; m < sizeof modes / sizeof modes[0]; m++) {
        assert_true(render("deferred", modes[m], s, &img));
        image_error e;
        char err[256];
        assert_true(image_compare(&img, &ref, &e, err, sizeof err));
        if (e.rmse >= RMSE_MAX || e.frac_over_1_255 >= 0.01)
            print_error("%s: msaa %d deferred mode %d vs forward-spml: rmse %.3f/255, "
                        "%.4f of pixels off by > 1/255\n", c->name, g_msaa, (int)modes[m],
                        e.rmse * 255, e.frac_over_1_255);
        assert_true(e.rmse < RMSE_MAX);
        assert_true(e.frac_over_1_255 < 0.01);
        assert_int_equal(e.nonfinite, 0);
        image_free(&img);
    }
    /* deferred-lighting: deferred's edge classes in its light passes, its material pass
     * per sample; the same tolerance in every mode, and (the last round, m == nmodes) by
     * the tiled lists, the dispatch's edge pixels per sample */
    const size_t nmodes = sizeof modes / sizeof modes[0];
    for (size_t m = 0; m <= nmodes; m++) {
        g_lpp_tiled = m == nmodes;
        bool ok = render("deferred-lighting", m < nmodes ? modes[m] : LIGHT_VOLUMES_STENCIL, s,
                         &img);
        g_lpp_tiled = false;
        assert_true(ok);
        image_error e;
        char err[256];
        assert_true(image_compare(&img, &ref, &e, err, sizeof err));
        print_message("%s: msaa %d deferred-lighting %s %d vs forward-spml: rmse %.3f/255, "
                      "%.4f of pixels off by > 1/255\n", c->name, g_msaa,
                      m < nmodes ? "mode" : "tiled", m < nmodes ? (int)modes[m] : 0,
                      e.rmse * 255, e.frac_over_1_255);
        assert_true(e.rmse < RMSE_MAX);
        assert_true(e.frac_over_1_255 < 0.01);
        assert_int_equal(e.nonfinite, 0);
        image_free(&img);
    }
    image_free(&ref);
    scene_destroy(s);
}

static void run_case(const light_case *c)
{
    if (g_msaa > 1) {
        run_case_msaa(c);
        return;
    }
    scene *s = build(c);
    assert_non_null(s);
    image ref = {0}, img = {0}, dark = {0};
    char what[160];
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &ref));

    /* the same view without its lights: the case really lights the scene */
    uint32_t n = s->nlights_active;
    s->nlights_active = 0;
    s->count.start = s->count.max = 0;
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &dark));
    s->nlights_active = n;
    s->count.start = s->count.max = n;
    expect_lit(&ref, &dark, c->name);
    image_free(&dark);

    /* forward-spml's two light buffers give the same image; the tiled renderers are
     * compared with the storage one (issue 10) */
    image stored = {0};
    assert_true(render_with("forward-spml", LIGHT_VOLUMES_STENCIL, true, s, &stored));
    snprintf(what, sizeof what, "%s: forward-spml storage vs uniform", c->name);
    expect_agree(what, &stored, &ref);
    static const char *const tiled[] = {"forward-plus", "clustered", "tiled-deferred",
                                        "visibility", "zbin", "zbin deferred"};
    for (size_t k = 0; k < sizeof tiled / sizeof tiled[0]; k++) {
        assert_true(render(tiled[k], LIGHT_VOLUMES_STENCIL, s, &img));
        snprintf(what, sizeof what, "%s: %s vs forward-spml (storage)", c->name, tiled[k]);
        expect_agree(what, &img, &stored);
        image_free(&img);
    }
    /* deferred-lighting by the tiled lists, which load the lights as the tiled renderers */
    g_lpp_tiled = true;
    bool tiled_ok = render("deferred-lighting", LIGHT_VOLUMES_STENCIL, s, &img);
    g_lpp_tiled = false;
    assert_true(tiled_ok);
    snprintf(what, sizeof what, "%s: deferred-lighting tiled vs forward-spml (storage)",
             c->name);
    expect_agree(what, &img, &stored);
    image_free(&img);
    image_free(&stored);

    assert_true(render("forward-mpml", LIGHT_VOLUMES_STENCIL, s, &img));
    snprintf(what, sizeof what, "%s: forward-mpml vs forward-spml", c->name);
    expect_agree(what, &img, &ref);
    image_free(&img);

    static const struct {
        light_volume_mode mode;
        const char *name;
    } modes[] = {{LIGHT_VOLUMES_STENCIL, "stencil"},
                 {LIGHT_VOLUMES_FULLSCREEN, "fullscreen"},
                 {LIGHT_VOLUMES_VOLUME, "volume"},
                 {LIGHT_VOLUMES_STENCIL_TWO_PASS, "stencil-two-pass"}};
    image first = {0};
    for (size_t m = 0; m < sizeof modes / sizeof modes[0]; m++) {
        assert_true(render("deferred", modes[m].mode, s, &img));
        snprintf(what, sizeof what, "%s: deferred (reference, %s) vs forward-spml", c->name,
                 modes[m].name);
        expect_agree(what, &img, &ref);
        if (m == 0) {
            first = img;
            img = (image){0};
            continue;
        }
        /* the light-volume modes differ in which pixels they visit, not in the image */
        image_error e;
        char err[256];
        assert_true(image_compare(&first, &img, &e, err, sizeof err));
        if (e.max_abs > 1.0 / 255.0)
            print_error("%s: deferred %s vs stencil: max %.1f/255\n", c->name, modes[m].name,
                        e.max_abs * 255);
        assert_true(e.max_abs <= 1.0 / 255.0);
        image_free(&img);
    }
    image_free(&first);

    /* deferred-lighting (the light pre-pass): its light buffer factors shade_light
     * exactly, so in every light-volume mode it agrees with forward-spml as deferred does;
     * with the 8-bit light buffer (Engel 2008) light above 1 clamps and 8 bits round:
     * within 2/255 RMSE on these cases */
    for (int m = LIGHT_VOLUMES_STENCIL; m <= (int)LIGHT_VOLUMES_SCISSOR; m++) {
        assert_true(render("deferred-lighting", (light_volume_mode)m, s, &img));
        snprintf(what, sizeof what, "%s: deferred-lighting (mode %d) vs forward-spml", c->name,
                 m);
        expect_agree(what, &img, &ref);
        image_free(&img);
    }
    for (int by_tiles = 0; by_tiles < 2; by_tiles++) {   /* by the volumes, by the lists */
        g_lpp = LPP_LIGHT_BUFFER_RGBA8;
        g_lpp_tiled = by_tiles;
        bool ok = render("deferred-lighting", LIGHT_VOLUMES_STENCIL, s, &img);
        g_lpp = LPP_LIGHT_BUFFER_RGBA16F;
        g_lpp_tiled = false;
        assert_true(ok);
        image_error e;
        char err[256];
        assert_true(image_compare(&img, &ref, &e, err, sizeof err));
        print_message("%s: deferred-lighting %s rgba8 vs forward-spml: rmse %.3f/255, max "
                      "%.1f/255\n", c->name, by_tiles ? "tiled" : "volumes", e.rmse * 255,
                      e.max_abs * 255);
        assert_int_equal(e.nonfinite, 0);
        assert_true(e.rmse < 2.0 / 255.0);
        image_free(&img);
    }
    image_free(&ref);
    scene_destroy(s);
}

/* The camera looks at the grid of objects from the side and above. */
#define EYE {0.0f, 12.0f, 28.0f}
#define TARGET {0.0f, 1.0f, 0.0f}

static void test_point(void **state)
{
    (void)state;
    light_case c = {"one point light", EYE, TARGET, 0, 1, {point(0, 6, 4, 14, 1.0f, 0.9f, 0.8f)}};
    run_case(&c);
}

static void test_spot(void **state)
{
    (void)state;
    light_case c = {"one spot light", EYE, TARGET, 0, 1, {spot(0, 10, 0, 0.2f, -1, 0.1f, 20, 30)}};
    run_case(&c);
}

static void test_directional(void **state)
{
    (void)state;
    light_case c = {"one directional light", EYE, TARGET, 0, 1, {{0}}};
    c.lights[0] = (scene_light){.type = LIGHT_DIRECTIONAL, .direction = {-0.4f, -1.0f, -0.3f},
                                .color = {0.8f, 0.8f, 0.7f}};
    sm_vec3_normalize(c.lights[0].direction);
    run_case(&c);
}

static void test_sixteen_lights(void **state)
{
    (void)state;
    light_case c = {"16 point lights", EYE, TARGET, 0, 16, {{0}}};
    for (int i = 0; i < 16; i++) {
        float x = (float)(i % 4) * 8.0f - 12.0f, z = (float)(i / 4) * 8.0f - 12.0f;
        c.lights[i] = point(x, 3.0f + (float)(i % 3), z, 7.0f, 0.2f + 0.05f * (float)(i % 5),
                            0.3f, 0.5f - 0.02f * (float)i);
    }
    run_case(&c);
}

static void test_camera_inside_point_volume(void **state)
{
    (void)state;
    light_case c = {"camera inside a point volume", EYE, TARGET, 0, 1,
                    {point(0, 11, 25, 30, 1.0f, 1.0f, 1.0f)}};
    run_case(&c);
}

static void test_camera_inside_spot_volume(void **state)
{
    (void)state;
    light_case c = {"camera inside a spot volume", EYE, TARGET, 0, 1,
                    {spot(0, 14, 32, 0, -0.5f, -1, 60, 35)}};
    run_case(&c);
}

/* glTF's doubleSided: the camera and a light inside the grid's first sphere (radius 2 at
 * (-10, 2.2, -10)), every material double-sided. Each renderer draws the inside of the
 * sphere, lit by the light with the back faces' normals turned inward, as forward-spml
 * does (run_case: every renderer and light-volume mode, msaa 1); single-sided, the inside
 * is culled and the view goes through the sphere; each pass that draws the objects turns
 * culling off and back on for each of them (deferred's G-buffer pass: two more state
 * changes a visible object, the same draws). */
static void test_double_sided(void **state)
{
    (void)state;
    light_case c = {"double-sided: inside a sphere", {-10.6f, 2.2f, -10.0f},
                    {-8.0f, 2.0f, -10.0f}, 0, 1, {point(-9.4f, 2.4f, -10.2f, 4.0f, 1.0f, 0.9f,
                                                        0.8f)}};
    g_double_sided = true;
    run_case(&c);
    scene *two = build(&c);
    g_double_sided = false;
    scene *one = build(&c);
    assert_non_null(two);
    assert_non_null(one);
    image a = {0}, b = {0};
    assert_true(render("deferred", LIGHT_VOLUMES_STENCIL, two, &a));
    const pass_stats g2 = *find_pass(&g_last, "gbuffer");
    assert_true(render("deferred", LIGHT_VOLUMES_STENCIL, one, &b));
    const pass_stats g1 = *find_pass(&g_last, "gbuffer");
    image_error e;
    char err[256];
    assert_true(image_compare(&a, &b, &e, err, sizeof err));
    print_message("double-sided vs single-sided inside the sphere: %.2f of the pixels differ "
                  "by > 1/255; G-buffer pass: %llu draws, %llu vs %llu state changes\n",
                  e.frac_over_1_255, (unsigned long long)g2.draw_calls,
                  (unsigned long long)g2.state_changes, (unsigned long long)g1.state_changes);
    assert_true(e.frac_over_1_255 > 0.5);
    assert_int_equal(g2.draw_calls, g1.draw_calls);
    assert_true(g2.draw_calls > 0);
    assert_int_equal(g2.state_changes, g1.state_changes + 2 * g2.draw_calls);
    image_free(&a);
    image_free(&b);
    scene_destroy(two);
    scene_destroy(one);
}

/* A scene feature that `flag` makes build() add: every renderer draws it as forward-spml
 * does (run_case), deferred's image with it differs from the one without on more than
 * min_frac of the pixels, and the pass plan's lighting line names it (`named`, a common
 * define compiled in only for a scene that has it). */
static void expect_feature(const light_case *c, bool *flag, double min_frac, const char *named)
{
    *flag = true;
    run_case(c);
    scene *with = build(c);
    *flag = false;
    scene *without = build(c);
    assert_non_null(with);
    assert_non_null(without);
    image a = {0}, b = {0};
    assert_true(render("deferred", LIGHT_VOLUMES_STENCIL, with, &a));
    assert_true(render("deferred", LIGHT_VOLUMES_STENCIL, without, &b));
    image_error e;
    char err[256];
    assert_true(image_compare(&a, &b, &e, err, sizeof err));
    print_message("%s: with and without, %.2f of the pixels differ by > 1/255\n", c->name,
                  e.frac_over_1_255);
    assert_true(e.frac_over_1_255 > min_frac);
    const gl_info *gi = gl_context_info(ctx);
    renderer_options o = {.width = W, .height = H, .gbuffer = GBUFFER_REFERENCE,
                          .light_volumes = LIGHT_VOLUMES_STENCIL, .hdr = HDR_RGBA16F,
                          .max_uniform_block_size = gi->max_uniform_block_size};
    renderer *r = test_renderer_create("forward-spml", &o, err, sizeof err);
    assert_non_null(r);
    assert_true(renderer_prepare(r, with, err, sizeof err));
    pass_plan p;
    renderer_describe(r, &p);
    print_message("plan: lighting %s\n", p.lighting);
    assert_non_null(strstr(p.lighting, named));
    renderer_destroy(r);
    image_free(&a);
    image_free(&b);
    scene_destroy(with);
    scene_destroy(without);
}

/* glTF's COLOR_0: the grid's first sphere coloured by its normals (mesh.colors), seen
 * and lit from the side: every renderer multiplies its diffuse colour by the interpolated
 * vertex colour (visibility interpolates it from its copy of the vertices); the sphere
 * covers about 15 % of the view; VERTEX_COLOR. */
static void test_vertex_colors(void **state)
{
    (void)state;
    light_case c = {"vertex colours", {-10.0f, 4.0f, -3.0f}, {-10.0f, 2.2f, -10.0f}, 0, 2,
                    {point(-7.0f, 5.0f, -6.0f, 12.0f, 1.0f, 1.0f, 1.0f),
                     point(-13.0f, 3.0f, -7.0f, 10.0f, 0.8f, 0.8f, 0.9f)}};
    expect_feature(&c, &g_vertex_colors, 0.1, ", vertex colours;");
}

/* glTF's texCoord 1: the grid's knot (material 2: checker diffuse and gloss maps) with a
 * second uv set three times its first, which both maps read: every renderer samples the
 * maps there (visibility with its own derivatives of the second set); UV2. */
static void test_second_uv_set(void **state)
{
    (void)state;
    light_case c = {"second uv set", {0.0f, 4.5f, -5.0f}, {0.0f, 2.2f, -10.0f}, 0, 2,
                    {point(3.0f, 6.0f, -6.0f, 14.0f, 1.0f, 1.0f, 1.0f),
                     point(-3.0f, 4.0f, -6.0f, 12.0f, 0.8f, 0.8f, 0.9f)}};
    expect_feature(&c, &g_uv2, 0.05, ", a second uv set;");
}

static bool catalog_scene_chosen(const char *name)
{
    for (size_t i = 0; g_scenes && g_scenes[i]; i++)
        if (strcmp(g_scenes[i], name) == 0)
            return true;
    return !g_scenes;
}

/* Every catalog scene (g_scenes: those) but the test-* faults at 1 s, its authored lights or 16 random ones
 * of colour up to color_max, shaded by `model`: each of `kinds` ("deferred-lighting
 * tiled": by the tiled lists) against forward-spml (storage), within RMSE 1/255, fewer
 * than 1 % of the pixels off by more than 1/255, nothing non-finite. */
static void expect_catalog_agrees(const char *const *kinds, size_t nkinds, shading_model model,
                                  float color_max)
{
    for (size_t i = 0; i < scene_catalog_count(); i++) {
        const char *name = scene_catalog_at(i)->name;
        if (strncmp(name, "test-", 5) == 0 || !catalog_scene_chosen(name))
            continue;
        bool authored = strcmp(name, "spot-coverage") == 0 ||
                        strcmp(name, "two-spots-overlap") == 0 ||
                        strcmp(name, "floating-spot") == 0 || strcmp(name, "glass") == 0;
        light_params lp = {.placement = authored ? PLACEMENT_SCENE : PLACEMENT_RANDOM,
                           .seed = 1337, .rng = RNG_MSVC,
                           .count = {.start = 16, .max = 16}, .radius = 10.0f,
                           .overlap = 2.0f, .color_max = color_max,
                           .attenuation = ATTENUATION_LINEAR_RANGE};
        char err[256];
        scene *s = scene_build(name, &lp, W, H, err, sizeof err);
        if (!s)
            fail_msg("scene %s: %s", name, err);
        assert_true(scene_set_shading(s, model));
        scene_update(s, 1.0);
        image ref = {0}, img = {0};
        assert_true(render_with("forward-spml", LIGHT_VOLUMES_STENCIL, true, s, &ref));
        for (size_t k = 0; k < nkinds; k++) {
            g_lpp_tiled = strcmp(kinds[k], "deferred-lighting tiled") == 0;
            bool ok = render(g_lpp_tiled ? "deferred-lighting" : kinds[k],
                             LIGHT_VOLUMES_STENCIL, s, &img);
            g_lpp_tiled = false;
            assert_true(ok);
            image_error e;
            assert_true(image_compare(&img, &ref, &e, err, sizeof err));
            print_message("%s%s: %s vs forward-spml (storage): rmse %.3f/255, max %.0f/255, "
                          "%.5f of the pixels off by > 1/255\n",
                          model == SHADING_PBR ? "pbr " : "", name, kinds[k], e.rmse * 255,
                          e.max_abs * 255, e.frac_over_1_255);
            assert_true(e.rmse < RMSE_MAX);
            assert_true(e.frac_over_1_255 < 0.01);
            assert_int_equal(e.nonfinite, 0);
            image_free(&img);
        }
        image_free(&ref);
        scene_destroy(s);
    }
}

/* Issue 26: every scene of the catalog (but the test-* faults) at 1 s of its own camera,
 * with its authored lights (the spot scenes, glass) or 16 random ones (seed 1337,
 * overlap 2): deferred-lighting by the light volumes and by the tiled lists, and
 * visibility, agree with forward-spml (storage) within RMSE 1/255, fewer than 1 % of the
 * pixels off by more than 1/255 and no value that is not finite. Not the max error: at a
 * spot's hard cone edge a position rebuilt from depth (deferred-lighting's, as deferred's)
 * can put a grazing pixel on the other side (two-spots-overlap: 46/255 on one pixel of
 * 19,200 for deferred, 40/255 for deferred-lighting). */
static void test_every_catalog_scene(void **state)
{
    (void)state;
    static const char *const kinds[] = {"deferred-lighting", "deferred-lighting tiled",
                                        "visibility", "zbin", "zbin deferred"};
    expect_catalog_agrees(kinds, 5, SHADING_PHONG, 0.3f);
}

/* Issue 25: under the metallic-roughness model (shading.model pbr), every renderer
 * agrees with forward-spml as under Phong: the hand-placed cases in every design (their
 * G-buffer the lossless reference), and every catalog scene (as above: its authored
 * lights or 16 random ones) in every renderer, deferred and tiled-deferred with the
 * default curtis G-buffer (metallic and roughness in its gloss and shininess channels),
 * within RMSE 1/255, fewer than 1 % of the pixels off by more than 1/255 and nothing
 * non-finite. */
static void test_pbr(void **state)
{
    g_pbr = true;
    test_point(state);
    test_spot(state);
    test_directional(state);
    test_sixteen_lights(state);
    test_camera_inside_spot_volume(state);
    g_pbr = false;
}

static void test_pbr_every_catalog_scene(void **state)
{
    (void)state;
    static const char *const kinds[] = {"forward-mpml", "forward-plus", "clustered",
                                        "deferred", "tiled-deferred", "deferred-lighting",
                                        "deferred-lighting tiled", "visibility", "zbin",
                                        "zbin deferred"};
    g_gbuffer = GBUFFER_CURTIS;
    expect_catalog_agrees(kinds, sizeof kinds / sizeof kinds[0], SHADING_PBR, 0.6f);
    g_gbuffer = GBUFFER_REFERENCE;
}

/* Issue 36: with the environment light (the sky in every renderer's ambient term and as
 * the sky), every renderer agrees with forward-spml as without it, under both shading
 * models: the point and spot cases in every design (deferred with the reference
 * G-buffer, then under pbr with the default curtis one, whose 8-bit normals the
 * environment's reflections read), RMSE < 1/255 and max 4/255. */
static void test_environment(void **state)
{
    g_env = true;
    for (int pbr = 0; pbr < 2; pbr++) {
        g_pbr = pbr;
        test_point(state);
        test_spot(state);
    }
    g_gbuffer = GBUFFER_CURTIS;
    test_point(state);
    g_gbuffer = GBUFFER_REFERENCE;
    g_pbr = g_env = false;
}

/* The eye is outside the light's sphere but inside the volume drawn for it (the
 * sphere scaled by 1.1), so the near plane cuts the volume; the light reaches the
 * floor in front of the camera. */
static void test_volume_cut_by_near_plane(void **state)
{
    (void)state;
    light_case c = {"volume cut by the near plane", {0.0f, 3.0f, 12.0f}, {0.0f, 0.0f, 0.0f}, 0,
                    1, {point(0, 1.0f, 9.6f, 3.0f, 1.0f, 0.8f, 0.6f)}};
    /* eye to light: sqrt(2^2 + 2.4^2) = 3.12, between the radius 3 and 3.3; the
     * floor (y = 0) is lit from z = 6.8 to 12.4 and seen up to z = 8.9 */
    run_case(&c);
}

/* A far plane at 30: the light's volume reaches beyond it, objects near it are lit. */
static void test_volume_cut_by_far_plane(void **state)
{
    (void)state;
    light_case c = {"volume cut by the far plane", EYE, TARGET, 30.0f, 1,
                    {point(0, 4, -6, 16, 1.0f, 1.0f, 0.9f)}};
    run_case(&c);
}

/* Fog on (seed 000 4.5.12): the same cases agree, forward's fog in the shaders
 * (forward-mpml's light passes scaled by the factor, the base pass adding the colour)
 * and deferred's in a pass of its own from depth. */
static void test_fog(void **state)
{
    (void)state;
    g_fog_density = 0.03f;
    light_case c = {"fog, 16 point lights", EYE, TARGET, 0, 16, {{0}}};
    for (int i = 0; i < 16; i++) {
        float x = (float)(i % 4) * 8.0f - 12.0f, z = (float)(i / 4) * 8.0f - 12.0f;
        c.lights[i] = point(x, 3.0f + (float)(i % 3), z, 7.0f, 0.2f + 0.05f * (float)(i % 5),
                            0.3f, 0.5f - 0.02f * (float)i);
    }
    run_case(&c);
    light_case d = {"fog, a spot and a directional light", EYE, TARGET, 0, 2,
                    {spot(0, 10, 0, 0.2f, -1, 0.1f, 20, 30), {0}}};
    d.lights[1] = (scene_light){.type = LIGHT_DIRECTIONAL, .direction = {-0.4f, -1.0f, -0.3f},
                                .color = {0.5f, 0.5f, 0.45f}};
    sm_vec3_normalize(d.lights[1].direction);
    run_case(&d);
    g_fog_density = 0.0f;
}

/* 64 lights of radius 1e5 placed as extremes-camera.yaml places them (MSVC rand seeded
 * 1337, colour at most 0.3, linear-range): every light reaches every pixel, and
 * forward-mpml adds 64 passes into its target. In RGBA16F each blend rounds to 11
 * significant bits (0.0048 RMSE against forward-spml on that manifest); in RGBA32F the
 * sum is forward-spml's within 1/255. */
static double mpml_rmse(hdr_format hdr, scene *s)
{
    image ref = {0}, img = {0};
    g_hdr = hdr;
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &ref));
    assert_true(render("forward-mpml", LIGHT_VOLUMES_STENCIL, s, &img));
    g_hdr = HDR_RGBA16F;
    image_error e;
    char err[256];
    assert_true(image_compare(&img, &ref, &e, err, sizeof err));
    assert_int_equal(e.nonfinite, 0);
    image_free(&ref);
    image_free(&img);
    return e.rmse;
}

static void test_rgba32f_many_overlapping_lights(void **state)
{
    (void)state;
    char err[256];
    light_params lp = {.placement = PLACEMENT_RANDOM, .seed = 1337, .rng = RNG_MSVC,
                       .count = {.start = 64, .max = 64}, .radius = 1e5f, .color_max = 0.3f,
                       .attenuation = ATTENUATION_LINEAR_RANGE};
    scene *s = scene_build("shapes", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("scene: %s", err);
    scene_update(s, 0.0);
    double r16 = mpml_rmse(HDR_RGBA16F, s), r32 = mpml_rmse(HDR_RGBA32F, s);
    print_message("forward-mpml vs forward-spml, 64 lights of radius 1e5: RMSE %.4f (%.2f/255) "
                  "in rgba16f, %.2e (%.3f/255) in rgba32f\n", r16, r16 * 255, r32, r32 * 255);
    assert_true(r32 < RMSE_MAX);
    assert_true(r32 < r16);
    scene_destroy(s);
}

/* Issue 37: with tiles.depth_culling: mask (Harada's 2.5D culling), forward-plus,
 * clustered, tiled-deferred and zbin (both shadings) on every catalog scene (as
 * test_every_catalog_scene) at msaa 1, and they, deferred-lighting by the tiled lists and
 * visibility at msaa 4 (where the shading's fallback reads the tile's cells) on shapes,
 * curtis-scene3, canyon and interior (since the edge rule compares materials:
 * test_msaa4_materials), then zbin with minmax there at msaa 4 (at msaa 1 it is in
 * test_every_catalog_scene), against forward-spml within RMSE 1/255, fewer than 1 % of
 * the pixels off by more than 1/255. */
static void test_depth_mask(void **state)
{
    (void)state;
    static const char *const kinds[] = {"forward-plus", "clustered", "tiled-deferred",
                                        "zbin", "zbin deferred", "deferred-lighting tiled",
                                        "visibility"};
    g_depth_mask = true;
    expect_catalog_agrees(kinds, 5, SHADING_PHONG, 0.3f);
    static const char *const some[] = {"shapes", "curtis-scene3", "canyon", "interior", NULL};
    g_scenes = some;
    g_msaa = 4;
    expect_catalog_agrees(kinds, 7, SHADING_PHONG, 0.3f);
    g_depth_mask = false;   /* and zbin with minmax at msaa 4 */
    expect_catalog_agrees(kinds + 3, 2, SHADING_PHONG, 0.3f);
    g_msaa = 0;
    g_scenes = NULL;
    g_depth_mask = false;
}

/* Issue 37: tiles.prune: samples (HDRP's fine pruning; at msaa 4 each pixel's box over
 * its samples) on the same kinds, at msaa 1 and 4 on shapes, curtis-scene3 and canyon,
 * against forward-spml within RMSE 1/255 as test_depth_mask's. */
static void test_prune_samples(void **state)
{
    (void)state;
    static const char *const kinds[] = {"forward-plus", "clustered", "tiled-deferred",
                                        "deferred-lighting tiled", "visibility"};
    static const char *const some[] = {"shapes", "curtis-scene3", "canyon", NULL};
    g_prune = true;
    g_scenes = some;
    expect_catalog_agrees(kinds, 3, SHADING_PHONG, 0.3f);
    g_msaa = 4;
    expect_catalog_agrees(kinds, 5, SHADING_PHONG, 0.3f);
    g_msaa = 0;
    g_scenes = NULL;
    g_prune = false;
}

/* Issue 37: tiles.levels: 2 (the big tiles culled first) on forward-plus, clustered,
 * tiled-deferred and deferred-lighting by the tiled lists (visibility stays one level),
 * at msaa 1 on shapes (gl-tiled holds its images to level 1's byte for byte) and at
 * msaa 4 on shapes, curtis-scene3 and canyon, against forward-spml within RMSE 1/255. */
static void test_two_levels(void **state)
{
    (void)state;
    static const char *const kinds[] = {"forward-plus", "clustered", "tiled-deferred",
                                        "deferred-lighting tiled"};
    static const char *const shapes[] = {"shapes", NULL};
    static const char *const some[] = {"shapes", "curtis-scene3", "canyon", NULL};
    g_levels = 2;
    g_scenes = shapes;
    expect_catalog_agrees(kinds, 4, SHADING_PHONG, 0.3f);
    g_scenes = some;
    g_msaa = 4;
    expect_catalog_agrees(kinds, 4, SHADING_PHONG, 0.3f);
    g_msaa = 0;
    g_scenes = NULL;
    g_levels = 1;
}

/* Issue 12: the cases above at msaa 4, forward-spml against deferred in every mode. */
static void test_msaa4(void **state)
{
    g_msaa = 4;
    test_point(state);
    test_spot(state);
    test_directional(state);
    test_sixteen_lights(state);
    test_camera_inside_point_volume(state);
    test_camera_inside_spot_volume(state);
    test_volume_cut_by_near_plane(state);
    test_volume_cut_by_far_plane(state);
    g_msaa = 0;
}

/* The MSAA edge rule compares materials (edge_rule.inc): on interior at msaa 4 the
 * generators' glowing caps meet their bodies and each other on planes the geometric rule
 * takes for one surface, and sample 0's material lit the whole pixel: deferred and
 * tiled-deferred were 1.7/255 RMSE off forward-spml there (83/255 at most), visibility
 * 1.8/255; now within 1/255 as everywhere, fewer than 1 % of the pixels off by more. */
static void test_msaa4_materials(void **state)
{
    (void)state;
    static const char *const kinds[] = {"deferred", "tiled-deferred", "visibility"};
    static const char *const interior[] = {"interior", NULL};
    g_scenes = interior;
    g_msaa = 4;
    expect_catalog_agrees(kinds, 3, SHADING_PHONG, 0.3f);
    g_msaa = 0;
    g_scenes = NULL;
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

/* `test_gl_agreement pbr` (meson's gl-agreement_pbr) runs the metallic-roughness cases,
 * `test_gl_agreement environment` (gl-agreement_environment) the environment's,
 * `test_gl_agreement mask` (gl-agreement_mask) tiles.depth_culling: mask's,
 * `test_gl_agreement culling` (gl-agreement_culling) tiles.prune: samples' and
 * tiles.levels: 2's, the
 * plain call the others: tests of meson's, each well inside its timeout under the
 * sanitizers, and run side by side. */
int main(int argc, char **argv)
{
    GL_TEST_SKIP_WITHOUT_EGL();
    const struct CMUnitTest phong[] = {
        cmocka_unit_test(test_point),
        cmocka_unit_test(test_spot),
        cmocka_unit_test(test_directional),
        cmocka_unit_test(test_sixteen_lights),
        cmocka_unit_test(test_camera_inside_point_volume),
        cmocka_unit_test(test_camera_inside_spot_volume),
        cmocka_unit_test(test_volume_cut_by_near_plane),
        cmocka_unit_test(test_volume_cut_by_far_plane),
        cmocka_unit_test(test_double_sided),
        cmocka_unit_test(test_vertex_colors),
        cmocka_unit_test(test_second_uv_set),
        cmocka_unit_test(test_every_catalog_scene),
        cmocka_unit_test(test_fog),
        cmocka_unit_test(test_rgba32f_many_overlapping_lights),
        cmocka_unit_test(test_msaa4),
        cmocka_unit_test(test_msaa4_materials),
    };
    const struct CMUnitTest pbr[] = {
        cmocka_unit_test(test_pbr),
        cmocka_unit_test(test_pbr_every_catalog_scene),
    };
    const struct CMUnitTest environment[] = {
        cmocka_unit_test(test_environment),
    };
    const struct CMUnitTest mask[] = {
        cmocka_unit_test(test_depth_mask),
    };
    const struct CMUnitTest culling[] = {
        cmocka_unit_test(test_prune_samples),
        cmocka_unit_test(test_two_levels),
    };
    if (argc > 1 && strcmp(argv[1], "pbr") == 0)
        return cmocka_run_group_tests(pbr, setup, teardown);
    if (argc > 1 && strcmp(argv[1], "environment") == 0)
        return cmocka_run_group_tests(environment, setup, teardown);
    if (argc > 1 && strcmp(argv[1], "mask") == 0)
        return cmocka_run_group_tests(mask, setup, teardown);
    if (argc > 1 && strcmp(argv[1], "culling") == 0)
        return cmocka_run_group_tests(culling, setup, teardown);
    return cmocka_run_group_tests(phong, setup, teardown);
}
