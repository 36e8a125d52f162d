/* The frontend: visible objects, lights, illumination sets and eye-inside flags of
 * one frame, decided once for every renderer (frontend.h says what each means). */
#include "renderers/frame/frontend.h"
#include "common/grow.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Illumination entries reserved at init when the worst case (objects x lights) is
 * larger; more are allocated (doubling) only in a frame that needs them. */
#define ILLUM_RESERVE ((size_t)1 << 20)

// >>light volumes

/* Spot angles usable for volumes: tan() finite and positive. */
static float clamp_spot_angle(float a)
{
    return sm_clamp(a, 1e-4f, SM_PI_2 - 1e-3f);
}

bool frontend_volume_meshes(mesh *sphere, mesh *cone, char *err, size_t errlen)
{
    mesh s = {0}, c = {0};
    char why[256] = "";
    if (!mesh_light_sphere(FRONTEND_SPHERE_SLICES, FRONTEND_SPHERE_STACKS, &s, why, sizeof why) ||
        !mesh_light_cone(SM_PI / 4.0f, FRONTEND_CONE_SEGMENTS, &c, why, sizeof why)) {
        mesh_free(&s);
        mesh_free(&c);
        if (sphere)
            memset(sphere, 0, sizeof *sphere);
        if (cone)
            memset(cone, 0, sizeof *cone);
        snprintf(err, errlen, "light volume meshes: %s", why);
        return false;
    }
    if (sphere)
        *sphere = s;
    else
        mesh_free(&s);
    if (cone)
        *cone = c;
    else
        mesh_free(&c);
    return true;
}

/* An orthonormal basis whose third vector is -dir (dir unit): the rotation taking
 * -Z onto dir. */
static void basis_minus_z_to(const sm_vec3 dir, sm_vec3 x, sm_vec3 y, sm_vec3 z)
{
    sm_vec3 helper = {0.0f, 1.0f, 0.0f};
    sm_vec3_negate_to(dir, z);
    if (fabsf(z[1]) > 0.9f)
        sm_vec3_make(1.0f, 0.0f, 0.0f, helper);
    sm_vec3_cross(helper, z, x);
    sm_vec3_normalize(x);
    sm_vec3_cross(z, x, y);
}

static void unit_direction(const scene_light *l, sm_vec3 dir)
{
    sm_vec3_normalize_to(l->direction, dir);
    if (dir[0] == 0.0f && dir[1] == 0.0f && dir[2] == 0.0f)
        sm_vec3_make(0.0f, -1.0f, 0.0f, dir);
}

void frontend_light_volume_model(const scene_light *l, sm_mat4 model)
{
    sm_mat4_identity(model);
    if (l->type == LIGHT_POINT) {
        float r = l->radius * FRONTEND_VOLUME_SCALE;
        model[0][0] = model[1][1] = model[2][2] = r;
    } else if (l->type == LIGHT_SPOT) {
        sm_vec3 dir, x, y, z;
        float w = l->radius * tanf(clamp_spot_angle(l->spot_angle));
        unit_direction(l, dir);
        basis_minus_z_to(dir, x, y, z);
        sm_vec3_scale(x, w, model[0]);
        sm_vec3_scale(y, w, model[1]);
        sm_vec3_scale(z, l->radius, model[2]);
    } else {
        return;
    }
    model[3][0] = l->position[0];
    model[3][1] = l->position[1];
    model[3][2] = l->position[2];
}

/* Smallest sphere holding a point (apex) and a disc of radius b whose centre is at
 * distance h from the apex along dir. */
static void cone_bound(const sm_vec3 apex, const sm_vec3 dir, float h, float b, sm_vec4 out)
{
    float t, r;
    h = fmaxf(h, 0.0f);
    b = fmaxf(b, 0.0f);
    if (b >= h) {
        t = h;   /* centred on the disc: the apex is within b of it */
        r = b;
    } else {
        t = (h * h + b * b) / (2.0f * h);   /* equidistant from the apex and the rim */
        r = t;
    }
    r *= 1.0f + 1e-5f;   /* rounding */
    out[0] = apex[0] + dir[0] * t;
    out[1] = apex[1] + dir[1] * t;
    out[2] = apex[2] + dir[2] * t;
    out[3] = r;
}

