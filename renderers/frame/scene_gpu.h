#pragma once
/* A scene's meshes and textures on the GPU, and the draws every renderer makes of
 * them, all through the state cache (gl/state.h) so they are counted.
 *
 *   scene_gpu *g = scene_gpu_create(s, err, sizeof err);   // after renderer_prepare's context is current
 *   scene_gpu_frame(g, s);                                  // once per frame: the Frame block (binding 0)
 *   scene_gpu_draw_object(g, st, s, i);                     // binds VAO + the material's maps, sets
 *                                                           // the mesh.vert/surface.inc uniforms, draws
 *   scene_gpu_draw_light_volume(g, st, s, light);           // the deferred light volumes
 * Uniform locations, texture units, the light volumes and the details (meshes,
 * textures, the Frame block, draws, programs): the comment above the scene_gpu
 * type below. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "renderers/gl/state.h"
#include "scenes/scene.h"

/* mesh.vert's a_color: a mesh's vertex colours (VERTEX_COLOR); a_uv2: its second uv
 * set (UV2). */
#define SCENE_GPU_COLOR_ATTRIB 4
#define SCENE_GPU_UV2_ATTRIB 5
/* mesh.vert's a_joints (uvec4) and a_weights: a skinned mesh's joints and weights
 * (SKINNING, skin.inc) */
#define SCENE_GPU_JOINTS_ATTRIB 6
#define SCENE_GPU_WEIGHTS_ATTRIB 7

/* Uniform locations are those of mesh.vert.glsl (0 model-view, 1 projection, 2 normal
 * matrix) and surface.inc.glsl (8..11 material); the material's maps go to texture
 * units 0 diffuse, 1 gloss, 2 normal, 3 emissive (only those it has). The program
 * must be bound (gl_state_program) before a draw. Light volumes: a low-poly sphere
 * enclosing the unit sphere, scaled to range x 1.1 (seed 000 appendix C), and a
 * cone enclosing the spot's cone (apex at the light, opening along its direction);
 * their vertex shader gets u_model_view (0) and u_proj (1) the same way.
 *
 * Details:
 * - Meshes: one vertex array + vertex buffer + index buffer per scene mesh (immutable
 *   storage), attributes 0 position (vec3), 1 normal (vec3), 2 tangent (vec4), 3 uv
 *   (vec2) from mesh_vertex; 32-bit indices. A mesh with vertex colours (mesh.colors)
 *   has a second buffer for attribute 4 (SCENE_GPU_COLOR_ATTRIB, RGBA8 normalised);
 *   the others leave it disabled, so that it reads the generic value scene_gpu_create
 *   sets, white. Programs read it only when compiled with VERTEX_COLOR
 *   (renderer_base_scene's common define for a scene with coloured meshes). A mesh
 *   that deforms (mesh.deforms: morph targets) has a dynamic vertex buffer, which
 *   scene_gpu_frame fills again from the posed vertices every frame. A mesh with a
 *   second uv set (mesh.uv2) has a third buffer for attribute 5 (SCENE_GPU_UV2_ATTRIB),
 *   the others read the generic (0, 0); with UV2 (a common define when the scene uses
 *   it, scene_uses_uv2) scene_gpu_draw_object sets LOC_UV1_MAPS, the maps read from it.
 *   A skinned mesh (mesh.joints, mesh.weights) has a fourth buffer for attributes 6
 *   (SCENE_GPU_JOINTS_ATTRIB, 4 x uint16 as integers) and 7 (SCENE_GPU_WEIGHTS_ATTRIB,
 *   4 floats); the others read the generic weights 0, no skin. Programs read them only
 *   with SKINNING (a common define for a scene with skins, scene_has_skins). The joint
 *   palette (scene_anim.h's joints) is a texture buffer (RGBA32F, a matrix's columns in
 *   4 texels), refilled and bound to unit BIND_TEX_JOINTS by every scene_gpu_frame
 *   (outside the cache, as the Frame block); why a texture buffer: joints_create.
 * - Textures: one per scene texture, RGBA8 (4 channels) or R8 (1 channel, read .r),
 *   full mip chain (glGenerateTextureMipmap), trilinear, GL_REPEAT. Not sRGB.
 * - Frame block: one uniform buffer (gpu_frame, 192 bytes) bound to uniform binding 0
 *   by scene_gpu_create and again by every scene_gpu_frame (not a counted state).
 * - Draws bind through the state cache: vertex array (counted in its own category),
 *   textures, and for sky and resolve program, framebuffer and fixed-function state.
 *   Uniforms are set with glUniform* on the bound program: they are not state changes.
 * - scene_gpu_draw_object: the bound program must declare every location it sets:
 *   mesh.vert + a fragment shader including surface.inc (GL ignores updates of
 *   explicitly located uniforms the compiler found unused, but refuses locations a
 *   program does not declare: GL_INVALID_OPERATION). Locations 0, 1, 2 (mat3) and 8..11
 *   are set every draw; exactly one draw call (glDrawElements) per object. Passes
 *   without a material use scene_gpu_draw_object_geometry.
 * - Every object draw (material, geometry, depth) of a double-sided material
 *   (scene_material.double_sided) turns culling off for its draw and back to the pass's
 *   after it: two cull changes an object, in whatever pass draws it (shadows included).
 * - The light volume meshes and their placement are frontend.h's ("Light volumes"):
 *   mesh_light_sphere(16, 8) scaled by 1.1 x radius; ONE unit cone
 *   (mesh_light_cone(pi/4, 16)) scaled non-uniformly per spot (radius tan(angle) across,
 *   radius along), so any spot angle needs no mesh of its own. Directional lights have
 *   no volume: drawing one is a bug (message, nothing drawn). One draw per light.
 * - Programs: the scene_gpu owns a small gl_program_cache of its own for the sky
 *   (fullscreen.vert + sky.frag, built only when the scene has a sky) and the
 *   resolve (fullscreen.vert + resolve.frag), both built by scene_gpu_create; the
 *   FULLSCREEN_UNCLIPPED variant when twice the scene's size fits GL_MAX_VIEWPORT_DIMS
 *   (exactly width x height fragments), the clipped one otherwise. scene_gpu_describe
 *   lists them for renderer_describe. */
