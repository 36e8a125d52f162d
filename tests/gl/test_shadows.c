/* Shadow maps for spot and directional lights (renderers/frame/shadow.h, frontend.h
 * "shadow"), in every renderer family, in a debug context (any GL error fails):
 *   - an occluder between a light (spot, directional) and the floor: shadowed floor
 *     pixels get exactly the ambient light, lit ones beside them are bright, and with
 *     shadows off both are bright (deferred in each light-volume mode and two G-buffer
 *     presets, forward-mpml, forward-spml);
 *   - deferred and forward-mpml agree with forward-spml on "shapes" with shadow-casting
 *     lights within test_agreement.c's bounds (RMSE < 1/255, max <= 4/255), and the
 *     shadows change the image;
 *   - the shadow-casting sets, recomputed here from the geometry, are the frontend's, and
 *     the shadows pass draws exactly the sum of their sizes in every renderer;
 *   - shadows off, or no light that casts: no shadows pass, program or pool, and the
 *     frame's draws those of the formulas without shadows;
 *   - a light on a surface, a camera inside a shadowed spot, spots of extreme angles,
 *     nothing visible: finite light, no GL error. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/frame/frontend.h"
#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "common/image_io.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

enum { W = 160, H = 120, MAX_OBJECTS = 128 };
#define RMSE_MAX (1.0 / 255.0)
#define MAX_ABS_MAX (4.0 / 255.0)

static gl_context *ctx;

static const light_volume_mode MODES[4] = {LIGHT_VOLUMES_STENCIL, LIGHT_VOLUMES_FULLSCREEN,
                                           LIGHT_VOLUMES_VOLUME, LIGHT_VOLUMES_STENCIL_TWO_PASS};
static const char *const MODE_NAMES[4] = {"stencil", "fullscreen", "volume", "stencil-two-pass"};

// >>lights and scenes

static scene_light spot(float x, float y, float z, float dx, float dy, float dz, float radius,
                        float angle_deg, bool shadows)
{
    scene_light l = {.type = LIGHT_SPOT, .position = {x, y, z}, .direction = {dx, dy, dz},
                     .color = {1.0f, 0.9f, 0.7f}, .radius = radius,
                     .spot_angle = sm_deg2rad(angle_deg), .spot_exponent = 2.0f,
                     .attenuation = ATTENUATION_LINEAR_RANGE, .shadows = shadows};
    sm_vec3_normalize(l.direction);
    return l;
}

static scene_light directional(float dx, float dy, float dz, bool shadows)
{
    scene_light l = {.type = LIGHT_DIRECTIONAL, .direction = {dx, dy, dz},
                     .color = {0.8f, 0.8f, 0.7f}, .shadows = shadows};
    sm_vec3_normalize(l.direction);
    return l;
}

static scene_light point(float x, float y, float z, float radius, bool shadows)
{
    scene_light l = {.type = LIGHT_POINT, .position = {x, y, z}, .color = {0.6f, 0.7f, 0.9f},
                     .radius = radius, .attenuation = ATTENUATION_LINEAR_RANGE,
                     .shadows = shadows};
    return l;
}

/* Looks from eye at target with the scene's lens (scene_update posed the rest). */
static void look(scene *s, const float eye[3], const float target[3])
{
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3_copy(eye, s->cam.eye);
    sm_vec3_copy(target, s->cam.target);
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
}

static void set_lights(scene *s, const scene_light *lights, uint32_t n)
{
    free(s->lights);
    s->lights = calloc(n ? n : 1, sizeof *s->lights);
    assert_non_null(s->lights);
    if (n)
        memcpy(s->lights, lights, n * sizeof *lights);
    s->nlights_total = n;
    s->count = (light_count){.start = n, .max = n};
    s->nlights_active = n;
}

/* "shapes" at t = 0 with exactly these lights, seen from eye. */
static scene *shapes(const scene_light *lights, uint32_t n, const float eye[3],
                     const float target[3])
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build("shapes", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("scene shapes: %s", err);
    set_lights(s, lights, n);
    scene_update(s, 0.0);
    look(s, eye, target);
    return s;
}

/* The mesh of s whose bounding box is centred at the origin with half extents h. */
static uint32_t find_mesh(const scene *s, float hx, float hy, float hz)
{
    for (uint32_t i = 0; i < s->nmeshes; i++) {
        const sm_vec3 *b = s->meshes[i].aabb;
        if (fabsf(b[0][0] + hx) < 1e-3f && fabsf(b[1][0] - hx) < 1e-3f &&
            fabsf(b[0][1] + hy) < 1e-3f && fabsf(b[1][1] - hy) < 1e-3f &&
            fabsf(b[0][2] + hz) < 1e-3f && fabsf(b[1][2] - hz) < 1e-3f)
            return i;
    }
    fail_msg("shapes has no mesh of half extents %g %g %g", hx, hy, hz);
    return 0;
}

/* "shapes" cut down to its floor (the 80 x 1 x 80 box, top at y = 0) and one 3 x 3 x 3
 * box, static, centred at (0, 5, 0): y from 3.5 to 6.5. The camera looks from (0, 14,
 * 20) at the origin. */
static const float OCC_EYE[3] = {0.0f, 14.0f, 20.0f}, OCC_TARGET[3] = {0.0f, 0.0f, 0.0f};

static scene *occluder_scene(const scene_light *lights, uint32_t n)
{
    scene *s = shapes(lights, n, OCC_EYE, OCC_TARGET);
    uint32_t floor_mesh = find_mesh(s, 40.0f, 0.5f, 40.0f);
    uint32_t box_mesh = find_mesh(s, 1.5f, 1.5f, 1.5f);
    scene_object floor = {0}, box = {0};
    bool have_floor = false, have_box = false;
    for (uint32_t i = 0; i < s->nobjects; i++) {
        if (s->objects[i].mesh == floor_mesh && !have_floor) {
            floor = s->objects[i];
            have_floor = true;
        } else if (s->objects[i].mesh == box_mesh && !have_box) {
            box = s->objects[i];
            have_box = true;
        }
    }
    assert_true(have_floor && have_box);
    sm_vec3_make(0.0f, -0.5f, 0.0f, floor.position);
    floor.spin_rate = 0.0f;
    sm_vec3_make(0.0f, 5.0f, 0.0f, box.position);
    box.scale = 1.0f;
    box.spin_rate = 0.0f;
    s->objects[0] = floor;
    s->objects[1] = box;
    s->nobjects = 2;
    scene_update(s, 0.0);
    look(s, OCC_EYE, OCC_TARGET);
    return s;
}

// >>renderers

typedef struct frame_out {
    frame_stats fs;
    pass_plan plan;
    float *hdr;                /* W x H RGBA, row 0 at the bottom */
    image rgba8;               /* the output, row 0 at the top */
} frame_out;

