/* The catalog's scenes (scenes/builtin/scene_*.c): every scene builds at 1x1 and 1600x1200 with
 * valid tables, finite poses and bounds; the papers' scenes have what their papers list
 * (seed 000 section 4.8, seed 003 section 6) and what scene_*.c promises. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/scene.h"

static scene *build(const char *name, light_placement p, uint32_t n, int w, int h)
{
    char err[256];
    light_params lp = {.placement = p, .seed = 1337, .rng = RNG_MSVC,
                       .count = {.start = n, .max = n}, .radius = 1.0f, .color_max = 0.3f};
    scene *s = scene_build(name, &lp, w, h, err, sizeof err);
    if (!s)
        fail_msg("scene_build(%s, %dx%d): %s", name, w, h, err);
    return s;
}

/* The solid sphere and the box share a point: the squared distance from the centre to
 * the box is at most radius^2. */
static bool box_meets_sphere(const sm_vec3 box[2], const sm_vec4 sphere)
{
    float d2 = 0.0f;
    for (int k = 0; k < 3; k++) {
        float c = sphere[k], d = c < box[0][k] ? box[0][k] - c : c > box[1][k] ? c - box[1][k] : 0;
        d2 += d * d;
    }
    return d2 <= sphere[3] * sphere[3];
}

static bool finite_n(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return false;
    return true;
}

/* Tables consistent, values finite, a usable projection, posed at several times. */
static void check_scene(const scene *s0, int w, int h)
{
    scene *s = (scene *)s0;
    const char *name = s->name;
    assert_true(s->width == w && s->height == h);
    for (int c = 0; c < 3; c++) {
        assert_true(isfinite(s->light_bounds_min[c]) && isfinite(s->light_bounds_max[c]));
        assert_true(s->light_bounds_min[c] <= s->light_bounds_max[c]);
    }
    assert_true(finite_n(s->ambient, 3) && finite_n(s->sky_color, 3));
    assert_true(s->fovy > 0.0f && s->fovy < 3.1f);
    assert_true(s->znear > 0.0f && s->zfar > s->znear && isfinite(s->zfar));
    assert_true(s->orbit_period > 0.0f);
    if (s->path == CAMERA_SCRIPTED)
        assert_true(s->nkeys >= 1 && s->nkeys <= 8);
    else
        assert_true(s->orbit_radius > 0.0f);
    for (uint32_t i = 0; i < s->nmaterials; i++) {
        const scene_material *m = &s->materials[i];
        const int maps[4] = {m->diffuse_map, m->gloss_map, m->normal_map, m->emissive_map};
        for (int k = 0; k < 4; k++)
            assert_true(maps[k] >= -1 && maps[k] < (int)s->ntextures);
        assert_true(finite_n(m->diffuse, 3) && finite_n(m->emissive, 3));
    }
    for (uint32_t i = 0; i < s->ntextures; i++)
        assert_non_null(s->textures[i].data);
    for (uint32_t i = 0; i < s->nmeshes; i++)
        assert_true(s->meshes[i].nindices > 0 && s->meshes[i].nindices % 3 == 0);
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        const scene_light *l = &s->lights[i];
        assert_true(finite_n(l->position, 3) && finite_n(l->direction, 3) &&
                    finite_n(l->color, 3) && isfinite(l->radius));
    }
    static const double times[] = {0.0, 5.0, 19.9, 59.99, 86400.5};
    for (size_t k = 0; k < sizeof times / sizeof times[0]; k++) {
        scene_update(s, times[k]);
        for (int c = 0; c < 4; c++) {
            if (!finite_n(s->view[c], 4) || !finite_n(s->proj[c], 4) ||
                !finite_n(s->viewproj[c], 4))
                fail_msg("%s at %dx%d, t = %g: a matrix is not finite", name, w, h, times[k]);
        }
        assert_true(s->proj[0][0] != 0.0f && s->proj[1][1] != 0.0f);   /* not the zero matrix */
        assert_true(finite_n(s->cam.eye, 3) && finite_n(s->cam.target, 3));
        for (uint32_t i = 0; i < s->nobjects; i++) {
            const scene_object *o = &s->objects[i];
            assert_true(o->mesh < s->nmeshes && o->material < s->nmaterials);
            assert_true(finite_n(o->bsphere, 4) && o->bsphere[3] > 0.0f);
            for (int c = 0; c < 4; c++)
                assert_true(finite_n(o->model[c], 4));
        }
        for (uint32_t i = 0; i < s->ncoverage_lights; i++) {
            double cov = scene_light_coverage(s, i);
            assert_true(cov >= 0.0 && cov <= 1.0);
        }
    }
}

