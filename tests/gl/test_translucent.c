/* The translucent pass (issue 12, renderers/frame/translucent.h), on small images: every
 * renderer against forward-spml on the catalog scene `glass` (fog too) with exact counts
 * of the pass's draws; a pane lit through or beside light volumes (deferred's stencil
 * and volume modes); the tiled renderers' translucent light lists (near plane to a
 * tile's max opaque depth: which lights they keep, their overflow of the shared index
 * budget); a shadowing spot (the SHADOWS variant); back-to-front order where two panes
 * overlap, from both sides; and a scene without translucency, where the pass, its
 * program and the tiled lists are planned as skipped and never built. Each test's
 * comment gives its tolerance. Every frame runs in a debug context; any GL error fails
 * the test. */
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

enum { W = 128, H = 96 };
#define RMSE_MAX (1.0 / 255.0)
#define MAX_ABS_MAX (4.0 / 255.0)

static gl_context *ctx;
static float g_fog_density;   /* what every render uses */
static int g_max_lights_per_tile;

static const uint8_t *px(const image *im)
{
    return im->pixels;
}

#define DL_TILED "deferred-lighting tiled"
static const char *const kinds[] = {"forward-spml", "forward-mpml",   "forward-plus",
                                    "clustered",    "deferred",       "tiled-deferred",
                                    "deferred-lighting", "visibility"};

