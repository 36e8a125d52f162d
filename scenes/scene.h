#pragma once
/* The world a renderer draws, with no OpenGL in it: camera, lights, objects.
 * scene_build() creates a named scene of the catalog; scene_update(s, t) poses it
 * at schedule time t (camera path, animation, active light count), deterministically. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "scenes/math/sm_bounds.h"
#include "scenes/lights.h"
#include "scenes/mesh.h"
#include "scenes/builtin/texture_gen.h"

typedef enum light_type { LIGHT_POINT = 0, LIGHT_SPOT, LIGHT_DIRECTIONAL } light_type;

/* Shading follows seed 000 appendix D (Phong): I = A + att * spot * (D + g * S), with
 * att one of the three forms below, evaluated only within the light's range (a point
 * or spot light reaches nothing beyond `radius`: that is what its volume bounds). */
typedef enum attenuation_kind {
    ATTENUATION_INVERSE_SQUARE = 0,   /* 1 / d^2 (d clamped below, see renderers' shaders) */
    ATTENUATION_LINEAR_RANGE,         /* max(0, 1 - d / radius) */
    ATTENUATION_QUADRATIC,            /* 1 / (a d^2 + b d + c) */
    ATTENUATION_WINDOWED,             /* (1 - (d / radius)^4)^2 / d^2, clamped to [0, 1]
                                       * inside: inverse-square windowed to 0 at the range
                                       * (Karis 2013), so the range is the lit extent */
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
    bool shadows;              /* spot and directional: casts shadows (renderers/frame/shadow.h) */
} scene_light;

/* How a material's alpha (diffuse alpha x the diffuse map's alpha) is used. */
typedef enum material_alpha {
    MATERIAL_OPAQUE = 0,       /* ignored */
    MATERIAL_MASK,             /* alpha test: fragments with alpha < alpha_cutoff discarded */
    MATERIAL_BLEND,            /* translucent: coverage = opacity x the diffuse map's alpha,
                                * drawn after the opaque scene, back to front, blended over
                                * it (renderers/frame/translucent.h); casts no shadow */
} material_alpha;

/* The two shading models (manifest key shading.model; renderers/shaders/lighting.inc):
 * seed 000's Phong, and glTF 2.0's metallic-roughness model (its Appendix B: GGX
 * distribution, separable Smith-GGX visibility, Schlick's Fresnel, Lambert diffuse). */
typedef enum shading_model { SHADING_PHONG = 0, SHADING_PBR } shading_model;

/* The environment light (manifest key environment.light, issue 36; renderers/frame/environment.h):
 * none (the scene's constant ambient light), or the procedural sky, which replaces the
 * ambient light in every renderer's ambient term and shows where no geometry is. */
typedef enum scene_environment { ENVIRONMENT_NONE = 0, ENVIRONMENT_SKY } scene_environment;

/* A material; a map index is -1 when the material has no such map. The shaders take
 * diffuse, specular, shininess, gloss_map and emissive (surface.inc): under Phong as
 * named; after scene_set_shading(s, SHADING_PBR) specular, shininess and gloss_map hold
 * the metallic-roughness model's metallic, roughness and ORM map (below), and diffuse is
 * the base colour. */
