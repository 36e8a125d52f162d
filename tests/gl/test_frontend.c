/* The code every renderer shares above the GL layer: the frontend (visible objects,
 * light culling, illumination sets, eye-inside flags, sort order; renderers/frame/frontend.h),
 * the packing of lights and frame values for the shaders (renderers/frame/shading.h) and the
 * scene on the GPU with its draws (renderers/frame/scene_gpu.h), on whatever headless GL this
 * machine has (llvmpipe in CI). Scenes are the catalog's "shapes" and hand-built poses
 * of it. GL tests run in a debug context and fail on any GL error. Exits 77 (skip) when
 * no EGL display can be created. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "renderers/frame/frontend.h"
#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/shaders.h"
#include "renderers/gl/state.h"
#include "renderers/gl/target.h"
#include "renderers/frame/scene_gpu.h"
#include "renderers/frame/shading.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 64, H = 48 };

// >>helpers

static scene *build_shapes(uint32_t nlights, int w, int h)
{
    light_params lp = {
        .placement = PLACEMENT_RANDOM,
        .seed = 1337,
        .rng = RNG_MSVC,
        .count = {.growth = false, .start = nlights, .max = nlights},
        .radius = 10.0f,
        .color_max = 0.3f,
        .attenuation = ATTENUATION_INVERSE_SQUARE,
    };
    char err[256] = "";
    scene *s = scene_build("shapes", &lp, w, h, err, sizeof err);
    if (!s)
        fail_msg("scene_build(shapes) failed: %s", err);
    return s;
}

/* The camera of the hand-built cases: eye at the origin looking down -Z, 90 degrees
 * vertical and horizontal (aspect 1), near 1, far 100. Inside the frustum:
 * |x| <= -z, |y| <= -z, 1 <= -z <= 100. */