static scene *build_glass(light_placement p)
{
    char err[256];
    light_params lp = {.placement = p, .count = {.start = 12, .max = 12}, .radius = 1.0f};
    scene *s = scene_build("glass", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("scene: %s", err);
    scene_update(s, 0.0);
    return s;
}

static void look(scene *s, float ex, float ey, float ez, float tx, float ty, float tz)
{
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3_make(ex, ey, ez, s->cam.eye);
    sm_vec3_make(tx, ty, tz, s->cam.target);
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
}

/* One frame of s with `kind`; the output read back into out (NULL: not read), the
 * frame's stats into fs and the plan into plan (either may be NULL). */
static bool render(const char *kind, light_volume_mode mode, scene *s, image *out,
                   frame_stats *fs_out, pass_plan *plan)
{
    char err[512];
    const gl_info *gi = gl_context_info(ctx);
    renderer_options o = {
        .width = W, .height = H, .queries = true,
        .timer_query = gi->timer_query, .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size,
        .gbuffer = GBUFFER_REFERENCE, .light_volumes = mode,
        .fog_density = g_fog_density, .fog_color = {0.55f, 0.6f, 0.7f},
        .max_lights_per_tile = g_max_lights_per_tile,
    };
    /* "deferred-lighting tiled": its lights by the tiled lists (deferred_lighting.lights) */
    if (strcmp(kind, DL_TILED) == 0) {
        o.lpp_tiled = true;
        kind = "deferred-lighting";
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
    if (fs_out)
        *fs_out = fs;
    if (plan)
        renderer_describe(r, plan);
    bool ok = true;
    if (out) {
        out->width = W;
        out->height = H;
        out->channels = 4;
        out->type = IMAGE_U8;
        out->pixels = malloc((size_t)W * H * 4);
        ok = gl_context_read_rgba8(ctx, out->pixels, err, sizeof err);
    }
    renderer_destroy(r);
    gl_context_poll_errors(ctx, kind);
    return ok && gl_context_error_count(ctx) == 0;
}

static void expect_agree(const char *what, const image *a, const image *b)
{
    gl_test_expect_agree(what, a, b, RMSE_MAX, MAX_ABS_MAX, true);
}

/* The translucent objects whose bounding sphere is in the frustum of s's pose. */
static uint64_t visible_translucent(const scene *s)
{
    sm_vec4 planes[6];
    sm_frustum_planes(s->viewproj, planes);
    uint64_t n = 0;
    for (uint32_t i = 0; i < s->nobjects; i++)
        if (scene_material_translucent(&s->materials[s->objects[i].material]) &&
            sm_sphere_in_frustum(planes, s->objects[i].bsphere))
            n++;
    return n;
}

static void expect_translucent_pass(const char *kind, const scene *s, const frame_stats *fs)
{
    const pass_stats *p = find_pass(fs, "translucent");
    assert_non_null(p);
    uint64_t want = visible_translucent(s);
    print_message("%s: %llu translucent draws\n", kind, (unsigned long long)p->draw_calls);
    if (p->draw_calls != want)
        print_error("%s: %llu translucent draws, %llu visible\n", kind,
                    (unsigned long long)p->draw_calls, (unsigned long long)want);
    assert_true(p->draw_calls == want);
    assert_true(p->samples > 0.0 || isnan(p->samples));
    /* it comes after the sky and right before the resolve */
    assert_string_equal(fs->pass[fs->npasses - 1].name, "resolve");
    assert_string_equal(fs->pass[fs->npasses - 2].name, "translucent");
    assert_string_equal(fs->pass[fs->npasses - 3].name, "sky");
}

static bool tiled_kind(const char *kind)
{
    return strcmp(kind, "forward-plus") == 0 || strcmp(kind, "clustered") == 0 ||
           strcmp(kind, "tiled-deferred") == 0 || strcmp(kind, "visibility") == 0;
}

/* The translucent lists of a tiled renderer's frame of a scene with translucency: one
 * per tile, built in the one cull (or tiled) dispatch, planned, and their pass's
 * programs the tiled ones. */
static void expect_translucent_lists(const char *kind, const frame_stats *fs,
                                     const pass_plan *plan)
{
    enum { TILES = ((W + 15) / 16) * ((H + 15) / 16) };
    print_message("%s: %u translucent lists, mean %.3f, max %.0f; opaque mean %.3f, max %.0f; "
                  "%u visible lights\n", kind, fs->translucent_lists,
                  fs->translucent_lights_mean, fs->translucent_lights_max,
                  fs->grid_lights_mean, fs->grid_lights_max, fs->lights_drawn);
    assert_int_equal(fs->translucent_lists, TILES);
    /* the one cull dispatch (visibility's shading dispatches apart) */
    if (strcmp(kind, "visibility") != 0)
        assert_int_equal(fs->total.dispatches, 1);
    bool deferred_tiled = strcmp(kind, "tiled-deferred") == 0 || strcmp(kind, DL_TILED) == 0;
    const pass_stats *cull = find_pass(fs, deferred_tiled ? "tiled" : "cull");
    assert_non_null(cull);
    assert_int_equal(cull->dispatches, 1);
    assert_int_equal(fs->overflow[0], '\0');
    assert_true(fs->translucent_lights_max >= fs->grid_lights_max);
    assert_true(fs->translucent_lights_max <= (double)fs->lights_drawn);
    if (strcmp(kind, "clustered") != 0)   /* per tile, a superset of the opaque list */
        assert_true(fs->translucent_lights_mean >= fs->grid_lights_mean);
    const pass_plan_entry *e = plan_pass(plan, "translucent-lists");
    assert_non_null(e);
    assert_true(e->run);
    bool tiled = false;
    for (size_t i = 0; i < plan->nprograms; i++)
        tiled |= strncmp(plan->program[i], "translucent_tiled", 17) == 0;
    assert_true(tiled);
}

/* On `glass` (its 12 authored point lights) every renderer agrees with forward-spml
 * within RMSE 1/255 (max 4/255) on the 8-bit output, and each one's `translucent` pass
 * draws exactly the translucent objects whose bounding sphere is in the frustum (counted
 * here independently; forward-spml at a pose among the particles too, where some are
 * culled), after the sky and before the resolve; with fog on (density 0.05) deferred
 * agrees too. The tiled renderers (visibility's and deferred-lighting's tiled lists too):
 * one translucent list a tile, the cull still 1 dispatch, the longest list no shorter
 * than the longest opaque one and no longer than the visible lights (forward-plus and
 * tiled-deferred, whose per-tile lists they contain: the mean no smaller). */
static void test_glass_agreement(void **state)
{
    (void)state;
    scene *s = build_glass(PLACEMENT_SCENE);
    /* t = 11: forward-spml's draw count only (a second pose, other particles culled) */
    scene_update(s, 11.0);
    look(s, 3.0f, 1.8f, 3.0f, -2.0f, 1.5f, -2.0f);   /* among the particles */
    assert_true(visible_translucent(s) > 0 && visible_translucent(s) < 28);
    frame_stats f11;
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, NULL, &f11, NULL));
    expect_translucent_pass("forward-spml", s, &f11);
    static const double times[] = {0.0};
    for (size_t t = 0; t < sizeof times / sizeof times[0]; t++) {
        scene_update(s, times[t]);
        assert_true(visible_translucent(s) >= 4);
        image ref = {0}, img = {0};
        frame_stats fs;
        assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &ref, &fs, NULL));
        expect_translucent_pass("forward-spml", s, &fs);
        for (size_t k = 1; k < sizeof kinds / sizeof kinds[0]; k++) {
            pass_plan plan;
            assert_true(render(kinds[k], LIGHT_VOLUMES_STENCIL, s, &img, &fs, &plan));
            expect_translucent_pass(kinds[k], s, &fs);
            if (tiled_kind(kinds[k]))
                expect_translucent_lists(kinds[k], &fs, &plan);
            char what[96];
            snprintf(what, sizeof what, "glass t = %g: %s vs forward-spml", times[t], kinds[k]);
            expect_agree(what, &img, &ref);
            image_free(&img);
        }
        image_free(&ref);
    }
    /* fog on: the FOG variant of the pass, after deferred's fog pass */
    g_fog_density = 0.05f;
    image ref = {0}, img = {0};
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &ref, NULL, NULL));
    assert_true(render("deferred", LIGHT_VOLUMES_STENCIL, s, &img, NULL, NULL));
    expect_agree("glass, fog 0.05: deferred vs forward-spml", &img, &ref);
    image_free(&img);
    image_free(&ref);
    g_fog_density = 0.0f;
    scene_destroy(s);
}