typedef struct scene_material {
    sm_vec3 diffuse;           /* multiplies the diffuse map (PBR: the base colour) */
    float specular;            /* specular intensity, multiplies the gloss map (PBR: metallic) */
    float shininess;           /* specular exponent n (PBR: roughness) */
    sm_vec3 emissive;          /* multiplies the emissive mask */
    int diffuse_map, gloss_map, normal_map, emissive_map;   /* into scene.textures */
    /* The metallic-roughness inputs, kept beside Phong's until scene_set_shading takes
     * them: metallic and roughness factors in [0, 1] (a catalog material: metallic 0, the
     * roughness whose GGX alpha matches its exponent n, alpha = sqrt(2 / (n + 2))); the ORM
     * map, glTF's channel packing (R occlusion, G roughness, B metallic; a file's
     * metallic-roughness map with its occlusion map put into R, 255 where it has none);
     * occlusion: the occlusion map's strength (0: R is not read). */
    float metallic, roughness, occlusion;
    int orm_map;
    material_alpha alpha;      /* catalog materials: opaque */
    float alpha_cutoff;        /* MATERIAL_MASK */
    float opacity;             /* MATERIAL_BLEND: the coverage alpha in [0, 1] (glTF base
                                * colour alpha, OBJ d); 1 for the others */
    unsigned uv1_maps;         /* the maps read from the mesh's second uv set (mesh.uv2):
                                * bit 0 diffuse, 1 gloss, 2 normal, 3 emissive (a file's
                                * texCoord 1); the first set for the others */
    bool double_sided;         /* glTF doubleSided (assimp's TWOSIDED): drawn without face
                                * culling in every pass (scene_gpu's object draws); a back
                                * face is shaded with its normal turned to the viewer
                                * (surface.inc, visibility_shade.comp), as glTF asks */
} scene_material;

/* Whether an object is drawn in the translucent pass (its material is MATERIAL_BLEND). */
static inline bool scene_material_translucent(const scene_material *m)
{
    return m->alpha == MATERIAL_BLEND;
}

/* One mesh instance. model and the world bounds are posed by scene_update():
 *   model = translate(position) * rotate(spin_axis, spin_rate t) * scale * transform
 * where transform is the object's node transform (a file's accumulated node matrices,
 * any affine matrix with a positive determinant; identity for the catalog's objects). */
typedef struct scene_object {
    uint32_t mesh;             /* into scene.meshes */
    uint32_t material;         /* into scene.materials */
    sm_vec3 position;
    float scale;
    sm_vec3 spin_axis;         /* unit; rotation about it through the object's origin */
    float spin_rate;           /* radians per second of schedule time (0: static) */
    sm_mat4 transform;         /* node transform, applied first */
    /* A file's animated node (scene.anim): 1 + its index, 0 for none; scene_update sets
     * transform = anim->world[anim_node - 1], times a mirror in x when anim_mirror (the
     * mesh is the node's mirrored copy, as the file's bind pose made it). */
    uint32_t anim_node;
    bool anim_mirror;
    sm_mat4 model;
    sm_vec4 bsphere;           /* world-space bounding sphere (the mesh's sphere under model:
                                * radius x model's largest axis scale) */
} scene_object;

typedef struct scene_camera {
    sm_vec3 eye, target, up;
    float fovy;                /* radians */
    float znear, zfar;
} scene_camera;

/* Camera overrides from a manifest's `camera:` block; NAN (or target[0] NAN) keeps the
 * scene's own value. camera_params_init() sets them all to NAN. */
typedef enum camera_path {
    CAMERA_ORBIT = 0,          /* circle of orbit_radius at orbit_height about orbit_target,
                                * one turn per orbit_period, starting on +X and turning
                                * towards +Z */
    CAMERA_SCRIPTED,           /* the scene's scripted path (the coverage scenes): a
                                * sequence of key poses, linearly interpolated, taking
                                * orbit_period seconds, then held at the last pose */
} camera_path;

typedef struct camera_params {
    float radius, height, period;   /* orbit (period also times a scripted path) */
    sm_vec3 target;
    float znear, zfar;
    float hold;                /* 0..1: stop the camera at this fraction of its path (orbit:
                                * of a turn; scripted: 0 the first key pose, 1 the last)
                                * for the whole run; NAN: move along it */
} camera_params;

void camera_params_init(camera_params *cp);

/* Clustered shading's depth slices (Olsson et al.): exponential from znear to zfar, each
 * `ratio` = 1 + 2 / (proj11 S_y) times deeper than the one before (proj11: the
 * projection's y scale, 1 / tan(fovy / 2); S_y: clustered.slices), so that a slice is
 * about as deep as a tile of a screen cut into S_y rows is wide. 1 for planes that make
 * no range; at most 1e6. renderers/tiled/grid.c refuses more than SCENE_DEPTH_SLICES_MAX,
 * and so does the plan check (runner/plan/plan_check.c), before GL. */
