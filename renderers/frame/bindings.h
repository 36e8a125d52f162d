#ifndef SHADESWEEP_BINDINGS_H
#define SHADESWEEP_BINDINGS_H
/* Binding slots, shared by C and GLSL: the C code includes this file, and every shader
 * that names a slot does `#include "bindings.h"` (renderers/gl/embed.c embeds it under
 * that name). Only #define lines of plain integers and comments: both languages' own
 * preprocessors read it.
 *
 * Uniform blocks (std140) */
#define BIND_UBO_FRAME 0            /* frame.inc's Frame (shading.h gpu_frame) */
#define BIND_UBO_LIGHTS 1           /* forward-spml's Lights with forward.light_buffer: uniform */
#define BIND_UBO_SHADOWS 2          /* shadow.inc's Shadows (renderers/frame/shadow.h) */
/* Shader storage blocks (std430) */
#define BIND_SSBO_LIGHTS 0          /* lights.inc: the frame's packed lights (gpu_light[]) */
#define BIND_SSBO_TILE_LISTS 1      /* tiles.inc: per tile/cluster (offset, count) */
#define BIND_SSBO_TILE_INDICES 2    /* tiles.inc: the light indices all lists point into */
#define BIND_SSBO_TILE_STATS 3      /* tiles.inc: the index allocator and overflow record */
#define BIND_SSBO_TILE_DEPTH 4      /* tiles.inc (msaa > 1): per tile the depth range culled */
#define BIND_SSBO_EDGES 5           /* tiled_deferred.comp (msaa > 1): edge pixels counted */
#define BIND_SSBO_COVERAGE 6        /* coverage.comp: the covered pixels counted */
#define BIND_SSBO_COARSE_LISTS 8    /* tiles.inc (tiles.levels: 2): the big tiles' heads */
#define BIND_SSBO_COARSE_INDICES 9  /* tiles.inc (tiles.levels: 2): their light indices */
#define BIND_SSBO_ZBIN_BINS 10      /* zbin.inc: the count, directional lights, the bins */
#define BIND_SSBO_ZBIN_MASKS 11     /* zbin.inc: a bit mask over the sorted lights a tile */
#define BIND_SSBO_ZBIN_SORTED 12    /* zbin.comp: the lights it sorts into (then b_lights) */
#define BIND_SSBO_ZBIN_KEYS 13      /* zbin.comp: its (key, index) pairs, then (z, r) */
/* lights_reaching.comp, between frames (no other block is bound then): the frame's
 * lights, and a count per pixel */
#define BIND_SSBO_REACH_LIGHTS 0
#define BIND_SSBO_REACH_COUNTS 6
/* visibility_shade.comp: its draws, and the scene's vertices and indices (slots 5-7: no
 * edge or coverage count in that dispatch, and 8 slots is GL's minimum) */
#define BIND_SSBO_VIS_DRAWS 5
#define BIND_SSBO_VIS_VERTICES 6
#define BIND_SSBO_VIS_INDICES 7
/* Texture units */
#define BIND_TEX_DIFFUSE 0          /* surface.inc's material maps */
#define BIND_TEX_GLOSS 1
#define BIND_TEX_NORMAL 2
#define BIND_TEX_EMISSIVE 3
#define BIND_TEX_HDR 0              /* resolve.frag's input (no material is bound then) */
#define BIND_TEX_GBUFFER0 4         /* G-buffer attachment k at unit 4 + k (k < 6) */
#define BIND_TEX_DEPTH 10           /* the depth-stencil target, sampled */
#define BIND_TEX_SPECULAR 11        /* deferred's separate specular target (compose) */
#define BIND_TEX_SHADOW 12          /* the shadow-map pool (sampler2DArrayShadow) */
#define BIND_TEX_LIGHT_DIFFUSE 13   /* deferred-lighting's light buffer: diffuse light */
#define BIND_TEX_LIGHT_SPECULAR 14  /* and specular light (the material pass reads both) */
#define BIND_TEX_VISIBILITY 4       /* visibility_shade.comp: the id target (no G-buffer there) */
#define BIND_TEX_JOINTS 15          /* skin.inc: the frame's joint matrices (samplerBuffer,
                                       RGBA32F, 4 texels a joint), bound by scene_gpu_frame */
#define BIND_TEX_ENVIRONMENT 16    /* environment.inc: the prefiltered sky (samplerCube,
                                       environment.light: sky), bound by scene_gpu_frame;
                                       past 15 (a unit index may reach
                                       GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, >= 80): it is
                                       one more sampler in a stage, whose minimum is 16:
                                       visibility_shade.comp and tiled_deferred.comp use
                                       at most 9 with it) */
/* Image units */
#define BIND_IMAGE_HDR 0            /* tiled-deferred writes the HDR target (deferred-lighting
                                       tiled: its light buffer's diffuse light) */
#define BIND_IMAGE_VIS_COUNTS 1     /* visibility_shade.comp's counts (r32ui, 3 x 1) */
#define BIND_IMAGE_LIGHT_SPECULAR 2 /* deferred-lighting tiled: the light buffer's specular */
/* Uniform locations: surface.inc's alpha cutoff of a MASK material (file scenes) */
#define LOC_ALPHA_CUTOFF 12
/* surface.inc's opacity of a MATERIAL_BLEND material (the TRANSLUCENT variant) */
#define LOC_OPACITY 13
/* surface.inc's maps read from the second uv set (UV2: scene_material.uv1_maps) */
#define LOC_UV1_MAPS 14
/* surface.inc's occlusion strength of an ORM map (SHADING_PBR with GLOSS_MAP) */
#define LOC_OCCLUSION 15
/* Uniform locations of one light (forward_light.frag, deferred_light.frag) and of a
 * renderer's own first uniform beside mesh.vert's and surface.inc's (0..11) */
#define LOC_RENDERER 16
/* Uniform location of fog.inc's u_fog (rgb colour, w density), past u_light[5] (16..20) */
#define LOC_FOG 24
/* forward_base.frag's u_base_lights (forward.directional_in_base: 5 per light), past u_fog */
#define LOC_BASE_LIGHTS 25
#endif