static void pose_camera(scene *s)
{
    sm_vec3 eye = {0, 0, 0}, target = {0, 0, -1}, up = {0, 1, 0};
    sm_vec3_copy(eye, s->cam.eye);
    sm_vec3_copy(target, s->cam.target);
    sm_vec3_copy(up, s->cam.up);
    s->cam.fovy = SM_PI_2;
    s->cam.znear = 1.0f;
    s->cam.zfar = 100.0f;
    sm_lookat(eye, target, up, s->view);
    sm_perspective(SM_PI_2, 1.0f, 1.0f, 100.0f, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
}

/* Every object the same mesh and material (so the sort keeps object order), its
 * bounding sphere parked far outside the view. */
static void park_objects(scene *s)
{
    for (uint32_t i = 0; i < s->nobjects; i++) {
        s->objects[i].mesh = 1;
        s->objects[i].material = 1;
        sm_vec4_make(0.0f, 1000.0f, 0.0f, 1.0f, s->objects[i].bsphere);
    }
}

static void set_point(scene_light *l, float x, float y, float z, float r)
{
    memset(l, 0, sizeof *l);
    l->type = LIGHT_POINT;
    sm_vec3_make(x, y, z, l->position);
    sm_vec3_make(0.0f, -1.0f, 0.0f, l->direction);
    sm_vec3_make(1.0f, 1.0f, 1.0f, l->color);
    l->radius = r;
}

static void set_spot(scene_light *l, float x, float y, float z, float dx, float dy, float dz,
                     float angle_deg, float r)
{
    set_point(l, x, y, z, r);
    l->type = LIGHT_SPOT;
    sm_vec3_make(dx, dy, dz, l->direction);
    sm_vec3_normalize(l->direction);
    l->spot_angle = sm_deg2rad(angle_deg);
    l->spot_exponent = 2.0f;
}

static void set_directional(scene_light *l)
{
    set_point(l, 0.0f, 0.0f, 0.0f, 0.0f);
    l->type = LIGHT_DIRECTIONAL;
}

static void assert_u32_list(const uint32_t *got, uint32_t ngot, const uint32_t *want,
                            uint32_t nwant, const char *what)
{
    char g[512] = "", w[512] = "";
    size_t gl_ = 0, wl = 0;
    for (uint32_t i = 0; i < ngot && gl_ < sizeof g - 16; i++)
        gl_ += (size_t)snprintf(g + gl_, sizeof g - gl_, " %u", got[i]);
    for (uint32_t i = 0; i < nwant && wl < sizeof w - 16; i++)
        wl += (size_t)snprintf(w + wl, sizeof w - wl, " %u", want[i]);
    if (ngot != nwant || (nwant && memcmp(got, want, nwant * sizeof *want) != 0))
        fail_msg("%s:%s, expected%s", what, g, w);
}

/* The illumination set of the frontend's j-th light. */
static void assert_illum(const frontend *f, uint32_t j, const uint32_t *want, uint32_t n)
{
    char what[64];
    snprintf(what, sizeof what, "illumination set of light %u", f->lights[j]);
    assert_u32_list(f->illum + f->illum_start[j], f->illum_start[j + 1] - f->illum_start[j],
                    want, n, what);
}

/* Index of light li in f->lights, or fail. */
static uint32_t light_slot(const frontend *f, uint32_t li)
{
    for (uint32_t j = 0; j < f->nlights; j++)
        if (f->lights[j] == li)
            return j;
    fail_msg("light %u is not in the frontend's list", li);
    return 0;
}

// >>frontend: no GL

static void test_shapes_sort_order(void **state)
{
    (void)state;
    scene *s = build_shapes(4, W, H);
    frontend f;
    char err[256];
    assert_true(frontend_init(&f, s, err, sizeof err));
    frontend_build(&f, s);
    /* t = 0: the camera at (35, 18, 0) sees the floor and the whole 3 x 3 grid.
     * Keys: material 1 has no maps (diffuse key 0), material 2 the checker (texture 0:
     * key 1), material 3 the bricks (texture 2: key 3), the floor's material 0 the
     * ground (texture 5: key 6); within a diffuse map by material, then mesh:
     *   mat 1: objects 1 (mesh 1), 9 (mesh 3), 6 (mesh 5)
     *   mat 2: objects 8 (mesh 1), 2 (mesh 2), 4 (mesh 4)
     *   mat 3: objects 5 (mesh 2), 3 (mesh 3), 7 (mesh 6)
     *   mat 0: object 0 */
    static const uint32_t want[] = {1, 9, 6, 8, 2, 4, 5, 3, 7, 0};
    assert_u32_list(f.visible, f.nvisible, want, 10, "visible (shapes, t = 0)");
    for (uint32_t i = 1; i < f.nvisible; i++)
        assert_true(frontend_sort_key(s, f.visible[i - 1]) <= frontend_sort_key(s, f.visible[i]));

    /* the key's fields */
    assert_int_equal(frontend_sort_key(s, 0), (uint64_t)6 << 42 | (uint64_t)0 << 21 | 0);
    assert_int_equal(frontend_sort_key(s, 7), (uint64_t)3 << 42 | (uint64_t)3 << 21 | 6);
    assert_int_equal(frontend_sort_key(s, 1), (uint64_t)0 << 42 | (uint64_t)1 << 21 | 1);

    /* ties keep object order, whatever qsort does with equal keys */
    for (uint32_t i = 0; i < s->nobjects; i++) {
        s->objects[i].mesh = 3;
        s->objects[i].material = 2;
    }
    frontend_build(&f, s);
    static const uint32_t in_order[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    assert_u32_list(f.visible, f.nvisible, in_order, 10, "visible, all keys equal");
    /* two tie groups interleaved by index */
    for (uint32_t i = 0; i < s->nobjects; i++)
        s->objects[i].material = i % 2 ? 1 : 2;
    frontend_build(&f, s);
    static const uint32_t odd_even[] = {1, 3, 5, 7, 9, 0, 2, 4, 6, 8};
    assert_u32_list(f.visible, f.nvisible, odd_even, 10, "visible, two tie groups");

    frontend_free(&f);
    frontend_free(&f);   /* twice is fine */
    scene_destroy(s);
}

/* A hand-made scene of n objects in front of the camera, with keys from a small
 * pseudo-random sequence (many ties): the sort against insertion sort, and the
 * frontend growing past the size it was made for. */
/* glass (issue 12): the translucent objects are not in `visible`; the visible ones are in
 * `translucent`, back to front by the view depth of their spheres' centres; none is in
 * an illumination set (forward-mpml's frontend computes them). */
static void test_translucent_list(void **state)
{
    (void)state;
    char err[256];
    light_params lp = {.placement = PLACEMENT_SCENE, .count = {.start = 12, .max = 12}};
    scene *s = scene_build("glass", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    frontend f;
    assert_true(frontend_init(&f, s, err, sizeof err));
    f.no_illumination = false;
    static const double times[] = {0.0, 7.5, 20.0};
    for (size_t t = 0; t < sizeof times / sizeof times[0]; t++) {
        scene_update(s, times[t]);
        frontend_build(&f, s);
        assert_int_equal(f.nvisible, 2);   /* the floor and the pillar */
        for (uint32_t i = 0; i < f.nvisible; i++)
            assert_false(scene_material_translucent(
                &s->materials[s->objects[f.visible[i]].material]));
        assert_int_equal(f.ntranslucent, 28);   /* all in view from the orbit */
        float prev = INFINITY;
        for (uint32_t i = 0; i < f.ntranslucent; i++) {
            const float *c = s->objects[f.translucent[i]].bsphere;
            sm_vec3 v;
            sm_mat4_mulv3(s->view, c, 1.0f, v);
            assert_true(-v[2] <= prev);   /* farthest first */
            prev = -v[2];
            assert_true(scene_material_translucent(
                &s->materials[s->objects[f.translucent[i]].material]));
        }
        for (uint32_t j = 0; j < f.illum_start[f.nlights]; j++)
            assert_true(f.illum[j] < 2);
    }
    /* t = 0, camera on +x: the panes (objects 2..5, x = 2.25, 0.75, -0.75, -2.25) come
     * in the order 5, 4, 3, 2 */
    scene_update(s, 0.0);
    frontend_build(&f, s);
    uint32_t panes[4], n = 0;
    for (uint32_t i = 0; i < f.ntranslucent; i++)
        if (f.translucent[i] >= 2 && f.translucent[i] < 6)
            panes[n++] = f.translucent[i];
    static const uint32_t want[] = {5, 4, 3, 2};
    assert_u32_list(panes, n, want, 4, "glass panes, back to front");
    frontend_free(&f);
    scene_destroy(s);
}

static void test_sort_many(void **state)
{
    (void)state;
    scene *s = build_shapes(0, W, H);
    frontend f;
    char err[256];
    assert_true(frontend_init(&f, s, err, sizeof err));
    size_t cap0 = f.cap_objects;
    enum { N = 300 };
    scene big = *s;
    scene_object objs[N];
    memset(objs, 0, sizeof objs);
    uint32_t x = 12345;
    for (uint32_t i = 0; i < N; i++) {
        x = x * 1103515245u + 12345u;
        objs[i].material = (x >> 16) % s->nmaterials;
        objs[i].mesh = (x >> 8) % 3;
        sm_vec4_make(0.0f, 0.0f, -10.0f, 1.0f, objs[i].bsphere);
    }
    big.objects = objs;
    big.nobjects = N;
    pose_camera(&big);
    frontend_build(&f, &big);
    assert_true(f.cap_objects >= N && f.cap_objects > cap0);
    assert_int_equal(f.nvisible, N);
    uint32_t want[N];
    for (uint32_t i = 0; i < N; i++) {   /* insertion sort: stable */
        uint32_t j = i;
        uint64_t k = frontend_sort_key(&big, i);
        while (j > 0 && frontend_sort_key(&big, want[j - 1]) > k) {
            want[j] = want[j - 1];
            j--;
        }
        want[j] = i;
    }
    assert_u32_list(f.visible, f.nvisible, want, N, "visible, 300 objects");
    frontend_free(&f);
    scene_destroy(s);
}

static void test_visible_sets(void **state)
{
    (void)state;
    scene *s = build_shapes(0, W, H);
    frontend f;
    char err[256];
    assert_true(frontend_init(&f, s, err, sizeof err));
    pose_camera(s);
    park_objects(s);
    /* 0 inside; 1 straddles the left plane (signed distance -0.35, radius 1); 2 just
     * outside it (-1.41); 3 behind the eye; 4 straddles the near plane; 5 beyond the
     * far plane (-2); 6 straddles the far plane; 7 straddles top and right at once;
     * 8, 9 parked. */
    sm_vec4_make(0.0f, 0.0f, -10.0f, 1.0f, s->objects[0].bsphere);
    sm_vec4_make(-10.5f, 0.0f, -10.0f, 1.0f, s->objects[1].bsphere);
    sm_vec4_make(-12.0f, 0.0f, -10.0f, 1.0f, s->objects[2].bsphere);
    sm_vec4_make(0.0f, 0.0f, 5.0f, 1.0f, s->objects[3].bsphere);
    sm_vec4_make(0.0f, 0.0f, -0.5f, 1.0f, s->objects[4].bsphere);
    sm_vec4_make(0.0f, 0.0f, -102.0f, 1.0f, s->objects[5].bsphere);
    sm_vec4_make(0.0f, 0.0f, -100.5f, 1.0f, s->objects[6].bsphere);
    sm_vec4_make(20.5f, 20.5f, -20.0f, 1.0f, s->objects[7].bsphere);
    frontend_build(&f, s);
    static const uint32_t want[] = {0, 1, 4, 6, 7};
    assert_u32_list(f.visible, f.nvisible, want, 5, "visible");
    assert_int_equal(f.nlights, 0);
    assert_int_equal(f.illum_start[0], 0);

    /* the planes are those of viewproj, normalized, pointing inside */
    sm_vec3 origin_ahead = {0.0f, 0.0f, -50.0f};
    for (int i = 0; i < 6; i++) {
        assert_float_equal(sm_vec3_norm(f.planes[i]), 1.0f, 1e-5f);
        assert_true(sm_plane_distance(f.planes[i], origin_ahead) > 0.0f);
    }
    assert_float_equal(sm_plane_distance(f.planes[SM_NEAR], origin_ahead), 49.0f, 1e-3f);
    /* the eye comes from the view matrix, not scene.cam */
    assert_float_equal(f.eye[0], 0.0f, 1e-6f);
    assert_float_equal(f.eye[2], 0.0f, 1e-6f);

    /* a scaled object: the bounding sphere the scene posed decides, as it is */
    sm_vec4_make(-13.0f, 0.0f, -10.0f, 2.2f, s->objects[2].bsphere);
    frontend_build(&f, s);
    static const uint32_t want2[] = {0, 1, 2, 4, 6, 7};
    assert_u32_list(f.visible, f.nvisible, want2, 6, "visible, object 2 grown");

    frontend_free(&f);
    scene_destroy(s);
}

static void test_lights_and_illumination(void **state)
{
    (void)state;
    scene *s = build_shapes(8, W, H);
    frontend f;
    char err[256];
    assert_true(frontend_init(&f, s, err, sizeof err));
    pose_camera(s);
    park_objects(s);
    /* visible objects: A = 0, B = 1 (straddling the left plane), E = 4, G = 6 */
    sm_vec4_make(0.0f, 0.0f, -10.0f, 1.0f, s->objects[0].bsphere);
    sm_vec4_make(-10.5f, 0.0f, -10.0f, 1.0f, s->objects[1].bsphere);
    sm_vec4_make(0.0f, 0.0f, -0.5f, 1.0f, s->objects[4].bsphere);
    sm_vec4_make(0.0f, 0.0f, -100.5f, 1.0f, s->objects[6].bsphere);

    scene_light *L = s->lights;
    set_point(&L[0], 0.0f, 0.0f, -10.0f, 2.0f);       /* in; lights A */
    set_point(&L[1], -13.0f, 0.0f, -10.0f, 2.0f);     /* left plane -2.12 < -2: culled */
    set_point(&L[2], -12.5f, 0.0f, -10.0f, 2.0f);     /* -1.77: in; lights B */
    set_spot(&L[3], 0.0f, 0.0f, -5.0f, 0, 0, 1, 20.0f, 10.0f);  /* towards the eye: E only
                                                                   (A is behind its apex) */
    set_spot(&L[4], 0.0f, 0.0f, 5.0f, 0, 0, -1, 30.0f, 10.0f);  /* from behind: E (A beyond range) */
    set_directional(&L[5]);                           /* everything visible */
    set_spot(&L[6], 0.0f, 0.0f, 5.0f, 0, 0, 1, 30.0f, 3.0f);    /* behind the eye, pointing
                                                                   away: culled */
    set_point(&L[7], 0.0f, 0.0f, -10.0f, 2.0f);       /* would light A, but is not active */
    s->nlights_active = 7;
    frontend_build(&f, s);

    static const uint32_t vis[] = {0, 1, 4, 6};
    assert_u32_list(f.visible, f.nvisible, vis, 4, "visible");
    static const uint32_t lights[] = {0, 2, 3, 4, 5};
    assert_u32_list(f.lights, f.nlights, lights, 5, "lights");
    static const uint32_t starts[] = {0, 1, 2, 3, 4, 8};
    assert_u32_list(f.illum_start, 6, starts, 6, "illum_start");
    assert_illum(&f, 0, (const uint32_t[]){0}, 1);
    assert_illum(&f, 1, (const uint32_t[]){1}, 1);
    assert_illum(&f, 2, (const uint32_t[]){4}, 1);
    assert_illum(&f, 3, (const uint32_t[]){4}, 1);
    assert_illum(&f, 4, (const uint32_t[]){0, 1, 4, 6}, 4);
    /* eye_inside: the points are far; both spots' cones pass through the eye; directional 1 */
    static const uint32_t inside[] = {0, 0, 1, 1, 1};
    assert_u32_list(f.eye_inside, f.nlights, inside, 5, "eye_inside");

    /* the spot turned away from E (pointing -Z from z = -5): lights A instead */
    set_spot(&L[3], 0.0f, 0.0f, -5.0f, 0, 0, -1, 20.0f, 10.0f);
    frontend_build(&f, s);
    assert_illum(&f, light_slot(&f, 3), (const uint32_t[]){0}, 1);
    assert_int_equal(f.eye_inside[light_slot(&f, 3)], 0);
    /* a spot just too narrow for B beside its axis: B at perpendicular distance 10.5,
     * axial 5 from a spot at (0, 0, -5) pointing -Z; half angle 60: reaches B */
    set_spot(&L[3], 0.0f, 0.0f, -5.0f, 0, 0, -1, 60.0f, 10.0f);
    frontend_build(&f, s);
    assert_illum(&f, light_slot(&f, 3), (const uint32_t[]){0, 1}, 2);
    set_spot(&L[3], 0.0f, 0.0f, -5.0f, 0, 0, -1, 45.0f, 10.0f);   /* 10.5 - 5 = 5.5 from the
                                                                     side line: misses B */
    frontend_build(&f, s);
    assert_illum(&f, light_slot(&f, 3), (const uint32_t[]){0}, 1);

    /* every active light counts once the active count grows; none when it is 0 */
    s->nlights_active = 8;
    frontend_build(&f, s);
    assert_int_equal(f.nlights, 6);
    assert_int_equal(f.lights[5], 7);
    s->nlights_active = 0;
    frontend_build(&f, s);
    assert_int_equal(f.nlights, 0);
    assert_int_equal(f.illum_start[0], 0);

    frontend_free(&f);
    scene_destroy(s);
}

static void test_eye_inside(void **state)
{
    (void)state;
    scene *s = build_shapes(8, W, H);
    frontend f;
    char err[256];
    assert_true(frontend_init(&f, s, err, sizeof err));
    /* the drawn sphere's vertices: 1.0389 x 1.1 x radius (mesh_light_sphere 16 x 8) */
    assert_float_equal(f.sphere_vertex_radius, 1.0389f, 1e-3f);
    assert_true(f.cone_apex_z > 0.0f && f.cone_apex_z < 1e-3f);
    assert_float_equal(f.cone_base_z, -1.0001f, 1e-5f);
    assert_true(f.cone_rim > 1.0002f && f.cone_rim < 1.03f);
    pose_camera(s);
    park_objects(s);
    scene_light *L = s->lights;
    /* bound of a point light of radius 2: 2 x 1.1 x 1.0389 = 2.2856 */
    set_point(&L[0], 0.0f, 0.0f, -1.5f, 2.0f);   /* the eye inside */
    set_point(&L[1], 0.0f, 0.0f, -4.0f, 2.0f);   /* eye 4, near rectangle 3: outside */
    set_point(&L[2], 1.8f, 0.0f, -2.0f, 2.0f);   /* eye 2.69 away, the near rectangle's
                                                    corner region 1.28: cut by the near plane */
    set_point(&L[3], 2.5f, 0.0f, -2.5f, 1.5f);   /* crosses the near plane (bound 1.714 >
                                                    1.5) but 2.12 from its rectangle: 0 */
    set_point(&L[4], 0.0f, 0.0f, -3.25f, 2.0f);  /* 2.25 from the near plane: 1.1 x 2 = 2.2
                                                    clears it, the drawn vertices (2.2856)
                                                    do not */
    set_spot(&L[5], 0.0f, 0.0f, -3.0f, 0, 0, 1, 30.0f, 5.0f);    /* reaches past the eye */
    set_spot(&L[6], 0.0f, 0.0f, -3.0f, 0, 0, -1, 30.0f, 5.0f);   /* points away: 0 */
    set_spot(&L[7], 0.0f, 3.0f, -4.0f, 0, -1, 0, 20.0f, 6.0f);   /* down through the view,
                                                                    1.9 from the near plane's
                                                                    top edge: cut */
    s->nlights_active = 8;
    frontend_build(&f, s);
    static const uint32_t lights[] = {0, 1, 2, 3, 4, 5, 6, 7};
    assert_u32_list(f.lights, f.nlights, lights, 8, "lights");
    static const uint32_t inside[] = {1, 0, 1, 0, 1, 1, 0, 1};
    assert_u32_list(f.eye_inside, f.nlights, inside, 8, "eye_inside");

    /* the bounds themselves */
    sm_vec4 b;
    frontend_light_volume_bound(&f, &L[1], b);
    assert_float_equal(b[2], -4.0f, 0.0f);
    assert_float_equal(b[3], 2.0f * 1.1f * f.sphere_vertex_radius, 1e-4f);
    frontend_light_volume_bound(&f, &L[6], b);
    /* apex (0,0,-3) and the base disc of radius ~5 tan 30 x rim at 5 along -Z: the
     * circumsphere through both */
    float h = 5.0f * (f.cone_apex_z - f.cone_base_z), r = 5.0f * tanf(sm_deg2rad(30.0f)) * f.cone_rim;
    float t = (h * h + r * r) / (2.0f * h);
    assert_float_equal(b[2], -3.0f + 5.0f * f.cone_apex_z - t, 1e-4f);   /* apex behind the light */
    assert_float_equal(b[3], t, 1e-3f);
    set_directional(&L[0]);
    frontend_light_volume_bound(&f, &L[0], b);
    assert_true(isinf(b[3]));

    /* a wide spot (60 degrees: base radius > height) is bounded about its base */
    sm_vec3 apex = {0, 0, 0}, dir = {0, 0, -1};
    frontend_spot_cone_bound(apex, dir, sm_deg2rad(60.0f), 2.0f, b);
    assert_float_equal(b[2], -2.0f, 1e-6f);
    assert_float_equal(b[3], 2.0f * tanf(sm_deg2rad(60.0f)), 1e-4f);

    frontend_free(&f);
    scene_destroy(s);
}

static void test_no_per_frame_allocation(void **state)
{
    (void)state;
    scene *s = build_shapes(64, W, H);
    frontend f;
    char err[256];
    assert_true(frontend_init(&f, s, err, sizeof err));
    assert_true(f.cap_objects >= s->nobjects);
    assert_true(f.cap_lights >= 64);
    assert_true(f.cap_illum >= (size_t)64 * s->nobjects);
    void *p[6] = {f.visible, f.lights, f.illum_start, f.illum, f.eye_inside, f.sort};
    uint32_t most = 0;
    for (int k = 0; k < 120; k++) {
        scene_update(s, k * 0.25);
        frontend_build(&f, s);
        void *q[6] = {f.visible, f.lights, f.illum_start, f.illum, f.eye_inside, f.sort};
        assert_memory_equal(p, q, sizeof p);
        assert_false(f.truncated);
        /* every set is a subsequence of visible, each light a point light in range */
        for (uint32_t j = 0; j < f.nlights; j++) {
            const scene_light *l = &s->lights[f.lights[j]];
            assert_true(f.lights[j] < s->nlights_active);
            uint32_t v = 0;
            for (uint32_t e = f.illum_start[j]; e < f.illum_start[j + 1]; e++) {
                while (v < f.nvisible && f.visible[v] != f.illum[e])
                    v++;
                assert_true(v < f.nvisible);
                const float *bs = s->objects[f.illum[e]].bsphere;
                assert_true(sm_vec3_distance(bs, l->position) <= bs[3] + l->radius);
            }
        }
        if (f.illum_start[f.nlights] > most)
            most = f.illum_start[f.nlights];
    }
    assert_true(most > 0);
    frontend_free(&f);
    scene_destroy(s);
}

// >>shading: no GL

static void test_pack_light(void **state)
{
    (void)state;
    sm_mat4 view;
    sm_vec3 eye = {1, 2, 3}, target = {1, 2, -7}, up = {0, 1, 0};
    sm_lookat(eye, target, up, view);   /* a translation by (-1, -2, -3) */
    scene_light l;
    set_spot(&l, 4, 5, 6, 0, 0, -2, 60.0f, 7.0f);
    l.direction[2] = -2.0f;   /* not unit: the packing normalizes */
    l.color[1] = 0.5f;
    l.spot_exponent = 8.0f;
    l.attenuation = ATTENUATION_QUADRATIC;
    l.att_a = 0.1f;
    l.att_b = 0.2f;
    l.att_c = 0.3f;
    gpu_light g;
    shading_pack_light(&l, view, &g);
    const float want[5][4] = {
        {3, 3, 3, 7},
        {1, 0.5f, 1, 1},
        {0, 0, -1, 0.5f},
        {8, 2, 0, 0},
        {0.1f, 0.2f, 0.3f, 0},
    };
    for (int i = 0; i < 5; i++)
        for (int k = 0; k < 4; k++)
            assert_float_equal(g.v[i][k], want[i][k], 1e-6f);

    /* a rotated view: position as a point, direction as a vector */
    sm_vec3 eye2 = {0, 0, 0}, target2 = {1, 0, 0};
    sm_lookat(eye2, target2, up, view);   /* looking down +X: world +X is view -Z */
    set_point(&l, 5, 0, 0, 3);
    l.attenuation = ATTENUATION_LINEAR_RANGE;
    sm_vec3_make(1, 0, 0, l.direction);
    shading_pack_light(&l, view, &g);
    assert_float_equal(g.v[0][2], -5.0f, 1e-5f);
    assert_float_equal(g.v[0][0], 0.0f, 1e-5f);
    assert_float_equal(g.v[2][2], -1.0f, 1e-5f);
    assert_float_equal(g.v[2][3], -1.0f, 0.0f);   /* not a spot: no cone */
    assert_float_equal(g.v[1][3], 0.0f, 0.0f);
    assert_float_equal(g.v[3][1], 1.0f, 0.0f);
    set_directional(&l);
    shading_pack_light(&l, view, &g);
    assert_float_equal(g.v[1][3], 2.0f, 0.0f);
    assert_float_equal(g.v[2][1], -1.0f, 1e-6f);   /* down stays down */
}

static void test_pack_frame(void **state)
{
    (void)state;
    scene *s = build_shapes(0, 160, 120);
    gpu_frame fr;
    /* std140: 2 mat4 + 4 vec4, then (ENVIRONMENT) a mat4 and 10 vec4 */
    assert_int_equal(sizeof fr, 192 + 64 + 160);
    assert_int_equal(offsetof(gpu_frame, ambient), 128);
    assert_int_equal(offsetof(gpu_frame, clip), 176);
    assert_int_equal(offsetof(gpu_frame, view_to_world), 192);
    assert_int_equal(offsetof(gpu_frame, environment), 256);
    assert_int_equal(offsetof(gpu_frame, environment_sh), 272);
    assert_int_equal(shading_frame_bytes(s), 192);   /* no environment: the block as before */
    shading_pack_frame(s, &fr);
    assert_memory_equal(fr.proj, s->proj, sizeof fr.proj);
    sm_mat4 p, ip, prod;
    memcpy(p, fr.proj, sizeof p);
    memcpy(ip, fr.inv_proj, sizeof ip);
    sm_mat4_mul(p, ip, prod);
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            assert_float_equal(prod[c][r], c == r ? 1.0f : 0.0f, 1e-5f);
    assert_float_equal(fr.ambient[0], 0.05f, 0.0f);
    assert_float_equal(fr.ambient[2], 0.06f, 0.0f);
    assert_float_equal(fr.viewport[0], 160.0f, 0.0f);
    assert_float_equal(fr.viewport[1], 120.0f, 0.0f);
    assert_float_equal(fr.viewport[2], 1.0f / 160.0f, 0.0f);
    assert_float_equal(fr.viewport[3], 1.0f / 120.0f, 0.0f);
    assert_float_equal(fr.sky[1], 0.6f, 0.0f);
    assert_float_equal(fr.sky[3], 1.0f, 0.0f);
    assert_float_equal(fr.clip[0], 0.5f, 0.0f);
    assert_float_equal(fr.clip[1], 200.0f, 0.0f);
    s->sky = false;
    shading_pack_frame(s, &fr);
    assert_float_equal(fr.sky[3], 0.0f, 0.0f);

    /* material defines, in order */
    const char *d[SHADING_MATERIAL_DEFINES];
    assert_int_equal(shading_material_defines(&s->materials[1], d), 0);
    assert_int_equal(shading_material_defines(&s->materials[2], d), 2);
    assert_string_equal(d[0], "DIFFUSE_MAP");
    assert_string_equal(d[1], "GLOSS_MAP");
    assert_int_equal(shading_material_defines(&s->materials[3], d), 3);
    assert_string_equal(d[0], "DIFFUSE_MAP");
    assert_string_equal(d[1], "NORMAL_MAP");
    assert_string_equal(d[2], "EMISSIVE_MAP");
    scene_material all = s->materials[3];
    all.gloss_map = 1;
    assert_int_equal(shading_material_defines(&all, d), 4);
    assert_string_equal(d[1], "GLOSS_MAP");
    assert_string_equal(d[3], "EMISSIVE_MAP");
    scene_destroy(s);
}

// >>GL fixture

typedef struct fixture {
    gl_context *ctx;
    scene *s;
    scene_gpu *g;
    gl_state *st;
    gl_target color, depth;
    gl_framebuffer fb;
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    char err[1024] = "";
    gl_context_desc desc = {.backend = GL_BACKEND_EGL, .device = -1, .debug = true,
                            .width = W, .height = H};
    f->ctx = gl_context_create(&desc, err, sizeof err);
    if (!f->ctx) {
        fprintf(stderr, "gl_context_create failed: %s\n", err);
        free(f);
        return -1;
    }
    f->s = build_shapes(8, W, H);
    f->g = scene_gpu_create(f->s, err, sizeof err);
    f->st = gl_state_create();
    if (!f->g || !f->st ||
        !gl_target_create(&f->color, &(gl_target_desc){.name = "color",
                          .format = GLT_FORMAT_RGBA8, .width = W, .height = H}, err, sizeof err) ||
        !gl_target_create(&f->depth, &(gl_target_desc){.name = "depth",
                          .format = GLT_FORMAT_DEPTH24_STENCIL8, .width = W, .height = H},
                          err, sizeof err) ||
        !gl_framebuffer_create(&f->fb, &(gl_framebuffer_desc){.name = "test",
                               .color = {&f->color}, .depth_stencil = &f->depth}, err, sizeof err)) {
        fprintf(stderr, "setup failed: %s\n", err);
        return -1;
    }
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    gl_context_poll_errors(f->ctx, "test end");
    uint64_t errors = gl_context_error_count(f->ctx);
    gl_framebuffer_destroy(&f->fb);
    gl_target_destroy(&f->color);
    gl_target_destroy(&f->depth);
    gl_state_destroy(f->st);
    scene_gpu_destroy(f->g);
    scene_gpu_destroy(NULL);
    scene_destroy(f->s);
    gl_context_destroy(f->ctx);
    free(f);
    if (errors) {
        fprintf(stderr, "%llu GL errors\n", (unsigned long long)errors);
        return -1;
    }
    return 0;
}

static void assert_no_gl_errors(fixture *f)
{
    gl_context_poll_errors(f->ctx, "test");
    assert_int_equal(gl_context_error_count(f->ctx), 0);
}

/* A program from raw sources (the tests' own fragment shaders, which the embedded
 * set has no business carrying): "#version 450 core", then the parts in order. */
static GLuint compile_stage(GLenum type, const char *const *parts, int nparts)
{
    const char *src[8];
    src[0] = "#version 450 core\n";
    for (int i = 0; i < nparts; i++)
        src[i + 1] = parts[i];
    GLuint sh = gl.CreateShader(type);
    gl.ShaderSource(sh, nparts + 1, src, NULL);
    gl.CompileShader(sh);
    GLint ok = 0;
    gl.GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = "";
        gl.GetShaderInfoLog(sh, sizeof log, NULL, log);
        fail_msg("test shader does not compile:\n%s", log);
    }
    return sh;
}

static GLuint test_program(const char *const *vs, int nvs, const char *const *fs, int nfs)
{
    GLuint v = compile_stage(GL_VERTEX_SHADER, vs, nvs);
    GLuint fr = compile_stage(GL_FRAGMENT_SHADER, fs, nfs);
    GLuint p = gl.CreateProgram();
    gl.AttachShader(p, v);
    gl.AttachShader(p, fr);
    gl.LinkProgram(p);
    gl.DeleteShader(v);
    gl.DeleteShader(fr);
    GLint ok = 0;
    gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = "";
        gl.GetProgramInfoLog(p, sizeof log, NULL, log);
        fail_msg("test program does not link:\n%s", log);
    }
    return p;
}

/* mesh.vert + surface.inc, writing `expr` (a vec3 of the Surface s). */
static GLuint surface_program(const char *defines, const char *expr)
{
    char main_src[512];
    snprintf(main_src, sizeof main_src,
             "layout(location = 0) out vec4 o_color;\n"
             "void main() { Surface s = surface_get(); o_color = vec4(%s, 1.0); }\n", expr);
    const char *vs[] = {gl_shader_source("mesh.vert")};
    /* surface.inc names its texture units from bindings.h: that file first, the
     * include line itself blanked (raw GLSL has no #include) */
    const char *surface = gl_shader_source("surface.inc");
    assert_non_null(surface);
    char *body = strdup(surface);
    assert_non_null(body);
    char *inc = strstr(body, "#include \"bindings.h\"");
    assert_non_null(inc);
    memset(inc, ' ', strlen("#include \"bindings.h\""));
    const char *fs[] = {defines, gl_shader_source("bindings.h"), body, main_src};
    assert_non_null(vs[0]);
    assert_non_null(fs[1]);
    GLuint p = test_program(vs, 1, fs, 4);
    free(body);
    return p;
}

static void read_color(fixture *f, uint8_t *px)
{
    gl.GetTextureImage(f->color.texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, W * H * 4, px);
}

/* px row 0 is the bottom row (GL's). */
static const uint8_t *pixel(const uint8_t *px, int x, int y)
{
    return px + ((size_t)y * W + (size_t)x) * 4;
}

static void begin_frame(fixture *f, const char *pass)
{
    gl_state_invalidate(f->st);
    gl_state_begin_pass(f->st, pass);
    gl_state_framebuffer(f->st, f->fb.fbo);
    gl_state_viewport(f->st, 0, 0, W, H);
    gl_state_clear(f->st, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT,
                   NULL, 1.0, 0);
}

// >>scene_gpu

static void test_draw_counts(void **state)
{
    fixture *f = *state;
    scene *s = f->s;
    GLuint prog = surface_program("#define DIFFUSE_MAP\n#define GLOSS_MAP\n#define NORMAL_MAP\n"
                                  "#define EMISSIVE_MAP\n",
                                  "s.diffuse + s.emissive + s.normal * s.gloss * s.shininess");
    frontend fe;
    char err[256];
    assert_true(frontend_init(&fe, s, err, sizeof err));
    for (int frame = 0; frame < 3; frame++) {
        scene_update(s, frame * 7.5);
        frontend_build(&fe, s);
        assert_true(fe.nvisible >= 8);
        /* what the cache must count: textures per unit where the bound one changes
         * (every unit unknown at the start), vertex arrays where the mesh changes */
        uint64_t want_tex = 0, want_vao = 0;
        int bound[4] = {-2, -2, -2, -2};
        int64_t last_mesh = -1;
        for (uint32_t i = 0; i < fe.nvisible; i++) {
            const scene_object *o = &s->objects[fe.visible[i]];
            const scene_material *m = &s->materials[o->material];
            const int maps[4] = {m->diffuse_map, m->gloss_map, m->normal_map, m->emissive_map};
            for (int u = 0; u < 4; u++)
                if (maps[u] >= 0 && maps[u] != bound[u]) {
                    want_tex++;
                    bound[u] = maps[u];
                }
            if ((int64_t)o->mesh != last_mesh) {
                want_vao++;
                last_mesh = o->mesh;
            }
        }
        begin_frame(f, "objects");
        scene_gpu_frame(f->g, s);
        gl_state_program(f->st, prog);
        gl_state_depth(f->st, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});
        gl_state_cull(f->st, GLS_CULL_BACK);
        for (uint32_t i = 0; i < fe.nvisible; i++)
            scene_gpu_draw_object(f->g, f->st, s, fe.visible[i]);
        pass_stats ps;
        gl_state_end_pass(f->st, &ps);
        const gls_counts *c = gl_state_pass_counts(f->st);
        assert_int_equal(ps.draw_calls, fe.nvisible);
        assert_int_equal(c->category[GLS_CAT_TEXTURE], want_tex);
        assert_int_equal(c->category[GLS_CAT_VERTEX_ARRAY], want_vao);
        assert_int_equal(c->category[GLS_CAT_PROGRAM], 1);
        assert_int_equal(c->category[GLS_CAT_FRAMEBUFFER], 1);
        if (frame == 0) {
            /* shapes at t = 0, in sorted order: textures 0 (checker) on unit 0 and 1
             * (its gloss) on unit 1; then bricks 2, 3, 4 on units 0, 2, 3; then the
             * ground 5 on unit 0: 6 binds, not one per object and map (14) */
            assert_int_equal(want_tex, 6);
            /* meshes 1 3 5 | 1 2 4 | 2 3 6 | 0: 10 */
            assert_int_equal(want_vao, 10);
        }
    }
    gl.Finish();
    uint8_t px[W * H * 4];
    read_color(f, px);
    int drawn = 0;
    for (int i = 0; i < W * H; i++)
        drawn += px[i * 4 + 3] == 255;
    assert_true(drawn > W * H / 4);   /* the floor and the grid fill much of the view */
    frontend_free(&fe);
    gl.DeleteProgram(prog);
    assert_no_gl_errors(f);
}

