#pragma once
/* What the two forward renderers share (forward_mpml.c, seed 000 4.6; forward_spml.c,
 * seed 003 4.1): the HDR target and its depth, the material variants, the pass that
 * draws the visible objects in state-bucket order, the sky and resolve passes, the
 * per-pass queries and the describe helpers.
 *
 * Every frame of both renderers:
 * Every frame of both renderers, the draw order, the material variants and the
 * uniforms and bindings of its programs: the comment above the first enum below. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/frame/base.h"
#include "renderers/frame/bindings.h"
#include "renderers/frame/frontend.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/query.h"
#include "renderers/gl/state.h"
#include "renderers/gl/target.h"
#include "renderers/renderer.h"
#include "renderers/frame/scene_gpu.h"
#include "renderers/frame/shadow.h"
#include "renderers/frame/translucent.h"
#include "scenes/scene.h"

/*     forward_begin_frame     renderer_base_begin_frame: cache invalidated (every frame
 *                             counted alike), frontend_build, scene_gpu_frame; then
 *                             renderer_base_shadow_pass when some spot or directional
 *                             light casts shadows (and shadows are not off): "shadows",
 *                             renderers/frame/shadow.h, one draw per object of each shadowed
 *                             light's shadow-casting set
 *     ... the renderer's own passes into fc->fb (the base's "hdr", in the run's HDR
 *         format, RGBA16F or RGBA32F, + "depth": renderer_base_targets) ...
 *     forward_sky_pass        when the scene has a sky: one draw into untouched depth
 *     translucent             when the scene has translucent objects (translucent.h):
 *                             one blended draw per visible one, back to front
 *     edge_aa_pass            with aa: edge, "edge-aa" (edge_aa.h): one draw into "hdr.aa",
 *                             which the resolve then reads
 *     forward_resolve_pass    hdr clamped into the output framebuffer: one draw
 *
 * Objects are drawn back faces culled (every scene mesh is closed or a shell seen
 * from its inside, mesh.h), in the frontend's `visible` order: state buckets by
 * diffuse map, then material, then mesh (seed 000 4.4.3), so that texture and
 * program changes happen only at bucket boundaries.
 *
 * Material variants: bit 0 diffuse map, 1 gloss map, 2 normal map, 3 emissive map
 * (the defines of shading_material_defines); only the variants some object's
 * material has are compiled. With fog on (opts.fog_density > 0) every program
 * forward_program builds has the FOG define and its u_fog set (fog.inc.glsl): fog at
 * the end of the shading, no pass of its own; describe lists "fog" (run or skipped)
 * before the sky.
 *
 * Programs bound here carry, beside mesh.vert's and surface.inc's uniforms (0..11),
 * FORWARD_UNIFORM_LIGHT (16): forward_light.frag's vec4 u_light[5] (one light),
 * forward_spml.frag's int u_light_count. forward-spml's light buffer is uniform
 * block binding FORWARD_LIGHTS_BINDING (1); binding 0 is the Frame block. */
enum {
    FORWARD_VARIANTS = 32,           /* 4 map bits and the alpha test */
    FORWARD_LIGHT_TYPES = 3,         /* LIGHT_POINT, LIGHT_SPOT, LIGHT_DIRECTIONAL */
    FORWARD_MAX_PASSES = 9,          /* shadows base lights sky translucent [msaa-resolve]
                                        edge-aa resolve; forward-plus: shadows depth cull
                                        shade sky translucent [msaa-resolve] edge-aa resolve */
    FORWARD_UNIFORM_LIGHT = LOC_RENDERER,   /* uniform location, see above */
    FORWARD_LIGHTS_BINDING = BIND_UBO_LIGHTS,   /* uniform block of forward-spml's lights */
};

enum {
    FORWARD_VARIANT_DIFFUSE = 1,
    FORWARD_VARIANT_GLOSS = 2,
    FORWARD_VARIANT_NORMAL = 4,
    FORWARD_VARIANT_EMISSIVE = 8,
    FORWARD_VARIANT_ALPHA_TEST = 16, /* MATERIAL_MASK */
};

typedef struct forward_common {
    renderer_base b;                 /* first: name, options, size, caches, queries, passes */
    bool illumination_sets;          /* the frontend computes them (forward-mpml sets this
                                        after init); the others leave it false */
    struct light_grid *grid;         /* the tiled ones' light grid (tiled/grid.h's
                                        forward_grid_collect reads it); NULL otherwise */

    /* >>made by forward_common_prepare */
    bool prepared;                   /* (the scene on the GPU, the frontend and the shadow
                                        maps are the base's: renderer_base_scene) */
    gl_framebuffer fb;               /* the base's hdr and depth targets */
    bool sky;                        /* the scene has a sky: the sky pass runs */
    unsigned variants;               /* bit v: some object's material is of variant v */
    unsigned light_types;            /* bit t: some light of the scene is of type t */
    uint32_t nobjects_variant[FORWARD_VARIANTS];   /* objects of each variant */
    GLuint base_program[FORWARD_VARIANTS];    /* forward-mpml's base pass */
    translucent_pass translucent;    /* the scene's MATERIAL_BLEND objects (translucent.h) */
    bool translucent_later;          /* the renderer calls translucent_compile itself (tiled) */
    const scene *frame_scene;        /* the scene forward_begin_frame was given */
} forward_common;
_Static_assert(offsetof(forward_common, b) == 0,
               "a forward renderer's object is read as its renderer_base (renderer_impl.collect)");

/* The variant of a material (FORWARD_VARIANT_* bits). */
unsigned forward_material_variant(const scene_material *m);