static void frame_out_free(frame_out *f)
{
    free(f->hdr);
    image_free(&f->rgba8);
    memset(f, 0, sizeof *f);
}

static renderer_options options(light_volume_mode mode, gbuffer_preset preset, bool no_shadows)
{
    const gl_info *gi = gl_context_info(ctx);
    return (renderer_options){
        .width = W, .height = H, .queries = true, .timer_query = gi->timer_query,
        .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size, .gbuffer = preset,
        .light_volumes = mode, .no_shadows = no_shadows};
}

/* One frame of s with `kind` under o: its stats, plan, float light and output. */
static void render(const char *kind, const renderer_options *o, const scene *s, frame_out *out)
{
    char err[512] = "";
    memset(out, 0, sizeof *out);
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    renderer *r = test_renderer_create(kind, o, err, sizeof err);
    if (!r || !renderer_prepare(r, s, err, sizeof err)) {
        renderer_destroy(r);
        fail_msg("%s: %s", kind, err);
    }
    renderer_describe(r, &out->plan);
    renderer_draw(r, s, &out->fs);
    gl.Finish();
    renderer_collect(r, &out->fs);
    out->hdr = malloc((size_t)W * H * 4 * sizeof *out->hdr);
    assert_non_null(out->hdr);
    size_t nonfinite = 1;
    assert_true(renderer_read_hdr(r, out->hdr, W, H, &nonfinite));
    if (nonfinite)
        print_error("%s: %zu non-finite values\n", kind, nonfinite);
    assert_int_equal(nonfinite, 0);
    out->rgba8 = (image){.width = W, .height = H, .channels = 4, .type = IMAGE_U8,
                         .pixels = malloc((size_t)W * H * 4)};
    assert_non_null(out->rgba8.pixels);
    assert_true(gl_context_read_rgba8(ctx, out->rgba8.pixels, err, sizeof err));
    renderer_destroy(r);
    gl_context_poll_errors(ctx, kind);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static size_t programs_containing(const pass_plan *p, const char *part)
{
    size_t n = 0;
    for (size_t i = 0; i < p->nprograms; i++)
        if (strstr(p->program[i], part))
            n++;
    return n;
}

/* Programs whose name starts with prefix and contains part. */
static size_t programs_with(const pass_plan *p, const char *prefix, const char *part)
{
    size_t n = 0;
    for (size_t i = 0; i < p->nprograms; i++)
        if (strncmp(p->program[i], prefix, strlen(prefix)) == 0 && strstr(p->program[i], part))
            n++;
    return n;
}

static const target_plan_entry *target_named(const pass_plan *p, const char *prefix)
{
    for (size_t i = 0; i < p->ntargets; i++)
        if (strncmp(p->target[i].name, prefix, strlen(prefix)) == 0)
            return &p->target[i];
    return NULL;
}

// >>pixels

/* The pixel (bottom-up, as the float light is read) where world point p lands. */
static void project(const scene *s, const float p[3], int *x, int *y)
{
    sm_vec4 c = {p[0], p[1], p[2], 1.0f};
    sm_mat4_mulv(s->viewproj, c, c);
    assert_true(c[3] > 0.0f);
    *x = (int)floorf((c[0] / c[3] * 0.5f + 0.5f) * (float)W);
    *y = (int)floorf((c[1] / c[3] * 0.5f + 0.5f) * (float)H);
    assert_true(*x >= 1 && *x < W - 1 && *y >= 1 && *y < H - 1);
}

/* The light at world point p: the mean of rgb over the pixel and its 8 neighbours. */
static float light_at(const scene *s, const float *hdr, const float p[3])
{
    int x, y;
    project(s, p, &x, &y);
    double sum = 0.0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            const float *px = hdr + ((size_t)(y + dy) * W + (size_t)(x + dx)) * 4;
            sum += (double)px[0] + px[1] + px[2];
        }
    return (float)(sum / 27.0);
}

typedef struct occluder_case {
    const char *name;
    scene_light light;
    float shadowed[3][3];      /* floor points in the occluder's shadow, seen by the camera */
    float lit[3][3];           /* floor points the light reaches, seen by the camera */
} occluder_case;

/* A spot 12 above the floor shining straight down, the 3-unit box 3.5 .. 6.5 above the
 * floor under it: the box's shadow on the floor is the square |x|, |z| <= 1.5 x 12 /
 * (12 - 6.5) = 3.27 (its top face projected from the light); the cone (40 degrees)
 * reaches the floor out to 12 tan 40 = 10.1. The camera's rays to the points chosen
 * pass beside the box. */
static const occluder_case SPOT_CASE = {
    "spot",
    {.type = LIGHT_SPOT, .position = {0.0f, 12.0f, 0.0f}, .direction = {0.0f, -1.0f, 0.0f},
     .color = {3.0f, 3.0f, 3.0f}, .radius = 30.0f, .spot_angle = 0.6981317f /* 40 deg */,
     .spot_exponent = 2.0f, .attenuation = ATTENUATION_LINEAR_RANGE, .shadows = true},
    {{0.0f, 0.0f, 2.5f}, {2.4f, 0.0f, 2.4f}, {-2.4f, 0.0f, 2.0f}},
    {{6.0f, 0.0f, 0.0f}, {-5.5f, 0.0f, 2.0f}, {0.0f, 0.0f, 6.5f}},
};

/* Light travelling along (0.3, -1, 0.2): the box's points at height y fall on the floor
 * shifted by (0.3 y, 0.2 y), so (x, 0, z) is in shadow when some y in [3.5, 6.5] has
 * |x - 0.3 y| <= 1.5 and |z - 0.2 y| <= 1.5; the shadowed points below have it at y = 5
 * with a margin of at least 0.5. */
static const occluder_case DIRECTIONAL_CASE = {
    "directional",
    {.type = LIGHT_DIRECTIONAL, .direction = {0.3f, -1.0f, 0.2f},   /* made unit */
     .color = {1.0f, 1.0f, 1.0f}, .shadows = true},
    {{1.5f, 0.0f, 1.0f}, {1.0f, 0.0f, 1.8f}, {2.0f, 0.0f, 0.5f}},
    {{5.0f, 0.0f, -2.0f}, {-4.0f, 0.0f, 3.0f}, {-3.0f, 0.0f, 6.0f}},
};

/* The occluder case in one renderer configuration: in-shadow points equal the frame
 * without any light (ambient only), lit points are clearly brighter, and with shadows
 * off the in-shadow points are lit too. */