/* Pane 0 (x = 2.25, its front face at x = 2.3, facing +x) seen from +x; light B's
 * volume (radius 1.8, drawn at 1.98) lies wholly behind the pane and lights the floor
 * there, seen through the pane; light A, 1 in front of the pane, lights the pane.
 * forward-spml and deferred (stencil and volume modes) light it the same: the image
 * within RMSE 1/255, the pane's centre pixel within 1/255. */
static void test_pane_in_front_of_light_volume(void **state)
{
    (void)state;
    scene *s = build_glass(PLACEMENT_NONE);
    static const scene_light a = {.type = LIGHT_POINT, .position = {3.3f, 1.5f, -2.7f},
                                  .color = {1.0f, 0.9f, 0.8f}, .radius = 1.5f,
                                  .attenuation = ATTENUATION_LINEAR_RANGE};
    static const scene_light b = {.type = LIGHT_POINT, .position = {0.0f, 0.8f, -2.7f},
                                  .color = {0.8f, 0.9f, 1.0f}, .radius = 1.8f,
                                  .attenuation = ATTENUATION_LINEAR_RANGE};
    s->lights = calloc(2, sizeof *s->lights);
    s->lights[0] = a;
    s->lights[1] = b;
    s->nlights_total = 2;
    s->count = (light_count){.start = 2, .max = 2};
    s->nobjects = 3;   /* floor, pillar, pane 0 */
    scene_update(s, 0.0);
    look(s, 9.0f, 2.0f, -2.7f, 0.0f, 1.5f, -2.7f);
    image ref = {0}, img = {0}, dark = {0};
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &ref, NULL, NULL));
    /* the light makes a difference on the pane: the centre pixel is on it */
    s->nlights_active = 0;
    s->count = (light_count){.start = 0, .max = 0};
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &dark, NULL, NULL));
    s->count = (light_count){.start = 2, .max = 2};
    s->nlights_active = 2;
    size_t c = ((size_t)(H / 2) * W + W / 2) * 4;
    int diff = 0;
    for (int k = 0; k < 3; k++)
        diff += abs((int)px(&ref)[c + k] - (int)px(&dark)[c + k]);
    assert_true(diff > 15);
    image_free(&dark);
    static const light_volume_mode modes[] = {LIGHT_VOLUMES_STENCIL, LIGHT_VOLUMES_VOLUME};
    for (size_t m = 0; m < sizeof modes / sizeof modes[0]; m++) {
        assert_true(render("deferred", modes[m], s, &img, NULL, NULL));
        char what[96];
        snprintf(what, sizeof what, "pane before a light volume: deferred (%s)",
                 m ? "volume" : "stencil");
        expect_agree(what, &img, &ref);
        int d = 0;
        for (int k = 0; k < 3; k++)
            d = abs((int)px(&img)[c + k] - (int)px(&ref)[c + k]) > d
                    ? abs((int)px(&img)[c + k] - (int)px(&ref)[c + k])
                    : d;
        assert_true(d <= 1);   /* the pane's own pixel */
        image_free(&img);
    }
    image_free(&ref);
    scene_destroy(s);
}

