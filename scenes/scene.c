/* Scene construction and posing. Each catalog scene is built here from its name;
 * the run's lights are placed from the manifest's light parameters. */
#include "scenes/scene.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Random placement: for each light in order, x, y, z uniform in the scene's light
 * bounds, then r, g, b uniform in [0, color_max]. Lights are generated up to the
 * schedule's maximum once, so growth adds lights without moving earlier ones. */
static void place_random(scene *s, const light_params *lp)
{
    rng g;
    rng_seed(&g, lp->rng, lp->seed);
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        scene_light *l = &s->lights[i];
        l->type = LIGHT_POINT;
        for (int k = 0; k < 3; k++) {
            float u = rng_unit(&g);
            l->position[k] = s->light_bounds_min[k] +
                             u * (s->light_bounds_max[k] - s->light_bounds_min[k]);
        }
        for (int k = 0; k < 3; k++)
            l->color[k] = rng_unit(&g) * lp->color_max;
        l->radius = lp->radius;
        l->attenuation = (attenuation_kind)lp->attenuation;
        l->att_a = lp->quadratic[0];
        l->att_b = lp->quadratic[1];
        l->att_c = lp->quadratic[2];
        sm_vec3 down = {0.0f, -1.0f, 0.0f};
        sm_vec3_copy(down, l->direction);
    }
}

/* Adds a mesh made by a generator call; false (with err) on failure. */
#define ADD_MESH(call)                                                                        \
    (s->nmeshes < MAX_MESHES && (call) ? (s->nmeshes++, true) : false)

enum { MAX_MESHES = 16, MAX_TEXTURES = 16, MAX_MATERIALS = 16 };

static bool alloc_tables(scene *s, uint32_t nobjects)
{
    s->meshes = calloc(MAX_MESHES, sizeof *s->meshes);
    s->textures = calloc(MAX_TEXTURES, sizeof *s->textures);
    s->materials = calloc(MAX_MATERIALS, sizeof *s->materials);
    s->objects = calloc(nobjects ? nobjects : 1, sizeof *s->objects);
    return s->meshes && s->textures && s->materials && s->objects;
}

static scene_material *add_material(scene *s, float r, float g, float b, float specular,
                                    float shininess)
{
    scene_material *m = &s->materials[s->nmaterials++];
    m->diffuse[0] = r;
    m->diffuse[1] = g;
    m->diffuse[2] = b;
    m->specular = specular;
    m->shininess = shininess;
    m->diffuse_map = m->gloss_map = m->normal_map = m->emissive_map = -1;
    return m;
}

static scene_object *add_object(scene *s, uint32_t meshi, uint32_t material, float x, float y,
                                float z, float scale)
{
    scene_object *o = &s->objects[s->nobjects++];
    o->mesh = meshi;
    o->material = material;
    o->position[0] = x;
    o->position[1] = y;
    o->position[2] = z;
    o->scale = scale;
    o->spin_axis[1] = 1.0f;
    return o;
}

/* A texture made by one of texture_gen's makers; its index, or -1 on failure. */
static int add_texture(scene *s, bool (*make)(const texture_desc *, texture_image *, char *, size_t),
                       const texture_desc *d, char *err, size_t errlen)
{
    if (s->ntextures >= MAX_TEXTURES || !make(d, &s->textures[s->ntextures], err, errlen))
        return -1;
    return (int)s->ntextures++;
}

/* "shapes": a floor and a 3 x 3 grid of objects (sphere, torus knot, box, icosphere,
 * cone, pillar...) under an orbiting camera; materials without maps, with diffuse
 * and gloss maps, and with diffuse, normal and emissive maps, so every shader
 * variant has work. Lights are placed above the floor. */
