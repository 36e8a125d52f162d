#pragma once
/* What the pieces of the file-scene loader share (scenes/file/file_*.c); not part of the
 * scenes interface (nothing outside scenes/ includes it).
 *   file_io.c        every byte assimp reads: each file read whole, once (file_set)
 *   file_prescan.c   glTF JSON, GLB lengths and OBJ mtllib paths checked before assimp
 *                    sees them
 *   file_import.cpp  the import with only the extension's importers (file_import.h)
 *   file_load.c      the import, its checks and the decoded images (loaded)
 *   file_materials.c assimp's materials onto the Phong model
 *   file_assimp.c    the node walk, scene_file_check and scene_build_file */
#include <limits.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <assimp/cfileio.h>
#include <assimp/material.h>
#include <assimp/scene.h>

#include "common/image_io.h"
#include "scenes/scene.h"
#include "scenes/scene_build.h"

/* Limits on what a file may ask for before anything is allocated for it. */
#define FILE_MAX_BYTES ((size_t)1 << 31)      /* one file, buffer or image: 2 GiB */
#define FILE_MAX_NODE_DEPTH 256u
/* The largest coordinate a vertex may have: a bounds' extent of 2e18 squared (its
 * diagonal, distances) stays below FLT_MAX (3.4e38). */
#define FILE_MAX_COORD 1e18

/* >>io (file_io.c) */
typedef struct read_file {
    char *path;
    unsigned char *data;
    size_t size;
} read_file;

/* Every file read for one load, in first-read order, each once. */
typedef struct file_set {
    read_file *files;
    uint32_t n;
    size_t cap;
    char err[3 * PATH_MAX + 256]; /* the first read failure that is not "no such file" */
    char missing[PATH_MAX];         /* the first referenced file that does not exist */
    char root[PATH_MAX];       /* referenced files must resolve inside it; "" while the
                                * scene file itself is read */
    bool allow_outside;        /* scene.allow_outside: no containment */
    bool obj;                  /* the scene is an .obj: any other file assimp opens is
                                * a material library (file_prescan_mtl) */
    struct aiFile **open;      /* assimp's files not closed yet (an importer that
                                * throws forgets its streams) */
    uint32_t nopen;
    size_t cap_open;
} file_set;

void file_set_free(file_set *fs);
/* The file's bytes (read once, then served from memory), or NULL with fs->err set for
 * anything but a file that does not exist (errno ENOENT then). */
const read_file *file_set_get(file_set *fs, const char *path);
/* A reference that names a URL (scheme://...): only local files are read. */
bool file_is_url(const char *p);
/* assimp's file callbacks over a file_set (aiFileIO's UserData). */
struct aiFile *file_io_open(struct aiFileIO *io, const char *path, const char *mode);
void file_io_close(struct aiFileIO *io, struct aiFile *af);

/* >>prescan (file_prescan.c): false with a message naming the file when its glTF JSON
 * (or a GLB's lengths) asks for what would hurt inside assimp. */
bool file_prescan_gltf(const char *path, const read_file *f, char *err, size_t errlen);
/* The same for an .obj (by path's extension; true for any other): a material library
 * path with a ':' in it, more triangles (a face of n corners makes n - 2) or vertex
 * positions than the limits (scene_file_options). */
bool file_prescan_obj(const char *path, const read_file *f, uint64_t max_triangles,
                      uint64_t max_vertices, char *err, size_t errlen);
/* An OBJ's material library, as assimp opens it: false with a message naming it when
 * a statement comes before its first newmtl (assimp 5.2 writes through a null
 * material for some of them). */
bool file_prescan_mtl(const char *path, const read_file *f, char *err, size_t errlen);
/* KHR_materials_emissive_strength of a glTF's materials (after file_prescan_gltf): *out
 * (malloc'd, NULL for none) holds each material's emissiveStrength, 1 where it has none,
 * *n of them, in the file's order, which assimp's glTF importer keeps. Not a glTF, or
 * malformed (assimp reports it): none. False with a message for a value that is not a
 * finite number >= 0. */
bool file_gltf_emissive_strengths(const char *path, const read_file *f, float **out, size_t *n,
                                  char *err, size_t errlen);

/* glTF (.gltf, .glb) by the path's extension (file_assimp.c). */
bool file_is_gltf(const char *path);

/* >>load (file_load.c) */
/* One loaded file: assimp's scene, the files read, the decoded images (one per distinct
 * texture reference, in first-use order) and the world transforms of the mesh nodes. */
typedef struct loaded_image {
    char *ref;                 /* the material's texture path ("*N": embedded) */
    image img;                 /* RGBA8 */
} loaded_image;

typedef struct loaded {
    const struct aiScene *ai;
    file_set files;
    loaded_image *images;
    uint32_t nimages;
    size_t cap_images;
    char dir[4096];            /* the file's folder, with a trailing '/', or "" */
    const char *path;
    float *emissive_strength;  /* glTF: per material (KHR_materials_emissive_strength) */
    size_t nemissive_strength;
    uint64_t max_image_bytes;  /* the limits in force (scene_file_options, defaults applied) */
    uint64_t max_triangles, max_vertices;
} loaded;