static void check_occluder(const occluder_case *c, const char *kind, light_volume_mode mode,
                           gbuffer_preset preset, const char *what)
{
    scene_light light = c->light;
    sm_vec3_normalize(light.direction);
    scene *s = occluder_scene(&light, 1);
    frame_out on, off, dark;
    renderer_options o = options(mode, preset, false);
    render(kind, &o, s, &on);
    assert_non_null(find_pass(&on.fs, "shadows"));
    o.no_shadows = true;
    render(kind, &o, s, &off);
    assert_null(find_pass(&off.fs, "shadows"));
    o.no_shadows = false;
    s->nlights_active = 0;
    s->count.start = s->count.max = 0;
    render(kind, &o, s, &dark);
    s->nlights_active = 1;
    s->count.start = s->count.max = 1;
    for (int i = 0; i < 3; i++) {
        float shadow = light_at(s, on.hdr, c->shadowed[i]);
        float ambient = light_at(s, dark.hdr, c->shadowed[i]);
        float unshadowed = light_at(s, off.hdr, c->shadowed[i]);
        float lit = light_at(s, on.hdr, c->lit[i]);
        float lit_ambient = light_at(s, dark.hdr, c->lit[i]);
        if (!(fabsf(shadow - ambient) <= 2e-3f) || !(unshadowed > ambient + 0.05f) ||
            !(lit > lit_ambient + 0.05f))
            print_error("%s, %s: shadowed point %d: %.4f (ambient alone %.4f, shadows off "
                        "%.4f); lit point %d: %.4f (ambient %.4f)\n",
                        c->name, what, i, shadow, ambient, unshadowed, i, lit, lit_ambient);
        assert_true(fabsf(shadow - ambient) <= 2e-3f);
        assert_true(unshadowed > ambient + 0.05f);
        assert_true(lit > lit_ambient + 0.05f);
    }
    frame_out_free(&on);
    frame_out_free(&off);
    frame_out_free(&dark);
    scene_destroy(s);
}

static void run_occluder(const occluder_case *c)
{
    char what[96];
    for (int m = 0; m < 4; m++) {
        snprintf(what, sizeof what, "deferred (curtis, %s)", MODE_NAMES[m]);
        check_occluder(c, "deferred", MODES[m], GBUFFER_CURTIS, what);
    }
    check_occluder(c, "deferred", LIGHT_VOLUMES_STENCIL, GBUFFER_REFERENCE,
                   "deferred (reference, stencil)");
    check_occluder(c, "deferred", LIGHT_VOLUMES_VOLUME, GBUFFER_SPHEREMAP,
                   "deferred (spheremap, volume)");
    check_occluder(c, "forward-mpml", LIGHT_VOLUMES_STENCIL, GBUFFER_CURTIS, "forward-mpml");
    check_occluder(c, "forward-spml", LIGHT_VOLUMES_STENCIL, GBUFFER_CURTIS, "forward-spml");
    /* the light pre-pass's light passes are deferred's, SHADOWS variant included */
    check_occluder(c, "deferred-lighting", LIGHT_VOLUMES_STENCIL, GBUFFER_CURTIS,
                   "deferred-lighting (stencil)");
    check_occluder(c, "deferred-lighting", LIGHT_VOLUMES_FULLSCREEN, GBUFFER_CURTIS,
                   "deferred-lighting (fullscreen)");
}

static void test_spot_occluder(void **state)
{
    (void)state;
    run_occluder(&SPOT_CASE);
}

static void test_directional_occluder(void **state)
{
    (void)state;
    run_occluder(&DIRECTIONAL_CASE);
}

// >>agreement

static void expect_agree(const char *what, const image *a, const image *b)
{
    gl_test_expect_agree(what, a, b, RMSE_MAX, MAX_ABS_MAX, false);
}

static const float EYE[3] = {0.0f, 12.0f, 28.0f}, TARGET[3] = {0.0f, 1.0f, 0.0f};

static void agree_on(scene *s, const char *name)
{
    char what[160];
    frame_out ref, img, off;
    renderer_options o = options(LIGHT_VOLUMES_STENCIL, GBUFFER_REFERENCE, false);
    render("forward-spml", &o, s, &ref);
    assert_non_null(find_pass(&ref.fs, "shadows"));
    render("visibility", &o, s, &img);   /* shade_light's shadows in a compute pass */
    assert_non_null(find_pass(&img.fs, "shadows"));
    snprintf(what, sizeof what, "%s: visibility vs forward-spml", name);
    expect_agree(what, &img.rgba8, &ref.rgba8);
    frame_out_free(&img);

    /* the shadows show: the same frame without them differs */
    o.no_shadows = true;
    render("forward-spml", &o, s, &off);
    o.no_shadows = false;
    image_error e;
    char err[256];
    assert_true(image_compare(&ref.rgba8, &off.rgba8, &e, err, sizeof err));
    if (e.frac_over_1_255 < 0.01)
        print_error("%s: shadows change only %.4f of the pixels\n", name, e.frac_over_1_255);
    assert_true(e.frac_over_1_255 >= 0.01);
    frame_out_free(&off);

    render("forward-mpml", &o, s, &img);
    snprintf(what, sizeof what, "%s: forward-mpml vs forward-spml", name);
    expect_agree(what, &img.rgba8, &ref.rgba8);
    frame_out_free(&img);
    for (int m = 0; m < 4; m++) {
        o.light_volumes = MODES[m];
        render("deferred", &o, s, &img);
        snprintf(what, sizeof what, "%s: deferred (reference, %s) vs forward-spml", name,
                 MODE_NAMES[m]);
        expect_agree(what, &img.rgba8, &ref.rgba8);
        frame_out_free(&img);
    }
    frame_out_free(&ref);
}

static void test_agreement(void **state)
{
    (void)state;
    /* a shadowed spot over the grid, a shadowed directional light, an unshadowed point
     * light and an unshadowed spot */
    scene_light lights[4] = {spot(0, 10, 0, 0.2f, -1, 0.1f, 20, 30, true),
                             directional(-0.4f, -1.0f, -0.3f, true),
                             point(-8, 4, 8, 9, false),
                             spot(10, 6, 10, -0.5f, -1, -0.5f, 14, 25, false)};
    scene *s = shapes(lights, 4, EYE, TARGET);
    agree_on(s, "shapes, shadowed spot and directional");
    scene_destroy(s);

    /* the spot alone, seen from close by, its centre outside the view */
    scene_light one = spot(-2, 9, -3, -0.4f, -1, 0.3f, 22, 40, true);
    static const float NEAR_EYE[3] = {-6.0f, 5.0f, 16.0f}, NEAR_TARGET[3] = {-8.0f, 1.0f, 0.0f};
    s = shapes(&one, 1, NEAR_EYE, NEAR_TARGET);
    agree_on(s, "shapes, a shadowed spot from close by");
    scene_destroy(s);
}