/* The glass scene's floor turned into a wall facing +x (its box's 0.5 half-height along
 * x), front face at x = front, its edge at z = edge (the wall spans z from there to
 * edge + 24 when edge is finite; else it is centred on z = -2.7); the pillar moved
 * behind it, out of sight; objects: wall, pillar, pane 0. */
static void make_wall(scene *s, float front, float edge)
{
    sm_vec3 axis = {0.0f, 0.0f, 1.0f};
    sm_mat4_rotate_make(SM_PI / 2.0f, axis, s->objects[0].transform);
    sm_vec3_make(front - 0.5f, 1.5f, isfinite(edge) ? edge + 12.0f : -2.7f,
                 s->objects[0].position);
    sm_vec3_make(-30.0f, 0.0f, -2.7f, s->objects[1].position);
    s->nobjects = 3;
}

static void set_lights(scene *s, const scene_light *l, uint32_t n)
{
    free(s->lights);
    s->lights = calloc(n, sizeof *s->lights);
    memcpy(s->lights, l, n * sizeof *l);
    s->nlights_total = n;
    s->count = (light_count){.start = n, .max = n};
}

/* Pane 0 (front face x = 2.3, view depth 6.7 from x = 9) before a wall filling the view
 * (front face x = -0.5, depth 9.5 in every pixel); light F (depth 5, range 2) lights the
 * pane and not the wall: wholly in front of every tile's min depth, in no opaque list;
 * W (depth 8.5, range 3) lights both: in both lists; B (depth 12, range 2) is behind the
 * wall: in neither (the translucent lists end at the tile's max depth). So exactly 2
 * lights in the longest translucent list, 1 in the longest opaque one, 3 visible, and the
 * pane lit as forward-spml lights it (F changes it). */
static void test_light_before_the_wall(void **state)
{
    (void)state;
    scene *s = build_glass(PLACEMENT_NONE);
    make_wall(s, -0.5f, NAN);
    static const scene_light l[3] = {
        {.type = LIGHT_POINT, .position = {4.0f, 1.5f, -2.7f}, .color = {1.0f, 0.9f, 0.8f},
         .radius = 2.0f, .attenuation = ATTENUATION_LINEAR_RANGE},
        {.type = LIGHT_POINT, .position = {0.5f, 1.5f, -2.7f}, .color = {0.5f, 0.6f, 0.9f},
         .radius = 3.0f, .attenuation = ATTENUATION_LINEAR_RANGE},
        {.type = LIGHT_POINT, .position = {-3.0f, 1.5f, -2.7f}, .color = {0.9f, 0.9f, 0.3f},
         .radius = 2.0f, .attenuation = ATTENUATION_LINEAR_RANGE},
    };
    set_lights(s, l, 3);
    scene_update(s, 0.0);
    look(s, 9.0f, 2.0f, -2.7f, 0.0f, 1.5f, -2.7f);
    image ref = {0}, img = {0}, dark = {0};
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &ref, NULL, NULL));
    size_t c = ((size_t)(H / 2) * W + W / 2) * 4;
    /* F makes a difference on the pane (the centre pixel) */
    set_lights(s, l + 1, 2);
    scene_update(s, 0.0);   /* the orbit camera again: */
    look(s, 9.0f, 2.0f, -2.7f, 0.0f, 1.5f, -2.7f);
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &dark, NULL, NULL));
    int diff = 0;
    for (int k = 0; k < 3; k++)
        diff += abs((int)px(&ref)[c + k] - (int)px(&dark)[c + k]);
    print_message("light before the wall: the pane's pixel changes by %d/255 with it\n", diff);
    assert_true(diff > 15);
    image_free(&dark);
    set_lights(s, l, 3);
    scene_update(s, 0.0);
    look(s, 9.0f, 2.0f, -2.7f, 0.0f, 1.5f, -2.7f);
    static const char *const tiled[] = {"forward-plus", "clustered", "tiled-deferred",
                                        "visibility", DL_TILED};
    for (size_t k = 0; k < 5; k++) {
        frame_stats fs;
        pass_plan plan;
        assert_true(render(tiled[k], LIGHT_VOLUMES_STENCIL, s, &img, &fs, &plan));
        expect_translucent_lists(tiled[k], &fs, &plan);
        assert_int_equal(fs.lights_drawn, 3);
        assert_true(fs.grid_lights_max == 1.0);          /* W alone */
        assert_true(fs.translucent_lights_max == 2.0);   /* F and W, not B */
        char what[96];
        snprintf(what, sizeof what, "light before the wall: %s vs forward-spml", tiled[k]);
        expect_agree(what, &img, &ref);
        int d = 0;
        for (int j = 0; j < 3; j++)
            d = abs((int)px(&img)[c + j] - (int)px(&ref)[c + j]) > d
                    ? abs((int)px(&img)[c + j] - (int)px(&ref)[c + j])
                    : d;
        assert_true(d <= 1);   /* the pane's own pixel */
        image_free(&img);
    }
    image_free(&ref);
    scene_destroy(s);
}