static void test_every_scene_builds(void **state)
{
    (void)state;
    static const int sizes[2][2] = {{1, 1}, {1600, 1200}};
    assert_true(scene_catalog_count() >= 10);
    for (size_t i = 0; i < scene_catalog_count(); i++) {
        const scene_catalog_entry *e = scene_catalog_at(i);
        assert_non_null(e->description);
        for (int k = 0; k < 2; k++) {
            scene *s = build(e->name, PLACEMENT_RANDOM, 16, sizes[k][0], sizes[k][1]);
            assert_string_equal(s->name, e->name);
            check_scene(s, sizes[k][0], sizes[k][1]);
            scene_destroy(s);
            char err[256];
            light_params lp = {.placement = PLACEMENT_SCENE, .count = {.start = 50, .max = 50}};
            s = scene_build(e->name, &lp, sizes[k][0], sizes[k][1], err, sizeof err);
            if (s) {
                check_scene(s, sizes[k][0], sizes[k][1]);
                scene_destroy(s);
            } else {
                assert_non_null(strstr(err, "has no authored lights"));
            }
        }
    }
}

static bool has_maps(const scene *s, uint32_t material)
{
    const scene_material *m = &s->materials[material];
    return m->diffuse_map >= 0 && m->gloss_map >= 0 && m->normal_map >= 0;
}

/* interior: 72 instances, each with diffuse, gloss and normal maps, a handful emissive;
 * draw distance 2048; the camera's orbit stays inside the hall and clear of every
 * object's bounding sphere except the room's own shell. */
static void test_interior(void **state)
{
    (void)state;
    scene *s = build("interior", PLACEMENT_SCENE, 9, 320, 240);
    assert_int_equal(s->nobjects, 72);
    unsigned emissive = 0;
    for (uint32_t i = 0; i < s->nobjects; i++) {
        assert_true(has_maps(s, s->objects[i].material));
        emissive += s->materials[s->objects[i].material].emissive_map >= 0;
    }
    assert_true(emissive >= 3 && emissive <= 10);
    assert_float_equal(s->zfar, 2048.0, 0.0);
    assert_false(s->sky);
    /* the eye is in the hall (x in [-576, 576], y in [0, 288], z in [-448, 448]) and
     * more than znear from every prop's world box (props: every object after the 10
     * shell pieces; none of them moves) */
    for (double t = 0.0; t < 60.0; t += 0.5) {
        scene_update(s, t);
        assert_true(fabsf(s->cam.eye[0]) < 576.0f && fabsf(s->cam.eye[2]) < 448.0f);
        assert_true(s->cam.eye[1] > 0.0f && s->cam.eye[1] < 288.0f);
        sm_vec4 eye = {s->cam.eye[0], s->cam.eye[1], s->cam.eye[2], s->znear};
        for (uint32_t i = 10; i < s->nobjects; i++) {
            const scene_object *o = &s->objects[i];
            const mesh *m = &s->meshes[o->mesh];
            assert_true(o->spin_rate == 0.0f);
            sm_vec3 box[2];
            for (int k = 0; k < 3; k++) {
                box[0][k] = o->position[k] + m->aabb[0][k] * o->scale;
                box[1][k] = o->position[k] + m->aabb[1][k] * o->scale;
            }
            if (box_meets_sphere(box, eye))
                fail_msg("t = %g: the eye is within znear of object %u", t, i);
        }
    }
    scene_destroy(s);
}

