/* The run's lights placed on a built scene (>>placement): authored, random or on a grid,
 * from the manifest's light parameters. See scenes/scene_make.c. */
#include "scenes/scene_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

/* A world-space corner of object o's triangle at schedule time 0 (no spin yet:
 * translate(position) x scale x transform, as scene_pose.c poses it). */
static void corner_at_0(const scene_object *o, const mesh *m, uint32_t index, sm_vec3 out)
{
    sm_mat4_mulv3(o->transform, m->vertices[index].position, 1.0f, out);
    for (int k = 0; k < 3; k++)
        out[k] = o->position[k] + o->scale * out[k];
}

double scene_triangle_at_0(const scene *s, const scene_object *o, uint32_t t, sm_vec3 w[3],
                            sm_vec3 n)
{
    const mesh *m = &s->meshes[o->mesh];
    for (int c = 0; c < 3; c++)
        corner_at_0(o, m, m->indices[3 * t + c], w[c]);
    sm_vec3 e1, e2;
    sm_vec3_sub(w[1], w[0], e1);
    sm_vec3_sub(w[2], w[0], e2);
    sm_vec3_cross(e1, e2, n);
    double a = 0.5 * sqrt((double)sm_vec3_dot(n, n));
    return isfinite(a) ? a : 0.0;
}

/* The surface area of every object's triangles at time 0 (surface placement). */
static double surface_area(const scene *s)
{
    double area = 0.0;
    sm_vec3 w[3], n;
    for (uint32_t i = 0; i < s->nobjects; i++)
        for (uint32_t t = 0; t < s->meshes[s->objects[i].mesh].nindices / 3; t++)
            area += scene_triangle_at_0(s, &s->objects[i], t, w, n);
    return area;
}

/* The run's point-light radius: lp->radius, or with lp->overlap > 0 the radius at which
 * the schedule's largest count reaches `overlap` lights per point of the light bounds
 * (lights_overlap_radius); surface placement has its own (place_surface). */
static float placement_radius(const scene *s, const light_params *lp)
{
    if (lp->overlap > 0.0f)
        return lights_overlap_radius(s->nlights_total, lp->overlap, s->light_bounds_min,
                                     s->light_bounds_max);
    return lp->radius;
}

/* Whether the ray from p along d crosses triangle w (Moller-Trumbore), at t > 0. */
static bool ray_crosses(const sm_vec3 p, const sm_vec3 d, sm_vec3 w[3])
{
    sm_vec3 e1, e2, h, q, sv;
    sm_vec3_sub(w[1], w[0], e1);
    sm_vec3_sub(w[2], w[0], e2);
    sm_vec3_cross(d, e2, h);
    double a = sm_vec3_dot(e1, h);
    if (fabs(a) < 1e-12)
        return false;
    sm_vec3_sub(p, w[0], sv);
    double u = sm_vec3_dot(sv, h) / a;
    if (u < 0.0 || u > 1.0)
        return false;
    sm_vec3_cross(sv, e1, q);
    double v = sm_vec3_dot(d, q) / a;
    if (v < 0.0 || u + v > 1.0)
        return false;
    return sm_vec3_dot(e2, q) / a > 0.0;
}

/* Whether p lies inside a closed mesh: an odd number of an object's triangles crossed
 * by a ray from p in a direction no axis-aligned face is parallel to, for any object
 * whose time-0 box (lo, hi: 3 floats an object) holds p. */
static bool inside_an_object(const scene *s, const float *lo, const float *hi, const sm_vec3 p)
{
    static const sm_vec3 d = {0.5773f, 0.5774f, 0.5775f};
    for (uint32_t o = 0; o < s->nobjects; o++) {
        if (p[0] < lo[3 * o] || p[1] < lo[3 * o + 1] || p[2] < lo[3 * o + 2] ||
            p[0] > hi[3 * o] || p[1] > hi[3 * o + 1] || p[2] > hi[3 * o + 2])
            continue;
        unsigned crossings = 0;
        sm_vec3 w[3], n;
        for (uint32_t t = 0; t < s->meshes[s->objects[o].mesh].nindices / 3; t++) {
            scene_triangle_at_0(s, &s->objects[o], t, w, n);
            crossings += ray_crosses(p, d, w);
        }
        if (crossings & 1u)
            return true;
    }
    return false;
}

/* Each object's box at time 0 (lo, hi: 3 floats an object, lo then hi in one block the
 * caller frees), or NULL with a message when memory runs out. */