/* A near wall (front face x = 5.5, depth 3.5) over the left part of the view, its edge
 * at z = -2.5 in front of pane 0 (depth 6.7), which is seen over the sky right of it;
 * light P (depth 6.2, range 1.5) is wholly behind the wall's depth and lights the pane
 * on both sides of the edge: the tiles the edge crosses have sky pixels, so their
 * translucent lists run to the far side and keep P. */
static void test_pane_beyond_a_wall_edge(void **state)
{
    (void)state;
    scene *s = build_glass(PLACEMENT_NONE);
    make_wall(s, 5.5f, -2.5f);
    static const scene_light p = {.type = LIGHT_POINT, .position = {2.8f, 1.5f, -3.5f},
                                  .color = {1.0f, 0.9f, 0.8f}, .radius = 1.5f,
                                  .attenuation = ATTENUATION_LINEAR_RANGE};
    set_lights(s, &p, 1);
    scene_update(s, 0.0);
    look(s, 9.0f, 2.0f, -2.7f, 0.0f, 1.5f, -2.7f);
    image ref = {0}, img = {0};
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &ref, NULL, NULL));
    static const char *const tiled[] = {"forward-plus", "clustered", "tiled-deferred",
                                        "visibility", DL_TILED};
    for (size_t k = 0; k < 5; k++) {
        frame_stats fs;
        pass_plan plan;
        assert_true(render(tiled[k], LIGHT_VOLUMES_STENCIL, s, &img, &fs, &plan));
        expect_translucent_lists(tiled[k], &fs, &plan);
        assert_true(fs.translucent_lights_max == 1.0);
        char what[96];
        snprintf(what, sizeof what, "pane beyond a wall's edge: %s vs forward-spml", tiled[k]);
        expect_agree(what, &img, &ref);
        image_free(&img);
    }
    image_free(&ref);
    scene_destroy(s);
}

/* The translucent lists share the opaque lists' index buffer and overflow rule: on
 * glass, with tiles.max_lights_per_tile 4 (capacity 4 x (48 opaque + 48 translucent
 * heads) = 384 entries) the opaque lists alone fit (157 entries) but not with the
 * translucent ones (480 in all): the frame reports the overflow, nothing is truncated
 * silently; with 12 everything fits. */
static void test_translucent_lists_overflow(void **state)
{
    (void)state;
    scene *s = build_glass(PLACEMENT_SCENE);
    static const char *const tiled[] = {"forward-plus", "tiled-deferred", "visibility"};
    for (size_t k = 0; k < 3; k++) {
        frame_stats fs;
        g_max_lights_per_tile = 4;
        assert_true(render(tiled[k], LIGHT_VOLUMES_STENCIL, s, NULL, &fs, NULL));
        print_message("%s, 4 a tile: opaque %.0f of 384, translucent %.0f: %s\n", tiled[k],
                      fs.grid_lights_mean * 48, fs.translucent_lights_mean * 48, fs.overflow);
        assert_true(fs.grid_lights_mean * 48 <= 384.0);
        assert_true((fs.grid_lights_mean + fs.translucent_lights_mean) * 48 > 384.0);
        assert_non_null(strstr(fs.overflow, "the index buffer holds 384"));
        g_max_lights_per_tile = 12;
        assert_true(render(tiled[k], LIGHT_VOLUMES_STENCIL, s, NULL, &fs, NULL));
        assert_int_equal(fs.overflow[0], '\0');
    }
    g_max_lights_per_tile = 0;
    scene_destroy(s);
}