uint32_t scene_depth_slices(double proj11, double znear, double zfar, int slices_y,
                            double *ratio);
#define SCENE_DEPTH_SLICES_MAX 1024u

/* A file camera's planes fitted to the scene in front of it (scene_build_file; the rule
 * is docs/notes/file-scenes.md's). file_near, file_far: the file's (world
 * units; <= 0 or not finite: none, glTF's infinite projection has no far); depth_near,
 * depth_far: the nearest and farthest view depths of the scene's bounds (depth_near <= 0
 * when the eye is among them); proj11 as above; size: the bounds' diagonal. out: near =
 * max(file near, depth_near / MARGIN), far = min(file far, depth_far x MARGIN); the
 * fitted pair where the file's planes hold none of the scene, the file's (else the
 * orbit's 1e-3 and 10 x size) where nothing is in front or the depths are not finite; then near raised to far / R,
 * R the smaller of SCENE_PLANES_RATIO and the ratio that clustered.slices' default
 * (SCENE_PLANES_SLICES_Y) cuts into SCENE_PLANES_SLICES slices. */
void scene_fit_planes(float file_near, float file_far, float depth_near, float depth_far,
                      float proj11, float size, float out[2]);
#define SCENE_PLANES_MARGIN 1.05f   /* beyond the bounds, for float rounding and an
                                     * animation sampled between its poses */
#define SCENE_PLANES_RATIO 1e4      /* far / near at most: the orbit's 1e-3 and 10 x the
                                     * diagonal; 24-bit depth then resolves 6e-4 x far */
#define SCENE_PLANES_SLICES_Y 24    /* clustered.slices' default (runner/manifest/params.def) */
#define SCENE_PLANES_SLICES 1000.0  /* below SCENE_DEPTH_SLICES_MAX, clear of rounding */

/* How the linear image is displayed (manifest keys exposure.* and tonemap): the last
 * pass of every renderer (resolve.frag) and its CPU twin (results/image_ref.c
 * image_display_rgba8). All zero: clamped as it is, the images of schema 1. */
typedef enum exposure_mode { EXPOSURE_NONE = 0, EXPOSURE_AUTO, EXPOSURE_FIXED } exposure_mode;
typedef enum tonemap_kind { TONEMAP_NONE = 0, TONEMAP_PBR_NEUTRAL } tonemap_kind;
typedef struct scene_display {
    bool exposed;              /* the resolve multiplies by `exposure` (mode auto or fixed) */
    float exposure;            /* linear factor (read only when exposed) */
    tonemap_kind tonemap;
} scene_display;

typedef struct scene {
    char name[64];
    int width, height;         /* the run's resolution (aspect of the projection) */
    sm_vec3 light_bounds_min, light_bounds_max;   /* where random lights are placed */
    sm_vec3 ambient;
    shading_model shading;     /* SHADING_PHONG until scene_set_shading */
    scene_display display;     /* set by the run after the build (runner/trial/run_setup.c) */
    bool from_file;            /* a file's scene (scene_source.file) */
    bool lights_outside;       /* random placement draws a position inside a closed mesh
                                * again (a file's lights_around) */
    bool sky;                  /* a sky is drawn where no geometry is */
    sm_vec3 sky_color;
    scene_environment environment;   /* ENVIRONMENT_NONE until scene_set_environment */
    float environment_intensity;     /* multiplies the environment's radiance */

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
    uint32_t lights_seed;      /* lights.seed (scene_place_lights): also the stream of
                                  stochastic light culling (renderers/frame/stochastic.h) */

    /* camera path: orbit about `orbit_target`, or the scene's scripted key poses */
    camera_path path;
    sm_vec3 orbit_target;
    float orbit_radius, orbit_height, orbit_period;   /* period in seconds of schedule time */
    float hold;                /* NAN, or the fixed path fraction (camera_params.hold) */
    uint32_t nkeys;            /* CAMERA_SCRIPTED: key poses, evenly spaced in time */
    sm_vec3 key_eye[8], key_target[8];
    float fovy, znear, zfar;
    /* A file's camera (camera: auto or NAME): the near and far planes the file gave
     * (world units; 0 where it gave none), before scene_fit_planes; false elsewhere. */
    bool file_camera;
    float file_planes[2];

    /* Lights whose screen coverage the run records per frame (coverage.csv): with
     * lights.placement scene, the coverage scenes (spot-coverage, two-spots-overlap,
     * floating-spot) set this to their authored lights (capped by the count); 0
     * elsewhere and with any other placement. */
    uint32_t ncoverage_lights;

    int fault;                 /* test scenes: what scene_update does at t >= 0.2 (scene_make.c) */
    struct scene_anim *anim;   /* a file's node animation (scene_anim.h), or NULL */

    /* posed by scene_update() */
    double t;
    uint32_t nlights_active;   /* lights[0 .. nlights_active) are on */
    scene_camera cam;
    sm_mat4 view, proj, viewproj;
} scene;