void frontend_spot_cone_bound(const sm_vec3 apex, const sm_vec3 dir, float half_angle,
                              float height, sm_vec4 out)
{
    float a = clamp_spot_angle(half_angle);
    cone_bound(apex, dir, height, height * tanf(a), out);
}

void frontend_light_volume_bound(const frontend *f, const scene_light *l, sm_vec4 out)
{
    if (l->type == LIGHT_POINT) {
        sm_vec4_from_vec3(l->position,
                          l->radius * FRONTEND_VOLUME_SCALE * f->sphere_vertex_radius *
                              (1.0f + 1e-5f),
                          out);
    } else if (l->type == LIGHT_SPOT) {
        sm_vec3 dir, apex;
        float r = l->radius, w = r * tanf(clamp_spot_angle(l->spot_angle));
        unit_direction(l, dir);
        /* the mesh's apex is at z = cone_apex_z (behind the light, -Z is forward) */
        sm_vec3_copy(l->position, apex);
        sm_vec3_muladds(dir, -f->cone_apex_z * r, apex);
        cone_bound(apex, dir, (f->cone_apex_z - f->cone_base_z) * r, f->cone_rim * w, out);
    } else {
        sm_vec4_make(0.0f, 0.0f, 0.0f, INFINITY, out);
    }
}

// >>init and free

/* *pp (any T *) reallocated to `bytes`; false, *pp unchanged, when out of memory. */
static bool resize(void *pp, size_t bytes)
{
    void *old;
    memcpy(&old, pp, sizeof old);
    void *p = realloc(old, bytes);
    if (!p)
        return false;
    memcpy(pp, &p, sizeof p);
    return true;
}

/* One array of a group: `per` elements a unit of the group's capacity plus `extra`. */
typedef struct group_array {
    void *pp;   /* a T ** */
    size_t elem, per, extra;
} group_array;
#define GROUP_ARRAY(p, per, extra) {&(p), sizeof *(p), (per), (extra)}

/* The arrays of a group (the objects: visible, translucent, and sort twice that for the
 * merge sort's two halves; the lights: lights, eye_inside, shadow_layer and
 * shadow_viewproj, with illum_start and shadow_start one more) hold what *cap says. The
 * first array grows (GROW); the others follow its capacity, which *cap takes once every
 * array has it (0 until then). */
static bool reserve_group(size_t *cap, size_t n, const group_array *a, size_t narrays)
{
    size_t c = *cap;
    if (!grow_array(a[0].pp, &c, n ? n : 1, a[0].elem, 16))
        return false;
    if (c == *cap)
        return true;
    for (size_t i = 1; i < narrays; i++)
        if (!resize(a[i].pp, (a[i].per * c + a[i].extra) * a[i].elem))
            return false;
    *cap = c;
    return true;
}

static bool reserve_objects(frontend *f, size_t n)
{
    const group_array a[] = {GROUP_ARRAY(f->visible, 1, 0), GROUP_ARRAY(f->translucent, 1, 0),
                             GROUP_ARRAY(f->sort, 2, 0)};
    return reserve_group(&f->cap_objects, n, a, sizeof a / sizeof a[0]);
}

static bool reserve_lights(frontend *f, size_t n)
{
    const group_array a[] = {
        GROUP_ARRAY(f->lights, 1, 0),          GROUP_ARRAY(f->eye_inside, 1, 0),
        GROUP_ARRAY(f->illum_start, 1, 1),     GROUP_ARRAY(f->shadow_layer, 1, 0),
        GROUP_ARRAY(f->shadow_start, 1, 1),    GROUP_ARRAY(f->shadow_viewproj, 1, 0),
    };
    return reserve_group(&f->cap_lights, n, a, sizeof a / sizeof a[0]);
}

static bool reserve_illum(frontend *f, size_t n)
{
    return GROW(f->illum, f->cap_illum, n ? n : 1, 16);
}

static bool reserve_shadow(frontend *f, size_t n)
{
    return GROW(f->shadow, f->cap_shadow, n ? n : 1, 16);
}

