#pragma once
/* The world a renderer draws, with no OpenGL in it: camera, lights, objects.
 * scene_build() creates a named scene of the catalog; scene_update(s, t) poses it
 * at schedule time t (camera path, animation, active light count), deterministically. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "scenes/math.h"
#include "scenes/lights.h"

typedef enum light_type { LIGHT_POINT = 0, LIGHT_SPOT, LIGHT_DIRECTIONAL } light_type;

typedef struct scene_light {
    light_type type;
    sm_vec3 position;          /* world space */
    sm_vec3 direction;         /* spot and directional: unit, world space */
    sm_vec3 color;
    float radius;              /* point and spot range */
} scene_light;

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