/* A shadowing spot over the panes: the translucent pass's SHADOWS variant (the pool
 * bound for it), in forward-spml and deferred alike; the panes cast no shadow (they are
 * in no shadow-casting set), so both agree. */
static void test_shadowed_spot(void **state)
{
    (void)state;
    scene *s = build_glass(PLACEMENT_NONE);
    s->lights = calloc(1, sizeof *s->lights);
    s->lights[0] = (scene_light){.type = LIGHT_SPOT, .position = {6.0f, 8.0f, 0.0f},
                                 .direction = {-0.6f, -0.8f, 0.0f}, .color = {1.0f, 1.0f, 0.9f},
                                 .radius = 20.0f, .spot_angle = sm_deg2rad(35.0f),
                                 .spot_exponent = 2.0f,
                                 .attenuation = ATTENUATION_LINEAR_RANGE, .shadows = true};
    s->nlights_total = 1;
    s->count = (light_count){.start = 1, .max = 1};
    scene_update(s, 0.0);
    image ref = {0}, img = {0};
    pass_plan plan;
    frame_stats fs;
    assert_true(render("forward-spml", LIGHT_VOLUMES_STENCIL, s, &ref, &fs, &plan));
    assert_non_null(find_pass(&fs, "shadows"));
    bool shadowed = false;
    for (size_t i = 0; i < plan.nprograms; i++)
        shadowed |= strstr(plan.program[i], "translucent_shadowed") != NULL;
    assert_true(shadowed);
    assert_true(render("deferred", LIGHT_VOLUMES_STENCIL, s, &img, NULL, NULL));
    expect_agree("glass, a shadowing spot: deferred vs forward-spml", &img, &ref);
    image_free(&img);
    image_free(&ref);
    scene_destroy(s);
}

static double over(double c, double a, double dst)
{
    return c * a + (1.0 - a) * dst;
}

/* Panes 0 (red, x = 2.25) and 1 (green, x = 0.75) alone, no lights, ambient 1: each
 * pane's colour is its diffuse colour; their overlap is z in [-2.9, -0.7]. */
static void check_order(const char *kind, bool from_plus_x)
{
    scene *s = build_glass(PLACEMENT_NONE);
    s->nobjects = 4;   /* floor, pillar, panes 0 and 1 (pane 0 first in object order) */
    sm_vec3_make(1.0f, 1.0f, 1.0f, s->ambient);
    scene_update(s, 0.0);
    if (from_plus_x)
        look(s, 14.0f, 1.5f, -1.8f, 0.0f, 1.5f, -1.8f);
    else
        look(s, -14.0f, 1.5f, -1.8f, 0.0f, 1.5f, -1.8f);
    image img = {0}, bg = {0};
    frame_stats fs;
    assert_true(render(kind, LIGHT_VOLUMES_STENCIL, s, &img, &fs, NULL));
    assert_true(find_pass(&fs, "translucent")->draw_calls == 2);
    s->nobjects = 2;   /* the background alone */
    assert_true(render(kind, LIGHT_VOLUMES_STENCIL, s, &bg, NULL, NULL));
    const scene_material *front = &s->materials[s->objects[from_plus_x ? 2 : 3].material];
    const scene_material *back = &s->materials[s->objects[from_plus_x ? 3 : 2].material];
    size_t c = ((size_t)(H / 2) * W + W / 2) * 4;
    double worst = 0.0, wrong = 0.0;
    for (int k = 0; k < 3; k++) {
        double b = px(&bg)[c + k] / 255.0;
        double right = over(front->diffuse[k], front->opacity,
                            over(back->diffuse[k], back->opacity, b));
        double reversed = over(back->diffuse[k], back->opacity,
                               over(front->diffuse[k], front->opacity, b));
        double got = px(&img)[c + k] / 255.0;
        worst = fmax(worst, fabs(got - right));
        wrong = fmax(wrong, fabs(right - reversed));
        print_message("%s from %s x: channel %d: %.4f, back to front %.4f, front to back %.4f\n",
                      kind, from_plus_x ? "+" : "-", k, got, right, reversed);
    }
    assert_true(worst <= 3.0 / 255.0);
    assert_true(wrong > 20.0 / 255.0);
    image_free(&img);
    image_free(&bg);
    scene_destroy(s);
}