/* One object seen from straight ahead: the matrices, the vertex array and the material
 * reach the shaders. */
static void test_object_pixels(void **state)
{
    fixture *f = *state;
    scene *s = f->s;
    /* object 1: the sphere of radius 2 at (-10, 2.2, -10), material 1 (0.8, 0.8, 0.85),
     * seen from 6 units along +Z */
    const scene_object *o = &s->objects[1];
    assert_int_equal(o->mesh, 1);
    assert_int_equal(o->material, 1);
    sm_vec3 eye = {o->position[0], o->position[1], o->position[2] + 6.0f}, up = {0, 1, 0};
    sm_lookat(eye, o->position, up, s->view);
    sm_perspective(sm_deg2rad(60.0f), (float)W / H, 0.5f, 50.0f, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);

    GLuint diffuse = surface_program("", "s.diffuse");
    GLuint normal = surface_program("", "max(s.normal, vec3(0.0))");
    /* a fragment shader without surface.inc: only the geometry draw may be used */
    const char *vs[] = {gl_shader_source("mesh.vert")};
    const char *fs[] = {"layout(location = 0) out vec4 o; void main() { o = vec4(1.0); }\n"};
    GLuint plain = test_program(vs, 1, fs, 1);
    GLuint progs[3] = {diffuse, normal, plain};
    uint8_t px[3][W * H * 4];
    for (int k = 0; k < 3; k++) {
        begin_frame(f, "object");
        gl_state_program(f->st, progs[k]);
        gl_state_depth(f->st, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});
        gl_state_cull(f->st, GLS_CULL_BACK);
        if (k < 2)
            scene_gpu_draw_object(f->g, f->st, s, 1);
        else
            scene_gpu_draw_object_geometry(f->g, f->st, s, 1);
        scene_gpu_draw_object(f->g, f->st, s, 99);            /* bugs: a message, no draw */
        scene_gpu_draw_object_geometry(f->g, f->st, s, 99);
        gl_state_end_pass(f->st, NULL);
        assert_int_equal(gl_state_pass_counts(f->st)->draw_calls, 1);
        assert_int_equal(gl_state_pass_counts(f->st)->category[GLS_CAT_TEXTURE], 0);
        read_color(f, px[k]);
    }
    /* the same pixels covered either way */
    for (int i = 0; i < W * H; i++)
        if (px[0][i * 4 + 3] != px[2][i * 4 + 3])
            fail_msg("pixel %d: coverage differs between the material and geometry draws", i);
    /* the centre: the material's colour, the normal towards the eye */
    const uint8_t *c = pixel(px[0], W / 2, H / 2);
    assert_int_equal(c[0], 204);
    assert_int_equal(c[1], 204);
    assert_int_equal(c[2], 217);
    assert_int_equal(c[3], 255);
    c = pixel(px[1], W / 2, H / 2);
    assert_true(c[0] <= 16 && c[1] <= 16 && c[2] >= 250);
    /* the sphere spans atan(2 / sqrt(32)) = 19.5 degrees of the 30 up: 0.65 x H/2
     * = 15.6 rows above and below the centre */
    assert_int_equal(pixel(px[0], W / 2, H / 2 + 13)[3], 255);
    assert_int_equal(pixel(px[0], W / 2, H / 2 + 17)[3], 0);
    assert_int_equal(pixel(px[0], W / 2, H / 2 - 14)[3], 255);
    assert_int_equal(pixel(px[0], W / 2, H / 2 - 18)[3], 0);
    assert_int_equal(pixel(px[0], 0, 0)[3], 0);
    /* the top of the sphere faces up */
    c = pixel(px[1], W / 2, H / 2 + 13);
    assert_true(c[1] > c[0] && c[1] > 128);
    gl.DeleteProgram(diffuse);
    gl.DeleteProgram(normal);
    gl.DeleteProgram(plain);
    assert_no_gl_errors(f);
}