bool frontend_init(frontend *f, const scene *s, char *err, size_t errlen)
{
    mesh sphere, cone;

    memset(f, 0, sizeof *f);
    if (!frontend_volume_meshes(&sphere, &cone, err, errlen))
        return false;
    f->sphere_vertex_radius = sphere.sphere[3];
    f->cone_apex_z = cone.aabb[1][2];
    f->cone_base_z = cone.aabb[0][2];
    for (uint32_t i = 0; i < cone.nvertices; i++) {
        const float *p = cone.vertices[i].position;
        float d = sqrtf(p[0] * p[0] + p[1] * p[1]);
        if (d > f->cone_rim)
            f->cone_rim = d;
    }
    mesh_free(&sphere);
    mesh_free(&cone);

    size_t worst = (size_t)s->nobjects * (size_t)s->nlights_total;
    size_t casters = 0;
    for (uint32_t i = 0; i < s->nlights_total; i++)
        if (frontend_light_casts_shadows(&s->lights[i]))
            casters++;
    size_t worst_shadow = (size_t)s->nobjects * casters;
    if (!reserve_objects(f, s->nobjects) || !reserve_lights(f, s->nlights_total) ||
        !reserve_illum(f, worst < ILLUM_RESERVE ? worst : ILLUM_RESERVE) ||
        (worst_shadow &&
         !reserve_shadow(f, worst_shadow < ILLUM_RESERVE ? worst_shadow : ILLUM_RESERVE))) {
        frontend_free(f);
        snprintf(err, errlen, "frontend: out of memory for %u objects and %u lights",
                 s->nobjects, s->nlights_total);
        return false;
    }
    f->illum_start[0] = 0;
    f->shadow_start[0] = 0;
    return true;
}

void frontend_free(frontend *f)
{
    if (!f)
        return;
    free(f->visible);
    free(f->translucent);
    free(f->lights);
    free(f->illum_start);
    free(f->illum);
    free(f->eye_inside);
    free(f->sort);
    free(f->shadow_layer);
    free(f->shadow_start);
    free(f->shadow);
    free(f->shadow_viewproj);
    memset(f, 0, sizeof *f);
}

// >>sorting

static uint64_t saturate(int64_t v, unsigned bits)
{
    uint64_t max = ((uint64_t)1 << bits) - 1;
    if (v < 0)
        return 0;
    return (uint64_t)v > max ? max : (uint64_t)v;
}

uint64_t frontend_sort_key(const scene *s, uint32_t object)
{
    const scene_object *o = &s->objects[object];
    int64_t diffuse = -1;
    if (o->material < s->nmaterials)
        diffuse = s->materials[o->material].diffuse_map;
    return saturate(diffuse + 1, 22) << 42 | saturate(o->material, 21) << 21 |
           saturate(o->mesh, 21);
}

/* Stable bottom-up merge sort of items[0 .. n) by key, with tmp (n items) as the
 * other buffer; returns the buffer that holds the result. No allocation (qsort may
 * allocate, and is not stable). Items go in in object order, so equal keys stay in
 * object order. */
static frontend_sort_item *merge_sort(frontend_sort_item *items, frontend_sort_item *tmp,
                                      size_t n)
{
    frontend_sort_item *src = items, *dst = tmp;
    for (size_t width = 1; width < n; width *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * width) {
            size_t mid = lo + width < n ? lo + width : n;
            size_t hi = lo + 2 * width < n ? lo + 2 * width : n;
            size_t a = lo, b = mid, k = lo;
            while (a < mid && b < hi)
                dst[k++] = src[b].key < src[a].key ? src[b++] : src[a++];
            while (a < mid)
                dst[k++] = src[a++];
            while (b < hi)
                dst[k++] = src[b++];
        }
        frontend_sort_item *t = src;
        src = dst;
        dst = t;
    }
    return src;
}

// >>per frame

/* Distance from p to the near rectangle (corners 0 left-bottom, 1 left-top, 3
 * right-bottom; a rectangle for every perspective or orthographic projection). */
