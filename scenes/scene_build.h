#pragma once
/* What the catalog scenes' builders share (scenes/scene_make.c and scenes/builtin/scene_*.c); not part
 * of the scenes interface (nothing outside scenes/ includes it).
 *
 * A builder fills a scene through a scene_builder: tables, meshes, maps, materials,
 * objects, and the scene's authored lights (placed by `lights.placement: scene`).
 * Failures are sticky: the first failing call records its message in b->err and sets
 * b->failed; every later call does nothing (index calls return -1, object and light
 * calls return a scratch record that may be written and is thrown away), so a builder
 * can make all its calls and check b->failed once at the end.
 *
 * The list of what it offers: the comment above scene_builder below. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "scenes/scene.h"

/* What it offers:
 *   setup      sb_begin, sb_fail
 *   meshes     sb_box, sb_sphere, sb_icosphere, sb_torus_knot, sb_cylinder, sb_pillar,
 *              sb_cone, sb_corridor, sb_heightfield, sb_mesh_transform, sb_mesh_uv_scale,
 *              sb_box_uv_tile, sb_mesh_triangles
 *   maps       sb_texture, sb_maps
 *   materials  sb_material, sb_material_maps
 *   objects    sb_object
 *   lights     sb_point, sb_spot, sb_directional
 *   scene      sb_set_bounds, sb_set_orbit, sb_set_keys, sb_set_projection, sb_set_sky */

/* Every table grows as it fills (doubling); nothing has a fixed cap. sb_reserve checks a
 * count against what a uint32_t index and size_t bytes can hold before allocating. */
typedef struct scene_builder {
    scene *s;
    char *err;
    size_t errlen;
    bool failed;
    size_t cap_meshes, cap_textures, cap_materials, cap_objects;   /* allocated slots */
    scene_light *authored;         /* the scene's authored lights (freed by scene_build) */
    uint32_t nauthored;
    size_t cap_authored;
    uint32_t ncoverage;            /* the first ncoverage authored lights are the ones a
                                    * run records the screen coverage of */
    scene_object scratch_object;   /* what sb_object returns after a failure */
    scene_light scratch_light;
} scene_builder;

/* A builder: fills b->s from its argument (NULL for the catalog's scenes, a
 * scene_file_options for a file scene), returns !b->failed. */
typedef bool (*scene_build_fn)(scene_builder *b, const void *arg);

/* The catalog's builder of an entry (catalog.c), and which test fault it injects (0: none;
 * scene_make.c's inject_fault). NULL / 0 for an entry that is not the catalog's. */
scene_build_fn scene_catalog_builder(const scene_catalog_entry *e);
int scene_catalog_fault(const scene_catalog_entry *e);