/* Seen from the origin down -Z, 90 degrees vertically at the target's aspect: the
 * pixel (column, row from the bottom) that sees point (x, y, z). */
static void project(float x, float y, float z, int *col, int *row)
{
    float nx = x / -z / ((float)W / H), ny = y / -z;   /* in [-1, 1] */
    *col = (int)floorf((nx * 0.5f + 0.5f) * W);
    *row = (int)floorf((ny * 0.5f + 0.5f) * H);
}

static void test_light_volumes(void **state)
{
    fixture *f = *state;
    scene *s = f->s;
    pose_camera(s);
    sm_perspective(SM_PI_2, (float)W / H, 1.0f, 100.0f, s->proj);   /* the target's aspect */
    sm_mat4_mul(s->proj, s->view, s->viewproj);
    const char *vs[] = {gl_shader_source("light_volume.vert")};
    const char *fs[] = {"layout(location = 0) out vec4 o; void main() { o = vec4(1.0); }\n"};
    assert_non_null(vs[0]);
    GLuint prog = test_program(vs, 1, fs, 1);
    scene_light *L = s->lights;
    set_point(&L[0], 0.0f, 0.0f, -20.0f, 4.0f);
    set_spot(&L[1], -6.0f, -2.0f, -20.0f, 1, 0, 0, 20.0f, 12.0f);   /* across the view */
    uint8_t px[2][W * H * 4];
    for (int k = 0; k < 2; k++) {
        begin_frame(f, "volumes");
        gl_state_program(f->st, prog);
        gl_state_depth(f->st, NULL);
        gl_state_cull(f->st, GLS_CULL_BACK);
        scene_gpu_draw_light_volume(f->g, f->st, s, (uint32_t)k);
        gl_state_end_pass(f->st, NULL);
        assert_int_equal(gl_state_pass_counts(f->st)->draw_calls, 1);
        read_color(f, px[k]);
    }
    /* The sphere: every pixel whose ray passes within 1.1 x 4 of the light (less a
     * margin) is covered, none whose ray misses the drawn vertices' sphere. The
     * horizontal field is wider than 90 degrees (aspect 4:3): ray direction per pixel. */
    float tan_x = (float)W / H;   /* tan of the horizontal half angle */
    int covered = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            sm_vec3 d = {((x + 0.5f) / W * 2.0f - 1.0f) * tan_x, (y + 0.5f) / H * 2.0f - 1.0f,
                         -1.0f};
            sm_vec3_normalize(d);
            sm_vec3 c = {0.0f, 0.0f, -20.0f}, cross;
            sm_vec3_cross(d, c, cross);
            float miss = sm_vec3_norm(cross);   /* ray's distance from the centre */
            bool on = pixel(px[0], x, y)[0] == 255;
            covered += on;
            if (miss < 4.4f * 0.99f && !on)
                fail_msg("pixel (%d, %d): ray %.3f from the light, inside 1.1 x radius, "
                         "not covered", x, y, miss);
            if (miss > 4.4f * 1.0389f * 1.01f && on)
                fail_msg("pixel (%d, %d): ray %.3f from the light, covered", x, y, miss);
        }
    assert_true(covered > 0);
    /* The spot: apex at (-6, -2, -20) along +X, 20 degrees, range 12 (seen side on,
     * a triangle). Inside: along the axis and near the rim of the base; outside:
     * behind the apex, beyond the base, beside the rim of the drawn pyramid. */
    struct {
        float along, across;
        bool in;
    } probes[] = {
        {1.0f, 0.0f, true},  {6.0f, 0.0f, true},   {11.5f, 0.0f, true},
        {11.0f, 0.9f, true}, {11.0f, -0.9f, true}, {6.0f, 0.9f, true},
        {-1.0f, 0.0f, false}, {14.0f, 0.0f, false}, {6.0f, 1.25f, false},
        {11.0f, 1.25f, false}, {6.0f, -1.25f, false},
    };
    for (size_t i = 0; i < sizeof probes / sizeof probes[0]; i++) {
        float t = tanf(sm_deg2rad(20.0f));
        float x = -6.0f + probes[i].along;
        float y = -2.0f + probes[i].across * probes[i].along * t;
        int col, row;
        project(x, y, -20.0f, &col, &row);
        bool on = pixel(px[1], col, row)[0] == 255;
        if (on != probes[i].in)
            fail_msg("spot probe %zu (along %.1f, across %.2f x the cone): pixel (%d, %d) %s",
                     i, probes[i].along, probes[i].across, col, row,
                     on ? "covered" : "not covered");
    }
    /* directional lights have no volume: a bug message, nothing drawn */
    set_directional(&L[2]);
    gl_state_begin_pass(f->st, "none");
    scene_gpu_draw_light_volume(f->g, f->st, s, 2);
    scene_gpu_draw_light_volume(f->g, f->st, s, 999);
    gl_state_end_pass(f->st, NULL);
    assert_int_equal(gl_state_pass_counts(f->st)->draw_calls, 0);
    gl.DeleteProgram(prog);
    assert_no_gl_errors(f);
}