static float distance_to_near(const frontend *f, const sm_vec3 p)
{
    sm_vec3 o, u, v, q, c;
    sm_vec3_copy(f->near_corners[0], o);
    sm_vec3_sub(f->near_corners[3], f->near_corners[0], u);
    sm_vec3_sub(f->near_corners[1], f->near_corners[0], v);
    sm_vec3_sub(p, o, q);
    float uu = sm_vec3_norm2(u), vv = sm_vec3_norm2(v);
    float su = uu > 0.0f ? sm_clamp(sm_vec3_dot(q, u) / uu, 0.0f, 1.0f) : 0.0f;
    float sv = vv > 0.0f ? sm_clamp(sm_vec3_dot(q, v) / vv, 0.0f, 1.0f) : 0.0f;
    sm_vec3_copy(o, c);
    sm_vec3_muladds(u, su, c);
    sm_vec3_muladds(v, sv, c);
    return sm_vec3_distance(p, c);
}

static bool volume_holds_eye(const frontend *f, const scene_light *l)
{
    sm_vec4 b;
    if (l->type == LIGHT_DIRECTIONAL)
        return true;
    frontend_light_volume_bound(f, l, b);
    if (sm_point_in_sphere(f->eye, b))
        return true;
    float d = distance_to_near(f, b);
    return !(d > b[3]);   /* a NaN (degenerate matrices) counts as inside */
}

/* The sphere that bounds a point light's range or a spot light's cone. */
static void light_bound(const scene_light *l, sm_vec4 b)
{
    if (l->type == LIGHT_SPOT) {
        sm_vec3 dir;
        unit_direction(l, dir);
        frontend_spot_cone_bound(l->position, dir, l->spot_angle, l->radius, b);
    } else {
        sm_vec4_from_vec3(l->position, l->radius, b);
    }
}

static bool light_visible(const frontend *f, const scene_light *l)
{
    if (l->type == LIGHT_DIRECTIONAL)
        return true;
    sm_vec4 b;
    light_bound(l, b);
    return sm_sphere_in_frustum(f->planes, b);
}

static bool light_reaches(const scene_light *l, const sm_vec4 bsphere)
{
    switch (l->type) {
    case LIGHT_DIRECTIONAL:
        return true;
    case LIGHT_SPOT: {
        sm_vec3 dir;
        unit_direction(l, dir);
        return sm_cone_sphere_intersects(l->position, dir, l->spot_angle, l->radius, bsphere);
    }
    default: {
        sm_vec4 ls;
        sm_vec4_from_vec3(l->position, l->radius, ls);
        return sm_sphere_sphere_intersects(ls, bsphere);
    }
    }
}

// >>shadow-casting sets (frontend.h, "shadow")

/* Drawn in the translucent pass, not in the opaque passes (frontend.h). */
static bool object_translucent(const scene *s, uint32_t o)
{
    uint32_t m = s->objects[o].material;
    return m < s->nmaterials && scene_material_translucent(&s->materials[m]);
}

/* A key whose ascending order is the descending order of the float d (NaN last). */
static uint64_t far_first_key(float d)
{
    uint32_t u;
    memcpy(&u, &d, sizeof u);
    if (d != d)
        return UINT64_MAX;
    u = (u & 0x80000000u) ? ~u : (u | 0x80000000u);   /* ascending with d */
    return (uint64_t)(~u);
}

bool frontend_light_casts_shadows(const scene_light *l)
{
    return l->shadows && (l->type == LIGHT_SPOT || l->type == LIGHT_DIRECTIONAL);
}

/* Appends object o to the shadow entries; false when memory ran out (the set is cut
 * short and the frame marked truncated). */
static bool push_shadow(frontend *f, size_t *k, uint32_t o)
{
    if (*k >= f->cap_shadow && !reserve_shadow(f, *k + 1)) {
        fprintf(stderr, "frontend: out of memory for %zu shadow-set entries: sets cut short\n",
                *k + 1);
        f->truncated = true;
        return false;
    }
    f->shadow[(*k)++] = o;
    return true;
}

/* On the inside of all six planes (on a plane counts as inside; NaN as outside). */
static bool point_in_frustum(const sm_vec4 planes[6], const sm_vec3 p)
{
    for (int i = 0; i < 6; i++)
        if (!(sm_plane_distance(planes[i], p) >= 0.0f))
            return false;
    return true;
}