/* Whether some mesh of the scene has vertex colours (the programs' VERTEX_COLOR). */
static inline bool scene_has_vertex_colors(const scene *s)
{
    for (uint32_t i = 0; i < s->nmeshes; i++)
        if (s->meshes[i].colors)
            return true;
    return false;
}

/* Whether some mesh of the scene is skinned (the programs' SKINNING: scene_anim.h). */
static inline bool scene_has_skins(const scene *s)
{
    for (uint32_t i = 0; i < s->nmeshes; i++)
        if (s->meshes[i].joints)
            return true;
    return false;
}

/* Whether the scene's programs read a second uv set (surface.inc's UV2): some material
 * reads a map from it and some mesh has one. */
static inline bool scene_uses_uv2(const scene *s)
{
    bool maps = false, uvs = false;
    for (uint32_t i = 0; i < s->nmaterials; i++)
        maps |= s->materials[i].uv1_maps != 0;
    for (uint32_t i = 0; maps && i < s->nmeshes; i++)
        uvs |= s->meshes[i].uv2 != NULL;
    return maps && uvs;
}

typedef struct scene_catalog_entry {
    const char *name;
    const char *description;
} scene_catalog_entry;

size_t scene_catalog_count(void);
const scene_catalog_entry *scene_catalog_at(size_t i);
const scene_catalog_entry *scene_catalog_find(const char *name);   /* NULL if unknown */

/* A scene from a file (scenes/file/file_assimp.c): glTF 2.0 (.gltf + .bin + images, .glb,
 * embedded), OBJ + MTL, and whatever else assimp reads. */
typedef enum scene_up { SCENE_UP_Y = 0, SCENE_UP_Z } scene_up;
typedef struct scene_file_options {
    const char *path;          /* the file (the caller resolves it against the manifest) */
    float scale;               /* uniform scale of the whole file; 0 counts as 1 */
    bool fit;                  /* instead of scale, the one that makes the diagonal of
                                * the file's bounds SCENE_FILE_FIT_DIAGONAL (a manifest's
                                * default) */
    scene_up up;               /* the file's up axis; z: rotated so that +Z becomes +Y */
    const char *camera;        /* NULL, "" or "auto": the file's first perspective camera,
                                * else a fixed view of the bounds from above and to the
                                * side; "orbit": an orbit about the bounds; otherwise the
                                * name of one of the file's cameras */
    bool allow_outside;        /* files it references may lie outside its folder */
    bool lights_around;        /* random and grid lights in the bounds grown by an eighth
                                * of their diagonal on every side, random ones drawn again
                                * inside a closed mesh (a manifest's default); false: in
                                * the bounds themselves, wherever they fall */
    bool phong;                /* the run shades it by Phong (shading.model): its
                                * metallic-roughness materials and maps are listed in
                                * not_rendered; false: by PBR, the file's default */
    /* What one small file may make the loader spend, checked from what the file says
     * before the work (scene.max_image_bytes, max_triangles, max_vertices; 0: the
     * defaults below): an image's decoded bytes, the whole file's triangles and
     * vertices (an .obj's counted before assimp reads it). */
    uint64_t max_image_bytes, max_triangles, max_vertices;
} scene_file_options;

