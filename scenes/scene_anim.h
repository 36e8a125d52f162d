#pragma once
/* A file's animation, played by scene_update (issue 25, part 2: "the scene's time drives
 * the file's animation"). The file's node tree is kept as a table, parents before
 * children; the first animation's channels move nodes by translation, rotation and scale
 * keys; each frame scene_anim_pose evaluates them at the scene's time, looping over the
 * animation's duration, and composes every node's world transform, which the objects
 * drawn from an animated subtree take as their transform (scene_object.anim_node).
 *
 * Morph targets, skins and their bounds, and how keys are interpolated: the comment
 * above the types below. */
#include <stdbool.h>
#include <stdint.h>

#include "scenes/mesh.h"
#include "scenes/math/sm_mat.h"

/* Morph targets: a mesh with targets keeps its own vertices and each target's position
 * and normal offsets; each frame its vertices are rebuilt as its own plus the weighted
 * offsets (the normals normalised; the tangents kept, which the shaders orthogonalise
 * to the normal), its bounds recomputed, and the mesh is marked `deforms` so that the
 * renderers upload it again (scene_gpu_frame, visibility's copy). The weights are the
 * mesh's defaults, or the first animation's morph channel of a node that draws it.
 * Skins (glTF skins, assimp's aiMesh.mBones): a skinned mesh keeps its bind-pose
 * vertices; its vertices name up to 4 joints of the scene's joint palette each
 * (mesh.joints, mesh.weights). Each frame every joint's matrix is its node's posed world
 * transform (the file's placement included) times its inverse bind matrix, into
 * scene_anim.joints, which the renderers upload once a frame and every pass that draws
 * the mesh blends in its vertex stage (renderers/shaders/skin.inc.glsl). As glTF asks, a
 * skinned mesh ignores the transform of the node that draws it: its objects' transform
 * is the identity (file_assimp.c), the joints place it. Its bounds (mesh.aabb, sphere,
 * which scene_update turns into the object's world sphere) are rebuilt every frame
 * from a bind-space sphere per joint about the vertices the joint moves, carried by the
 * joint's matrix: a skinned vertex is a weighted mean of its joints' images of it, so it
 * lies in the hull of those spheres, which the union's bound holds. Conservative, and
 * O(joints) a frame rather than O(vertices).
 *
 * Keys are interpolated linearly, rotations spherically (glTF's LINEAR); assimp 5.2 does
 * not say a channel's interpolation, so STEP and CUBICSPLINE channels play as linear
 * between their values. Before the first key a channel holds it, after the last too.
 * clock: fixed stays deterministic (the time is the schedule's). */
typedef struct anim_keys {
    uint32_t n;
    float *t;                  /* seconds, ascending */
    float *v;                  /* n values of 3 (translation, scale) or 4 (rotation: x y z w,
                                * unit) floats */
} anim_keys;

typedef struct anim_channel {
    uint32_t node;             /* into scene_anim.nodes */
    anim_keys pos, rot, scale; /* a set with n 0 keeps the node's own */
} anim_channel;

typedef struct anim_node {
    int32_t parent;            /* index of a node before it, or -1 (the root) */
    sm_vec3 pos, scale;        /* its own transform as translation, rotation, scale ... */
    float rot[4];
    sm_mat4 local;             /* ... and as the file's matrix (used when not animated) */
    int32_t channel;           /* into scene_anim.channels, or -1 */
} anim_node;

typedef struct anim_morph {
    uint32_t mesh;             /* into scene.meshes */
    uint32_t ntargets;
    mesh_vertex *base;         /* the mesh's own vertices */
    float *dpos, *dnorm;       /* ntargets x nvertices x 3: each target's offsets */
    float *weights;            /* ntargets: the mesh's default weights */
    anim_keys keys;            /* weights over time, ntargets values a key; n 0: defaults */
} anim_morph;

/* At most this many joints in all skins of a scene: 4 RGBA32F texels a joint in one
 * texture buffer, whose GL 4.5 minimum size is 65536 texels (renderers/frame/scene_gpu.c). */
#define SCENE_ANIM_MAX_JOINTS 16384u

typedef struct anim_skin {
    uint32_t mesh;             /* into scene.meshes */
    uint32_t first, njoints;   /* its joints: scene_anim.joints[first .. first + njoints) */
    int32_t *node;             /* njoints: the joint's node, or -1: none found (the
                                * joint's matrix is then the file's placement alone) */
    sm_mat4 *offset;           /* njoints: inverse bind matrices (finite) */
    sm_vec4 *bind_sphere;      /* njoints: the vertices it moves, in bind space (w < 0:
                                * none) */
    sm_vec4 *posed_sphere;     /* njoints: scratch, bind_sphere under this frame's joint
                                * matrix (pose_skin) */
} anim_skin;

typedef struct scene_anim {
    anim_node *nodes;
    uint32_t nnodes;
    anim_channel *channels;
    uint32_t nchannels;
    anim_morph *morphs;
    uint32_t nmorphs;
    anim_skin *skins;
    uint32_t nskins;
    uint32_t njoints;          /* the joint palette's size, every skin's joints */
    sm_mat4 *joints;           /* njoints: posed by scene_anim_pose */
    double duration;           /* seconds; > 0 */
    sm_mat4 root;              /* the file's placement (scale, up axis) above its root */
    sm_mat4 *world;            /* nnodes: posed by scene_anim_pose */
} scene_anim;

/* Every node's world transform at time t (seconds, looped over the duration), every
 * morphed mesh of `meshes` (the scene's) rebuilt with the weights at t, every joint's
 * matrix and every skinned mesh's bounds. */
void scene_anim_pose(scene_anim *a, mesh *meshes, double t);
/* k->bind_sphere from mesh m's vertices (k's mesh, its joints and weights set): per joint
 * the sphere of the vertices it moves (a weight above 0), centred on their aabb, radius
 * to the farthest; w -1 for a joint that moves none. O(vertices); a mesh that also has
 * morph targets gets it again every frame. False (k unchanged) out of memory. */
bool scene_anim_skin_spheres(const mesh *m, anim_skin *k);
/* What the animation holds, and the animation; NULL is fine. */
void scene_anim_free(scene_anim *a);