/* The sky lands only where depth is still 1 (no geometry), with the gradient the
 * shader documents. */
static void test_sky(void **state)
{
    fixture *f = *state;
    scene *s = f->s;
    scene_update(s, 3.0);
    begin_frame(f, "sky");
    /* "geometry": a rectangle of depth 0.5 and red, by a scissored clear */
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(16, 12, 32, 24);
    gl.ClearColor(1.0f, 0.0f, 0.0f, 1.0f);
    gl.ClearDepth(0.5);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.Disable(GL_SCISSOR_TEST);
    scene_gpu_frame(f->g, s);
    scene_gpu_draw_sky(f->g, f->st);
    gl_state_end_pass(f->st, NULL);
    const gls_counts *c = gl_state_pass_counts(f->st);
    assert_int_equal(c->draw_calls, 1);
    assert_int_equal(c->category[GLS_CAT_PROGRAM], 1);
    uint8_t px[W * H * 4];
    read_color(f, px);

    sm_mat4 ip;
    sm_mat4_inv(s->proj, ip);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *p = pixel(px, x, y);
            if (x >= 16 && x < 48 && y >= 12 && y < 36) {
                if (p[0] != 255 || p[1] != 0 || p[2] != 0 || p[3] != 255)
                    fail_msg("geometry pixel (%d, %d) is %u,%u,%u,%u: the sky overwrote it",
                             x, y, p[0], p[1], p[2], p[3]);
                continue;
            }
            sm_vec4 q = {(x + 0.5f) / W * 2.0f - 1.0f, (y + 0.5f) / H * 2.0f - 1.0f, -1.0f, 1.0f};
            sm_mat4_mulv(ip, q, q);
            sm_vec3 d = {q[0] / q[3], q[1] / q[3], q[2] / q[3]};
            sm_vec3_normalize(d);
            float k = 1.0f + (0.6f - 1.0f) * sm_clamp(d[1], 0.0f, 1.0f);
            for (int ch = 0; ch < 3; ch++) {
                float want = s->sky_color[ch] * k * 255.0f;
                if (fabsf((float)p[ch] - want) > 1.0f)
                    fail_msg("sky pixel (%d, %d) channel %d is %u, expected %.2f", x, y, ch,
                             p[ch], want);
            }
            assert_int_equal(p[3], 255);
        }
    /* the camera looks down on the scene: the top row is bluer-darker than the bottom */
    assert_true(pixel(px, 0, H - 1)[2] < pixel(px, 0, 0)[2]);
    assert_no_gl_errors(f);
}