/* Two overlapping panes of different colours, the front one first in object order (so
 * drawing in object order would be wrong): where they overlap the pixel is the
 * back-to-front "over" of the two over the background, computed here from the materials
 * and the background pixel, within 3/255, and differs from the front-to-back order by
 * more than 20/255; from the other side the order turns with the camera (every renderer
 * from +x, forward-spml and deferred from -x too). */
static void test_back_to_front(void **state)
{
    (void)state;
    /* both sides in forward-spml and deferred; one side in the others (the pass and
     * the frontend's order are shared; what differs is the opaque image under it) */
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        check_order(kinds[k], true);
        if (strcmp(kinds[k], "forward-spml") == 0 || strcmp(kinds[k], "deferred") == 0)
            check_order(kinds[k], false);
    }
}

/* shapes has no translucent material: the pass is planned as "skipped: no translucent
 * materials", no such pass runs and no translucent program is compiled; the tiled
 * renderers plan their translucent lists as skipped and build none (test_tiled.c's exact
 * dispatch counts hold). */
static void test_no_translucency_skips_the_pass(void **state)
{
    (void)state;
    char err[256];
    light_params lp = {.placement = PLACEMENT_RANDOM, .seed = 1, .rng = RNG_PCG32,
                       .count = {.start = 8, .max = 8}, .radius = 8.0f, .color_max = 0.5f};
    scene *s = scene_build("shapes", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("scene: %s", err);
    scene_update(s, 0.0);
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        frame_stats fs;
        pass_plan plan;
        assert_true(render(kinds[k], LIGHT_VOLUMES_STENCIL, s, NULL, &fs, &plan));
        const pass_plan_entry *e = plan_pass(&plan, "translucent");
        assert_non_null(e);
        assert_false(e->run);
        assert_string_equal(e->reason, "skipped: no translucent materials");
        assert_null(find_pass(&fs, "translucent"));
        for (size_t i = 0; i < plan.nprograms; i++)   /* no *_cull_translucent either */
            assert_null(strstr(plan.program[i], "translucent"));
        if (tiled_kind(kinds[k])) {   /* no translucent lists: planned as skipped */
            e = plan_pass(&plan, "translucent-lists");
            assert_non_null(e);
            assert_false(e->run);
            assert_string_equal(e->reason, "skipped: no translucent materials");
            assert_int_equal(fs.translucent_lists, 0);
            assert_true(isnan(fs.translucent_lights_max));
        }
    }
    scene_destroy(s);
    /* glass plans it as run, and compiles its program */
    s = build_glass(PLACEMENT_SCENE);
    pass_plan plan;
    assert_true(render("deferred", LIGHT_VOLUMES_STENCIL, s, NULL, NULL, &plan));
    assert_true(plan_pass(&plan, "translucent")->run);
    bool compiled = false;
    for (size_t i = 0; i < plan.nprograms; i++)
        compiled |= strstr(plan.program[i], "translucent") != NULL;
    assert_true(compiled);
    scene_destroy(s);
}

GL_TEST_MAIN(ctx, W, H,
             cmocka_unit_test(test_glass_agreement),
             cmocka_unit_test(test_pane_in_front_of_light_volume),
             cmocka_unit_test(test_light_before_the_wall),
             cmocka_unit_test(test_pane_beyond_a_wall_edge),
             cmocka_unit_test(test_translucent_lists_overflow),
             cmocka_unit_test(test_shadowed_spot),
             cmocka_unit_test(test_back_to_front),
             cmocka_unit_test(test_no_translucency_skips_the_pass))
