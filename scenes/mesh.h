#pragma once
/* scenes/mesh.h: procedural meshes with normals, tangents and texture coordinates, and
 * the deferred renderer's light volumes. No OpenGL in here: a mesh is two arrays the
 * renderers upload as they are.
 *
 * Solids, shells (room, corridor), terrain, light volumes and editing. The conventions
 * every generator keeps, its errors and ownership, the vertex and index counts and the
 * list of generators: the comment above the limits below. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "scenes/math/sm_bounds.h"

/* Conventions (every generator):
 *   - Right-handed, Y up. Triangles are counter-clockwise seen from the side the normals
 *     point to (outside for solids, inside for room and corridor shells), so the usual
 *     glFrontFace(GL_CCW) + glCullFace(GL_BACK) culls the far side.
 *   - 32-bit indices, 3 per triangle; no degenerate (zero-area) triangles.
 *   - normal: unit. tangent.xyz: unit, orthogonal to the normal, along dP/du;
 *     tangent.w = +1 or -1, with bitangent = w * cross(normal, tangent.xyz) along dP/dv
 *     (the MikkTSpace convention). Every generator here has w = +1 unless a transform
 *     mirrored it.
 *   - uv (0, 0) is the first texel of the first row of a texture as uploaded (GL's s = t
 *     = 0); v grows with the row index; a tangent-space normal map's +y is +v.
 *   - Positions shared by several vertices (seams, hard edges, poles) are bit-identical,
 *     so closed meshes are watertight under rasterization.
 *   - Degenerate frames (sphere and cone poles, flat terrain, zero-length derivatives)
 *     get defined unit vectors; nothing produces NaN for parameters a generator accepts.
 *   - aabb is tight (min and max over the vertices); sphere is centred on the aabb's
 *     centre with the smallest radius about that centre holding every vertex.
 *
 * Every generator returns false with a one-line message in err (NULL is fine) on bad
 * parameters (non-finite or non-positive sizes, too few segments, too many vertices)
 * or when out of memory; *out is then zeroed. On success *out owns its arrays:
 * mesh_free() releases them.
 *
 * Vertex and index counts (S slices/segments/sides, T stacks, f = 2^subdivisions):
 *   mesh_sphere          V = (T-1)(S+1) + 2S        I = 6 S (T-1)
 *   mesh_icosphere       V = (f+1)(10f+1)           I = 60 f^2   (V = 22 for n = 0)
 *   mesh_cone capped     V = 3S + 2                 I = 6S
 *   mesh_cone open       V = 2S + 1                 I = 3S
 *   mesh_box, mesh_room  V = 24                     I = 36
 *   mesh_corridor        V = 16                     I = 24
 *   mesh_lathe           per profile segment: ring-ring V = 2(S+1), I = 6S;
 *                        axis-ring or ring-axis V = 2S+1, I = 3S
 *   mesh_cylinder        V = 6S + 4                 I = 12S
 *   mesh_pillar          V = 14S + 12               I = 36S
 *   mesh_torus_knot      V = (S+1)(sides+1)         I = 6 S sides
 *   mesh_heightfield     V = (cx+1)(cz+1)           I = 6 cx cz
 *   mesh_light_sphere    as mesh_sphere; mesh_light_cone as mesh_cone capped
 *
 * What it offers:
 *   solids       mesh_sphere, mesh_icosphere, mesh_cone, mesh_box, mesh_cylinder,
 *                mesh_lathe, mesh_pillar, mesh_torus_knot
 *   shells       mesh_room, mesh_corridor (normals inward)
 *   terrain      mesh_heightfield, mesh_heightfield_fn, mesh_terrain_init,
 *                mesh_terrain_height
 *   volumes      mesh_light_sphere, mesh_light_cone
 *   editing      mesh_transform, mesh_append, mesh_compute_bounds, mesh_compute_tangents,
 *                mesh_free
 */