static bool build_shapes(scene *s, char *err, size_t errlen)
{
    if (!alloc_tables(s, 10))
        goto oom;
    texture_desc checker = {.width = 256, .height = 256, .pattern = TEXTURE_CHECKER, .cells = 8,
                            .color_a = {0.9f, 0.85f, 0.7f}, .color_b = {0.35f, 0.3f, 0.25f}};
    texture_desc bricks = {.width = 256, .height = 256, .pattern = TEXTURE_BRICKS, .cells = 8,
                           .seed = 7, .color_a = {0.7f, 0.3f, 0.2f}, .color_b = {0.8f, 0.8f, 0.75f},
                           .emissive_fraction = 0.1f, .emissive_color = {1.0f, 0.6f, 0.2f}};
    texture_desc ground = {.width = 256, .height = 256, .pattern = TEXTURE_NOISE, .cells = 4,
                           .seed = 3, .color_a = {0.25f, 0.3f, 0.2f}, .color_b = {0.5f, 0.5f, 0.4f},
                           .noise = 0.5f};
    int t_checker = add_texture(s, texture_diffuse, &checker, err, errlen);
    int t_checker_gloss = add_texture(s, texture_gloss, &checker, err, errlen);
    int t_bricks = add_texture(s, texture_diffuse, &bricks, err, errlen);
    int t_bricks_normal = add_texture(s, texture_normal_map, &bricks, err, errlen);
    int t_bricks_emissive = add_texture(s, texture_emissive, &bricks, err, errlen);
    int t_ground = add_texture(s, texture_diffuse, &ground, err, errlen);
    if (t_checker < 0 || t_checker_gloss < 0 || t_bricks < 0 || t_bricks_normal < 0 ||
        t_bricks_emissive < 0 || t_ground < 0)
        return false;

    scene_material *floor = add_material(s, 1, 1, 1, 0.2f, 16);
    floor->diffuse_map = t_ground;
    add_material(s, 0.8f, 0.8f, 0.85f, 0.6f, 32);                  /* 1: plain */
    scene_material *glossy = add_material(s, 1, 1, 1, 1.0f, 64);    /* 2: checker + gloss */
    glossy->diffuse_map = t_checker;
    glossy->gloss_map = t_checker_gloss;
    scene_material *brick = add_material(s, 1, 1, 1, 0.3f, 24);     /* 3: bricks */
    brick->diffuse_map = t_bricks;
    brick->normal_map = t_bricks_normal;
    brick->emissive_map = t_bricks_emissive;
    brick->emissive[0] = brick->emissive[1] = brick->emissive[2] = 1.0f;

    sm_vec3 floor_half = {40.0f, 0.5f, 40.0f}, box_half = {1.5f, 1.5f, 1.5f};
    if (!ADD_MESH(mesh_box(floor_half, &s->meshes[s->nmeshes], err, errlen)) ||
        !ADD_MESH(mesh_sphere(2.0f, 32, 16, &s->meshes[s->nmeshes], err, errlen)) ||
        !ADD_MESH(mesh_torus_knot(2, 3, 1.6f, 0.5f, 128, 12, &s->meshes[s->nmeshes], err, errlen)) ||
        !ADD_MESH(mesh_box(box_half, &s->meshes[s->nmeshes], err, errlen)) ||
        !ADD_MESH(mesh_icosphere(2.0f, 2, &s->meshes[s->nmeshes], err, errlen)) ||
        !ADD_MESH(mesh_cone(1.8f, 3.5f, 24, true, &s->meshes[s->nmeshes], err, errlen)) ||
        !ADD_MESH(mesh_pillar(1.0f, 5.0f, 16, &s->meshes[s->nmeshes], err, errlen)))
        return false;

    add_object(s, 0, 0, 0.0f, -0.5f, 0.0f, 1.0f);
    /* mesh, material per grid cell, row by row */
    static const uint32_t grid[9][2] = {{1, 1}, {2, 2}, {3, 3}, {4, 2}, {2, 3},
                                        {5, 1}, {6, 3}, {1, 2}, {3, 1}};
    for (int i = 0; i < 9; i++) {
        float x = (float)(i % 3 - 1) * 10.0f, z = (float)(i / 3 - 1) * 10.0f;
        /* the pillar stands on the floor, the cone lies on its side */
        float y = grid[i][0] == 6 ? 0.0f : (grid[i][0] == 5 ? 1.8f : 2.2f);
        scene_object *o = add_object(s, grid[i][0], grid[i][1], x, y, z, 1.0f);
        if (grid[i][0] == 2 || grid[i][0] == 3)
            o->spin_rate = 0.5f;   /* the papers' rotating models */
    }
    sm_vec3 bmin = {-20.0f, 0.5f, -20.0f}, bmax = {20.0f, 8.0f, 20.0f};
    sm_vec3_copy(bmin, s->light_bounds_min);
    sm_vec3_copy(bmax, s->light_bounds_max);
    sm_vec3 amb = {0.05f, 0.05f, 0.06f};
    sm_vec3_copy(amb, s->ambient);
    s->sky = true;
    s->sky_color[0] = 0.45f;
    s->sky_color[1] = 0.6f;
    s->sky_color[2] = 0.8f;
    sm_vec3_zero(s->orbit_target);
    s->orbit_radius = 35.0f;
    s->orbit_height = 18.0f;
    s->orbit_period = 30.0f;
    s->fovy = sm_deg2rad(60.0f);
    s->znear = 0.5f;
    s->zfar = 200.0f;
    return true;
oom:
    snprintf(err, errlen, "out of memory building scene 'shapes'");
    return false;
}

static void build_empty(scene *s)
{
    sm_vec3 bmin = {-50.0f, 0.0f, -50.0f}, bmax = {50.0f, 20.0f, 50.0f};
    sm_vec3_copy(bmin, s->light_bounds_min);
    sm_vec3_copy(bmax, s->light_bounds_max);
    sm_vec3 amb = {0.1f, 0.1f, 0.1f};
    sm_vec3_copy(amb, s->ambient);
    sm_vec3_zero(s->orbit_target);
    s->orbit_radius = 80.0f;
    s->orbit_height = 30.0f;
    s->orbit_period = 60.0f;
    s->fovy = sm_deg2rad(60.0f);
    s->znear = 0.1f;
    s->zfar = 1000.0f;
}