/* Creation of a forward renderer's object: `size` zeroed bytes that begin with its
 * forward_common; records the output framebuffer (the draw framebuffer bound now), makes
 * the state cache, the program cache and (opts->queries) FORWARD_MAX_PASSES pass
 * queries. NULL with a message. */
void *forward_common_new(size_t size, const char *name, const renderer_options *opts,
                         char *err, size_t errlen);
/* Everything new and prepare made, and the object itself (NULL is fine); the renderer
 * releases what it made of its own first. */
void forward_common_free(forward_common *fc);

/* What both renderers need of a scene: the frontend, the scene on the GPU, the HDR
 * target and depth, the variants and light types present, the shadow-map plan and,
 * when it runs, the pool and its depth program. Compiles no lighting program. A
 * second call releases what the first made first. */
bool forward_common_prepare(forward_common *fc, const scene *s, char *err, size_t errlen);

/* The program of fragment shader `fragment` (with mesh.vert) for material variant
 * v, with extra defines (NULL-terminated list, or NULL), named `display`. */
bool forward_program(forward_common *fc, const char *display, const char *fragment,
                     unsigned variant, const char *const *extra, GLuint *program, char *err,
                     size_t errlen);

/* forward_base.frag for every variant present, into fc->base_program. */
bool forward_compile_base(forward_common *fc, char *err, size_t errlen);

// >>per frame

void forward_begin_frame(forward_common *fc, const scene *s, frame_stats *out);
/* A forward_draw_objects on_program hook's light count: count into FORWARD_UNIFORM_LIGHT
 * of the bound program once a frame; *seen is the frame its variant last got it. */
void forward_light_count_once(uint64_t *seen, uint64_t frame, int count);

/* The SHADOWS defines for programs lighting type t ("SHADOWS", "MAX_SHADOWS n") into
 * defs, or nothing (shadow_maps_for_type); returns how many. type < 0: any type (a
 * program that lights every type, forward-spml), i.e. whether the pass runs. */
unsigned forward_shadow_defines(const forward_common *fc, int type, const char *defs[2]);

/* Pass bracketing: the pass gets the next index of out->pass, its queries and the
 * state cache's counts. */
void forward_pass_begin(forward_common *fc, frame_stats *out, const char *name);
void forward_pass_end(forward_common *fc, frame_stats *out);

/* Binds the HDR framebuffer and its viewport. */
void forward_bind_target(forward_common *fc);

/* Clears hdr to (0, 0, 0, 1) and depth to 1 (stencil 0). */
void forward_clear_target(forward_common *fc);

/* Draws objects[0..n) with programs[variant of each object's material], one draw
 * each. on_program (may be NULL) runs after each program is bound, before the
 * object is drawn, for uniforms of the renderer's own. */
typedef void (*forward_program_fn)(void *user, unsigned variant, GLuint program);
void forward_draw_objects(forward_common *fc, const scene *s, const uint32_t *objects,
                          uint32_t n, const GLuint programs[FORWARD_VARIANTS],
                          forward_program_fn on_program, void *user);

/* The sky pass (one draw; only call it when fc->sky) and the resolve pass (one draw). */
void forward_sky_pass(forward_common *fc, frame_stats *out);
void forward_resolve_pass(forward_common *fc, frame_stats *out);
/* The end of every forward frame: the sky (when the scene has one), the translucent
 * pass (when the scene has translucent objects), the edge-aa pass (aa: edge) and the
 * resolve; then the frame's draws must equal the formula: the shadows pass's (the sum of
 * the shadow-casting sets, fe.shadow_start[fe.nlights], when it runs), one per visible
 * opaque object in the first pass, `light_draws` more, the sky, one per visible
 * translucent object, the edge-aa pass and the resolve (asserted in debug builds). */
void forward_end_frame(forward_common *fc, frame_stats *out, uint64_t light_draws);

/* Fills GPU times and fragment counts after the frame's sync point (NAN without queries). */

// >>describe

/* Appends a pass row: name, whether it runs, and why (printf format). */
void forward_describe_pass(pass_plan *out, const char *name, bool run, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* The targets (hdr, depth), their bytes, the programs compiled; gbuffer_bytes 0. */
void forward_describe_resources(const forward_common *fc, pass_plan *out);
/* How every describe begins: the plan emptied, then the "shadows" entry when some
 * light of the scene asks for shadows (it runs, or why not: "shadows: off", point
 * lights only); a scene where no light asks has no entry (the forward plans list only
 * their own passes then). */
void forward_describe_begin(const forward_common *fc, pass_plan *out);
/* The fog (run, in the shaders, or skipped), sky and resolve entries, then the
 * resources: how every describe ends. */
void forward_describe_tail(const forward_common *fc, pass_plan *out);

// >>forward-spml's light limit

// >>for tests: self is what the renderer_impl's create returned

/* The state cache's counts of pass i of the last frame drawn, or NULL past its passes. */
const gls_counts *forward_last_pass_counts(const void *self, size_t pass);
/* The HDR colour target (RGBA16F, or RGBA32F with hdr) the frame was lit in, and its
 * depth-stencil target. */
const gl_target *forward_hdr_target(const void *self);
const gl_target *forward_depth_target(const void *self);

/* Both renderers' renderer_impl.read_hdr: the "hdr" target of the last frame
 * as RGBA floats, row 0 at the bottom (renderer_read_hdr). False when not prepared or
 * width x height is not the target's. Direct state access: the cache is not disturbed. */
bool forward_read_hdr(void *self, float *rgba, int width, int height);

/* The most lights forward-spml can hold in one uniform block of the context:
 * max_uniform_block_size / sizeof(gpu_light) (80 bytes: 5 vec4s, std140), 0 for a
 * size <= 0. `shadesweep info` reports it. */
uint32_t forward_spml_max_lights(int max_uniform_block_size);