/* Limits on what one generator builds (48 bytes a vertex, 4 an index). */
#define MESH_MAX_VERTICES (1u << 26)
#define MESH_MAX_INDICES  (1u << 28)

typedef struct mesh_vertex {
    float position[3];
    float normal[3];           /* unit */
    float tangent[4];          /* xyz unit, orthogonal to normal; w = +1 or -1 (handedness) */
    float uv[2];
} mesh_vertex;

typedef struct mesh {
    mesh_vertex *vertices;
    uint32_t nvertices;
    uint32_t *colors;          /* NULL, or per vertex an RGBA8 colour (R in the low byte)
                                * that multiplies the material's base colour and opacity
                                * (a file's COLOR_0); mesh_free frees it */
    float (*uv2)[2];           /* NULL, or per vertex a second texture coordinate set (a
                                * file's TEXCOORD_1), for the maps a material reads from
                                * it (scene_material.uv1_maps); mesh_free frees it */
    uint16_t (*joints)[4];     /* NULL, or per vertex 4 joints of the scene's joint palette
                                * (a skinned mesh: scenes/scene_anim.h), each < the
                                * palette's size; mesh_free frees it */
    float (*weights)[4];       /* with joints: their weights, each finite and >= 0, summing
                                * to 1 */
    bool deforms;              /* its vertices change from frame to frame (morph targets,
                                * scenes/scene_anim.h): uploaded again every frame */
    uint32_t *indices;         /* triangles, CCW seen from the side the normals point to */
    uint32_t nindices;         /* a multiple of 3 */
    sm_vec3 aabb[2];           /* min, max corner */
    sm_vec4 sphere;            /* xyz centre, w radius */
} mesh;

/* >>solids ----------------------------------------------------------------------------- */

/* UV sphere about the origin, poles on the Y axis. slices >= 3 around, stacks >= 2 from
 * the south pole (v = 0) to the north pole (v = 1); u = longitude / 2 pi, the seam at +Z.
 * Each pole has one vertex per slice (u at the slice's middle), so the pole tangent is
 * that slice's east direction. */
bool mesh_sphere(float radius, uint32_t slices, uint32_t stacks, mesh *out,
                 char *err, size_t errlen);

/* Icosahedron subdivided `subdivisions` times (0..8; each splits every triangle in 4),
 * vertices pushed onto the sphere. Poles on the Y axis. Texture coordinates unwrap the
 * icosahedron into its usual net of five strips: u = net x / 5.5, v = net y / 3 (in edge
 * lengths), so every texel belongs to exactly one place on the sphere; tangents follow
 * the net's u (mesh_compute_tangents). */
bool mesh_icosphere(float radius, uint32_t subdivisions, mesh *out, char *err, size_t errlen);

/* Cone with its apex at the origin, opening along -Z: base disc of `radius` at z =
 * -height. segments >= 3. Smooth side normals; the apex has one vertex per segment (u at
 * the segment's middle). capped adds the base disc (normal -Z). Side uv: u around, v from
 * the rim (0) to the apex (1); cap uv: planar, (0.5 + 0.5 x / r, 0.5 - 0.5 y / r). */
bool mesh_cone(float radius, float height, uint32_t segments, bool capped, mesh *out,
               char *err, size_t errlen);

/* Box about the origin with half extents half[0..2] > 0; 4 vertices a face (hard
 * edges), each face's uv 0..1 (upright on the side faces). */
bool mesh_box(const sm_vec3 half, mesh *out, char *err, size_t errlen);

/* Closed cylinder about the origin along Y, y in [-height/2, height/2]: mesh_lathe of
 * (0, -h/2), (r, -h/2), (r, h/2), (0, h/2). */
bool mesh_cylinder(float radius, float height, uint32_t segments, mesh *out,
                   char *err, size_t errlen);