// >>shadow-casting sets and draw calls

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* The expected shadow-casting set of light l (a light the frontend found visible), by
 * the formula of frontend.h, computed here from the geometry:
 *
 *   V = {o : sm_sphere_in_frustum(planes of viewproj, bsphere(o))}
 *   spot:  I = {o in V : sm_cone_sphere_intersects(pos, dir, angle, radius, bsphere(o))}
 *          C = {}                                   if I is empty
 *              I                                    if pos is inside all six planes
 *              {o : the cone meets bsphere(o)}      otherwise (every object)
 *   directional, in the light's view L = look(origin, dir, +Y) (c = L x centre, r):
 *          R = [min over V of c.x - r, max c.x + r] x [min c.y - r, max c.y + r]
 *          dmax = max over V of (-c.z + r)
 *          C = {o : dist((c.x, c.y), R)^2 <= r^2 and -c.z - r <= dmax}   ({} when V is)
 *   other lights, or lights without shadows = true: no set.
 * Returns |C|; the set, sorted, in out. */
static uint32_t expected_set(const scene *s, const scene_light *l, uint32_t *out)
{
    sm_vec4 planes[6];
    sm_frustum_planes(s->viewproj, planes);
    bool visible[MAX_OBJECTS];
    assert_true(s->nobjects <= MAX_OBJECTS);
    uint32_t nvis = 0;
    for (uint32_t o = 0; o < s->nobjects; o++) {
        visible[o] = sm_sphere_in_frustum(planes, s->objects[o].bsphere);
        nvis += visible[o];
    }
    uint32_t n = 0;
    if (!l->shadows || l->type == LIGHT_POINT)
        return 0;
    if (l->type == LIGHT_SPOT) {
        sm_vec3 dir;
        sm_vec3_normalize_to(l->direction, dir);
        bool any = false;
        for (uint32_t o = 0; o < s->nobjects; o++)
            if (visible[o] && sm_cone_sphere_intersects(l->position, dir, l->spot_angle,
                                                        l->radius, s->objects[o].bsphere))
                any = true;
        if (!any)
            return 0;
        bool inside = true;
        for (int i = 0; i < 6; i++)
            if (sm_plane_distance(planes[i], l->position) < 0.0f)
                inside = false;
        for (uint32_t o = 0; o < s->nobjects; o++)
            if ((visible[o] || !inside) &&
                sm_cone_sphere_intersects(l->position, dir, l->spot_angle, l->radius,
                                          s->objects[o].bsphere))
                out[n++] = o;
        return n;
    }
    if (nvis == 0)
        return 0;
    sm_mat4 view;
    sm_vec3 origin = {0, 0, 0}, up = {0, 1, 0}, dir;
    sm_vec3_normalize_to(l->direction, dir);
    sm_look(origin, dir, up, view);
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY, dmax = -INFINITY;
    for (uint32_t o = 0; o < s->nobjects; o++) {
        if (!visible[o])
            continue;
        sm_vec3 c;
        sm_mat4_mulv3(view, s->objects[o].bsphere, 1.0f, c);
        double r = s->objects[o].bsphere[3];
        x0 = fmin(x0, c[0] - r);
        x1 = fmax(x1, c[0] + r);
        y0 = fmin(y0, c[1] - r);
        y1 = fmax(y1, c[1] + r);
        dmax = fmax(dmax, -c[2] + r);
    }
    for (uint32_t o = 0; o < s->nobjects; o++) {
        sm_vec3 c;
        sm_mat4_mulv3(view, s->objects[o].bsphere, 1.0f, c);
        double r = s->objects[o].bsphere[3];
        double dx = fmax(fmax(x0 - c[0], c[0] - x1), 0.0);
        double dy = fmax(fmax(y0 - c[1], c[1] - y1), 0.0);
        /* a small tolerance against float rounding in the frontend: no case here is
         * that close */
        if (dx * dx + dy * dy <= r * r * (1.0 + 1e-5) && -c[2] - r <= dmax + 1e-4)
            out[n++] = o;
    }
    return n;
}

/* The frame's counts from the geometry alone (frontend.h's definitions, recomputed
 * here without the frontend):
 *   V     objects whose bounding sphere is not outside the frustum
 *   lights[t]  active lights of type t that can light something visible: directional
 *         always; point when the sphere (position, radius) is not outside the frustum;
 *         spot when the bounding sphere of its cone is not outside it
 *   illum the sum over those lights of |I(l)|: visible objects whose bounding sphere
 *         meets the light's sphere or cone (every visible object for directional) */
typedef struct frame_counts {
    uint32_t visible, lights[3];
    uint64_t illum;
} frame_counts;

static frame_counts expected_counts(const scene *s)
{
    sm_vec4 planes[6];
    sm_frustum_planes(s->viewproj, planes);
    frame_counts c = {0};
    for (uint32_t o = 0; o < s->nobjects; o++)
        c.visible += sm_sphere_in_frustum(planes, s->objects[o].bsphere);
    for (uint32_t i = 0; i < s->nlights_active; i++) {
        const scene_light *l = &s->lights[i];
        sm_vec3 dir;
        sm_vec4 b;
        sm_vec3_normalize_to(l->direction, dir);
        if (l->type == LIGHT_SPOT)
            frontend_spot_cone_bound(l->position, dir, l->spot_angle, l->radius, b);
        else
            sm_vec4_from_vec3(l->position, l->radius, b);
        if (l->type != LIGHT_DIRECTIONAL && !sm_sphere_in_frustum(planes, b))
            continue;
        c.lights[l->type]++;
        for (uint32_t o = 0; o < s->nobjects; o++) {
            const float *bs = s->objects[o].bsphere;
            if (!sm_sphere_in_frustum(planes, bs))
                continue;
            c.illum += l->type == LIGHT_DIRECTIONAL ? 1
                       : l->type == LIGHT_SPOT
                           ? sm_cone_sphere_intersects(l->position, dir, l->spot_angle,
                                                       l->radius, bs)
                           : sm_sphere_sphere_intersects(b, bs);
        }
    }
    return c;
}

typedef struct set_check {
    uint64_t shadow_draws;     /* sum of |C(l)| */
    uint32_t visible;          /* V */
    uint32_t lights[3];        /* visible lights per type */
    uint64_t illum;            /* sum of |I(l)| */
    bool outside_case;         /* some spot's set holds an object that is not visible */
    bool inside_case;          /* some spot with its centre in view has a non-empty set */
    bool empty_case;           /* some shadowed light in view has an empty set */
} set_check;

/* Builds the frontend on s as the renderers do and checks its shadow-casting sets and
 * layers against expected_set; returns the counts the draw formulas need. */