static float *object_boxes(const scene *s, char *err, size_t errlen)
{
    float *lo = malloc((s->nobjects ? s->nobjects : 1) * 6 * sizeof *lo);
    if (!lo) {
        snprintf(err, errlen, "out of memory placing lights about the %u objects of scene "
                 "'%s'", s->nobjects, s->name);
        return NULL;
    }
    float *hi = lo + 3 * s->nobjects;
    sm_vec3 w[3], nrm;
    for (uint32_t o = 0; o < s->nobjects; o++) {
        for (int k = 0; k < 3; k++) {
            lo[3 * o + k] = INFINITY;
            hi[3 * o + k] = -INFINITY;
        }
        for (uint32_t t = 0; t < s->meshes[s->objects[o].mesh].nindices / 3; t++) {
            scene_triangle_at_0(s, &s->objects[o], t, w, nrm);
            for (int c = 0; c < 3; c++)
                for (int k = 0; k < 3; k++) {
                    lo[3 * o + k] = fminf(lo[3 * o + k], w[c][k]);
                    hi[3 * o + k] = fmaxf(hi[3 * o + k], w[c][k]);
                }
        }
    }
    return lo;
}

/* Random placement: for each light in order, x, y, z uniform in the scene's light
 * bounds, then r, g, b uniform in [0, color_max]. Lights are generated up to the
 * schedule's maximum once, so growth adds lights without moving earlier ones. A scene
 * with lights_outside (a file's, lights around) draws x, y, z again while they fall
 * inside a closed mesh, up to 16 times (then keeps the last): a light in a closed
 * model lights none of its faces. False with a message when memory runs out. */
static bool place_random(scene *s, const light_params *lp, char *err, size_t errlen)
{
    float *lo = NULL;
    if (s->lights_outside && s->nlights_total && !(lo = object_boxes(s, err, errlen)))
        return false;
    const float *hi = lo ? lo + 3 * s->nobjects : NULL;
    rng g;
    rng_seed(&g, lp->rng, lp->seed);
    float radius = placement_radius(s, lp);
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        scene_light *l = &s->lights[i];
        for (int attempt = 0; attempt < 16; attempt++) {
            for (int k = 0; k < 3; k++) {
                float u = rng_unit(&g);
                l->position[k] = s->light_bounds_min[k] +
                                 u * (s->light_bounds_max[k] - s->light_bounds_min[k]);
            }
            if (!lo || !inside_an_object(s, lo, hi, l->position))
                break;
        }
        for (int k = 0; k < 3; k++)
            l->color[k] = rng_unit(&g) * lp->color_max;
        point_light_from_params(l, lp, radius);
    }
    free(lo);
    return true;
}

/* Surface placement (scenes/lights.h): per light in order, u0 picks a triangle by area
 * (a binary search of the running sum over objects and their triangles, in order), u1
 * and u2 a point on it uniformly (barycentrics 1 - sqrt(u1), sqrt(u1)(1 - u2),
 * sqrt(u1) u2), and the light stands a quarter of its radius in front of it; a spot
 * inside a closed mesh (a floor under a pillar: the pillar's inside) is drawn again, up
 * to 16 times; then r, g, b as random. False with a message when the scene has no
 * triangle area or memory runs out. */
