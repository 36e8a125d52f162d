#pragma once
/* Shadow maps for spot and directional lights (seed 000 4.4.4 - 4.6.4), the same for
 * every renderer: deferred samples them in its light passes (4.5.6), forward-mpml in
 * its per-light passes (4.6.4), forward-spml in its one pass (every map of the frame in
 * memory at once: the cost seed 000's literature review ascribes to SPML).
 * Which lights and objects, the pass, the pool and what a shader reads: the comment
 * above struct shadow_maps below. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/frame/frontend.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/state.h"
#include "renderers/renderer.h"
#include "renderers/frame/scene_gpu.h"
#include "renderers/frame/bindings.h"
#include "scenes/scene.h"

enum {
    SHADOW_TEXTURE_UNIT = BIND_TEX_SHADOW,
    SHADOW_UBO_BINDING = BIND_UBO_SHADOWS,
    SHADOW_DEFAULT_SIZE = 1024,
    SHADOW_LIGHT_TYPES = 3,
};
#define SHADOW_OFFSET_FACTOR 2.0f
#define SHADOW_OFFSET_UNITS 4.0f

/* Which lights, which objects: the frontend (frontend.h, "shadow"): per frame, every
 * visible light that casts shadows gets a layer of the pool, a matrix and its
 * shadow-casting set. Here:
 *
 *   pool      one GL_TEXTURE_2D_ARRAY of GL_DEPTH_COMPONENT32F, size x size texels
 *             (renderer_options.shadow_map_size, 0: SHADOW_DEFAULT_SIZE = 1024), one
 *             layer per light of the scene that may cast shadows (the most a frame can
 *             need, since lights come and go over a run), 4 bytes a texel: the plan's
 *             target "shadow.maps[N]" has size x size x 4 x N bytes. Compare mode
 *             REF_TO_TEXTURE, LEQUAL, linear filtering (2x2 PCF), clamp to edge. One
 *             depth-only framebuffer per layer.
 *   pass      "shadows", the first pass of the frame in every renderer, for each light
 *             with a layer (frontend order): its framebuffer bound (one framebuffer
 *             state change), viewport size x size, depth cleared to 1 (not a draw),
 *             then ONE DRAW PER OBJECT OF ITS SHADOW-CASTING SET (shadow.vert +
 *             shadow.frag, "shadow_depth"), depth LESS with writes, no colour. So
 *                 shadows pass draws = sum over lights with a layer of |C(l)|
 *             = fe->shadow_start[fe->nlights], which every renderer adds to its own
 *             count; the pass has its own row in frame_stats (draw calls, state changes,
 *             GPU time), so totals with and without shadow maps can be rebuilt as
 *             seed 000's tables 5.3.2 (shadows on) and 5.3.3 (off) give them. The
 *             state cache is invalidated at the end of the pass, so the passes after
 *             it count their state changes exactly as in a frame without shadow maps,
 *             but for one texture change: the pool bound (shadow_maps_bind) in the
 *             first pass that samples it. So, per frame,
 *                 draws(on)         = draws(off) + shadows pass draws
 *                 state changes(on) = state changes(off) + shadows pass changes + 1
 *   bias      only faces turned away from the light go into the maps (cull FRONT), so
 *             a lit surface is compared with the far side of its own object, never with
 *             itself (no acne where it matters: faces turned away are unlit by N.L
 *             anyway); plus a slope-scaled polygon offset, glPolygonOffset(
 *             SHADOW_OFFSET_FACTOR, SHADOW_OFFSET_UNITS) = (2, 4), which pushes those
 *             depths further away, switched on for the pass and off after it (the state
 *             cache assumes it off). No constant bias in the shaders. This casts
 *             correctly for closed meshes, shells (mesh_room: seen from a light inside,
 *             every wall faces it and casts nothing inward, which nothing inside needs;
 *             from a light outside, e.g. a moon over a closed hall, the ceiling casts)
 *             and heightfields (a ridge casts with its slope turned away: a ray into
 *             the valley behind it leaves the ridge through that slope); an open surface
 *             turned towards the light casts nothing (heightfields are the only open
 *             meshes mesh.h makes, and nothing lies under the ground).
 *   lookup    shaders/shadow.inc, from lighting.inc's shade_light when SHADOWS is
 *             defined: the Shadows block (binding SHADOW_UBO_BINDING) holds per layer
 *             the matrix view space -> map coordinates [0, 1]^3 (bias x the light's
 *             view-projection x inverse view: seed 000 4.5.6's chain, view space back
 *             to world, then the light's view and projection), the pool is on
 *             SHADOW_TEXTURE_UNIT, a light's layer is its packed params.z - 1
 *             (shading_set_shadow_layer).
 *
 * Only what the scene needs is made: nothing (no pool, no program, no SHADOWS variant)
 * unless the plan runs the pass. Needs a current GL 4.5 context. */
