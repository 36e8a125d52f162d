/* Scene construction and posing. Each catalog scene is built by its builder (the
 * registry below; scenes/scene_*.c); the run's lights are then placed from the manifest's
 * light parameters; scene_update poses everything from schedule time alone.
 *
 * Sections: >>registry >>placement >>build >>probe >>posing >>camera-overrides >>coverage */
#include "scenes/scene.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scenes/scene_build.h"

// >>registry

/* The scene sources: the catalog (catalog.c's table, each entry with its builder) and
 * files (file_assimp.c); each builder takes its source's argument. */
typedef struct source_plan {
    char name[64];
    scene_build_fn build;
    const void *arg;
    int fault;
} source_plan;

static bool plan_source(const scene_source *src, source_plan *p, char *err, size_t errlen)
{
    memset(p, 0, sizeof *p);
    if (src->file) {
        const char *path = src->file->path ? src->file->path : "";
        const char *base = strrchr(path, '/');
        snprintf(p->name, sizeof p->name, "%s", base ? base + 1 : path);
        p->build = scene_build_file;
        p->arg = src->file;
        return true;
    }
    const char *name = src->name ? src->name : "";
    const scene_catalog_entry *e = scene_catalog_find(name);
    if (!e) {
        snprintf(err, errlen, "unknown scene '%s'", name);
        return false;
    }
    snprintf(p->name, sizeof p->name, "%s", name);
    p->build = scene_catalog_builder(e);
    p->fault = scene_catalog_fault(e);
    if (!p->build) {
        snprintf(err, errlen, "bug: scene '%s' is in the catalog but has no builder", name);
        return false;
    }
    return true;
}

// >>placement

static void point_light_from_params(scene_light *l, const light_params *lp, float radius)
{
    l->type = LIGHT_POINT;
    l->radius = radius;
    l->attenuation = (attenuation_kind)lp->attenuation;
    l->att_a = lp->quadratic[0];
    l->att_b = lp->quadratic[1];
    l->att_c = lp->quadratic[2];
    sm_vec3_make(0.0f, -1.0f, 0.0f, l->direction);
}

/* The run's point-light radius: lp->radius, or with lp->overlap > 0 the radius at which
 * the schedule's largest count reaches `overlap` lights per point of the light bounds
 * (lights_overlap_radius). */
static float placement_radius(const scene *s, const light_params *lp)
{
    if (lp->overlap > 0.0f)
        return lights_overlap_radius(s->nlights_total, lp->overlap, s->light_bounds_min,
                                     s->light_bounds_max);
    return lp->radius;
}

/* Random placement: for each light in order, x, y, z uniform in the scene's light
 * bounds, then r, g, b uniform in [0, color_max]. Lights are generated up to the
 * schedule's maximum once, so growth adds lights without moving earlier ones. */
static void place_random(scene *s, const light_params *lp)
{
    rng g;
    rng_seed(&g, lp->rng, lp->seed);
    float radius = placement_radius(s, lp);
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        scene_light *l = &s->lights[i];
        for (int k = 0; k < 3; k++) {
            float u = rng_unit(&g);
            l->position[k] = s->light_bounds_min[k] +
                             u * (s->light_bounds_max[k] - s->light_bounds_min[k]);
        }
        for (int k = 0; k < 3; k++)
            l->color[k] = rng_unit(&g) * lp->color_max;
        point_light_from_params(l, lp, radius);
    }
}

/* A grid: n[] cells along x, y, z; the nearest neighbours are `spacing` apart. */
typedef struct grid_layout {
    uint32_t n[3];
    double spacing;
} grid_layout;

/* Distance between neighbouring cell centres along an axis; no neighbour: infinite. */
static double axis_spacing(uint32_t cells, double extent)
{
    return cells > 1 ? extent / (double)cells : INFINITY;
}

/* m lights in one layer of x-z cells, as square as the extents allow: nx near
 * sqrt(m ex / ez) (cells of side sqrt(ex ez / m)), the floor or ceiling of it, whichever
 * spaces them further apart (the smaller on a tie), and nz = ceil(m / nx) rows. A flat
 * extent gets one cell that way. */