static set_check check_sets(const scene *s, bool no_shadows)
{
    frontend f;
    char err[256];
    assert_true(frontend_init(&f, s, err, sizeof err));
    f.no_shadows = no_shadows;
    frontend_build(&f, s);
    assert_false(f.truncated);
    set_check c = {.visible = f.nvisible};
    sm_vec4 planes[6];
    sm_frustum_planes(s->viewproj, planes);
    uint32_t layer = 0;
    for (uint32_t k = 0; k < f.nlights; k++) {
        const scene_light *l = &s->lights[f.lights[k]];
        c.lights[l->type]++;
        c.illum += f.illum_start[k + 1] - f.illum_start[k];
        uint32_t want[MAX_OBJECTS], got[MAX_OBJECTS];
        uint32_t nwant = no_shadows ? 0 : expected_set(s, l, want);
        uint32_t ngot = f.shadow_start[k + 1] - f.shadow_start[k];
        bool casts = !no_shadows && l->shadows && l->type != LIGHT_POINT;
        if (casts)
            assert_int_equal(f.shadow_layer[k], layer++);
        else
            assert_int_equal(f.shadow_layer[k], FRONTEND_NO_SHADOW);
        if (ngot != nwant)
            print_error("light %u (type %d): shadow set of %u objects, expected %u\n",
                        f.lights[k], (int)l->type, ngot, nwant);
        assert_int_equal(ngot, nwant);
        if (ngot)   /* f.shadow is NULL when no light of the scene casts shadows */
            memcpy(got, f.shadow + f.shadow_start[k], ngot * sizeof *got);
        qsort(got, ngot, sizeof *got, cmp_u32);
        for (uint32_t i = 0; i < ngot; i++) {
            assert_int_equal(got[i], want[i]);
            if (!sm_sphere_in_frustum(planes, s->objects[got[i]].bsphere))
                c.outside_case = true;
        }
        c.shadow_draws += ngot;
        if (casts && ngot == 0)
            c.empty_case = true;
        if (casts && ngot > 0 && l->type == LIGHT_SPOT) {
            bool inside = true;
            for (int i = 0; i < 6; i++)
                inside &= sm_plane_distance(planes[i], l->position) >= 0.0f;
            c.inside_case |= inside;
        }
    }
    assert_int_equal(f.nshadowed, layer);
    frontend_free(&f);
    /* V, the visible lights and the illumination sets the formulas use are the
     * geometry's, not only the frontend's word for them */
    frame_counts want = expected_counts(s);
    if (want.visible != c.visible || want.illum != c.illum ||
        memcmp(want.lights, c.lights, sizeof want.lights) != 0)
        print_error("frontend V %u, lights %u/%u/%u, sum |I| %llu; geometry V %u, lights "
                    "%u/%u/%u, sum |I| %llu\n", c.visible, c.lights[0], c.lights[1],
                    c.lights[2], (unsigned long long)c.illum, want.visible, want.lights[0],
                    want.lights[1], want.lights[2], (unsigned long long)want.illum);
    assert_int_equal(c.visible, want.visible);
    assert_memory_equal(c.lights, want.lights, sizeof want.lights);
    assert_int_equal(c.illum, want.illum);
    return c;
}

/* The renderers' draws against the formulas:
 *   deferred (stencil):  Sh + V + 1 + D + 2 (P + S) + [sky] + 1
 *   deferred (fullscreen):  Sh + V + 1 + D + P + S + [sky] + 1
 *   forward-mpml:        Sh + V + sum |I(l)| + [sky] + 1
 *   forward-mpml, forward.directional_in_base:  Sh + V + sum |I(l)| - D V + [sky] + 1
 *                        (the directional lights, |I(l)| = V each, shaded in the base pass)
 *   forward-spml:        Sh + V + [sky] + 1
 * with Sh = sum of |C(l)| (the shadows pass's draws) when shadows are on, 0 off.
 * Returns the counts check_sets found. */
static set_check check_draws(const scene *s, bool no_shadows)
{
    set_check c = check_sets(s, no_shadows);
    uint64_t sky = s->sky ? 1u : 0u;
    uint64_t sh = no_shadows ? 0u : c.shadow_draws;
    uint64_t dv = (uint64_t)c.lights[LIGHT_DIRECTIONAL] * c.visible;
    struct {
        const char *kind;
        light_volume_mode mode;
        uint64_t draws;
        bool fold;
    } cases[] = {
        {"deferred", LIGHT_VOLUMES_STENCIL,
         sh + c.visible + 1 + c.lights[LIGHT_DIRECTIONAL] +
             2 * (c.lights[LIGHT_POINT] + c.lights[LIGHT_SPOT]) + sky + 1, false},
        {"deferred", LIGHT_VOLUMES_FULLSCREEN,
         sh + c.visible + 1 + c.lights[LIGHT_DIRECTIONAL] + c.lights[LIGHT_POINT] +
             c.lights[LIGHT_SPOT] + sky + 1, false},
        {"forward-mpml", LIGHT_VOLUMES_STENCIL, sh + c.visible + c.illum + sky + 1, false},
        {"forward-mpml", LIGHT_VOLUMES_STENCIL, sh + c.visible + c.illum - dv + sky + 1, true},
        {"forward-spml", LIGHT_VOLUMES_STENCIL, sh + c.visible + sky + 1, false},
        /* the light pre-pass: both geometry passes, deferred's light draws, no ambient */
        {"deferred-lighting", LIGHT_VOLUMES_STENCIL,
         sh + 2 * (uint64_t)c.visible + c.lights[LIGHT_DIRECTIONAL] +
             2 * (c.lights[LIGHT_POINT] + c.lights[LIGHT_SPOT]) + sky + 1, false},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        renderer_options o = options(cases[i].mode, GBUFFER_CURTIS, no_shadows);
        o.directional_in_base = cases[i].fold;
        frame_out f;
        render(cases[i].kind, &o, s, &f);
        const pass_stats *p = find_pass(&f.fs, "shadows");
        bool casters = false;
        for (uint32_t l = 0; l < s->nlights_total; l++)
            casters |= s->lights[l].shadows && s->lights[l].type != LIGHT_POINT;
        if (no_shadows || !casters) {
            assert_null(p);
        } else {
            assert_non_null(p);
            assert_int_equal(p->draw_calls, sh);
            assert_string_equal(f.fs.pass[0].name, "shadows");
            /* the frame without shadow maps is this one less the shadows pass (and the
             * pool's one texture bind): tables 5.3.2 and 5.3.3 from one run */
            frame_out off;
            o.no_shadows = true;
            render(cases[i].kind, &o, s, &off);
            assert_int_equal(f.fs.total.draw_calls - p->draw_calls, off.fs.total.draw_calls);
            assert_int_equal(f.fs.total.state_changes - p->state_changes,
                             off.fs.total.state_changes + 1);
            assert_int_equal(f.fs.npasses, off.fs.npasses + 1);
            for (size_t k = 1; k < f.fs.npasses; k++) {
                assert_string_equal(f.fs.pass[k].name, off.fs.pass[k - 1].name);
                assert_int_equal(f.fs.pass[k].draw_calls, off.fs.pass[k - 1].draw_calls);
            }
            frame_out_free(&off);
        }
        if (total_draws(&f.fs) != cases[i].draws)
            print_error("%s%s: %llu draws, the formula gives %llu\n", cases[i].kind,
                        cases[i].fold ? " (directional_in_base)" : "",
                        (unsigned long long)total_draws(&f.fs),
                        (unsigned long long)cases[i].draws);
        assert_int_equal(total_draws(&f.fs), cases[i].draws);
        assert_int_equal(f.fs.total.draw_calls, cases[i].draws);
        frame_out_free(&f);
    }
    return c;
}

