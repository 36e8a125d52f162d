#pragma once
/* The renderer interface (DESIGN.md): a static registry from name to
 * implementation, one opaque object per run. Renderers draw into the context's
 * off-screen framebuffer.
 *
 * Adding a renderer:
 *   1. its code, renderers/x.c (or its family's folder; in renderers/meson.build):
 *      x_create/prepare/draw/describe/destroy and `const renderer_impl renderer_x_impl =
 *      RENDERER_IMPL(x, "x", reads, description, ...)`, `reads` naming the keys or groups
 *      it reads beyond every run's ("x hdr msaa fog aa");
 *   2. its shaders, renderers/shaders/x*.glsl (listed in renderers/meson.build);
 *   3. its keys, if any, in renderers/x_keys.def (format: renderers/keys.h), included by
 *      renderers/keys.def: the manifest, docs, completion and renderer_options follow;
 *   4. its test, tests/gl/test_x.c (a line in tests/meson.build's gl_tests);
 *   5. one line in renderers/renderer.c's RENDERER_REGISTRY. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/keys.h"
#include "renderers/gl/stats.h"
#include "results/bandwidth.h"

struct scene;

/* What a renderer is made with: the context's facts, then the members the key tables
 * declare (renderers/keys.def's KEY_OPTION), which the runner sets by each key's `apply`
 * (params_to_renderer_options); a test starts from renderer_options_default(). */
typedef struct renderer_options {
    int width, height;
    bool queries;              /* use timer / pipeline-statistics queries where the context has them */
    bool timer_query, pipeline_statistics;  /* what the context offers (from gl_info) */
    int max_uniform_block_size;   /* the context's limit, for forward-spml's light buffer */
    int shadow_map_size;       /* side of each shadow map in texels; 0: 1024 */
#define KEY_ENUM(...)
#define PARAM_META(...)
#define PARAM(...)
#define KEY_OPTION(type, member, dims) type member dims;
#include "renderers/keys.def"
#undef KEY_ENUM
#undef PARAM_META
#undef PARAM
#undef KEY_OPTION
} renderer_options;

/* Every key at its default: the tables' default texts, each by its value's C type, made
 * into options by the keys' `apply` as the runner makes a run's (tests/unit/test_params.c
 * checks the two agree). */
renderer_options renderer_options_default(void);
/* What a test means by a key's member it leaves zero: the default's (a member a test sets
 * to zero on purpose is the default's already, fog_color aside). */
void renderer_options_complete(renderer_options *o);

struct renderer_estimate;

typedef struct renderer_impl {
    const char *name;
    const char *description;
    /* The manifest keys whose value changes its output beyond those every run reads
     * (runner/manifest/params.def readers "*"), space-separated; a group name stands for its keys
     * ("gbuffer": gbuffer.*). A sweep folds the runs of a renderer that differ only in
     * keys it does not read; docs/manifest.md's "read by" is made from these. */
    const char *reads;
    void *(*create)(const renderer_options *opts, char *err, size_t errlen);
    bool (*prepare)(void *self, const struct scene *s, char *err, size_t errlen);
    void (*draw)(void *self, const struct scene *s, frame_stats *out);
    /* A frame drawn only to build the driver's shader variants before anything is
     * measured (renderer_prime): every draw state the frame would use, not its every
     * draw. Optional (NULL: draw). forward-mpml draws one light of each kind. */
    void (*prime)(void *self, const struct scene *s, frame_stats *out);
    /* After the frame's sync point: fills GPU times and query counts of that frame.
     * Optional (NULL: the object begins with a renderer_base, renderers/frame/base.h, and its
     * counters are all the renderer collects). */
    bool no_base;   /* the object does not begin with a renderer_base (null): it has
                       neither the base's counters nor its depth target */
    void (*collect)(void *self, frame_stats *out);
    void (*describe)(const void *self, pass_plan *out);
    void (*destroy)(void *self);
    /* Optional (NULL: the renderer has no float target, as null): the float light
     * accumulation (RGBA16F, or RGBA32F with hdr_format) of the last frame drawn, as floats, see renderer_read_hdr. False,
     * with nothing written, when not prepared or width x height is not the target's. */
    bool (*read_hdr)(void *self, float *rgba, int width, int height);
    /* Optional (NULL: no light grid): after collect, the light-list length of every
     * tile (or cluster) of the last frame collected, *n of them (lightgrid.csv). */
    const uint32_t *(*light_grid)(const void *self, size_t *n);
    /* Optional (NULL: no G-buffer, both NAN): seed 002's G-buffer traffic of a collected
     * frame (results/bandwidth.h's MRT terms): the bytes the renderer's per-sample
     * surface target (a G-buffer, the visibility ids) is written and read in it. */
    gbuffer_traffic (*traffic)(const void *self, const frame_stats *fs);
    /* Optional (NULL: none): the bytes of the targets and buffers the design makes
     * beyond the base's (hdr, depth, msaa resolve, edge AA, shadow maps, light lists),
     * for the memory estimate a run is checked against before it starts
     * (runner/plan/memory.c): a model, no GL call. */
    uint64_t (*own_bytes)(const struct renderer_estimate *e);
    /* Optional (NULL: 0): for the memory estimate, the draw calls a frame makes for each
     * light, which llvmpipe bins until the frame ends (light volumes and their stencil
     * marks, forward-mpml's meshes a light reaches). */
    uint64_t (*draws_per_light)(const struct renderer_estimate *e);
    /* Optional (NULL: no limit of its own): the most lights an object made with opts
     * (NULL: its most limited design) holds in a context whose uniform blocks hold
     * max_uniform_block_size bytes; UINT32_MAX where opts choose no such limit. */
    uint32_t (*max_lights)(const renderer_options *opts, int max_uniform_block_size);
    /* Optional (NULL: none, or the gbuffer.* keys choose it): the name of the per-sample
     * surface target the design keeps when no key chooses its layout (summary.csv's
     * gbuffer column): deferred-lighting's "light-prepass", visibility's "ids". */
    const char *gbuffer_layout;
    /* Optional (NULL: the entries above serve): a renderer that is one of two designs
     * chosen by an option (clustered: forward or deferred shading over the same cluster
     * lists) returns the registered renderer whose entry points serve an object made with
     * opts; its own create (when it has one) makes the object, the design does the rest.
     * The registry's entry keeps the name, description and reads. */
    const struct renderer_impl *(*variant)(const renderer_options *opts);
} renderer_impl;

