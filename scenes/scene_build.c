/* The builders' shared helpers: see scenes/scene_build.h. */
#include "scenes/scene_build.h"

#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/grow.h"

// >>setup

bool sb_fail(scene_builder *b, const char *fmt, ...)
{
    if (!b->failed) {
        b->failed = true;
        if (b->err && b->errlen) {
            va_list ap;
            va_start(ap, fmt);
            vsnprintf(b->err, b->errlen, fmt, ap);
            va_end(ap);
        }
    }
    return false;
}

bool sb_reserve(scene_builder *b, void **items, size_t *cap, uint32_t n, uint32_t more,
                size_t size, const char *what)
{
    if (b->failed)
        return false;
    if (more > UINT32_MAX - n)
        return sb_fail(b, "too many %s (%u + %u)", what, n, more);
    uint32_t need = n + more;
    if (need > SIZE_MAX / size)
        return sb_fail(b, "too many %s (%u)", what, need);
    size_t old = *cap;
    if (!grow_array(items, cap, need, size, 8))
        return sb_fail(b, "out of memory for %u %s (%.0f MiB)", need, what,
                       (double)need * (double)size / 1048576.0);
    /* the new slots start zeroed, as calloc'ed tables did */
    memset((char *)*items + old * size, 0, (*cap - old) * size);
    return true;
}

bool sb_begin(scene_builder *b, uint32_t nobjects)
{
    scene *s = b->s;
    return sb_reserve(b, (void **)&s->meshes, &b->cap_meshes, 0, 1, sizeof *s->meshes,
                      "meshes") &&
           sb_reserve(b, (void **)&s->textures, &b->cap_textures, 0, 1, sizeof *s->textures,
                      "textures") &&
           sb_reserve(b, (void **)&s->materials, &b->cap_materials, 0, 1,
                      sizeof *s->materials, "materials") &&
           sb_reserve(b, (void **)&s->objects, &b->cap_objects, 0, nobjects ? nobjects : 1,
                      sizeof *s->objects, "objects");
}

// >>meshes

/* The next free mesh slot (the table grown when full), or NULL after a failure. */
static mesh *slot(scene_builder *b)
{
    if (!sb_reserve(b, (void **)&b->s->meshes, &b->cap_meshes, b->s->nmeshes, 1,
                    sizeof *b->s->meshes, "meshes"))
        return NULL;
    return &b->s->meshes[b->s->nmeshes];
}

/* Keeps the mesh just built in slot(); a generator's failure left its message in err. */
static int keep(scene_builder *b, bool ok)
{
    if (!ok) {
        b->failed = true;
        return -1;
    }
    return (int)b->s->nmeshes++;
}

int sb_box(scene_builder *b, float hx, float hy, float hz)
{
    mesh *m = slot(b);
    sm_vec3 half = {hx, hy, hz};
    return m ? keep(b, mesh_box(half, m, b->err, b->errlen)) : -1;
}

int sb_sphere(scene_builder *b, float radius, uint32_t slices, uint32_t stacks)
{
    mesh *m = slot(b);
    return m ? keep(b, mesh_sphere(radius, slices, stacks, m, b->err, b->errlen)) : -1;
}

int sb_icosphere(scene_builder *b, float radius, uint32_t subdivisions)
{
    mesh *m = slot(b);
    return m ? keep(b, mesh_icosphere(radius, subdivisions, m, b->err, b->errlen)) : -1;
}

int sb_torus_knot(scene_builder *b, uint32_t p, uint32_t q, float radius, float tube,
                  uint32_t segments, uint32_t sides)
{
    mesh *m = slot(b);
    return m ? keep(b, mesh_torus_knot(p, q, radius, tube, segments, sides, m, b->err,
                                       b->errlen))
             : -1;
}

int sb_cylinder(scene_builder *b, float radius, float height, uint32_t segments)
{
    mesh *m = slot(b);
    return m ? keep(b, mesh_cylinder(radius, height, segments, m, b->err, b->errlen)) : -1;
}

int sb_pillar(scene_builder *b, float radius, float height, uint32_t segments)
{
    mesh *m = slot(b);
    return m ? keep(b, mesh_pillar(radius, height, segments, m, b->err, b->errlen)) : -1;
}