/* The defaults of those limits: every 8192 x 8192 texture of 4 float channels; ten
 * million triangles and vertices (an .obj of 10 million faces took 55 s and 3.5 GB to
 * check; the largest model of the tests has under a million). */
#define SCENE_FILE_MAX_IMAGE_BYTES (1ull << 30)
#define SCENE_FILE_MAX_TRIANGLES 10000000ull
#define SCENE_FILE_MAX_VERTICES 10000000ull

enum { SCENE_FILE_MAX_NOT_RENDERED = 16 };

/* scale: fit makes a file this many world units across its bounds' diagonal, one size
 * for every file, so that the manifest's world-unit defaults (lights.radius 10 reaches
 * half of it) mean the same whatever units the file was authored in; about the light
 * bounds of the smaller catalog scenes (two-spots-overlap and glass: 29). */
#define SCENE_FILE_FIT_DIAGONAL 20.0f

/* What scene_file_check found (also what meta.yaml records). */
typedef struct scene_file_info {
    uint32_t meshes;           /* after post-processing (one per primitive) */
    uint64_t triangles;        /* drawn: each node's meshes once per instance */
    uint32_t objects;          /* mesh instances */
    uint32_t materials, textures, lights, cameras;
    char view[96];             /* what the run looks through: "the file's camera 'NAME'",
                                * "an orbit about the bounds" or "the bounds framed from
                                * above and to the side" */
    uint32_t materials_mask;   /* alphaMode MASK: alpha tested */
    uint32_t materials_blend;  /* alphaMode BLEND (or OBJ d < 1): translucent, drawn in the
                                * renderers' translucent pass */
    uint32_t files;            /* the file and every buffer and image it pulled in */
    uint64_t hash;             /* FNV-1a 64 over those files' bytes, in the order read */
    sm_vec3 bounds_min, bounds_max;   /* world bounds after scale and up */
    float scale;               /* the scale applied: the manifest's, or fit's factor */
    /* What the file has that shadesweep reads but does not render (skin influences after
     * a vertex's 4 largest, animations after the first, texture coordinate sets after the
     * second, orthographic cameras, glTF extensions of extensionsUsed it does not
     * implement, ...: file_unrendered.c's file_not_rendered), one phrase each: meta.yaml
     * lists them and validate, list and run warn of them. */
    uint32_t nnot_rendered;
    char not_rendered[SCENE_FILE_MAX_NOT_RENDERED][72];
} scene_file_info;

/* Opens the file and everything it references and checks it all, without GL: a missing
 * file, buffer or image, a parse error, NaN or infinite positions, indices out of range,
 * a recursive node hierarchy, an empty scene, an undecodable texture, a camera name the
 * file lacks, counts beyond what memory can hold. False with a one-line message naming
 * the file; info (NULL is fine) filled on success. */
bool scene_file_check(const scene_file_options *o, scene_file_info *info, char *err,
                      size_t errlen);

/* scene_file_check, and the paths of the files it read (the scene file, its buffers and
 * images), in the order its content hash takes them: files (NULL is fine) is filled on
 * success, scene_file_list_free frees it. */
typedef struct scene_file_list {
    char **path;
    uint32_t n;
} scene_file_list;
bool scene_file_check_list(const scene_file_options *o, scene_file_info *info,
                           scene_file_list *files, char *err, size_t errlen);
void scene_file_list_free(scene_file_list *f);   /* NULL is fine */

/* What this thread's file loads (each scene_file_check and file scene build loads the
 * file) spent since the last call, which zeroes it: the import (reading the files,
 * assimp's parse and post-processing, the checks) and the texture decode, in seconds of
 * CLOCK_MONOTONIC; loads: how many loads. */