static void grid_layer(uint32_t m, double ex, double ez, uint32_t *nx, uint32_t *nz,
                       double *spacing)
{
    *nx = *nz = 1;
    if (m > 1) {
        if (ex > 0 && ez > 0) {
            double r = sqrt((double)m * ex / ez);
            double cand[2] = {floor(r), ceil(r)};
            double best = -1.0;
            for (int c = 0; c < 2; c++) {
                uint32_t x = (uint32_t)fmin(fmax(cand[c], 1.0), (double)m);
                uint32_t z = (m + x - 1) / x;
                double sp = fmin(axis_spacing(x, ex), axis_spacing(z, ez));
                if (sp > best) {
                    best = sp;
                    *nx = x;
                    *nz = z;
                }
            }
        } else if (ez > 0) {
            *nz = m;
        } else {
            *nx = m;   /* along x, or all in one point when both are flat */
        }
    }
    *spacing = fmin(axis_spacing(*nx, ex), axis_spacing(*nz, ez));
}

/* The grid for n lights in extents e[3] with the largest nearest-neighbour spacing:
 * ny layers (one at mid-height unless the bounds are tall enough that more layers
 * space the lights further apart), each holding ceil(n / ny) lights as grid_layer
 * lays them out. Ties keep the fewer layers. */
static grid_layout grid_plan(uint32_t n, const double e[3])
{
    grid_layout best = {{1, 1, 1}, -1.0};
    uint32_t most = n < 4096 ? n : 4096;
    for (uint32_t ny = 1; ny <= most || ny == 1; ny++) {
        double sy = axis_spacing(ny, e[1]);
        if (sy <= best.spacing)
            break;   /* more layers only bring them closer */
        uint32_t m = n ? (n + ny - 1) / ny : 0, nx, nz;
        double sxz;
        grid_layer(m, e[0], e[2], &nx, &nz, &sxz);
        double sp = fmin(sy, sxz);
        if (sp > best.spacing) {
            best.n[0] = nx;
            best.n[1] = ny;
            best.n[2] = nz;
            best.spacing = sp;
        }
    }
    return best;
}

/* Whether grid placement fits: the layout for the schedule's largest count (grid_plan)
 * in the light bounds' extents e, and the radius; false with the message when the
 * radius exceeds half the spacing (neighbouring spheres would overlap). */
static bool grid_fits(const scene *s, const light_params *lp, double e[3], grid_layout *g,
                      float *radius, char *err, size_t errlen)
{
    for (int k = 0; k < 3; k++)
        e[k] = fmax(0.0, (double)s->light_bounds_max[k] - (double)s->light_bounds_min[k]);
    *g = grid_plan(s->nlights_total, e);
    *radius = placement_radius(s, lp);
    if ((double)*radius > g->spacing / 2.0) {
        snprintf(err, errlen,
                 "scene '%s': grid placement of %u lights in %u x %u x %u cells (x, y, z) "
                 "of the light bounds puts neighbours %.6g apart: radius %.6g makes them "
                 "overlap; the largest radius allowed is %.6g",
                 s->name, s->nlights_total, g->n[0], g->n[1], g->n[2], g->spacing,
                 (double)*radius, g->spacing / 2.0);
        return false;
    }
    return true;
}

/* Grid placement: the layout is planned for the schedule's largest count (grid_plan),
 * and light k takes cell k in row order (x fastest, then z, then the layer), at the
 * cell's centre: growth adds lights without moving earlier ones. Colours r, g, b uniform
 * in [0, color_max] from the seeded generator, per light in order. Fails when the
 * radius exceeds half the spacing (grid_fits). */