int sb_cone(scene_builder *b, float radius, float height, uint32_t segments, bool capped)
{
    mesh *m = slot(b);
    return m ? keep(b, mesh_cone(radius, height, segments, capped, m, b->err, b->errlen)) : -1;
}

int sb_corridor(scene_builder *b, float width, float height, float length, float uv_scale)
{
    mesh *m = slot(b);
    return m ? keep(b, mesh_corridor(width, height, length, uv_scale, m, b->err, b->errlen))
             : -1;
}

int sb_heightfield(scene_builder *b, float size_x, float size_z, uint32_t cells_x,
                   uint32_t cells_z, mesh_height_fn fn, void *user)
{
    mesh *m = slot(b);
    return m ? keep(b, mesh_heightfield_fn(size_x, size_z, cells_x, cells_z, fn, user, m,
                                           b->err, b->errlen))
             : -1;
}

static mesh *built(scene_builder *b, int m)
{
    if (b->failed)
        return NULL;
    if (m < 0 || (uint32_t)m >= b->s->nmeshes) {
        sb_fail(b, "bug: no mesh %d", m);
        return NULL;
    }
    return &b->s->meshes[m];
}

void sb_mesh_transform(scene_builder *b, int m, const sm_mat4 mat)
{
    mesh *me = built(b, m);
    if (me && !mesh_transform(me, mat, b->err, b->errlen))
        b->failed = true;
}

void sb_mesh_uv_scale(scene_builder *b, int m, float su, float sv)
{
    mesh *me = built(b, m);
    if (!me)
        return;
    for (uint32_t i = 0; i < me->nvertices; i++) {
        me->vertices[i].uv[0] *= su;
        me->vertices[i].uv[1] *= sv;
    }
}

/* The axis (0, 1, 2) a unit vector is closest to. */
static int major_axis(const float *v)
{
    float ax = fabsf(v[0]), ay = fabsf(v[1]), az = fabsf(v[2]);
    return ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
}

void sb_box_uv_tile(scene_builder *b, int m, const sm_vec3 half, float tile)
{
    mesh *me = built(b, m);
    if (!me)
        return;
    for (uint32_t i = 0; i < me->nvertices; i++) {
        mesh_vertex *v = &me->vertices[i];
        sm_vec3 bt;
        sm_vec3_cross(v->normal, v->tangent, bt);
        /* a box face's u runs along its tangent's axis, v along the bitangent's */
        v->uv[0] *= 2.0f * half[major_axis(v->tangent)] / tile;
        v->uv[1] *= 2.0f * half[major_axis(bt)] / tile;
    }
}

uint64_t sb_mesh_triangles(const scene *s)
{
    uint64_t n = 0;
    for (uint32_t i = 0; i < s->nobjects; i++)
        n += s->meshes[s->objects[i].mesh].nindices / 3;
    return n;
}

// >>maps and materials

/* The maps this process has made, kept to be copied rather than made again: a sweep
 * builds its scene in the parent (the plan check) and again in each trial's child, which
 * inherits this memo across fork. The built-in scenes' noise maps were a fifth of a
 * small trial's time on llvmpipe. Bounded; a map beyond the bound is made each time. */
typedef bool (*texture_maker)(const texture_desc *, texture_image *, char *, size_t);
typedef struct made_map {
    texture_maker make;
    texture_desc desc;
    texture_image img;
} made_map;
#define MADE_MAX 64
#define MADE_BYTES_MAX ((size_t)64 << 20)
/* made_copy compares descriptions with memcmp: they must have no padding bytes */
_Static_assert(sizeof(texture_desc) == 19 * 4, "texture_desc has padding or new fields");
static made_map made[MADE_MAX];
static unsigned nmade;
static size_t made_bytes;
static pthread_mutex_t made_lock = PTHREAD_MUTEX_INITIALIZER;

static size_t map_bytes(const texture_image *t)
{
    return (size_t)t->width * t->height * t->channels;
}

/* A copy of the map made from (make, d) before, into *out: false when there is none
 * (or no memory for the copy). */