/* Which of a material's maps exist: diffuse, normal, emissive, metallic-roughness and
 * occlusion references, "" if none. */
typedef struct material_refs {
    char diffuse[1024], normal[1024], emissive[1024], mr[1024], occlusion[1024];
    unsigned diffuse_uv, normal_uv, emissive_uv, mr_uv, occlusion_uv;   /* the texture
                                                                         * coordinate set of each */
} material_refs;

/* Imports and checks everything; on success l holds the scene and every texture. */
bool file_load(const scene_file_options *o, loaded *l, char *err, size_t errlen);
void file_loaded_free(loaded *l);
/* The paths of the files l read, in the order of the content hash (scene.h). */
bool file_loaded_list(const loaded *l, scene_file_list *out, char *err, size_t errlen);
/* The image a material references, decoded (once per reference), or -1 with a message. */
int file_load_image(loaded *l, const char *ref, char *err, size_t errlen);
void file_material_refs(const struct aiMaterial *m, material_refs *r);
/* >>unrendered (file_unrendered.c): what the file has that no renderer draws, as
 * phrases of info->not_rendered (phong: the file's materials mapped onto Phong). */
void file_not_rendered(const loaded *l, bool phong, scene_file_info *info);

/* Whether the scene's camera option is the word (auto, orbit); NULL and "" are auto. */
static inline bool file_camera_is(const char *camera, const char *word)
{
    return strcmp(camera && camera[0] ? camera : "auto", word) == 0;
}

/* assimp's row-major matrix as ours (column-major). */
static inline void file_matrix_from_ai(const struct aiMatrix4x4 *a, sm_mat4 m)
{
    const float r[4][4] = {{a->a1, a->a2, a->a3, a->a4},
                           {a->b1, a->b2, a->b3, a->b4},
                           {a->c1, a->c2, a->c3, a->c4},
                           {a->d1, a->d2, a->d3, a->d4}};
    for (int c = 0; c < 4; c++)
        for (int k = 0; k < 4; k++)
            m[c][k] = r[k][c];
}

static inline bool file_finite3(const struct aiVector3D *v)
{
    return isfinite(v->x) && isfinite(v->y) && isfinite(v->z);
}

/* >>animation (file_anim.c) */
/* The file's first animation, when it moves a node that has meshes below it, and its
 * meshes' morph targets (scene mesh mesh_index[i] of file mesh i; their weights the
 * defaults or the animation's) and skins (file_skin_load) as the scene's animation
 * (scene.anim, scene_anim.h; the root transform `root` above the file's root), and *moves
 * (malloc'd; NULL when the file has none of them): per node in walk's order (pre-order,
 * FILE_MAX_NODE_DEPTH levels) whether it moves. False (b failed) for a key that is not
 * finite or times that go back, more than 64 targets on a mesh, what file_skin_load
 * refuses, or out of memory. */
bool file_anim_load(scene_builder *b, const char *path, const struct aiScene *ai,
                    const uint32_t *mesh_index, const sm_mat4 root, bool **moves);

/* >>skins (file_skin.c) */
/* The node of the tree (file_anim.c's table) named name, or -1. */
typedef int32_t (*file_node_lookup)(const void *ctx, const char *name);
struct scene_anim;
/* The skins of the file's meshes with bones (scene mesh mesh_index[i] of file mesh i)
 * into a (scene_anim.h: skins, the joint palette), their vertices' joints and weights
 * into the scene meshes. False (b failed) for more than SCENE_ANIM_MAX_JOINTS joints in
 * all, an inverse bind matrix that is not finite, or out of memory. */
bool file_skin_load(scene_builder *b, const char *path, const struct aiScene *ai,
                    const uint32_t *mesh_index, file_node_lookup lookup, const void *ctx,
                    struct scene_anim *a);
/* How many of the mesh's vertices have more than 4 influences (the rest dropped). */
unsigned file_skin_over4(const struct aiMesh *am);
/* lo, hi grown by the skinned meshes' vertices at time 0 (the scene's animation posed
 * then, the vertices skinned on the CPU): where the skins are drawn, which their
 * bind-pose vertices under their nodes' transforms (scene_file_check's bounds) need not
 * be. For the camera's framing. */
void file_skin_bounds(scene *s, sm_vec3 lo, sm_vec3 hi);

/* >>materials (file_materials.c) */
/* A material's alpha mode (glTF alphaMode; OBJ: d < 1 is translucent) and cutoff. */
material_alpha file_alpha_mode(const struct aiMaterial *am, float *cutoff);
/* Material `index` of the file as a scene material, its maps as scene textures (map: file
 * image -> scene texture, -1 where not made yet), its emissive scaled by its
 * KHR_materials_emissive_strength. */
void file_add_material(scene_builder *b, loaded *l, unsigned index, int *map);
/* The material's KHR_texture_transform as uv' = out x (u, v, 1) in our uv: 1 when its maps
 * have one and agree on it, 0 when they have none (out: identity or untouched), -1 when
 * they differ (out: the base colour map's, else the first map's; one uv set carries one). */
int file_uv_transform(const struct aiMaterial *am, float out[2][3]);