/* Surface of revolution about the Y axis. profile[k] = (r, y), r >= 0, npoints >= 2;
 * consecutive points distinct, no segment lying on the axis (both r = 0). The profile
 * runs so that the solid is on its left going along it in the (r, y) plane: bottom to
 * top on the outside (e.g. (0, y0) -> (r, y0) -> (r, y1) -> (0, y1) is a closed
 * cylinder). Every profile point is a hard edge (its ring is repeated with each
 * segment's own normal); a profile starting and ending on the axis gives a closed solid.
 * u = angle / 2 pi (seam at +Z), v = arc length along the profile / total length. */
bool mesh_lathe(const sm_vec2 *profile, uint32_t npoints, uint32_t segments, mesh *out,
                char *err, size_t errlen);

/* An interior column about the origin, y in [-height/2, height/2]: shaft of `radius`,
 * plinth and capital of 1.4 radius, 6% of the height each, joined to the shaft by
 * chamfers 4% of the height tall (a lathe of 8 profile points, 7 segments). */
bool mesh_pillar(float radius, float height, uint32_t segments, mesh *out,
                 char *err, size_t errlen);

/* (p, q) torus knot about the origin, lying in the XZ plane: centre line
 *   c(t) = radius / 3 * ((2 + cos qt) sin pt, sin qt, (2 + cos qt) cos pt), t in [0, 2 pi),
 * so its distance from the Y axis is between radius / 3 and radius; a tube of
 * tube_radius about it. p, q >= 1 and coprime (a knot, not a link); 0 < tube_radius <
 * radius / 3 (keeps the tube off the axis; tight knots with a fat tube still
 * self-intersect). segments >= 3 along the curve, sides >= 3 around the tube.
 * u runs along the curve, repeating round(length / (2 pi tube_radius)) times (>= 1), so
 * texels stay roughly square; v around the tube. Papers' stand-in for a detailed model. */
bool mesh_torus_knot(uint32_t p, uint32_t q, float radius, float tube_radius,
                     uint32_t segments, uint32_t sides, mesh *out, char *err, size_t errlen);

/* >>shells ----------------------------------------------------------------------------- */

/* Inward-facing box shell about the origin (the camera is inside): normals point in,
 * triangles CCW seen from inside. uv_scale > 0: texture repeats per world unit
 * (uv = distance along the face * uv_scale, so walls of any size tile alike);
 * uv_scale = 0: each face 0..1. */
bool mesh_room(const sm_vec3 half, float uv_scale, mesh *out, char *err, size_t errlen);

/* Corridor along Z about the origin: floor (y = -height/2), ceiling and two walls
 * (x = +-width/2), open at z = +-length/2, normals inward; uv_scale as mesh_room. */
bool mesh_corridor(float width, float height, float length, float uv_scale, mesh *out,
                   char *err, size_t errlen);

/* >>terrain ---------------------------------------------------------------------------- */

/* Height y at (x, z); must return a finite value. */
typedef float (*mesh_height_fn)(float x, float z, void *user);

/* Grid over x in [-size_x/2, size_x/2], z in [-size_z/2, size_z/2], cells_x by cells_z
 * cells (>= 1 each), heights from fn. Triangles CCW seen from above (+Y). Normals by
 * central differences of fn one cell either side (so they match the triangles; at the
 * border fn is sampled outside), always with y > 0. u = (x + size_x/2) / size_x,
 * v = (size_z/2 - z) / size_z (v grows towards -Z). Row-major: vertex (i, k) is
 * k * (cells_x + 1) + i, i along x, k along -z. */
bool mesh_heightfield_fn(float size_x, float size_z, uint32_t cells_x, uint32_t cells_z,
                         mesh_height_fn fn, void *user, mesh *out, char *err, size_t errlen);

#define MESH_TERRAIN_OCTAVES 6

/* Fractal gradient-noise terrain: 6 octaves (lacunarity 2, gain 0.5), the first with a
 * feature size of a quarter of the larger side, the octave keys drawn from PCG32 with
 * the seed. The height function does not depend on the tessellation: the same seed and
 * sizes give the same terrain at any cell count, and scenes can place things on it.
 * The finest octave's features are side / 128 across: grids of fewer than ~512 cells a
 * side sample them coarsely (valid, but jagged; every octave is equally steep). */