/* Records the first failure (printf-style); false. */
bool sb_fail(scene_builder *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Allocates the tables: room for nobjects objects to start with (they grow past it). */
bool sb_begin(scene_builder *b, uint32_t nobjects);

/* Makes room for `more` entries past *n in the array *items of *cap entries of `size`
 * bytes (doubling); false with "too many WHAT (N)" or "out of memory for N WHAT". */
bool sb_reserve(scene_builder *b, void **items, size_t *cap, uint32_t n, uint32_t more,
                size_t size, const char *what);

/* >>meshes: each builds one mesh with the mesh_gen.c generator of the same name (see
 * scenes/mesh.h for the parameters) and returns its index, or -1. */
int sb_box(scene_builder *b, float hx, float hy, float hz);
int sb_sphere(scene_builder *b, float radius, uint32_t slices, uint32_t stacks);
int sb_icosphere(scene_builder *b, float radius, uint32_t subdivisions);
int sb_torus_knot(scene_builder *b, uint32_t p, uint32_t q, float radius, float tube,
                  uint32_t segments, uint32_t sides);
int sb_cylinder(scene_builder *b, float radius, float height, uint32_t segments);
int sb_pillar(scene_builder *b, float radius, float height, uint32_t segments);
int sb_cone(scene_builder *b, float radius, float height, uint32_t segments, bool capped);
int sb_corridor(scene_builder *b, float width, float height, float length, float uv_scale);
int sb_heightfield(scene_builder *b, float size_x, float size_z, uint32_t cells_x,
                   uint32_t cells_z, mesh_height_fn fn, void *user);
/* Bakes a transform into mesh `m` (mesh_transform). */
void sb_mesh_transform(scene_builder *b, int m, const sm_mat4 mat);
/* Multiplies every texture coordinate of mesh `m` (a positive scale keeps the tangents). */
void sb_mesh_uv_scale(scene_builder *b, int m, float su, float sv);
/* A mesh_box of half extents `half`: each face's uv made to repeat once per `tile`
 * world units (u along the face's tangent axis, v along its bitangent axis) instead of
 * once per face, so boxes of any size share a texel density. */
void sb_box_uv_tile(scene_builder *b, int m, const sm_vec3 half, float tile);
/* Triangles drawn for the scene's objects (each object's mesh once). */
uint64_t sb_mesh_triangles(const scene *s);

/* >>maps and materials */
int sb_texture(scene_builder *b,
               bool (*make)(const texture_desc *, texture_image *, char *, size_t),
               const texture_desc *d);
typedef struct sb_map_set {
    int diffuse, gloss, normal, emissive;   /* texture indices; -1 where not made */
} sb_map_set;
/* Diffuse, gloss and normal maps of one pattern, and its emissive mask if `emissive`. */
sb_map_set sb_maps(scene_builder *b, const texture_desc *d, bool emissive);
/* A material without maps; its index (0 after a failure). */
uint32_t sb_material(scene_builder *b, float r, float g, float bl, float specular,
                     float shininess);
/* A material using a map set: diffuse tint white, emissive `emissive` (x the mask) when the
 * set has an emissive map. */
uint32_t sb_material_maps(scene_builder *b, const sb_map_set *maps, float specular,
                          float shininess, float emissive);

/* >>objects: a static (spin_rate 0) instance with an identity node transform; the caller
 * may set spin and transform afterwards. */
scene_object *sb_object(scene_builder *b, int mesh_index, uint32_t material, float x, float y,
                        float z, float scale);

/* >>authored lights (linear-range attenuation unless the caller changes it) */
scene_light *sb_point(scene_builder *b, float x, float y, float z, float radius, float r,
                      float g, float bl);
/* A spot at `pos` aimed at `at`; half_angle_deg the cone's outer half angle. */
scene_light *sb_spot(scene_builder *b, const sm_vec3 pos, const sm_vec3 at, float half_angle_deg,
                     float exponent, float range, const sm_vec3 color, bool shadows);
scene_light *sb_directional(scene_builder *b, const sm_vec3 direction, const sm_vec3 color,
                            bool shadows);

/* >>scene values */
void sb_set_bounds(scene_builder *b, float x0, float y0, float z0, float x1, float y1, float z1);
void sb_set_orbit(scene_builder *b, float tx, float ty, float tz, float radius, float height,
                  float period);
/* A scripted path through n key poses (eye, target pairs), over `period` seconds. */
void sb_set_keys(scene_builder *b, uint32_t n, const float (*eyes)[3], const float (*targets)[3],
                 float period);
void sb_set_projection(scene_builder *b, float fovy_deg, float znear, float zfar);
/* A sky of colour (r, g, bl) where no object covers the frame (without it: black). */
void sb_set_sky(scene_builder *b, float r, float g, float bl);

/* >>the builders (catalog.c's table) */
bool scene_build_empty(scene_builder *b, const void *arg);
bool scene_build_shapes(scene_builder *b, const void *arg);
bool scene_build_curtis1(scene_builder *b, const void *arg);
bool scene_build_curtis2(scene_builder *b, const void *arg);
bool scene_build_curtis3(scene_builder *b, const void *arg);
bool scene_build_canyon(scene_builder *b, const void *arg);
bool scene_build_interior(scene_builder *b, const void *arg);
bool scene_build_spot_coverage(scene_builder *b, const void *arg);
bool scene_build_two_spots(scene_builder *b, const void *arg);
bool scene_build_floating_spot(scene_builder *b, const void *arg);
bool scene_build_glass(scene_builder *b, const void *arg);
/* A file scene through assimp (scenes/file/file_assimp.c); arg: a scene_file_options. */
bool scene_build_file(scene_builder *b, const void *arg);