scene *scene_build(const char *name, const light_params *lp, int width, int height,
                   char *err, size_t errlen)
{
    if (!scene_catalog_find(name)) {
        snprintf(err, errlen, "unknown scene '%s'", name);
        return NULL;
    }
    if (width <= 0 || height <= 0) {
        snprintf(err, errlen, "bug: scene '%s' built for a %dx%d target", name, width, height);
        return NULL;
    }
    scene *s = calloc(1, sizeof *s);
    if (!s)
        goto oom;
    snprintf(s->name, sizeof s->name, "%s", name);
    s->width = width;
    s->height = height;
    if (strcmp(name, "shapes") == 0) {
        if (!build_shapes(s, err, errlen)) {
            char why[256];
            snprintf(why, sizeof why, "%s", err);
            scene_destroy(s);
            snprintf(err, errlen, "scene 'shapes': %s", why);
            return NULL;
        }
    } else {
        build_empty(s);   /* "empty" and the test scenes */
    }
    static const char *const faults[] = {"test-abort", "test-segv", "test-sigkill", "test-hang"};
    for (int i = 0; i < 4; i++)
        if (strcmp(name, faults[i]) == 0)
            s->fault = i + 1;

    s->count = lp->count;
    s->nlights_total = lp->placement == PLACEMENT_NONE ? 0 : light_count_max(&lp->count);
    if (s->nlights_total) {
        s->lights = calloc(s->nlights_total, sizeof *s->lights);
        if (!s->lights)
            goto oom;
        place_random(s, lp);
    }
    scene_update(s, 0.0);
    return s;
oom:
    scene_destroy(s);
    snprintf(err, errlen, "out of memory building scene '%s' with %u lights", name,
             light_count_max(&lp->count));
    return NULL;
}

/* model = translate(position) * rotate(spin_axis, spin_rate * t) * scale, and the
 * world bounding sphere of the object's mesh under it. */
static void pose_object(const scene *s, scene_object *o, double t)
{
    sm_mat4 tr, rot, sc, tmp;
    double angle = o->spin_rate != 0.0f ? fmod((double)o->spin_rate * t, 2.0 * SM_PI) : 0.0;
    sm_vec3 scale = {o->scale, o->scale, o->scale};
    sm_mat4_translate_make(o->position, tr);
    sm_mat4_rotate_make((float)angle, o->spin_axis, rot);
    sm_mat4_scale_make(scale, sc);
    sm_mat4_mul(tr, rot, tmp);
    sm_mat4_mul(tmp, sc, o->model);
    const mesh *m = &s->meshes[o->mesh];
    sm_vec3 c = {m->sphere[0], m->sphere[1], m->sphere[2]};
    sm_vec3 wc;
    sm_mat4_mulv3(o->model, c, 1.0f, wc);
    o->bsphere[0] = wc[0];
    o->bsphere[1] = wc[1];
    o->bsphere[2] = wc[2];
    o->bsphere[3] = m->sphere[3] * o->scale;
}

/* The test scenes' faults (catalog.c): each says what it does, then does it. */
static void inject_fault(const scene *s)
{
    fprintf(stderr, "%s: failing at t = %.3f s, as this test scene does\n", s->name, s->t);
    fflush(stderr);
    switch (s->fault) {
    case 1: abort();
    case 2: raise(SIGSEGV); break;
    case 3: raise(SIGKILL); break;
    case 4:
        for (;;) {
            struct timespec ts = {1, 0};
            nanosleep(&ts, NULL);
        }
    }
}

void scene_update(scene *s, double t)
{
    s->t = t;
    if (s->fault && t >= 0.2)
        inject_fault(s);
    uint32_t n = s->nlights_total ? light_count_at(&s->count, t) : 0;
    s->nlights_active = n < s->nlights_total ? n : s->nlights_total;

    /* Orbit: one revolution per orbit_period seconds of schedule time. The angle
     * is reduced in double precision so long runs keep a precise camera. */
    double turns = s->orbit_period > 0 ? fmod(t / s->orbit_period, 1.0) : 0.0;
    float a = (float)(turns * 2.0 * SM_PI);
    scene_camera *c = &s->cam;
    c->eye[0] = s->orbit_target[0] + s->orbit_radius * cosf(a);
    c->eye[1] = s->orbit_target[1] + s->orbit_height;
    c->eye[2] = s->orbit_target[2] + s->orbit_radius * sinf(a);
    sm_vec3_copy(s->orbit_target, c->target);
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3_copy(up, c->up);
    c->fovy = s->fovy;
    c->znear = s->znear;
    c->zfar = s->zfar;
    for (uint32_t i = 0; i < s->nobjects; i++)
        pose_object(s, &s->objects[i], t);
    sm_lookat(c->eye, c->target, c->up, s->view);
    sm_perspective(c->fovy, (float)s->width / (float)s->height, c->znear, c->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
}

void scene_destroy(scene *s)
{
    if (!s)
        return;
    for (uint32_t i = 0; i < s->nmeshes; i++)
        mesh_free(&s->meshes[i]);
    for (uint32_t i = 0; i < s->ntextures; i++)
        texture_free(&s->textures[i]);
    free(s->meshes);
    free(s->textures);
    free(s->materials);
    free(s->objects);
    free(s->lights);
    free(s);
}