/* The resolve clamps HDR values to [0, 1] into the RGBA8 output, pixel for pixel. */
static void test_resolve(void **state)
{
    fixture *f = *state;
    gl_target hdr;
    char err[256];
    assert_true(gl_target_create(&hdr, &(gl_target_desc){.name = "hdr",
                                 .format = GLT_FORMAT_RGBA16F, .width = W, .height = H},
                                 err, sizeof err));
    /* per pixel: values exact in half floats, above 1, below 0 and between */
    static const float values[5] = {-3.5f, 0.0f, 0.25f, 0.75f, 6.0f};
    static const uint8_t want8[5] = {0, 0, 64, 191, 255};
    static float data[W * H * 4];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int ch = 0; ch < 4; ch++)
                data[(y * W + x) * 4 + ch] = values[(x + 2 * y + ch) % 5];
    gl.TextureSubImage2D(hdr.texture, 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, data);

    for (int frame = 0; frame < 2; frame++) {
        gl_state_invalidate(f->st);
        gl_state_begin_pass(f->st, "resolve");
        scene_gpu_resolve(f->g, f->st, hdr.texture, f->fb.fbo, W, H);
        gl_state_end_pass(f->st, NULL);
        const gls_counts *c = gl_state_pass_counts(f->st);
        assert_int_equal(c->draw_calls, 1);
        assert_int_equal(c->category[GLS_CAT_FRAMEBUFFER], 1);
        assert_int_equal(c->category[GLS_CAT_PROGRAM], 1);
        assert_int_equal(c->category[GLS_CAT_TEXTURE], 1);
    }
    uint8_t px[W * H * 4];
    read_color(f, px);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *p = pixel(px, x, y);
            for (int ch = 0; ch < 3; ch++)
                if (p[ch] != want8[(x + 2 * y + ch) % 5])
                    fail_msg("pixel (%d, %d) channel %d is %u, expected %u (HDR %g)", x, y, ch,
                             p[ch], want8[(x + 2 * y + ch) % 5], values[(x + 2 * y + ch) % 5]);
            assert_int_equal(p[3], 255);
        }
    gl_target_destroy(&hdr);
    assert_no_gl_errors(f);
}