static void test_sets_and_draws(void **state)
{
    (void)state;
    /* Seen from close by, only part of the grid is visible.
     *   0 a spot whose centre is in view (its set: visible objects in its cone)
     *   1 a spot whose centre is out of view, shining into it (every object in its cone)
     *   2 a shadowed directional light
     *   3 a point light asking for shadows (none: spot and directional only)
     *   4 a spot without shadows
     *   5 a shadowed spot in view but far beyond the floor (whose bounding sphere, of
     *     radius 56.6 about the origin, meets every cone near it), shining away from
     *     everything: in view, it lights nothing, so its set is empty */
    static const float NEAR_EYE[3] = {-6.0f, 5.0f, 16.0f}, NEAR_TARGET[3] = {-8.0f, 1.0f, 0.0f};
    scene_light lights[6] = {spot(-8, 5, 4, 0, -1, -0.3f, 16, 45, true),
                             spot(16, 9, -4, -1, -0.5f, 0.2f, 40, 30, true),
                             directional(-0.3f, -1.0f, -0.5f, true),
                             point(-10, 3, 6, 8, true),
                             spot(-4, 6, 6, 0, -1, 0, 12, 30, false),
                             spot(-15.6f, -14.3f, -61, 0, 0, -1, 2, 20, true)};
    scene *s = shapes(lights, 6, NEAR_EYE, NEAR_TARGET);
    set_check c = check_sets(s, false);
    assert_true(c.outside_case);   /* the out-of-view spot's set reaches beyond the view */
    assert_true(c.inside_case);    /* the in-view spot's set: visible objects only */
    assert_true(c.empty_case);     /* the spot pointing into the air */
    assert_true(c.shadow_draws > 0);
    check_draws(s, false);
    check_draws(s, true);

    /* the whole grid from above and afar: every light in view */
    look(s, EYE, TARGET);
    check_draws(s, false);
    scene_destroy(s);
}

/* Seed 000's two scenes with their authored lights, at points of their camera paths,
 * shadows on and off: every renderer's draws equal the formulas above with V, D, P, S,
 * the illumination sets and the shadow-casting sets computed from the scene's
 * geometry (expected_counts, expected_set).
 *   interior: 72 objects; lights: the moon (directional, shadows), five omni lights
 *     (no shadows), three spots (shadows). So Sh = |C(moon)| + the three spots' sets.
 *   canyon: 4 terrain tiles, the sky, one directional sun without shadows: no
 *     shadows pass, the same draws with shadows on and off: V + 1 + 1 + 1 + 1 for
 *     deferred (gbuffer, ambient, the sun, sky, resolve), V + V + 1 + 1 for
 *     forward-mpml (base, the sun over every visible tile, sky, resolve). */