/* canyon: 4 terrain tiles 128 x 128 cells, each with its own diffuse, gloss and normal
 * maps, meeting exactly at their borders; draw distance 8192; the sky on; its orbit sees
 * terrain at view depths beyond 7500 inside the frustum, and some cut by the far plane
 * (depth > 8192); the eye stays above the terrain. */
static void test_canyon(void **state)
{
    (void)state;
    scene *s = build("canyon", PLACEMENT_SCENE, 1, 320, 240);
    assert_int_equal(s->nobjects, 4);
    assert_float_equal(s->zfar, 8192.0, 0.0);
    assert_true(s->sky);
    for (uint32_t i = 0; i < 4; i++) {
        const mesh *m = &s->meshes[s->objects[i].mesh];
        assert_int_equal(m->nvertices, 129 * 129);
        assert_int_equal(m->nindices, 6 * 128 * 128);
        assert_true(has_maps(s, s->objects[i].material));
        for (uint32_t j = 0; j < i; j++)
            assert_true(s->objects[i].material != s->objects[j].material);
    }
    /* tiles 0 (x < 0) and 1 (x > 0) share the column x = 0: vertex (128, k) of tile 0 and
     * (0, k) of tile 1 in world space */
    const mesh *a = &s->meshes[s->objects[0].mesh], *b = &s->meshes[s->objects[1].mesh];
    for (uint32_t k = 0; k <= 128; k += 8) {
        sm_vec3 pa, pb;
        sm_vec3_add(a->vertices[k * 129 + 128].position, s->objects[0].position, pa);
        sm_vec3_add(b->vertices[k * 129 + 0].position, s->objects[1].position, pb);
        assert_memory_equal(pa, pb, sizeof pa);
    }
    /* the farthest terrain vertex in the frustum at eight points of the orbit */
    double farthest = 0.0;
    bool cut = false;
    for (int q = 0; q < 8; q++) {
        scene_update(s, 7.5 * q);
        for (uint32_t i = 0; i < 4; i++) {
            const mesh *m = &s->meshes[s->objects[i].mesh];
            for (uint32_t v = 0; v < m->nvertices; v += 3) {
                sm_vec3 w;
                sm_vec4 p, clip;
                sm_vec3_add(m->vertices[v].position, s->objects[i].position, w);
                sm_vec4_from_vec3(w, 1.0f, p);
                sm_mat4_mulv(s->viewproj, p, clip);
                bool in_xy = fabsf(clip[0]) <= clip[3] && fabsf(clip[1]) <= clip[3];
                if (in_xy && clip[3] > s->zfar)
                    cut = true;
                else if (in_xy && clip[3] > 0.0f && clip[3] > farthest)
                    farthest = clip[3];
            }
        }
    }
    if (!(farthest > 7500.0 && cut))
        fail_msg("farthest terrain in view %.0f, cut by the far plane: %d", farthest, cut);
    /* above every vertex within 500 units (horizontally) of the eye's path */
    for (double t = 0.0; t < 60.0; t += 1.0) {
        scene_update(s, t);
        for (uint32_t i = 0; i < 4; i++) {
            const mesh *m = &s->meshes[s->objects[i].mesh];
            for (uint32_t v = 0; v < m->nvertices; v++) {
                const float *p = m->vertices[v].position;
                float dx = p[0] + s->objects[i].position[0] - s->cam.eye[0];
                float dz = p[2] + s->objects[i].position[2] - s->cam.eye[2];
                if (dx * dx + dz * dz < 500.0f * 500.0f)
                    assert_true(p[1] + 200.0f < s->cam.eye[1]);
            }
        }
    }
    scene_destroy(s);
}