static bool place_surface(scene *s, const light_params *lp, char *err, size_t errlen)
{
    size_t ntri = 0;
    for (uint32_t o = 0; o < s->nobjects; o++)
        ntri += s->meshes[s->objects[o].mesh].nindices / 3;
    double *sum = malloc((ntri ? ntri : 1) * sizeof *sum);
    uint32_t(*which)[2] = malloc((ntri ? ntri : 1) * sizeof *which);   /* object, triangle */
    float *lo = object_boxes(s, err, errlen);
    if (!sum || !which || !lo) {
        free(sum);
        free(which);
        free(lo);
        snprintf(err, errlen, "out of memory placing lights near the %zu triangles of scene "
                 "'%s'", ntri, s->name);
        return false;
    }
    float *hi = lo + 3 * s->nobjects;
    size_t n = 0;
    double area = 0.0;
    sm_vec3 w[3], nrm;
    for (uint32_t o = 0; o < s->nobjects; o++)
        for (uint32_t t = 0; t < s->meshes[s->objects[o].mesh].nindices / 3; t++) {
            double a = scene_triangle_at_0(s, &s->objects[o], t, w, nrm);
            if (!(a > 0.0))
                continue;
            area += a;
            sum[n] = area;
            which[n][0] = o;
            which[n++][1] = t;
        }
    bool ok = n > 0;
    if (!ok)
        snprintf(err, errlen, "scene '%s' has no surface to place lights near (placement "
                 "surface): its triangles have no area", s->name);
    rng g;
    rng_seed(&g, lp->rng, lp->seed);
    /* with overlap: n pi r^2 / area = overlap, per point of the surfaces */
    float radius = lp->overlap > 0.0f && ok
                       ? (float)sqrt((double)lp->overlap * area /
                                     ((double)SM_PI * (double)s->nlights_total))
                       : lp->radius;
    for (uint32_t i = 0; ok && i < s->nlights_total; i++) {
        scene_light *l = &s->lights[i];
        for (int attempt = 0; attempt < 16; attempt++) {
            double want = (double)rng_unit(&g) * area;
            float u1 = rng_unit(&g), u2 = rng_unit(&g);
            size_t a = 0, b = n - 1;   /* the first running sum >= want */
            while (a < b) {
                size_t mid = a + (b - a) / 2;
                if (sum[mid] >= want)
                    b = mid;
                else
                    a = mid + 1;
            }
            scene_triangle_at_0(s, &s->objects[which[a][0]], which[a][1], w, nrm);
            sm_vec3_normalize(nrm);
            float r1 = sqrtf(u1), bc[3] = {1.0f - r1, r1 * (1.0f - u2), r1 * u2};
            for (int k = 0; k < 3; k++)
                l->position[k] = bc[0] * w[0][k] + bc[1] * w[1][k] + bc[2] * w[2][k] +
                                 0.25f * radius * nrm[k];
            if (!inside_an_object(s, lo, hi, l->position))
                break;
        }
        for (int k = 0; k < 3; k++)
            l->color[k] = rng_unit(&g) * lp->color_max;
        point_light_from_params(l, lp, radius);
    }
    free(sum);
    free(which);
    free(lo);
    return ok;
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
bool scene_place_lights(scene *s, const scene_light *authored, uint32_t nauthored,
                        uint32_t ncoverage, const light_params *lp, bool check, char *err,
                        size_t errlen)
{
    const char *name = s->name;
    s->count = lp->count;
    s->lights_seed = lp->seed;
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
    case PLACEMENT_SURFACE:
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
        if (lp->placement == PLACEMENT_SURFACE && !(surface_area(s) > 0.0)) {
            snprintf(err, errlen, "scene '%s' has no surface to place lights near (placement "
                     "surface): its triangles have no area", name);
            return false;
        }
        return lp->placement != PLACEMENT_GRID || grid_fits(s, lp, e, &g, &radius, err, errlen);
    }
    if (lp->placement == PLACEMENT_SCENE)
        memcpy(s->lights, authored, s->nlights_total * sizeof *s->lights);
    else if (lp->placement == PLACEMENT_RANDOM)
        return place_random(s, lp, err, errlen);
    else if (lp->placement == PLACEMENT_SURFACE)
        return place_surface(s, lp, err, errlen);
    else if (!place_grid(s, lp, err, errlen))
        return false;
    return true;
}

// >>sizing

bool scene_size_lights(scene *s, const light_params *lp, float exposure, char *err,
                       size_t errlen)
{
    if (lp->sizing == LIGHT_SIZING_RADIUS || lp->placement == PLACEMENT_SCENE ||
        lp->placement == PLACEMENT_NONE)
        return true;
    if (!(exposure > 0.0f) || !isfinite(exposure) || !(lp->cutoff > 0.0f)) {
        snprintf(err, errlen, "lights.sizing: an exposure of %g and a cutoff of %g give no "
                 "light range", (double)exposure, (double)lp->cutoff);
        return false;
    }
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        scene_light *l = &s->lights[i];
        if (l->type == LIGHT_DIRECTIONAL)
            continue;
        if (lp->sizing == LIGHT_SIZING_RANGE_FROM_INTENSITY) {
            float c = fmaxf(l->color[0], fmaxf(l->color[1], l->color[2]));
            double r = sqrt((double)c * (double)exposure / (double)lp->cutoff);
            l->radius = r > 1e-6 ? (float)r : 1e-6f;
        } else {
            double k = (double)lp->cutoff * (double)l->radius * (double)l->radius /
                       ((double)exposure * (double)lp->color_max);
            if (lp->color_max > 0.0f)
                for (int c = 0; c < 3; c++)
                    l->color[c] = (float)(l->color[c] * k);
        }
        if (!isfinite(l->radius) || !isfinite(l->color[0]) || !isfinite(l->color[1]) ||
            !isfinite(l->color[2])) {
            snprintf(err, errlen, "lights.sizing: light %u's %s is not finite (exposure %g, "
                     "cutoff %g)", i, lp->sizing == LIGHT_SIZING_RANGE_FROM_INTENSITY ?
                     "range" : "colour", (double)exposure, (double)lp->cutoff);
            return false;
        }
    }
    return true;
}