typedef struct scene_gpu scene_gpu;

scene_gpu *scene_gpu_create(const scene *s, char *err, size_t errlen);
void scene_gpu_destroy(scene_gpu *g);   /* NULL is fine */

/* Uploads this frame's Frame block (shading_pack_frame) to binding 0, the deforming
 * meshes' vertices and the joint palette (texture unit BIND_TEX_JOINTS). */
void scene_gpu_frame(scene_gpu *g, const scene *s);

void scene_gpu_draw_object(scene_gpu *g, gl_state *st, const scene *s, uint32_t object);
/* The same draw without the material: sets locations 0, 1, 2 only and binds no
 * texture, for passes whose fragment shader does not include surface.inc (depth or
 * stencil only, shadow maps): mesh.vert + any fragment shader. One draw call. */
void scene_gpu_draw_object_geometry(scene_gpu *g, gl_state *st, const scene *s,
                                    uint32_t object);
/* The object's mesh for a depth-only pass from another point of view (shadow maps,
 * shadow.vert): sets location 0 = viewproj x the object's model matrix (object to that
 * clip space) and nothing else, binds no texture. One draw call. */
void scene_gpu_draw_object_depth(scene_gpu *g, gl_state *st, const scene *s, uint32_t object,
                                 const sm_mat4 viewproj);
void scene_gpu_draw_light_volume(scene_gpu *g, gl_state *st, const scene *s, uint32_t light);

/* The sky, drawn last into untouched depth (z = w, depth test LEQUAL against a depth
 * cleared to 1): the same gradient for every renderer. One draw.
 * Sets through the cache: its program, depth {LEQUAL, no writes}, blend off, stencil
 * off, cull none, colour mask RGBA, the empty vertex array and the viewport of
 * gl_state_draw_fullscreen (size from the scene given to scene_gpu_create), into the
 * framebuffer bound now. The Frame block must be current (scene_gpu_frame). A scene
 * without a sky has no sky program: calling this is a bug (message, nothing drawn). */
void scene_gpu_draw_sky(scene_gpu *g, gl_state *st);

/* Every renderer accumulates light in a float target of the run's size (RGBA16F, or
 * RGBA32F with hdr: rgba32f; renderer_base_targets) (HDR, so
 * that N additive passes are not clamped and rounded to 8 bits N times) and ends the
 * frame with this pass: hdr_texture clamped to [0, 1] into output_fbo (the context's
 * RGBA8 framebuffer). One draw.
 * Sets through the cache: framebuffer output_fbo, its program, texture unit 0 =
 * hdr_texture, depth, blend and stencil off, cull none, colour mask RGBA, the empty
 * vertex array, the viewport of gl_state_draw_fullscreen. Output alpha is 1. */
void scene_gpu_resolve(scene_gpu *g, gl_state *st, unsigned hdr_texture, unsigned output_fbo,
                       int width, int height);

/* The GL texture of scene texture `index` (0 when out of range): for passes that bind a
 * material's maps themselves (visibility.c's shading dispatches). */
unsigned scene_gpu_texture(const scene_gpu *g, int index);

/* Seconds this process spent in scene_gpu_create's uploads (meshes, textures, the
 * environment's maps, the Frame block; up to a glFinish; the programs after them not
 * included), summed over its calls: a trial reads it before and after its renderer's
 * prepare. */
double scene_gpu_upload_s(void);

/* Bytes of vertex, index and texture data on the GPU (textures with their whole mip
 * chain; the light volumes and the Frame block included), for renderer_describe. */
uint64_t scene_gpu_bytes(const scene_gpu *g);

/* Appends the programs scene_gpu built (sky, resolve) to out->program[]
 * (gl_program_cache_describe). */
void scene_gpu_describe(const scene_gpu *g, pass_plan *out);