static void spot_shadow_viewproj(const scene_light *l, sm_mat4 out)
{
    sm_vec3 dir, up = {0.0f, 1.0f, 0.0f};
    sm_mat4 view, proj;
    unit_direction(l, dir);
    sm_look(l->position, dir, up, view);
    float far = l->radius;
    /* radius <= 0 (or NaN) gives the zero matrix: nothing is drawn, every lookup is lit */
    sm_perspective(2.0f * clamp_spot_angle(l->spot_angle), 1.0f, far * 1e-3f, far, proj);
    sm_mat4_mul(proj, view, out);
}

/* The spot's set (frontend.h), entries from *k on. illum/nillum: its illumination set. */
static void spot_shadow_set(frontend *f, const scene *s, const scene_light *l,
                            const uint32_t *illum, uint32_t nillum, size_t *k)
{
    if (nillum == 0)
        return;
    if (point_in_frustum(f->planes, l->position)) {
        for (uint32_t i = 0; i < nillum; i++)
            if (!push_shadow(f, k, illum[i]))
                return;
        return;
    }
    for (uint32_t o = 0; o < s->nobjects; o++)
        if (!object_translucent(s, o) && light_reaches(l, s->objects[o].bsphere) &&
            !push_shadow(f, k, o))
            return;
}

/* The directional light's set and matrix (frontend.h). */
static void directional_shadow(frontend *f, const scene *s, const scene_light *l, size_t *k,
                               sm_mat4 out)
{
    sm_vec3 dir, up = {0.0f, 1.0f, 0.0f}, origin = {0.0f, 0.0f, 0.0f};
    sm_mat4 view, proj;
    unit_direction(l, dir);
    sm_look(origin, dir, up, view);
    float x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    float dmin = INFINITY, dmax = -INFINITY;
    for (uint32_t v = 0; v < f->nvisible; v++) {
        const float *b = s->objects[f->visible[v]].bsphere;
        sm_vec3 c;
        sm_mat4_mulv3(view, b, 1.0f, c);
        float r = b[3];
        x0 = fminf(x0, c[0] - r);
        x1 = fmaxf(x1, c[0] + r);
        y0 = fminf(y0, c[1] - r);
        y1 = fmaxf(y1, c[1] + r);
        dmin = fminf(dmin, -c[2] - r);
        dmax = fmaxf(dmax, -c[2] + r);
    }
    if (!(x0 <= x1 && y0 <= y1 && dmin <= dmax && isfinite(x1 - x0) && isfinite(y1 - y0) &&
          isfinite(dmax - dmin))) {
        sm_mat4_zero(out);   /* nothing visible: no receiver, nothing drawn */
        return;
    }
    for (uint32_t o = 0; o < s->nobjects; o++) {
        if (object_translucent(s, o))
            continue;
        const float *b = s->objects[o].bsphere;
        sm_vec3 c;
        sm_mat4_mulv3(view, b, 1.0f, c);
        float r = b[3];
        float dx = fmaxf(fmaxf(x0 - c[0], c[0] - x1), 0.0f);
        float dy = fmaxf(fmaxf(y0 - c[1], c[1] - y1), 0.0f);
        if (!(dx * dx + dy * dy <= r * r && -c[2] - r <= dmax))
            continue;
        if (!push_shadow(f, k, o))
            break;
        dmin = fminf(dmin, -c[2] - r);
    }
    float ex = fmaxf(0.01f * (x1 - x0), 1e-3f), ey = fmaxf(0.01f * (y1 - y0), 1e-3f),
          ed = fmaxf(0.01f * (dmax - dmin), 1e-3f);
    sm_ortho(x0 - ex, x1 + ex, y0 - ey, y1 + ey, dmin - ed, dmax + ed, proj);
    sm_mat4_mul(proj, view, out);
}

// >>per frame, everything