typedef struct mesh_terrain {
    uint32_t keys[MESH_TERRAIN_OCTAVES];
    float frequency;           /* of the first octave, per world unit */
    float height_scale;
} mesh_terrain;

void mesh_terrain_init(mesh_terrain *t, float size_x, float size_z, float height_scale,
                       uint32_t seed);
/* Height at (x, z), in about [-height_scale, height_scale] (never beyond); a
 * mesh_height_fn (user: the mesh_terrain). Non-finite x or z count as 0. */
float mesh_terrain_height(float x, float z, void *terrain);

/* mesh_heightfield_fn with mesh_terrain_init(size_x, size_z, height_scale, seed).
 * height_scale >= 0 (0: flat). */
bool mesh_heightfield(float size_x, float size_z, uint32_t cells_x, uint32_t cells_z,
                      float height_scale, uint32_t seed, mesh *out, char *err, size_t errlen);

/* >>light volumes ---------------------------------------------------------------------- */

/* A low-poly convex sphere that contains the whole unit sphere: mesh_sphere(1, slices,
 * stacks) scaled about the origin so that every face plane is at least 1 + 1e-4 from
 * the origin. Draw it scaled by the light's range (no extra factor: seed 000's 1.1
 * made up for D3DXCreateSphere's vertices lying on the sphere, which leaves the faces
 * inside it). Its vertices then lie at out->sphere.w (the circumradius; 1.0389 for
 * seed 000's 16 x 8). */
bool mesh_light_sphere(uint32_t slices, uint32_t stacks, mesh *out, char *err, size_t errlen);

/* A convex pyramid that strictly contains the spot light cone of half angle
 * `half_angle` (0 < half_angle < pi/2) and height 1, apex at the origin opening along -Z
 * (the cone sm_cone_sphere_intersects tests; a spot light of range R lies inside it
 * scaled by R): mesh_cone with its base polygon circumscribed about a circle of
 * tan(half_angle) (1 + 2e-4), its apex moved 1e-4 behind the origin (z = +1e-4) and its
 * base to z = -(1 + 1e-4), so the true cone is at least 1e-4 tan(half_angle) inside at
 * its base and the apex strictly inside too. Capped. Scale uniformly by the range,
 * rotate -Z onto the spot direction, translate to the light. */
bool mesh_light_cone(float half_angle, uint32_t segments, mesh *out, char *err, size_t errlen);

/* >>editing ---------------------------------------------------------------------------- */

/* Transforms in place: positions by m, normals by m's normal matrix, tangents by m's
 * upper 3x3 (then made orthogonal to the normal again); a mirroring m (negative
 * determinant) flips every triangle's winding and every tangent's w, so the mesh stays
 * CCW outward. Bounds are recomputed. False (mesh unchanged) for a singular or
 * non-finite m. */
bool mesh_transform(mesh *m, const sm_mat4 mat, char *err, size_t errlen);

/* Appends src, transformed by mat (NULL: as it is), to dst (which may be a zeroed mesh).
 * False (dst unchanged) on a bad mat, too many vertices, a skinned mesh (either has
 * joints) or out of memory. */
bool mesh_append(mesh *dst, const mesh *src, const sm_mat4 mat, char *err, size_t errlen);

/* aabb and sphere from the vertices (an empty mesh: sm_aabb_empty, zero sphere). */
void mesh_compute_bounds(mesh *m);

/* Tangents from the triangles' uv derivatives (Lengyel's per-triangle sums, made
 * orthogonal to each vertex normal; w from the summed bitangents). A vertex whose sums
 * vanish or are parallel to its normal gets a defined unit tangent orthogonal to the
 * normal, w = +1. Normals are used as they are and must be unit. False (tangents
 * unchanged) when out of memory. */
bool mesh_compute_tangents(mesh *m);

/* Frees the arrays and zeroes *m; NULL or an already freed mesh is fine. */
void mesh_free(mesh *m);
