#pragma once
/* The translucent pass every drawing renderer ends its frame with (before resolve):
 * the frontend's `translucent` objects (MATERIAL_BLEND materials, back to front by
 * the view depth of their bounding sphere's centre), drawn over the opaque image and
 * its depth buffer, after the sky (which would otherwise overwrite them: it fills
 * every pixel still at depth 1) and after deferred's fog pass.
 * Its program, lights, state and draws, and when it is skipped: the comment
 * above TRANSLUCENT_VARIANTS below. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/frame/base.h"
#include "renderers/frame/frontend.h"
#include "renderers/frame/light_buffer.h"
#include "renderers/frame/scene_gpu.h"
#include "renderers/frame/shading.h"
#include "renderers/frame/shadow.h"
#include "scenes/scene.h"

/* The pass:
 *
 *   program   forward_spml.frag (mesh.vert) with LIGHTS_STORAGE and TRANSLUCENT, one
 *             per material map variant the translucent objects have, plus SHADOWS
 *             when the run's shadows pass runs and FOG when fog is on: the same
 *             surface, lighting and fog code as every forward pass, every visible
 *             light of the frame (the frontend's `lights`, in its order) in one pass,
 *             so forward-mpml's additive per-light passes never meet blending (an
 *             object is lit fully before it is blended once)
 *   lights    the frame's visible lights from a storage buffer of the pass's own;
 *             or, given a grid (translucent_compile: forward-plus, clustered and
 *             tiled-deferred when their cull runs), forward_tiled.frag's TRANSLUCENT
 *             variant over the fragment's tile's translucent list, which the
 *             renderer's cull dispatch builds beside the opaque lists (TLISTS,
 *             tile_cull.inc: near plane to the tile's max opaque depth, van Oosten's
 *             transparent lists), from the renderer's own light and list buffers
 *   state     blend premultiplied: RGB ONE, ONE_MINUS_SRC_ALPHA (the shader writes
 *             (c a, a)); alpha ZERO, ONE (the HDR target's alpha stays 1); depth test
 *             LESS, no depth writes; back faces culled (one layer per closed mesh)
 *   draws     one per translucent object visible (frontend.ntranslucent); its
 *             samples and fragments are the pass's like any other pass's
 *
 * A scene with no MATERIAL_BLEND object skips the pass: no program, no buffer, and the
 * plan's entry says "skipped: no translucent materials". */
enum { TRANSLUCENT_VARIANTS = 16 };   /* the four map bits (no alpha test) */

/* A tiled renderer's translucent lists (see "lights" above). */
typedef struct translucent_grid {
    const char *defines[3];          /* TILE_SIZE, TILES_X, TLISTS (the opaque cells) */
    GLuint lights, tiles, indices;   /* the renderer's buffers (tiles.inc) */
} translucent_grid;

typedef struct translucent_pass {
    bool run;                        /* the scene has translucent objects */
    uint32_t nobjects;               /* the scene's translucent objects */
    unsigned variants;               /* bit v: some translucent object is of variant v */
    GLuint program[TRANSLUCENT_VARIANTS];
    light_buffer lights;             /* storage buffer: the frame's visible lights */
    uint32_t capacity;               /* lights a frame draws with (the run's lights) */
    int count;                       /* lights uploaded this frame */
    uint64_t frame, program_frame[TRANSLUCENT_VARIANTS];
    uint64_t last_draws;             /* the last frame's draws (for tests) */
    bool gridded;                    /* lights from `grid`'s tile lists */
    translucent_grid grid;
} translucent_pass;

/* The material map variant (bits: diffuse 1, gloss 2, normal 4, emissive 8). */
unsigned translucent_variant(const scene_material *m);

/* Plans the pass for s and, when it runs, compiles its programs into b's cache (with
 * SHADOWS when sm runs, FOG when b's fog is on; not with `later`: the caller then calls
 * translucent_compile) and makes the light buffer. A second call releases what the
 * first made. False with a message. */
bool translucent_prepare(translucent_pass *t, renderer_base *b, const scene *s,
                         const shadow_maps *sm, bool later, char *err, size_t errlen);
void translucent_release(translucent_pass *t);   /* a zeroed pass is fine */

/* After translucent_prepare(later), a no-op unless t->run: the programs, g NULL as
 * translucent_prepare compiles them; else the pass lights from g's per-tile
 * translucent lists (forward_tiled.frag's TRANSLUCENT variant; its own light buffer
 * released): the renderer builds the lists each frame before the pass, and keeps g's
 * buffers until it releases the pass. False with a message. */
bool translucent_compile(translucent_pass *t, renderer_base *b, const shadow_maps *sm,
                         const translucent_grid *g, char *err, size_t errlen);

/* The "translucent" pass (when t->run) into framebuffer fbo (the HDR target and the
 * opaque depth, nothing else attached); returns its draws (0 when skipped). */
uint64_t translucent_draw(translucent_pass *t, renderer_base *b, scene_gpu *gpu,
                          const frontend *fe, const scene *s, const shadow_maps *sm, GLuint fbo,
                          frame_stats *out);

/* The plan entry's reason (run or skipped) into buf. */
void translucent_reason(const translucent_pass *t, bool prepared, char *buf, size_t len);