/* seed 003's scenes: 1 model; 2 models spinning about X and Z and 2 icospheres; 100
 * spheres and 4 spinning models; each orbit 60 s. */
static void test_curtis_scenes(void **state)
{
    (void)state;
    scene *s1 = build("curtis-scene1", PLACEMENT_RANDOM, 160, 320, 240);
    assert_int_equal(s1->nobjects, 1);
    assert_true(s1->objects[0].spin_rate != 0.0f);
    assert_float_equal(s1->orbit_period, 60.0, 0.0);
    /* the model sits in its light bounds, every light within the recommended radius 10
     * of its centre */
    for (uint32_t i = 0; i < s1->nlights_total; i++)
        assert_true(sm_vec3_distance(s1->lights[i].position, s1->objects[0].position) < 10.0f);
    scene_destroy(s1);

    scene *s2 = build("curtis-scene2", PLACEMENT_RANDOM, 160, 320, 240);
    assert_int_equal(s2->nobjects, 4);
    unsigned about_x = 0, about_z = 0;
    for (uint32_t i = 0; i < 4; i++) {
        const scene_object *o = &s2->objects[i];
        if (o->spin_rate != 0.0f) {
            about_x += o->spin_axis[0] == 1.0f;
            about_z += o->spin_axis[2] == 1.0f;
        }
    }
    assert_int_equal(about_x, 1);
    assert_int_equal(about_z, 1);
    assert_float_equal(s2->orbit_period, 60.0, 0.0);
    scene_destroy(s2);

    scene *s3 = build("curtis-scene3", PLACEMENT_RANDOM, 590, 320, 240);
    assert_int_equal(s3->nobjects, 104);
    unsigned spinning = 0;
    for (uint32_t i = 0; i < s3->nobjects; i++)
        spinning += s3->objects[i].spin_rate != 0.0f;
    assert_int_equal(spinning, 4);
    assert_float_equal(s3->orbit_period, 60.0, 0.0);
    scene_destroy(s3);
}

/* curtis-scene2's big icosphere fills the screen around t = 20 s (seed 003 section
 * 8.1.2): its coverage, as a ball just inside its faces (0.995 of its radius), is 1 at
 * 19 to 21 s at 4:3 and 16:9, and not at 17 or 23 s. */
static void test_curtis2_occlusion(void **state)
{
    (void)state;
    static const int sizes[2][2] = {{320, 240}, {1280, 720}};
    for (int k = 0; k < 2; k++) {
        scene *s = build("curtis-scene2", PLACEMENT_NONE, 0, sizes[k][0], sizes[k][1]);
        const scene_object *big = NULL;
        for (uint32_t i = 0; i < s->nobjects; i++)
            if (!big || s->objects[i].bsphere[3] > big->bsphere[3])
                big = &s->objects[i];
        s->lights = calloc(1, sizeof *s->lights);
        s->lights[0].type = LIGHT_POINT;
        sm_vec3_copy(big->bsphere, s->lights[0].position);
        s->lights[0].radius = 0.995f * big->bsphere[3];
        s->nlights_total = 1;
        static const double full[] = {19.0, 19.5, 20.0, 20.5, 21.0}, part[] = {17.0, 23.0};
        for (size_t i = 0; i < sizeof full / sizeof full[0]; i++) {
            scene_update(s, full[i]);
            if (scene_light_coverage(s, 0) != 1.0)
                fail_msg("%dx%d t = %g: the ball covers %.4f", sizes[k][0], sizes[k][1],
                         full[i], scene_light_coverage(s, 0));
        }
        for (size_t i = 0; i < 2; i++) {
            scene_update(s, part[i]);
            assert_true(scene_light_coverage(s, 0) < 1.0);
        }
        /* the eye never enters the ball */
        for (double t = 0.0; t < 60.0; t += 0.25) {
            scene_update(s, t);
            assert_true(sm_vec3_distance(s->cam.eye, s->lights[0].position) >
                        big->bsphere[3] + s->znear);
        }
        scene_destroy(s);
    }
}