static bool made_copy(texture_maker make, const texture_desc *d, texture_image *out)
{
    bool hit = false;
    pthread_mutex_lock(&made_lock);
    for (unsigned i = 0; i < nmade && !hit; i++) {
        if (made[i].make != make || memcmp(&made[i].desc, d, sizeof *d) != 0)
            continue;
        size_t n = map_bytes(&made[i].img);
        uint8_t *data = malloc(n);
        if (data) {
            memcpy(data, made[i].img.data, n);
            *out = made[i].img;
            out->data = data;
            hit = true;
        }
        break;
    }
    pthread_mutex_unlock(&made_lock);
    return hit;
}

static void made_keep(texture_maker make, const texture_desc *d, const texture_image *t)
{
    size_t n = map_bytes(t);
    pthread_mutex_lock(&made_lock);
    if (nmade < MADE_MAX && n <= MADE_BYTES_MAX - made_bytes) {
        uint8_t *data = malloc(n);
        if (data) {
            memcpy(data, t->data, n);
            made[nmade] = (made_map){.make = make, .desc = *d, .img = *t};
            made[nmade++].img.data = data;
            made_bytes += n;
        }
    }
    pthread_mutex_unlock(&made_lock);
}

int sb_texture(scene_builder *b, texture_maker make, const texture_desc *d)
{
    if (!sb_reserve(b, (void **)&b->s->textures, &b->cap_textures, b->s->ntextures, 1,
                    sizeof *b->s->textures, "textures"))
        return -1;
    texture_image *t = &b->s->textures[b->s->ntextures];
    if (!made_copy(make, d, t)) {
        if (!make(d, t, b->err, b->errlen)) {
            b->failed = true;
            return -1;
        }
        made_keep(make, d, t);
    }
    return (int)b->s->ntextures++;
}

sb_map_set sb_maps(scene_builder *b, const texture_desc *d, bool emissive)
{
    sb_map_set m;
    m.diffuse = sb_texture(b, texture_diffuse, d);
    m.gloss = sb_texture(b, texture_gloss, d);
    m.normal = sb_texture(b, texture_normal_map, d);
    m.emissive = emissive ? sb_texture(b, texture_emissive, d) : -1;
    return m;
}

uint32_t sb_material(scene_builder *b, float r, float g, float bl, float specular,
                     float shininess)
{
    if (!sb_reserve(b, (void **)&b->s->materials, &b->cap_materials, b->s->nmaterials, 1,
                    sizeof *b->s->materials, "materials"))
        return 0;
    scene_material *m = &b->s->materials[b->s->nmaterials];
    memset(m, 0, sizeof *m);
    sm_vec3_make(r, g, bl, m->diffuse);
    m->specular = specular;
    m->shininess = shininess;
    m->opacity = 1.0f;
    m->diffuse_map = m->gloss_map = m->normal_map = m->emissive_map = m->orm_map = -1;
    /* the metallic-roughness model's view of a Phong material (scene.h): a dielectric
     * whose GGX alpha matches the Blinn-Phong exponent, alpha = sqrt(2 / (n + 2)) */
    m->metallic = 0.0f;
    m->roughness = sm_clamp(sqrtf(sqrtf(2.0f / (fmaxf(shininess, 0.0f) + 2.0f))), 0.0f, 1.0f);
    return b->s->nmaterials++;
}

uint32_t sb_material_maps(scene_builder *b, const sb_map_set *maps, float specular,
                          float shininess, float emissive)
{
    uint32_t i = sb_material(b, 1.0f, 1.0f, 1.0f, specular, shininess);
    if (b->failed)
        return 0;
    scene_material *m = &b->s->materials[i];
    m->diffuse_map = maps->diffuse;
    m->gloss_map = maps->gloss;
    m->normal_map = maps->normal;
    m->emissive_map = maps->emissive;
    if (maps->emissive >= 0)
        sm_vec3_make(emissive, emissive, emissive, m->emissive);
    return i;
}

// >>objects