/* A renderer_impl whose five required entry points are P_create, P_prepare, P_draw,
 * P_describe and P_destroy (each has its own type, so a wrong one does not compile); the
 * optional entries (collect among them) follow as designated initializers:
 *     const renderer_impl renderer_x_impl = RENDERER_IMPL(
 *         x, "x", "keys it reads", "description", .read_hdr = x_read_hdr); */
#define RENDERER_IMPL(P, NAME, READS, DESCRIPTION, ...)                                    \
    {                                                                                      \
        .name = NAME, .description = DESCRIPTION, .reads = READS, .create = P##_create,    \
        .prepare = P##_prepare, .draw = P##_draw, .describe = P##_describe,                \
        .destroy = P##_destroy, __VA_ARGS__                                                \
    }

/* The destroy of a renderer whose object begins with its family's base (forward_common,
 * deferred_renderer): RELEASE(self) frees what the renderer made itself (only for an
 * object), BASE_FREE(self) the base's resources and the object. */
#define RENDERER_DESTROY(P, RELEASE, BASE_FREE)                                            \
    static void P##_destroy(void *self)                                                    \
    {                                                                                      \
        if (self)                                                                          \
            RELEASE(self);                                                                 \
        BASE_FREE(self);                                                                   \
    }

typedef struct renderer renderer;

size_t renderer_kind_count(void);
const renderer_impl *renderer_kind_at(size_t i);
const renderer_impl *renderer_kind_find(const char *name);   /* NULL if unknown */
/* Whether a renderer_impl.reads list names the manifest key path, or a group above it
 * ("gbuffer" names gbuffer.preset). */
bool renderer_reads(const char *reads, const char *path);
/* Whether the design that serves `kind` with options o (renderer_impl.variant: clustered's
 * forward or deferred shading, deferred-lighting's volumes or tiles) reads path; the
 * registry's entry reads what any of its designs does. */
bool renderer_design_reads(const char *kind, const renderer_options *o, const char *path);

renderer *renderer_create(const char *kind, const renderer_options *opts, char *err, size_t errlen);
bool renderer_prepare(renderer *r, const struct scene *s, char *err, size_t errlen);
/* Seconds this process has spent uploading scenes to the GPU (scene_gpu_upload_s): the
 * difference across a renderer_prepare is that prepare's upload. */
double renderer_upload_s(void);
void renderer_draw(renderer *r, const struct scene *s, frame_stats *out);
/* A priming frame (renderer_impl.prime): not measured, its counters not the frame's. */
void renderer_prime(renderer *r, const struct scene *s, frame_stats *out);
void renderer_collect(renderer *r, frame_stats *out);   /* also computes out->total */
/* Whether renderer_coverage can count (every renderer but null, which draws nothing). */
bool renderer_has_coverage(const renderer *r);
/* The pixels the last frame drawn covers: any sample nearer than the far plane
 * (renderer_base_coverage; between frames, never inside a measured one). False with
 * a message when the renderer has no depth target or is not prepared. */
bool renderer_coverage(renderer *r, uint64_t *covered, char *err, size_t errlen);
/* The lights that reach each pixel's surface in the last frame drawn, s posed for it
 * (renderer_base_lights_reaching: counts is width x height, GL's rows, UINT32_MAX where
 * nothing was drawn; between frames). False with a message where renderer_coverage is. */
bool renderer_lights_reaching(renderer *r, const struct scene *s, uint32_t *counts, char *err,
                              size_t errlen);
/* An object's collect as renderer_collect calls it (renderer_impl.collect, or the
 * base's when that is NULL), without the totals: for tests that drive an impl. */
