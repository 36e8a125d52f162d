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
        sm_vec3 down = {0.0f, -1.0f, 0.0f};
        sm_vec3_copy(down, l->direction);
    }
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
    build_empty(s);   /* every scene of the catalog is the empty one so far */
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
    sm_lookat(c->eye, c->target, c->up, s->view);
    sm_perspective(c->fovy, (float)s->width / (float)s->height, c->znear, c->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
}

void scene_destroy(scene *s)
{
    if (!s)
        return;
    free(s->lights);
    free(s);
}