/* floating-spot: its cone (its bounding sphere) meets no object's world box: it lights
 * nothing. */
static void test_floating_spot_lights_nothing(void **state)
{
    (void)state;
    scene *s = build("floating-spot", PLACEMENT_SCENE, 1, 320, 240);
    const scene_light *l = &s->lights[0];
    /* the smallest sphere holding the cone of height h and rim radius b (b < h) */
    float h = l->radius, b = h * tanf(l->spot_angle);
    assert_true(b < h);
    float t = (h * h + b * b) / (2.0f * h);
    sm_vec4 bound = {l->position[0] + l->direction[0] * t, l->position[1] + l->direction[1] * t,
                     l->position[2] + l->direction[2] * t, t};
    for (uint32_t i = 0; i < s->nobjects; i++) {
        const scene_object *o = &s->objects[i];
        assert_true(o->spin_rate == 0.0f);
        const mesh *m = &s->meshes[o->mesh];
        sm_vec3 box[2];
        for (int k = 0; k < 3; k++) {
            box[0][k] = o->position[k] + m->aabb[0][k] * o->scale;
            box[1][k] = o->position[k] + m->aabb[1][k] * o->scale;
        }
        if (box_meets_sphere(box, bound))
            fail_msg("the floating spot's volume meets object %u", i);
    }
    scene_destroy(s);
}

/* glass (scene_glass.c): a floor and a pillar (opaque), 4 panes and 24 particles
 * (translucent, MATERIAL_BLEND, opacity in (0, 1)), 12 authored point lights; the
 * panes are of four different colours and, from the camera at t = 0 (on +x), each
 * overlaps the next on screen (their z ranges overlap, their x differ) and none
 * intersects another (boxes apart in x). */
static void test_glass(void **state)
{
    (void)state;
    scene *s = build("glass", PLACEMENT_SCENE, 12, 320, 240);
    assert_int_equal(s->nobjects, 30);
    assert_int_equal(s->nlights_total, 12);
    uint32_t opaque = 0, translucent = 0;
    for (uint32_t i = 0; i < s->nobjects; i++) {
        const scene_material *m = &s->materials[s->objects[i].material];
        if (scene_material_translucent(m)) {
            translucent++;
            assert_true(m->opacity > 0.0f && m->opacity < 1.0f);
        } else {
            opaque++;
            assert_int_equal(m->alpha, MATERIAL_OPAQUE);
        }
    }
    assert_int_equal(opaque, 2);
    assert_int_equal(translucent, 28);
    for (uint32_t i = 0; i < s->nlights_total; i++)
        assert_int_equal(s->lights[i].type, LIGHT_POINT);
    for (uint32_t i = 2; i < 6; i++) {   /* the panes */
        const scene_object *p = &s->objects[i];
        assert_true(p->mesh == s->objects[2].mesh);
        for (uint32_t j = i + 1; j < 6; j++) {
            const scene_object *q = &s->objects[j];
            const float *a = s->materials[p->material].diffuse, *b = s->materials[q->material].diffuse;
            assert_false(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]);
            assert_true(fabsf(p->position[0] - q->position[0]) >= 1.5f);   /* 0.1 thick */
        }
        if (i < 5)   /* 4 wide, 1.8 apart in z: they overlap by 2.2 */
            assert_true(fabsf(p->position[2] - s->objects[i + 1].position[2]) < 4.0f);
    }
    scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_scene_builds),
        cmocka_unit_test(test_interior),
        cmocka_unit_test(test_canyon),
        cmocka_unit_test(test_curtis_scenes),
        cmocka_unit_test(test_curtis2_occlusion),
        cmocka_unit_test(test_floating_spot_lights_nothing),
        cmocka_unit_test(test_glass),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