static void test_catalog_draws(void **state)
{
    (void)state;
    char err[256];
    light_params lp = {.placement = PLACEMENT_SCENE, .radius = 1.0f,
                       .count = {.start = LIGHT_COUNT_ALL, .max = LIGHT_COUNT_ALL}};
    scene *s = scene_build("interior", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("interior: %s", err);
    assert_int_equal(s->nobjects, 72);
    assert_int_equal(s->nlights_total, 9);
    uint64_t shadow_draws = 0;
    for (double t = 0.0; t < 60.0; t += 7.5) {
        scene_update(s, t);
        shadow_draws += check_draws(s, false).shadow_draws;
        check_draws(s, true);
    }
    assert_true(shadow_draws > 0);   /* the path sees shadows cast */
    scene_destroy(s);

    s = scene_build("canyon", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("canyon: %s", err);
    assert_int_equal(s->nobjects, 4);
    assert_true(s->sky);
    assert_int_equal(s->nlights_total, 1);
    assert_int_equal(s->lights[0].type, LIGHT_DIRECTIONAL);
    assert_false(s->lights[0].shadows);
    for (double t = 0.0; t < 60.0; t += 15.0) {
        scene_update(s, t);
        set_check c = check_draws(s, false);
        assert_int_equal(c.shadow_draws, 0);
        assert_int_equal(c.lights[LIGHT_DIRECTIONAL], 1);
        check_draws(s, true);
        /* in numbers: forward-mpml 2V + 2 with the sun in its own pass, V + 2 with it in
         * the base pass (forward.directional_in_base); deferred V + 4 */
        renderer_options o = options(LIGHT_VOLUMES_STENCIL_TWO_PASS, GBUFFER_FAT, false);
        frame_out f;
        render("forward-mpml", &o, s, &f);
        assert_int_equal(f.fs.total.draw_calls, 2 * (uint64_t)c.visible + 2);
        frame_out_free(&f);
        o.directional_in_base = true;
        render("forward-mpml", &o, s, &f);
        assert_int_equal(f.fs.total.draw_calls, (uint64_t)c.visible + 2);
        frame_out_free(&f);
        render("deferred", &o, s, &f);
        assert_int_equal(f.fs.total.draw_calls, (uint64_t)c.visible + 4);
        frame_out_free(&f);
    }
    scene_destroy(s);
}

/* forward.directional_in_base: forward-mpml with the directional lights shaded in its
 * base pass agrees with the same renderer drawing them in passes of their own (RMSE <
 * 1/255, max <= 4/255: fp16 rounds the sum once instead of per pass) on "shapes" with a
 * shadowed directional light among others, on the canyon (its sun, no shadows) and on
 * the interior (its shadowed moon, omni lights and shadowed spots); draws V x D fewer
 * (check_draws asserts the formula); compiles the BASE_DIRECTIONAL variants (SHADOWS
 * only when a directional light casts shadows) and no light-pass program for
 * directional lights; the canyon's light pass is skipped and says why. */
static void fold_case(scene *s, const char *name, bool shadowed_directional, bool only_directional)
{
    char what[160];
    frame_out a, b;
    renderer_options o = options(LIGHT_VOLUMES_STENCIL, GBUFFER_CURTIS, false);
    render("forward-mpml", &o, s, &a);
    o.directional_in_base = true;
    render("forward-mpml", &o, s, &b);
    snprintf(what, sizeof what, "%s: directional lights in the base pass vs their own passes",
             name);
    expect_agree(what, &b.rgba8, &a.rgba8);
    set_check c = check_sets(s, false);
    assert_true(c.lights[LIGHT_DIRECTIONAL] > 0);
    assert_true(c.visible > 0);
    assert_int_equal(a.fs.total.draw_calls - b.fs.total.draw_calls,
                     (uint64_t)c.lights[LIGHT_DIRECTIONAL] * c.visible);
    assert_int_equal(b.fs.lights_drawn, a.fs.lights_drawn);
    /* the variants: folded base programs only when folded, no directional light pass */
    assert_int_equal(programs_with(&a.plan, "forward_base_directional", ""), 0);
    assert_true(programs_with(&a.plan, "forward_directional", "") > 0);
    assert_true(programs_with(&b.plan, "forward_base_directional", "") > 0);
    assert_int_equal(programs_with(&b.plan, "forward_base", ""),
                     programs_with(&b.plan, "forward_base_directional", ""));
    assert_int_equal(programs_with(&b.plan, "forward_directional", ""), 0);
    assert_int_equal(programs_with(&b.plan, "forward_base_directional_shadowed", ""),
                     shadowed_directional ? programs_with(&b.plan, "forward_base_directional", "")
                                          : 0);
    const pass_plan_entry *base = plan_pass(&b.plan, "base");
    assert_non_null(base);
    assert_non_null(strstr(base->reason, "directional light"));
    assert_non_null(strstr(base->reason, "(forward.directional_in_base)"));
    const pass_plan_entry *lights = plan_pass(&b.plan, "lights");
    assert_non_null(lights);
    assert_int_equal(lights->run, !only_directional);
    if (only_directional) {
        assert_string_equal(lights->reason,
                            "skipped: the scene's only lights are directional, shaded in the "
                            "base pass");
        assert_null(find_pass(&b.fs, "lights"));
    }
    frame_out_free(&a);
    frame_out_free(&b);
}

static void test_directional_in_base(void **state)
{
    (void)state;
    scene_light lights[4] = {spot(0, 10, 0, 0.2f, -1, 0.1f, 20, 30, true),
                             directional(-0.4f, -1.0f, -0.3f, true),
                             point(-8, 4, 8, 9, false),
                             spot(10, 6, 10, -0.5f, -1, -0.5f, 14, 25, false)};
    scene *s = shapes(lights, 4, EYE, TARGET);
    fold_case(s, "shapes", true, false);
    /* two directional lights, one shadowed */
    scene_light two[3] = {directional(-0.4f, -1.0f, -0.3f, true),
                          directional(0.6f, -0.5f, 0.2f, false), point(-8, 4, 8, 9, false)};
    set_lights(s, two, 3);
    fold_case(s, "shapes, two directional lights", true, false);
    /* more directional lights than the base pass holds: refused in prepare, saying so */
    scene_light nine[9];
    for (int i = 0; i < 9; i++)
        nine[i] = directional(-0.4f + 0.1f * (float)i, -1.0f, -0.3f, false);
    set_lights(s, nine, 9);
    renderer_options o = options(LIGHT_VOLUMES_STENCIL, GBUFFER_CURTIS, false);
    o.directional_in_base = true;
    char msg[512] = "";
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    renderer *r = test_renderer_create("forward-mpml", &o, msg, sizeof msg);
    assert_non_null(r);
    assert_false(renderer_prepare(r, s, msg, sizeof msg));
    assert_string_equal(msg, "forward-mpml: forward.directional_in_base shades at most 8 "
                             "directional lights in the base pass; the scene has 9");
    renderer_destroy(r);
    gl_context_poll_errors(ctx, "forward-mpml, nine directional lights");
    assert_int_equal(gl_context_error_count(ctx), 0);
    scene_destroy(s);

    char err[256];
    light_params lp = {.placement = PLACEMENT_SCENE, .radius = 1.0f,
                       .count = {.start = LIGHT_COUNT_ALL, .max = LIGHT_COUNT_ALL}};
    s = scene_build("canyon", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("canyon: %s", err);
    scene_update(s, 10.0);
    fold_case(s, "canyon", false, true);
    scene_destroy(s);
    s = scene_build("interior", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("interior: %s", err);
    scene_update(s, 10.0);
    fold_case(s, "interior", true, false);
    scene_destroy(s);
}

// >>plans

static void test_plans(void **state)
{
    (void)state;
    scene_light lights[5] = {spot(0, 10, 0, 0.2f, -1, 0.1f, 20, 30, true),
                             spot(8, 8, 8, -0.5f, -1, -0.5f, 20, 30, true),
                             directional(-0.4f, -1.0f, -0.3f, true),
                             point(-8, 4, 8, 9, true), point(8, 4, -8, 9, false)};
    scene *s = shapes(lights, 5, EYE, TARGET);
    static const char *const kinds[3] = {"deferred", "forward-mpml", "forward-spml"};
    for (int k = 0; k < 3; k++) {
        /* on: the pass runs and says why, the pool is a target, SHADOWS variants exist */
        renderer_options o = options(LIGHT_VOLUMES_STENCIL, GBUFFER_CURTIS, false);
        frame_out f;
        render(kinds[k], &o, s, &f);
        const pass_plan_entry *e = plan_pass(&f.plan, "shadows");
        assert_non_null(e);
        assert_true(e->run);
        assert_string_equal(e->reason,
                            "2 spot and 1 directional lights cast shadows (1 point light asks: "
                            "not drawn)");
        assert_string_equal(f.plan.pass[0].name, "shadows");
        assert_int_equal(programs_containing(&f.plan, "shadow_depth"), 1);
        /* the shadow variants say so in their names (cut at 63 characters in the plan,
         * the defines may not all show) */
        if (k == 0) {
            /* one program per light type; spot and directional in their shadow variant */
            assert_int_equal(programs_with(&f.plan, "deferred_point+", ""), 1);
            assert_int_equal(programs_with(&f.plan, "deferred_spot_shadowed+", ""), 1);
            assert_int_equal(programs_with(&f.plan, "deferred_directional_shadowed+", ""), 1);
            assert_int_equal(programs_containing(&f.plan, "_shadowed"), 2);
            assert_int_equal(programs_with(&f.plan, "deferred_spot+", ""), 0);
        } else if (k == 1) {
            /* 4 material variants x (spot, directional) with shadows, x point without */
            assert_int_equal(programs_with(&f.plan, "forward_spot_shadowed+", ""), 4);
            assert_int_equal(programs_with(&f.plan, "forward_directional_shadowed+", ""), 4);
            /* the shortest shows the pool's size */
            assert_int_equal(programs_with(&f.plan, "forward_spot_shadowed+LIGHT_TYPE=LIGHT_SPOT"
                                                    "+MAX_SHADOWS=3", ""), 1);
            assert_int_equal(programs_with(&f.plan, "forward_point+", "SHADOWS"), 0);
            assert_int_equal(programs_with(&f.plan, "forward_point+", ""), 4);
            assert_int_equal(programs_with(&f.plan, "forward_spot+", ""), 0);
        } else {
            assert_int_equal(programs_with(&f.plan, "forward_spml_shadowed+", ""), 4);
            assert_int_equal(programs_with(&f.plan, "forward_spml_shadowed+MAX_LIGHTS=16"
                                                    "+MAX_SHADOWS=3+SHADOWS", ""), 1);
            assert_int_equal(programs_with(&f.plan, "forward_spml+", ""), 0);
        }
        const target_plan_entry *t = target_named(&f.plan, "shadow.maps");
        assert_non_null(t);
        assert_string_equal(t->name, "shadow.maps[3]");
        assert_string_equal(t->format, "depth32f");
        assert_int_equal(t->width, 1024);
        assert_int_equal(t->height, 1024);
        assert_int_equal(t->bytes, (uint64_t)1024 * 1024 * 4 * 3);
        uint64_t sum = 0;
        for (size_t i = 0; i < f.plan.ntargets; i++)
            sum += f.plan.target[i].bytes;
        assert_true(f.plan.target_bytes >= sum);
        frame_out_free(&f);

        /* off: skipped, says so, nothing of it built */
        o.no_shadows = true;
        render(kinds[k], &o, s, &f);
        e = plan_pass(&f.plan, "shadows");
        assert_non_null(e);
        assert_false(e->run);
        assert_string_equal(e->reason, "shadows: off");
        assert_int_equal(programs_containing(&f.plan, "SHADOWS"), 0);
        assert_int_equal(programs_containing(&f.plan, "shadow"), 0);
        assert_null(target_named(&f.plan, "shadow.maps"));
        assert_null(find_pass(&f.fs, "shadows"));
        frame_out_free(&f);

        /* a smaller pool by option */
        o.no_shadows = false;
        o.shadow_map_size = 256;
        render(kinds[k], &o, s, &f);
        t = target_named(&f.plan, "shadow.maps");
        assert_non_null(t);
        assert_int_equal(t->bytes, (uint64_t)256 * 256 * 4 * 3);
        frame_out_free(&f);
    }

    /* only point lights ask: skipped (they cannot), said so */
    scene_light points[2] = {point(-8, 4, 8, 9, true), point(8, 4, -8, 9, true)};
    set_lights(s, points, 2);
    for (int k = 0; k < 3; k++) {
        renderer_options o = options(LIGHT_VOLUMES_STENCIL, GBUFFER_CURTIS, false);
        frame_out f;
        render(kinds[k], &o, s, &f);
        const pass_plan_entry *e = plan_pass(&f.plan, "shadows");
        assert_non_null(e);
        assert_false(e->run);
        assert_string_equal(e->reason,
                            "2 point lights ask for shadows: only spot and directional lights "
                            "cast them");
        assert_int_equal(programs_containing(&f.plan, "SHADOWS"), 0);
        assert_int_equal(programs_containing(&f.plan, "shadow"), 0);
        assert_null(find_pass(&f.fs, "shadows"));
        frame_out_free(&f);
    }

    /* no light asks: deferred lists the pass as skipped, the forward plans leave it out */
    scene_light plain[2] = {spot(0, 10, 0, 0.2f, -1, 0.1f, 20, 30, false),
                            directional(-0.4f, -1.0f, -0.3f, false)};
    set_lights(s, plain, 2);
    for (int k = 0; k < 3; k++) {
        renderer_options o = options(LIGHT_VOLUMES_STENCIL, GBUFFER_CURTIS, false);
        frame_out f;
        render(kinds[k], &o, s, &f);
        const pass_plan_entry *e = plan_pass(&f.plan, "shadows");
        if (k == 0) {
            assert_non_null(e);
            assert_false(e->run);
            assert_string_equal(e->reason, "no light casts shadows");
        } else {
            assert_null(e);
        }
        assert_int_equal(programs_containing(&f.plan, "SHADOWS"), 0);
        assert_int_equal(programs_containing(&f.plan, "shadow"), 0);
        assert_null(target_named(&f.plan, "shadow.maps"));
        assert_null(find_pass(&f.fs, "shadows"));
        frame_out_free(&f);
    }
    check_draws(s, false);
    scene_destroy(s);
}

// >>extremes

static void finite_everywhere(scene *s, const char *what)
{
    static const char *const kinds[3] = {"deferred", "forward-mpml", "forward-spml"};
    for (int k = 0; k < 3; k++)
        for (int m = 0; m < (k == 0 ? 4 : 1); m++) {
            for (int g = 0; g < (k == 0 ? 2 : 1); g++) {
                renderer_options o = options(MODES[m], g ? GBUFFER_CURTIS : GBUFFER_REFERENCE,
                                             false);
                if (k == 0 && g == 1 && m == 0)
                    o.gbuffer_position = GBUFFER_POSITION_DEPTH;
                frame_out f;
                render(kinds[k], &o, s, &f);   /* asserts finite light and no GL error */
                assert_non_null(find_pass(&f.fs, "shadows"));
                (void)what;
                frame_out_free(&f);
            }
        }
}

static void test_extremes(void **state)
{
    (void)state;
    /* lights exactly on the floor's top (y = 0): shining up, down into it, along it; a
     * spot of almost 90 degrees; one of a tiny angle; one of zero range; light straight
     * down */
    scene_light on_surface[7] = {spot(0, 0, 0, 0, 1, 0, 20, 40, true),
                                 spot(3, 0, 3, 0, -1, 0, 20, 40, true),
                                 spot(-3, 0, 3, 1, 0, 0, 20, 40, true),
                                 spot(0, 8, 0, 0, -1, 0, 20, 89.99f, true),
                                 spot(4, 8, 0, 0, -1, 0, 20, 0.001f, true),
                                 spot(-4, 8, 0, 0, -1, 0, 0, 30, true),
                                 directional(0, -1, 0, true)};
    scene *s = shapes(on_surface, 7, EYE, TARGET);
    finite_everywhere(s, "lights on a surface");

    /* the camera inside a shadowed spot's cone */
    scene_light inside[2] = {spot(0, 14, 32, 0, -0.5f, -1, 60, 35, true),
                             directional(0.2f, -1, 0.1f, true)};
    set_lights(s, inside, 2);
    finite_everywhere(s, "camera inside a spot");

    /* looking at the sky: nothing visible, no receiver */
    static const float UP_TARGET[3] = {0.0f, 200.0f, 30.0f};
    look(s, EYE, UP_TARGET);
    finite_everywhere(s, "nothing visible");
    scene_destroy(s);
}

GL_TEST_MAIN(ctx, W, H,
             cmocka_unit_test(test_spot_occluder),
             cmocka_unit_test(test_directional_occluder),
             cmocka_unit_test(test_agreement),
             cmocka_unit_test(test_sets_and_draws),
             cmocka_unit_test(test_catalog_draws),
             cmocka_unit_test(test_directional_in_base),
             cmocka_unit_test(test_plans),
             cmocka_unit_test(test_extremes))
