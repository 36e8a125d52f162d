#pragma once
/* The world a renderer draws, with no OpenGL in it: camera, lights, objects.
 * scene_build() creates a named scene of the catalog; scene_update(s, t) poses it
 * at schedule time t (camera path, animation, active light count), deterministically. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "scenes/math.h"
#include "scenes/lights.h"
#include "scenes/mesh.h"
#include "scenes/texture_gen.h"

typedef enum light_type { LIGHT_POINT = 0, LIGHT_SPOT, LIGHT_DIRECTIONAL } light_type;

/* Shading follows seed 000 appendix D (Phong): I = A + att * spot * (D + g * S), with
 * att one of the three forms below, evaluated only within the light's range (a point
 * or spot light reaches nothing beyond `radius`: that is what its volume bounds). */
typedef enum attenuation_kind {
    ATTENUATION_INVERSE_SQUARE = 0,   /* 1 / d^2 (d clamped below, see renderers' shaders) */
    ATTENUATION_LINEAR_RANGE,         /* max(0, 1 - d / radius) */
    ATTENUATION_QUADRATIC,            /* 1 / (a d^2 + b d + c) */
} attenuation_kind;

typedef struct scene_light {
    light_type type;
    sm_vec3 position;          /* world space */
    sm_vec3 direction;         /* spot and directional: unit, world space (light travels along it) */
    sm_vec3 color;
    float radius;              /* point and spot range */
    float spot_angle;          /* spot: outer half-angle, radians (the cone's cut-off c) */
    float spot_exponent;       /* spot: falloff f in (-L.A)^f */
    attenuation_kind attenuation;
    float att_a, att_b, att_c; /* ATTENUATION_QUADRATIC */
    bool shadows;              /* casts shadows (a later milestone renders them) */
} scene_light;

/* Phong material; a map index is -1 when the material has no such map. */
typedef struct scene_material {
    sm_vec3 diffuse;           /* multiplies the diffuse map */
    float specular;            /* specular intensity (multiplies the gloss map) */
    float shininess;           /* specular exponent n */
    sm_vec3 emissive;          /* multiplies the emissive mask */
    int diffuse_map, gloss_map, normal_map, emissive_map;   /* into scene.textures */
} scene_material;

/* One mesh instance. model and the world bounds are posed by scene_update(). */
typedef struct scene_object {
    uint32_t mesh;             /* into scene.meshes */
    uint32_t material;         /* into scene.materials */
    sm_vec3 position;
    float scale;
    sm_vec3 spin_axis;         /* unit; rotation about it through the object's origin */
    float spin_rate;           /* radians per second of schedule time (0: static) */
    sm_mat4 model;
    sm_vec4 bsphere;           /* world-space bounding sphere */
} scene_object;

typedef struct scene_camera {
    sm_vec3 eye, target, up;
    float fovy;                /* radians */
    float znear, zfar;
} scene_camera;

typedef struct scene {
    char name[32];
    int width, height;         /* the run's resolution (aspect of the projection) */
    sm_vec3 light_bounds_min, light_bounds_max;   /* where random lights are placed */
    sm_vec3 ambient;
    bool sky;                  /* a sky is drawn where no geometry is */
    sm_vec3 sky_color;

    mesh *meshes;
    uint32_t nmeshes;
    texture_image *textures;
    uint32_t ntextures;
    scene_material *materials;
    uint32_t nmaterials;
    scene_object *objects;
    uint32_t nobjects;

    scene_light *lights;       /* every light the run will ever have, in placement order */
    uint32_t nlights_total;
    light_count count;         /* how many of them are active over time */

    /* camera path: orbit about `orbit_target` */
    sm_vec3 orbit_target;
    float orbit_radius, orbit_height, orbit_period;   /* period in seconds of schedule time */
    float fovy, znear, zfar;

    int fault;                 /* test scenes: what scene_update does at t >= 0.2 (scene.c) */

    /* posed by scene_update() */
    double t;
    uint32_t nlights_active;   /* lights[0 .. nlights_active) are on */
    scene_camera cam;
    sm_mat4 view, proj, viewproj;
} scene;

typedef struct scene_catalog_entry {
    const char *name;
    const char *description;
} scene_catalog_entry;

size_t scene_catalog_count(void);
const scene_catalog_entry *scene_catalog_at(size_t i);
const scene_catalog_entry *scene_catalog_find(const char *name);   /* NULL if unknown */

/* NULL with a message on failure (unknown name, out of memory). */
scene *scene_build(const char *name, const light_params *lp, int width, int height,
                   char *err, size_t errlen);
void scene_update(scene *s, double t);
void scene_destroy(scene *s);   /* NULL is fine */