typedef struct scene_file_times {
    double import_s, decode_s;
    uint32_t loads;
} scene_file_times;
void scene_file_times_take(scene_file_times *t);

/* Where a scene comes from: the catalog (name) or a file (file != NULL). */
typedef struct scene_source {
    const char *name;          /* catalog name; ignored when file is set */
    const scene_file_options *file;
} scene_source;

/* NULL with a message on failure: unknown name, out of memory, grid placement whose
 * radius makes neighbours overlap, scene placement on a scene without authored lights
 * ("scene 'X' has no authored lights"), a file that scene_file_check refuses.
 * Placement: scenes/lights.h. scene_build(name, ...) is the catalog's source. */
scene *scene_build_source(const scene_source *src, const light_params *lp, int width,
                          int height, char *err, size_t errlen);
scene *scene_build(const char *name, const light_params *lp, int width, int height,
                   char *err, size_t errlen);

/* The scene cache (scenes/scene_cache.c; docs/notes/file-scenes.md): a file
 * scene as its builder made it, before the run's lights, in a file named by a hash of
 * the files' content hash, the loading options, the resolution and the cache format.
 * scene_cache_name: that name ("<16 hex digits>.scene"). scene_cache_read: the scene
 * of the cache file at path when every check holds (header, sizes, checksum, key, the
 * files it lists hashing to content_hash today, every index in range), with the
 * scene_file_info stored with it in *info; else NULL, note "" where there is no file,
 * else one line saying why it was not used. */
typedef struct scene_cached scene_cached;
#define SCENE_CACHE_NAME_LEN 24
void scene_cache_name(const scene_file_options *o, uint64_t content_hash, int width,
                      int height, char out[SCENE_CACHE_NAME_LEN]);
scene_cached *scene_cache_read(const char *path, const scene_file_options *o,
                               uint64_t content_hash, int width, int height,
                               scene_file_info *info, char *note, size_t notelen);
void scene_cached_free(scene_cached *c);   /* NULL is fine */
/* Where scene_build_cache writes a scene it built (path NULL: nowhere), and what came of
 * it: written; animated (an animated scene is not cached); or note says why not (a write
 * failure). */
typedef struct scene_cache_store {
    const char *path;
    const scene_file_options *o;
    uint64_t content_hash;
    const scene_file_info *info;
    const scene_file_list *files;
    bool written, animated;
    char note[600];
    double write_s;            /* seconds the write took */
} scene_cache_store;
/* scene_build_source, from `from` when not NULL (taken: freed here, built or not), else
 * built and then stored as `to` says (NULL: not stored; a failed store fails nothing). */
scene *scene_build_cache(const scene_source *src, scene_cached *from, scene_cache_store *to,
                         const light_params *lp, int width, int height, char *err,
                         size_t errlen);
void scene_update(scene *s, double t);

/* What a plan check asks of many runs' scenes without building each (runner/plan/plan_check.c):
 * a source built once, without lights (maps and meshes included: a file whose texture
 * does not decode fails here), against which each run's lights and camera are checked
 * with no further building. scene_probe_build: NULL with scene_build_source's message when
 * the source cannot be built. scene_probe_check: true when scene_build_source with lp at
 * width x height, then scene_set_camera with cp (NULL: none), would succeed; else false
 * with the message the first of them would give. */
typedef struct scene_probe scene_probe;
scene_probe *scene_probe_build(const scene_source *src, char *err, size_t errlen);
/* The view a run would start with: its projection's y scale (proj[1][1]) and planes, what
 * scene_depth_slices takes (the plan check's clustered slices). */
typedef struct scene_view {
    float proj11, znear, zfar;
} scene_view;
/* view (NULL is fine) gets the run's view when it returns true. */
bool scene_probe_check(const scene_probe *p, const light_params *lp, const camera_params *cp,
                       int width, int height, scene_view *view, char *err, size_t errlen);