void frontend_build(frontend *f, const scene *s)
{
    sm_mat4 inv;
    sm_vec4 corners[8];
    uint32_t nactive = s->nlights_active < s->nlights_total ? s->nlights_active
                                                             : s->nlights_total;

    f->nvisible = 0;
    f->ntranslucent = 0;
    f->nlights = 0;
    f->nshadowed = 0;
    f->truncated = false;
    if (!reserve_objects(f, s->nobjects) || !reserve_lights(f, nactive)) {
        fprintf(stderr, "frontend: out of memory for %u objects and %u lights: nothing drawn\n",
                s->nobjects, nactive);
        if (f->illum_start)
            f->illum_start[0] = 0;
        if (f->shadow_start)
            f->shadow_start[0] = 0;
        f->truncated = true;
        return;
    }

    sm_frustum_planes(s->viewproj, f->planes);
    sm_mat4_inv(s->view, inv);
    sm_vec3_copy(inv[3], f->eye);
    sm_mat4_inv(s->viewproj, inv);
    sm_frustum_corners(inv, corners);
    for (int i = 0; i < 4; i++)
        sm_vec4_copy(corners[i], f->near_corners[i]);

    /* visible objects, sorted */
    uint32_t n = 0, nt = 0;
    for (uint32_t i = 0; i < s->nobjects; i++)
        if (sm_sphere_in_frustum(f->planes, s->objects[i].bsphere)) {
            if (object_translucent(s, i)) {
                f->translucent[nt++] = i;   /* sorted below */
                continue;
            }
            f->sort[n].key = frontend_sort_key(s, i);
            f->sort[n].object = i;
            n++;
        }
    const frontend_sort_item *sorted = merge_sort(f->sort, f->sort + f->cap_objects, n);
    for (uint32_t i = 0; i < n; i++)
        f->visible[i] = sorted[i].object;
    f->nvisible = n;

    /* translucent objects back to front: the view depth of each sphere's centre */
    for (uint32_t i = 0; i < nt; i++) {
        uint32_t o = f->translucent[i];
        const float *c = s->objects[o].bsphere;
        float z = s->view[0][2] * c[0] + s->view[1][2] * c[1] + s->view[2][2] * c[2] +
                  s->view[3][2];
        f->sort[i].key = far_first_key(-z);
        f->sort[i].object = o;
    }
    sorted = merge_sort(f->sort, f->sort + f->cap_objects, nt);
    for (uint32_t i = 0; i < nt; i++)
        f->translucent[i] = sorted[i].object;
    f->ntranslucent = nt;

    /* lights, their illumination sets and shadow-casting sets */
    size_t k = 0, ks = 0;
    f->illum_start[0] = 0;
    f->shadow_start[0] = 0;
    for (uint32_t li = 0; li < nactive; li++) {
        const scene_light *l = &s->lights[li];
        if (!light_visible(f, l))
            continue;
        uint32_t j = f->nlights++;
        f->lights[j] = li;
        f->eye_inside[j] = volume_holds_eye(f, l) ? 1u : 0u;
        bool sets = !f->no_illumination ||
                    (!f->no_shadows && l->type == LIGHT_SPOT && frontend_light_casts_shadows(l));
        for (uint32_t v = 0; sets && v < f->nvisible && !f->truncated; v++) {
            uint32_t o = f->visible[v];
            if (!light_reaches(l, s->objects[o].bsphere))
                continue;
            if (k >= f->cap_illum && !reserve_illum(f, k + 1)) {
                fprintf(stderr, "frontend: out of memory for %zu illumination entries: "
                        "sets cut short\n", k + 1);
                f->truncated = true;
                break;
            }
            f->illum[k++] = o;
        }
        f->illum_start[j + 1] = (uint32_t)k;

        f->shadow_layer[j] = FRONTEND_NO_SHADOW;
        if (!f->no_shadows && frontend_light_casts_shadows(l)) {
            f->shadow_layer[j] = f->nshadowed++;
            if (l->type == LIGHT_SPOT) {
                spot_shadow_viewproj(l, f->shadow_viewproj[j]);
                if (!f->truncated)
                    spot_shadow_set(f, s, l, f->illum + f->illum_start[j],
                                    f->illum_start[j + 1] - f->illum_start[j], &ks);
            } else if (!f->truncated) {
                directional_shadow(f, s, l, &ks, f->shadow_viewproj[j]);
            } else {
                sm_mat4_zero(f->shadow_viewproj[j]);
            }
        }
        f->shadow_start[j + 1] = (uint32_t)ks;
    }
}