static bool place_grid(scene *s, const light_params *lp, char *err, size_t errlen)
{
    double e[3];
    grid_layout g;
    float radius;
    if (!grid_fits(s, lp, e, &g, &radius, err, errlen))
        return false;
    rng r;
    rng_seed(&r, lp->rng, lp->seed);
    uint32_t per_layer = g.n[0] * g.n[2];
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        scene_light *l = &s->lights[i];
        uint32_t cell[3] = {i % per_layer % g.n[0], i / per_layer, i % per_layer / g.n[0]};
        for (int k = 0; k < 3; k++)
            l->position[k] = (float)((double)s->light_bounds_min[k] +
                                     ((double)cell[k] + 0.5) * e[k] / (double)g.n[k]);
        for (int k = 0; k < 3; k++)
            l->color[k] = rng_unit(&r) * lp->color_max;
        point_light_from_params(l, lp, radius);
    }
    return true;
}

/* The run's lights on a built scene: the authored ones (placement scene) or placed from
 * lp. With `check`, only whether they can be: the same failures and messages, but no
 * light is placed and s->lights is left NULL (what a plan check asks of many runs). */
static bool place_lights(scene *s, const scene_light *authored, uint32_t nauthored,
                         uint32_t ncoverage, const light_params *lp, bool check, char *err,
                         size_t errlen)
{
    const char *name = s->name;
    s->count = lp->count;
    uint32_t most = light_count_max(&lp->count);
    switch (lp->placement) {
    case PLACEMENT_NONE:
        s->nlights_total = 0;
        break;
    case PLACEMENT_SCENE:
        /* the authored lights in their order; the count caps how many are ever on */
        if (nauthored == 0) {
            snprintf(err, errlen, "scene '%s' has no authored lights", name);
            return false;
        }
        s->nlights_total = most < nauthored ? most : nauthored;
        s->ncoverage_lights = ncoverage < s->nlights_total ? ncoverage : s->nlights_total;
        break;
    case PLACEMENT_RANDOM:
    case PLACEMENT_GRID:
        s->nlights_total = most;
        break;
    default:
        snprintf(err, errlen, "bug: light placement %d", (int)lp->placement);
        return false;
    }
    if (!s->nlights_total)
        return true;
    s->lights = calloc(s->nlights_total, sizeof *s->lights);
    if (!s->lights) {
        snprintf(err, errlen, "out of memory building scene '%s' with %u lights", name,
                 s->nlights_total);
        return false;
    }
    if (check) {
        free(s->lights);
        s->lights = NULL;
        double e[3];
        grid_layout g;
        float radius;
        return lp->placement != PLACEMENT_GRID || grid_fits(s, lp, e, &g, &radius, err, errlen);
    }
    if (lp->placement == PLACEMENT_SCENE)
        memcpy(s->lights, authored, s->nlights_total * sizeof *s->lights);
    else if (lp->placement == PLACEMENT_RANDOM)
        place_random(s, lp);
    else if (!place_grid(s, lp, err, errlen))
        return false;
    return true;
}

// >>build

scene *scene_build(const char *name, const light_params *lp, int width, int height,
                   char *err, size_t errlen)
{
    scene_source src = {.name = name, .file = NULL};
    return scene_build_source(&src, lp, width, height, err, errlen);
}

/* The scene from its builder, without the run's lights (nlights_total 0), at t = 0; the
 * builder's authored lights are left in *bout's authored (the caller frees *bout and its
 * authored). NULL with the message on failure. */
static scene *build_unlit(const scene_source *src, int width, int height, scene_builder **bout,
                          char *err, size_t errlen)
{
    *bout = NULL;
    source_plan plan;
    if (!plan_source(src, &plan, err, errlen))
        return NULL;
    const char *name = plan.name;
    if (width <= 0 || height <= 0) {
        snprintf(err, errlen, "bug: scene '%s' built for a %dx%d target", name, width, height);
        return NULL;
    }
    scene *s = calloc(1, sizeof *s);
    scene_builder *b = calloc(1, sizeof *b);
    if (!s || !b) {
        free(b);
        free(s);
        snprintf(err, errlen, "out of memory building scene '%s'", name);
        return NULL;
    }
    snprintf(s->name, sizeof s->name, "%s", name);
    s->width = width;
    s->height = height;
    s->hold = NAN;
    char why[256] = "";
    b->s = s;
    b->err = why;
    b->errlen = sizeof why;
    if (!plan.build(b, plan.arg) || b->failed) {
        snprintf(err, errlen, "scene '%s': %s", name, why);
        free(b->authored);
        free(b);
        scene_destroy(s);
        return NULL;
    }
    s->fault = plan.fault;
    *bout = b;
    return s;
}