scene_object *sb_object(scene_builder *b, int mesh_index, uint32_t material, float x, float y,
                        float z, float scale)
{
    scene *s = b->s;
    if (!b->failed)
        sb_reserve(b, (void **)&s->objects, &b->cap_objects, s->nobjects, 1, sizeof *s->objects,
                   "objects");
    if (!b->failed && (mesh_index < 0 || (uint32_t)mesh_index >= s->nmeshes ||
                       material >= s->nmaterials))
        sb_fail(b, "bug: object of mesh %d, material %u", mesh_index, material);
    if (b->failed) {
        memset(&b->scratch_object, 0, sizeof b->scratch_object);
        return &b->scratch_object;
    }
    scene_object *o = &s->objects[s->nobjects++];
    memset(o, 0, sizeof *o);
    o->mesh = (uint32_t)mesh_index;
    o->material = material;
    sm_vec3_make(x, y, z, o->position);
    o->scale = scale;
    sm_vec3_make(0.0f, 1.0f, 0.0f, o->spin_axis);
    sm_mat4_identity(o->transform);
    return o;
}

// >>authored lights

static scene_light *new_light(scene_builder *b, light_type type)
{
    if (!b->failed)
        sb_reserve(b, (void **)&b->authored, &b->cap_authored, b->nauthored, 1,
                   sizeof *b->authored, "authored lights");
    scene_light *l = b->failed ? &b->scratch_light : &b->authored[b->nauthored++];
    memset(l, 0, sizeof *l);
    l->type = type;
    l->attenuation = ATTENUATION_LINEAR_RANGE;
    l->att_a = 1.0f;
    l->att_c = 1.0f;
    sm_vec3_make(0.0f, -1.0f, 0.0f, l->direction);
    return l;
}

scene_light *sb_point(scene_builder *b, float x, float y, float z, float radius, float r,
                      float g, float bl)
{
    scene_light *l = new_light(b, LIGHT_POINT);
    sm_vec3_make(x, y, z, l->position);
    sm_vec3_make(r, g, bl, l->color);
    l->radius = radius;
    return l;
}

scene_light *sb_spot(scene_builder *b, const sm_vec3 pos, const sm_vec3 at, float half_angle_deg,
                     float exponent, float range, const sm_vec3 color, bool shadows)
{
    scene_light *l = new_light(b, LIGHT_SPOT);
    sm_vec3_copy(pos, l->position);
    sm_vec3_sub(at, pos, l->direction);
    sm_vec3_normalize(l->direction);
    sm_vec3_copy(color, l->color);
    l->radius = range;
    l->spot_angle = sm_deg2rad(half_angle_deg);
    l->spot_exponent = exponent;
    l->shadows = shadows;
    return l;
}

scene_light *sb_directional(scene_builder *b, const sm_vec3 direction, const sm_vec3 color,
                            bool shadows)
{
    scene_light *l = new_light(b, LIGHT_DIRECTIONAL);
    sm_vec3_normalize_to(direction, l->direction);
    sm_vec3_copy(color, l->color);
    l->shadows = shadows;
    return l;
}

// >>scene values

void sb_set_bounds(scene_builder *b, float x0, float y0, float z0, float x1, float y1, float z1)
{
    sm_vec3_make(x0, y0, z0, b->s->light_bounds_min);
    sm_vec3_make(x1, y1, z1, b->s->light_bounds_max);
}

void sb_set_orbit(scene_builder *b, float tx, float ty, float tz, float radius, float height,
                  float period)
{
    scene *s = b->s;
    s->path = CAMERA_ORBIT;
    sm_vec3_make(tx, ty, tz, s->orbit_target);
    s->orbit_radius = radius;
    s->orbit_height = height;
    s->orbit_period = period;
}

void sb_set_keys(scene_builder *b, uint32_t n, const float (*eyes)[3], const float (*targets)[3],
                 float period)
{
    scene *s = b->s;
    if (n < 1 || n > sizeof s->key_eye / sizeof s->key_eye[0]) {
        sb_fail(b, "bug: %u camera keys", n);
        return;
    }
    s->path = CAMERA_SCRIPTED;
    s->nkeys = n;
    for (uint32_t i = 0; i < n; i++) {
        sm_vec3_copy(eyes[i], s->key_eye[i]);
        sm_vec3_copy(targets[i], s->key_target[i]);
    }
    s->orbit_period = period;
}

void sb_set_projection(scene_builder *b, float fovy_deg, float znear, float zfar)
{
    b->s->fovy = sm_deg2rad(fovy_deg);
    b->s->znear = znear;
    b->s->zfar = zfar;
}

void sb_set_sky(scene_builder *b, float r, float g, float bl)
{
    b->s->sky = true;
    sm_vec3_make(r, g, bl, b->s->sky_color);
}