void renderer_impl_collect(const renderer_impl *impl, void *self, frame_stats *out);
void renderer_describe(const renderer *r, pass_plan *out);
void renderer_destroy(renderer *r);                     /* NULL is fine */
/* The light-list lengths of the last frame collected (renderer_impl.light_grid), or
 * NULL with *n = 0 for a renderer without a light grid. */
const uint32_t *renderer_light_grid(const renderer *r, size_t *n);
/* renderer_impl.traffic of a collected frame; NAN for both without one. */
gbuffer_traffic renderer_traffic(const renderer *r, const frame_stats *fs);
bool renderer_has_light_grid(const renderer *r);

/* The renderer's float light accumulation of the last frame drawn (what its resolve
 * pass clamps into the output; deferred with separate_specular: the diffuse target
 * after the compose pass added the specular one into it, i.e. the sum of both) into
 * rgba: width x height pixels of 4 floats (RGBA), tightly packed, row 0 at the BOTTOM
 * as GL stores it (gl_context_read_rgba8's row 0 is the top one). Alpha is whatever
 * the accumulation holds (the resolve writes 1 whatever it is). *nonfinite (may be
 * NULL) gets the number of values that are Inf or NaN: an RGBA16F target overflows to
 * Inf beyond 65504. False, nothing read and *nonfinite = 0, when the renderer has no
 * float target (null), is not prepared, or w x h is not its target's size. Reads
 * with direct state access: no binding the renderer's state cache keeps is touched
 * (pixel-pack state is restored). Before the first frame the contents are undefined. */
bool renderer_read_hdr(renderer *r, float *rgba, int w, int h, size_t *nonfinite);

/* >>models the runner asks of the renderers without making one (the memory estimate,
 * seed 002's bandwidth columns, `info` and the plan's warnings) */

/* What a scene's materials make a G-buffer hold (deferred_needs_of). */
typedef struct deferred_needs {
    bool gloss;                        /* some object's material has specular > 0: gloss and
                                          shininess (a gloss map only scales it) */
    bool emissive;                     /* some object's material has an emissive colour > 0 */
    bool pbr;                          /* the scene is shaded by the metallic-roughness model:
                                          gloss and shininess hold metallic and roughness,
                                          stored as they are; deferred-lighting's G-buffer
                                          adds F0 */
    bool occlusion;                    /* pbr, and some object's material has an occlusion map */
} deferred_needs;

/* What renderer_impl.own_bytes is given: the run's options (msaa already the samples a
 * pixel), the output's pixels, its HDR target's bytes a sample, and what the scene
 * needs (scene false: not built; then the widest bound). */
typedef struct renderer_estimate {
    const renderer_options *opts;
    uint64_t pixels;
    uint64_t samples;             /* >= 1 */
    uint64_t hdr_bytes;           /* 8 (RGBA16F) or 16 (RGBA32F) */
    bool scene;
    deferred_needs needs;         /* (scene) the materials' G-buffer needs */
    uint64_t scene_bytes;         /* (scene) the meshes' vertices and indices */
    uint32_t nmeshes;             /* (scene) its meshes */
} renderer_estimate;
/* renderer_impl.own_bytes of the design that serves `kind` with e->opts (its variant);
 * 0 for an unknown kind or a design without one. */
uint64_t renderer_own_bytes(const char *kind, const renderer_estimate *e);
/* renderer_impl.draws_per_light of the registry's entry `kind`; 0 without one. */
uint64_t renderer_draws_per_light(const char *kind, const renderer_estimate *e);
/* renderer_impl.max_lights of the registry's entry `kind` (o NULL: its most limited
 * design); UINT32_MAX for a renderer without one or an unknown kind. */
uint32_t renderer_max_lights(const char *kind, const renderer_options *o,
                             int max_uniform_block_size);
/* The bytes one light takes in the renderers' light buffers (std140 vec4s). */
uint64_t renderer_light_bytes(void);
/* The bytes of one shadow map layer at the default size (renderers/frame/shadow.h). */
uint64_t renderer_shadow_layer_bytes(void);
/* The depth slices clustered.slices slices_y makes of s's camera (its light grid's
 * depth, renderers/frame/shading.h), and whether the planes proj11, znear, zfar hold them
 * (false with the message the grid gives at prepare, naming kind). */
uint32_t renderer_cluster_slices(const struct scene *s, int slices_y);
bool renderer_cluster_slices_ok(const char *kind, double proj11, double znear, double zfar,
                                int slices_y, char *err, size_t errlen);

/* What objects' materials of s write (opaque and alpha-tested ones: translucent objects
 * never reach the G-buffer, renderers/frame/translucent.h). */
deferred_needs deferred_needs_of(const struct scene *s);

/* Whether the renderer `kind` with options o shades from a G-buffer: whether the design
 * that serves it (renderer_impl.variant) reads the gbuffer keys. */
bool renderer_uses_gbuffer(const char *kind, const renderer_options *o);
/* renderer_impl.gbuffer_layout of the design that serves kind with o; "" without one. */
const char *renderer_gbuffer_layout(const char *kind, const renderer_options *o);