static void test_bytes_and_describe(void **state)
{
    fixture *f = *state;
    scene *s = f->s;
    uint64_t want = 192;   /* the Frame block */
    for (uint32_t i = 0; i < s->nmeshes; i++)
        want += (uint64_t)s->meshes[i].nvertices * 48 + (uint64_t)s->meshes[i].nindices * 4;
    for (uint32_t i = 0; i < s->ntextures; i++) {
        const texture_image *t = &s->textures[i];
        assert_int_equal(t->width, 256);
        want += (uint64_t)t->channels * 87381;   /* 256^2 + 128^2 + ... + 1 */
    }
    mesh sphere, cone;
    char err[256];
    assert_true(frontend_volume_meshes(&sphere, &cone, err, sizeof err));
    assert_int_equal(sphere.nvertices, 7 * 17 + 32);   /* mesh_sphere V = (T-1)(S+1) + 2S */
    assert_int_equal(cone.nvertices, 3 * 16 + 2);
    want += (uint64_t)(sphere.nvertices + cone.nvertices) * 48 +
            (uint64_t)(sphere.nindices + cone.nindices) * 4;
    mesh_free(&sphere);
    mesh_free(&cone);
    assert_int_equal(scene_gpu_bytes(f->g), want);
    assert_int_equal(scene_gpu_bytes(NULL), 0);

    pass_plan plan;
    memset(&plan, 0, sizeof plan);
    scene_gpu_describe(f->g, &plan);
    assert_int_equal(plan.nprograms, 2);
    assert_string_equal(plan.program[0], "sky+FULLSCREEN_FAR+FULLSCREEN_UNCLIPPED");
    assert_string_equal(plan.program[1], "resolve+FULLSCREEN_UNCLIPPED");

    /* a scene without a sky builds no sky program, and drawing it draws nothing */
    s->sky = false;
    scene_gpu *g = scene_gpu_create(s, err, sizeof err);
    assert_non_null(g);
    memset(&plan, 0, sizeof plan);
    scene_gpu_describe(g, &plan);
    assert_int_equal(plan.nprograms, 1);
    gl_state_begin_pass(f->st, "no sky");
    scene_gpu_draw_sky(g, f->st);
    gl_state_end_pass(f->st, NULL);
    assert_int_equal(gl_state_pass_counts(f->st)->draw_calls, 0);
    scene_gpu_destroy(g);
    s->sky = true;
    assert_no_gl_errors(f);
}