scene *scene_build_source(const scene_source *src, const light_params *lp, int width,
                          int height, char *err, size_t errlen)
{
    scene_builder *b;
    scene *s = build_unlit(src, width, height, &b, err, errlen);
    if (!s)
        return NULL;
    bool ok = place_lights(s, b->authored, b->nauthored, b->ncoverage, lp, false, err, errlen);
    free(b->authored);
    free(b);
    if (!ok) {
        scene_destroy(s);
        return NULL;
    }
    scene_update(s, 0.0);
    return s;
}

// >>probe

struct scene_probe {
    scene *s;                  /* built without lights, at t = 0 */
    uint32_t nauthored, ncoverage;
};

scene_probe *scene_probe_build(const scene_source *src, char *err, size_t errlen)
{
    scene_probe *p = calloc(1, sizeof *p);
    if (!p) {
        snprintf(err, errlen, "out of memory building scene '%s'",
                 src->file ? (src->file->path ? src->file->path : "") : src->name);
        return NULL;
    }
    scene_builder *b;
    p->s = build_unlit(src, 1, 1, &b, err, errlen);
    if (!p->s) {
        free(p);
        return NULL;
    }
    p->nauthored = b->nauthored;
    p->ncoverage = b->ncoverage;
    free(b->authored);
    free(b);
    scene_update(p->s, 0.0);
    return p;
}

bool scene_probe_check(const scene_probe *p, const light_params *lp, const camera_params *cp,
                       int width, int height, char *err, size_t errlen)
{
    if (width <= 0 || height <= 0) {
        snprintf(err, errlen, "bug: scene '%s' built for a %dx%d target", p->s->name, width,
                 height);
        return false;
    }
    /* a copy of the probe's values: place_lights in check mode and scene_set_camera
     * change only values, and the copy's pointers stay the probe's */
    scene t = *p->s;
    t.width = width;
    t.height = height;
    t.lights = NULL;
    if (!place_lights(&t, NULL, p->nauthored, p->ncoverage, lp, true, err, errlen))
        return false;
    t.count = lp->count;
    return !cp || scene_set_camera(&t, cp, err, errlen);
}

void scene_probe_destroy(scene_probe *p)
{
    if (!p)
        return;
    scene_destroy(p->s);
    free(p);
}

// >>posing

/* An upper bound on how far the upper 3x3 of m stretches any vector (its largest
 * singular value): sqrt of the largest absolute row sum of M^T M, which bounds M^T M's
 * largest eigenvalue. Exactly 1 for the identity, s for a uniform scale s. */
static float transform_stretch(const sm_mat4 m)
{
    double most = 0.0;
    for (int i = 0; i < 3; i++) {
        double row = 0.0;
        for (int j = 0; j < 3; j++)
            row += fabs((double)m[i][0] * m[j][0] + (double)m[i][1] * m[j][1] +
                        (double)m[i][2] * m[j][2]);
        most = fmax(most, row);
    }
    return (float)sqrt(most);
}

/* model = translate(position) * rotate(spin_axis, spin_rate * t) * scale * transform,
 * and the world bounding sphere of the object's mesh under it (its radius times scale
 * times the transform's stretch bound, so non-uniform scales and shears stay inside). */