typedef struct shadow_maps {
    /* >>the plan (shadow_maps_plan, no GL) */
    bool run;                  /* the shadows pass runs */
    char reason[96];           /* why it runs or is skipped */
    uint32_t asking[SHADOW_LIGHT_TYPES];   /* lights of the scene with shadows = true */
    uint32_t layers;           /* the pool: spot + directional lights asking */
    int size;                  /* side of a map in texels */
    /* >>GL (shadow_maps_create) */
    GLuint texture;            /* GL_TEXTURE_2D_ARRAY; 0 when none */
    GLuint *fbo;               /* per layer */
    GLuint ubo;                /* the Shadows block */
    GLuint program;            /* shadow_depth (in the renderer's program cache) */
    uint64_t bytes;            /* the pool's texels */
    char max_define[32];       /* "MAX_SHADOWS <layers>" */
    float (*staging)[16];      /* per layer, the frame's matrices */
} shadow_maps;

/* The plan for scene s under o (no GL; *sm is reset first): the pass runs when some
 * spot or directional light of the scene has shadows = true and o->no_shadows is
 * false. reason: "3 spot and 1 directional lights cast shadows" (with "(2 point
 * lights ask: not drawn)" when point lights ask too), or, skipped, "shadows: off",
 * "N point lights ask for shadows: only spot and directional lights cast them", "no
 * light casts shadows". */
void shadow_maps_plan(shadow_maps *sm, const scene *s, const renderer_options *o);

/* Whether programs that light lights of type t need the SHADOWS variant: the pass runs
 * and some light of that type casts shadows. */
bool shadow_maps_for_type(const shadow_maps *sm, int type);

/* The defines of a SHADOWS variant ("SHADOWS", "MAX_SHADOWS <layers>") into defs[0..1];
 * returns 2, or 0 (nothing written) when the pass does not run. */
unsigned shadow_maps_defines(const shadow_maps *sm, const char *defs[2]);

/* When the plan runs the pass: the pool, its framebuffers, the Shadows buffer and the
 * depth program (built in pc, named "shadow_depth"). Refused, with a message prefixed
 * by `who`, when the size is negative or beyond GL_MAX_TEXTURE_SIZE, or the layers
 * exceed GL_MAX_ARRAY_TEXTURE_LAYERS or GL_MAX_UNIFORM_BLOCK_SIZE / 64. Makes nothing
 * (and succeeds) when the pass does not run. */
bool shadow_maps_create(shadow_maps *sm, gl_program_cache *pc, const char *who, char *err,
                        size_t errlen);
/* Deletes the GL objects (the program belongs to its cache) and forgets the plan; a
 * zeroed sm is fine. */
void shadow_maps_destroy(shadow_maps *sm);

/* The frame's shadow maps, inside the renderer's "shadows" pass (the caller brackets
 * it): for every light of fe with a layer, its map drawn from its shadow-casting set;
 * the Shadows block updated and bound to SHADOW_UBO_BINDING. Returns the draws
 * (fe->shadow_start[fe->nlights]). Ends with gl_state_invalidate(st): the next pass
 * sets, and counts, all it needs (shadow.h). */
uint64_t shadow_maps_draw(shadow_maps *sm, gl_state *st, scene_gpu *gpu, const frontend *fe,
                          const scene *s);

/* The pool on SHADOW_TEXTURE_UNIT, through the cache (nothing when the pass does not
 * run), before a pass whose programs sample it. */
void shadow_maps_bind(const shadow_maps *sm, gl_state *st);

/* The pool's row of the plan's targets ("shadow.maps[N]", "depth32f", size x size,
 * bytes), added to target_bytes; nothing when the pass does not run. */
void shadow_maps_describe(const shadow_maps *sm, pass_plan *out);