void scene_probe_destroy(scene_probe *p);   /* NULL is fine */

/* Applies a manifest's camera overrides (call after scene_build, before the run; it
 * re-poses at the scene's current t). False with a message naming the manifest key
 * ("camera.near: expected a finite number > 0, found -1"; znear and zfar are the
 * manifest's camera.near and camera.far), and the scene unchanged, for values that
 * cannot make a camera: znear not finite and > 0, zfar not finite and > znear, radius or
 * period not finite and > 0, a non-finite height or target, hold outside [0, 1], an eye
 * that meets the target anywhere on the path; and for radius, height or target on a
 * scene with a scripted path (which has no orbit: they would be silently ignored). */
bool scene_set_camera(scene *s, const camera_params *cp, char *err, size_t errlen);

/* The manifest's `translucency: opaque`: every translucent material (MATERIAL_BLEND)
 * becomes opaque with opacity 1, so that the renderers draw it in their opaque passes
 * and build no translucent pass. Returns how many materials changed. */
uint32_t scene_make_opaque(scene *s);

/* The manifest's shading.model: SHADING_PBR switches a built scene (always built for
 * Phong, s->shading) to the metallic-roughness model: every material's specular,
 * shininess and gloss_map take its metallic, roughness and orm_map, and s->shading says
 * so. Once: a scene shaded by PBR stays so (false for SHADING_PHONG then; true
 * otherwise). scene_own_shading: what `shading.model: scene` (the default) picks, Phong
 * for the catalog and PBR for a file, whose glTF materials are authored for it. */
bool scene_set_shading(scene *s, shading_model m);

/* lights.sizing's derived forms on a built scene's placed lights (placement random, grid
 * or surface: every light of the scene; none for placement scene), for the run's linear
 * exposure: LIGHT_SIZING_RANGE_FROM_INTENSITY sets each light's range to
 * sqrt(max channel x exposure / cutoff), where its unwindowed inverse-square light meets
 * the cutoff; LIGHT_SIZING_INTENSITY_FROM_RANGE keeps the range and scales every colour by
 * cutoff r^2 / (exposure color_max), so that the brightest colour the placement can draw
 * meets the cutoff at the range. A light whose derived range is 0 (a black light) keeps
 * a range of 1e-6. Nothing for LIGHT_SIZING_RADIUS. False, with a message, when the
 * exposure or a result is not a positive finite number. */
bool scene_size_lights(scene *s, const light_params *lp, float exposure, char *err,
                       size_t errlen);
shading_model scene_own_shading(const scene *s);
/* The manifest's environment.light: ENVIRONMENT_SKY lights the scene by the procedural
 * sky at `intensity` instead of its ambient light and draws it as the sky (s->sky set:
 * the renderers' sky pass shows the environment, not sky_color); ENVIRONMENT_NONE
 * leaves the scene as built. */
void scene_set_environment(scene *s, scene_environment e, float intensity);

/* Fraction of the screen's pixels (0..1) whose view ray, through the pixel's centre,
 * passes through light i's volume (point: its ball of `radius`; spot: its cone of half
 * angle spot_angle, clamped to [1e-4, pi/2 - 1e-3] as the renderers clamp it, capped by
 * the plane at distance `radius` along its direction: the volume the renderers cull and
 * draw (mesh_light_cone of height = range), which holds the sphere-capped part that the
 * light can reach; directional: 1), at the current pose. Geometry only: what occludes
 * the volume does not matter, and the whole ray from the eye counts (neither the near
 * nor the far plane cuts it), so an eye inside the volume gives 1. Sampled on a grid of
 * at most 128 x 128 pixel centres spread over the screen (row j of sh samples takes the
 * pixel row floor((j + 0.5) H / sh); exact for a screen at or below that size).
 * Deterministic; 0 for i >= nlights_total; whether the light is active does not matter. */
double scene_light_coverage(const scene *s, uint32_t i);
void scene_destroy(scene *s);   /* NULL is fine */