static void pose_object(const scene *s, scene_object *o, double t)
{
    sm_mat4 tr, rot, sc, tmp;
    double angle = o->spin_rate != 0.0f ? fmod((double)o->spin_rate * t, 2.0 * SM_PI) : 0.0;
    sm_vec3 scale = {o->scale, o->scale, o->scale};
    sm_mat4_translate_make(o->position, tr);
    sm_mat4_rotate_make((float)angle, o->spin_axis, rot);
    sm_mat4_scale_make(scale, sc);
    sm_mat4 trs;
    sm_mat4_mul(tr, rot, tmp);
    sm_mat4_mul(tmp, sc, trs);
    sm_mat4_mul(trs, o->transform, o->model);
    const mesh *m = &s->meshes[o->mesh];
    sm_vec3 c = {m->sphere[0], m->sphere[1], m->sphere[2]};
    sm_vec3 wc;
    sm_mat4_mulv3(o->model, c, 1.0f, wc);
    o->bsphere[0] = wc[0];
    o->bsphere[1] = wc[1];
    o->bsphere[2] = wc[2];
    o->bsphere[3] = m->sphere[3] * o->scale * transform_stretch(o->transform);
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

/* Where the camera is at schedule time t, from the scene's path values alone.
 *   orbit:    angle = 2 pi x (hold, or t / orbit_period reduced to one turn in double
 *             precision, so long runs keep a precise camera); eye = orbit_target +
 *             (orbit_radius cos angle, orbit_height, orbit_radius sin angle), looking at
 *             orbit_target.
 *   scripted: the path fraction f = hold, or clamp(t / orbit_period, 0, 1); the nkeys key
 *             poses sit at f = k / (nkeys - 1), and eye and target are interpolated
 *             linearly between the two around f (f = 0 and f = 1 give the first and last
 *             key exactly).
 * Up is +Y. A t that is not a number counts as 0. */
static void camera_at(const scene *s, double t, scene_camera *c)
{
    if (isnan(t))
        t = 0.0;
    if (s->path == CAMERA_SCRIPTED && s->nkeys > 0) {
        double f = !isnan(s->hold) ? (double)s->hold
                                      : (s->orbit_period > 0 ? t / s->orbit_period : 1.0);
        f = f > 0.0 ? (f < 1.0 ? f : 1.0) : 0.0;
        double pos = f * (double)(s->nkeys - 1);
        uint32_t k = (uint32_t)pos;
        if (k + 1 >= s->nkeys) {
            sm_vec3_copy(s->key_eye[s->nkeys - 1], c->eye);
            sm_vec3_copy(s->key_target[s->nkeys - 1], c->target);
        } else {
            double u = pos - (double)k;
            for (int i = 0; i < 3; i++) {
                c->eye[i] = (float)((1.0 - u) * s->key_eye[k][i] + u * s->key_eye[k + 1][i]);
                c->target[i] =
                    (float)((1.0 - u) * s->key_target[k][i] + u * s->key_target[k + 1][i]);
            }
        }
    } else {
        double turns = !isnan(s->hold)
                           ? (double)s->hold
                           : (s->orbit_period > 0 ? fmod(t / s->orbit_period, 1.0) : 0.0);
        float a = (float)(turns * 2.0 * SM_PI);
        c->eye[0] = s->orbit_target[0] + s->orbit_radius * cosf(a);
        c->eye[1] = s->orbit_target[1] + s->orbit_height;
        c->eye[2] = s->orbit_target[2] + s->orbit_radius * sinf(a);
        sm_vec3_copy(s->orbit_target, c->target);
    }
    sm_vec3_make(0.0f, 1.0f, 0.0f, c->up);
    c->fovy = s->fovy;
    c->znear = s->znear;
    c->zfar = s->zfar;
}

static void pose_camera(scene *s, double t)
{
    camera_at(s, t, &s->cam);
    const scene_camera *c = &s->cam;
    sm_lookat(c->eye, c->target, c->up, s->view);
    sm_perspective(c->fovy, (float)s->width / (float)s->height, c->znear, c->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
}

void scene_update(scene *s, double t)
{
    s->t = t;
    if (s->fault && t >= 0.2)
        inject_fault(s);
    uint32_t n = s->nlights_total ? light_count_at(&s->count, t) : 0;
    s->nlights_active = n < s->nlights_total ? n : s->nlights_total;
    for (uint32_t i = 0; i < s->nobjects; i++)
        pose_object(s, &s->objects[i], t);
    pose_camera(s, t);
}

// >>camera-overrides

void camera_params_init(camera_params *cp)
{
    cp->radius = cp->height = cp->period = NAN;
    cp->target[0] = cp->target[1] = cp->target[2] = NAN;
    cp->znear = cp->zfar = NAN;
    cp->hold = NAN;
}

static bool finite_positive(float x) { return isfinite(x) && x > 0.0f; }

/* Whether a camera pose can make a view: finite, and the eye apart from the target by
 * more than float rounding at their magnitude. */
static bool pose_ok(const scene_camera *c)
{
    float big = 0.0f, d2 = 0.0f;
    for (int i = 0; i < 3; i++) {
        if (!isfinite(c->eye[i]) || !isfinite(c->target[i]))
            return false;
        big = fmaxf(big, fmaxf(fabsf(c->eye[i]), fabsf(c->target[i])));
        d2 += (c->eye[i] - c->target[i]) * (c->eye[i] - c->target[i]);
    }
    return sqrtf(d2) > 1e-5f * fmaxf(big, 1.0f);
}

bool scene_set_camera(scene *s, const camera_params *cp, char *err, size_t errlen)
{
    bool scripted = s->path == CAMERA_SCRIPTED;
    bool has_target = !isnan(cp->target[0]);
    /* an orbit's values on a scripted path would be silently ignored: refuse them */
    if (scripted && (!isnan(cp->radius) || !isnan(cp->height) || has_target)) {
        const char *key = !isnan(cp->radius) ? "radius" : !isnan(cp->height) ? "height" : "target";
        snprintf(err, errlen, "camera.%s: scene '%s' follows a scripted path, which has no "
                 "orbit %s (period, hold, near and far apply)", key, s->name, key);
        return false;
    }
    if (!isnan(cp->radius) && !finite_positive(cp->radius)) {
        snprintf(err, errlen, "camera.radius: expected a finite number > 0, found %g",
                 (double)cp->radius);
        return false;
    }
    if (!isnan(cp->height) && !isfinite(cp->height)) {
        snprintf(err, errlen, "camera.height: expected a finite number, found %g",
                 (double)cp->height);
        return false;
    }
    if (!isnan(cp->period) && !finite_positive(cp->period)) {
        snprintf(err, errlen, "camera.period: expected a finite number of seconds > 0, found %g",
                 (double)cp->period);
        return false;
    }
    if (has_target && !(isfinite(cp->target[0]) && isfinite(cp->target[1]) &&
                        isfinite(cp->target[2]))) {
        snprintf(err, errlen, "camera.target: expected three finite numbers, found [%g, %g, %g]",
                 (double)cp->target[0], (double)cp->target[1], (double)cp->target[2]);
        return false;
    }
    if (!isnan(cp->znear) && !finite_positive(cp->znear)) {
        snprintf(err, errlen, "camera.near: expected a finite number > 0, found %g",
                 (double)cp->znear);
        return false;
    }
    float znear = isnan(cp->znear) ? s->znear : cp->znear;
    if (!isnan(cp->zfar) && !(isfinite(cp->zfar) && cp->zfar > znear)) {
        snprintf(err, errlen, "camera.far: expected a finite number > near (%g), found %g",
                 (double)znear, (double)cp->zfar);
        return false;
    }
    float zfar = isnan(cp->zfar) ? s->zfar : cp->zfar;
    if (!(zfar > znear)) {
        snprintf(err, errlen, "camera.near: %g is not below the scene's far plane (%g)",
                 (double)znear, (double)zfar);
        return false;
    }
    if (!isnan(cp->hold) && !(cp->hold >= 0.0f && cp->hold <= 1.0f)) {
        snprintf(err, errlen, "camera.hold: expected a path fraction in [0, 1], found %g",
                 (double)cp->hold);
        return false;
    }

    scene trial = *s;   /* camera values only: the copy's pointers are not used */
    if (!isnan(cp->radius))
        trial.orbit_radius = cp->radius;
    if (!isnan(cp->height))
        trial.orbit_height = cp->height;
    if (!isnan(cp->period))
        trial.orbit_period = cp->period;
    if (has_target)
        sm_vec3_copy(cp->target, trial.orbit_target);
    trial.znear = znear;
    trial.zfar = zfar;
    if (!isnan(cp->hold))
        trial.hold = cp->hold;
    /* every pose the path can take: an orbit's eye at the quarter turns (and where it
     * holds), a scripted path's keys (the poses between lie on the segments) */
    scene_camera c;
    bool ok = true;
    if (scripted) {
        for (uint32_t k = 0; k < trial.nkeys && ok; k++) {
            trial.hold = trial.nkeys > 1 ? (float)k / (float)(trial.nkeys - 1) : 0.0f;
            camera_at(&trial, 0.0, &c);
            ok = pose_ok(&c);
        }
    } else {
        for (int q = 0; q < 4 && ok; q++) {
            trial.hold = (float)q * 0.25f;
            camera_at(&trial, 0.0, &c);
            ok = pose_ok(&c);
        }
    }
    trial.hold = isnan(cp->hold) ? s->hold : cp->hold;
    if (ok) {
        camera_at(&trial, s->t, &c);
        ok = pose_ok(&c);
    }
    if (!ok) {
        snprintf(err, errlen, "camera: the eye (%g, %g, %g) meets the target (%g, %g, %g) or "
                 "is not finite: no view direction (radius %g, height %g)",
                 (double)c.eye[0], (double)c.eye[1], (double)c.eye[2], (double)c.target[0],
                 (double)c.target[1], (double)c.target[2], (double)trial.orbit_radius,
                 (double)trial.orbit_height);
        return false;
    }
    s->orbit_radius = trial.orbit_radius;
    s->orbit_height = trial.orbit_height;
    s->orbit_period = trial.orbit_period;
    sm_vec3_copy(trial.orbit_target, s->orbit_target);
    s->znear = trial.znear;
    s->zfar = trial.zfar;
    s->hold = trial.hold;
    pose_camera(s, s->t);
    return true;
}

// >>coverage

/* Whether the ray o + t d (t >= 0, d unit) meets the ball of radius r about c. */
static bool ray_meets_sphere(const double o[3], const double d[3], const float c[3], double r)
{
    double v[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
    double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (vv <= r * r)
        return true;   /* the eye is inside */
    double b = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
    return b > 0.0 && vv - b * b <= r * r;
}

/* Whether the ray o + t d (t >= 0, d unit) meets the finite cone of apex a, unit axis u,
 * half angle th and height h (the points p with 0 <= (p - a).u <= h and angle(p - a, u) <=
 * th: capped by the plane at distance h along the axis). On the part of the ray within the
 * two planes, (p - a).u >= 0, so p is in the cone exactly when
 *   q(t) = ((p - a).u)^2 - cos^2(th) |p - a|^2 >= 0,
 * a quadratic in t; the ray meets the cone when q's largest value over that part (at an
 * end or at the vertex) is >= 0. */
static bool ray_meets_cone(const double o[3], const double d[3], const float a[3],
                           const double u[3], double th, double h)
{
    double w[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
    double wu = w[0] * u[0] + w[1] * u[1] + w[2] * u[2];
    double du = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    double t0 = 0.0, t1 = INFINITY;
    if (du == 0.0) {
        if (wu < 0.0 || wu > h)
            return false;
    } else {
        double ta = -wu / du, tb = (h - wu) / du;
        t0 = fmax(0.0, fmin(ta, tb));
        t1 = fmax(ta, tb);
        if (t0 > t1)
            return false;
    }
    double c2 = cos(th) * cos(th);
    double dw = d[0] * w[0] + d[1] * w[1] + d[2] * w[2];
    double ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    double A = du * du - c2, B = du * wu - c2 * dw, C = wu * wu - c2 * ww;
#define Q(t) ((A * (t) + 2.0 * B) * (t) + C)
    if (Q(t0) >= 0.0 || (isfinite(t1) && Q(t1) >= 0.0))
        return true;
    if (A < 0.0) {
        double tv = -B / A;
        if (tv > t0 && tv < t1 && Q(tv) >= 0.0)
            return true;
    }
#undef Q
    return false;
}

/* Point: the ball of `radius`. Spot: the cone of half angle spot_angle (clamped to
 * [1e-4, pi/2 - 1e-3], as the renderers clamp it), apex at the light, along its direction
 * (a zero direction counts as -Y, as in the renderers), capped by the PLANE at distance
 * `radius` along the axis: the volume renderers/frontend.c culls with and the deferred
 * renderer rasterizes (mesh_light_cone of height = range). The lit part of it (within
 * `radius` of the light, lighting.inc) is the cone capped by the sphere, inside this.
 * The ray is the whole ray from the eye: neither the near nor the far plane cuts it.
 * An index beyond nlights_total gives 0; whether the light is active does not matter. */
double scene_light_coverage(const scene *s, uint32_t i)
{
    if (!s || i >= s->nlights_total)
        return 0.0;
    const scene_light *l = &s->lights[i];
    if (l->type == LIGHT_DIRECTIONAL)
        return 1.0;
    if (!(l->radius > 0.0f) || !isfinite(l->radius))
        return 0.0;
    double axis[3] = {l->direction[0], l->direction[1], l->direction[2]};
    double len = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (!(len > 0.0) || !isfinite(len)) {
        axis[0] = 0.0;
        axis[1] = -1.0;
        axis[2] = 0.0;
        len = 1.0;
    }
    for (int k = 0; k < 3; k++)
        axis[k] /= len;
    double th = sm_clamp(l->spot_angle, 1e-4f, SM_PI_2 - 1e-3f);

    /* the view's rows are the camera's right, up and backward axes in world space */
    double right[3], up[3], back[3];
    for (int k = 0; k < 3; k++) {
        right[k] = s->view[k][0];
        up[k] = s->view[k][1];
        back[k] = s->view[k][2];
    }
    double ty = tan((double)s->cam.fovy / 2.0), tx = ty * (double)s->width / (double)s->height;
    double eye[3] = {s->cam.eye[0], s->cam.eye[1], s->cam.eye[2]};
    uint32_t sw = s->width < 128 ? (uint32_t)s->width : 128;
    uint32_t sh = s->height < 128 ? (uint32_t)s->height : 128;
    uint64_t hits = 0;
    for (uint32_t j = 0; j < sh; j++) {
        /* the pixel row at the sample's place, and that pixel's centre */
        double py = floor(((double)j + 0.5) * s->height / sh) + 0.5;
        double yn = 1.0 - 2.0 * py / s->height;
        for (uint32_t k = 0; k < sw; k++) {
            double px = floor(((double)k + 0.5) * s->width / sw) + 0.5;
            double xn = 2.0 * px / s->width - 1.0;
            double d[3], dd = 0.0;
            for (int c = 0; c < 3; c++) {
                d[c] = xn * tx * right[c] + yn * ty * up[c] - back[c];
                dd += d[c] * d[c];
            }
            dd = sqrt(dd);
            for (int c = 0; c < 3; c++)
                d[c] /= dd;
            bool hit = l->type == LIGHT_POINT
                           ? ray_meets_sphere(eye, d, l->position, l->radius)
                           : ray_meets_cone(eye, d, l->position, axis, th, l->radius);
            hits += hit;
        }
    }
    return (double)hits / ((double)sw * (double)sh);
}

void scene_destroy(scene *s)
{
    if (!s)
        return;
    for (uint32_t i = 0; s->meshes && i < s->nmeshes; i++)
        mesh_free(&s->meshes[i]);
    for (uint32_t i = 0; s->textures && i < s->ntextures; i++)
        texture_free(&s->textures[i]);
    free(s->meshes);
    free(s->textures);
    free(s->materials);
    free(s->objects);
    free(s->lights);
    free(s);
}

uint32_t scene_make_opaque(scene *s)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->nmaterials; i++) {
        scene_material *m = &s->materials[i];
        if (!scene_material_translucent(m))
            continue;
        m->alpha = MATERIAL_OPAQUE;
        m->opacity = 1.0f;
        n++;
    }
    return n;
}