/* The mip levels scene_gpu_create makes on the CPU (renderers/frame/scene_gpu.c's
 * mip_down) against glGenerateMipmap's of the same map on this GL: every byte of every
 * level of every shapes map equal on llvmpipe (whose filter mip_down follows), within
 * one unit elsewhere. */
static void test_mip_levels(void **state)
{
    fixture *f = *state;
    scene *s = f->s;
    const char *device = (const char *)gl.GetString(GL_RENDERER);
    int tolerance = device && strstr(device, "llvmpipe") ? 0 : 1;
    assert_true(s->ntextures > 0);
    for (uint32_t i = 0; i < s->ntextures; i++) {
        const texture_image *t = &s->textures[i];
        assert_int_equal(t->width, 256);   /* the sizes below: 256 x 256, 9 levels */
        assert_int_equal(t->height, 256);
        GLenum fmt = t->channels == 4 ? GL_RGBA : GL_RED;
        GLuint ref = 0;
        gl.CreateTextures(GL_TEXTURE_2D, 1, &ref);
        gl.TextureStorage2D(ref, 9, t->channels == 4 ? GL_RGBA8 : GL_R8, 256, 256);
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl.TextureSubImage2D(ref, 0, 0, 0, 256, 256, fmt, GL_UNSIGNED_BYTE, t->data);
        gl.GenerateTextureMipmap(ref);
        size_t n = (size_t)256 * 256 * t->channels;
        uint8_t *a = malloc(n), *b = malloc(n);
        assert_non_null(a);
        assert_non_null(b);
        for (int l = 1, side = 128; l < 9; l++, side /= 2) {
            size_t bytes = (size_t)side * side * t->channels;
            gl.GetTextureImage(scene_gpu_texture(f->g, (int)i), l, fmt, GL_UNSIGNED_BYTE,
                               (GLsizei)bytes, a);
            gl.GetTextureImage(ref, l, fmt, GL_UNSIGNED_BYTE, (GLsizei)bytes, b);
            for (size_t k = 0; k < bytes; k++)
                if (abs((int)a[k] - (int)b[k]) > tolerance)
                    fail_msg("map %u level %d byte %zu: %d made, %d from glGenerateMipmap", i,
                             l, k, a[k], b[k]);
        }
        free(a);
        free(b);
        gl.DeleteTextures(1, &ref);
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    }
    assert_no_gl_errors(f);
}

int main(void)
{
    char why[256];
    const struct CMUnitTest cpu_tests[] = {
        cmocka_unit_test(test_shapes_sort_order),
        cmocka_unit_test(test_sort_many),
        cmocka_unit_test(test_translucent_list),
        cmocka_unit_test(test_visible_sets),
        cmocka_unit_test(test_lights_and_illumination),
        cmocka_unit_test(test_eye_inside),
        cmocka_unit_test(test_no_per_frame_allocation),
        cmocka_unit_test(test_pack_light),
        cmocka_unit_test(test_pack_frame),
    };
    int failed = cmocka_run_group_tests_name("frontend", cpu_tests, NULL, NULL);
    if (!egl_display_available(why, sizeof why)) {
        printf("skip: %s\n", why);
        return failed ? 1 : 77;
    }
    const struct CMUnitTest gl_tests[] = {
        cmocka_unit_test_setup_teardown(test_draw_counts, setup, teardown),
        cmocka_unit_test_setup_teardown(test_object_pixels, setup, teardown),
        cmocka_unit_test_setup_teardown(test_light_volumes, setup, teardown),
        cmocka_unit_test_setup_teardown(test_sky, setup, teardown),
        cmocka_unit_test_setup_teardown(test_resolve, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bytes_and_describe, setup, teardown),
        cmocka_unit_test_setup_teardown(test_mip_levels, setup, teardown),
    };
    return failed | cmocka_run_group_tests_name("scene_gpu", gl_tests, NULL, NULL);
}
