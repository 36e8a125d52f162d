#pragma once
/* The renderer interface (DESIGN.md): a static registry from name to
 * implementation, one opaque object per run. Renderers draw into the context's
 * off-screen framebuffer. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/gl/stats.h"
#include "results/bandwidth.h"

struct scene;

/* Every enum of renderer_options begins with an UNSET zero, and sizes are 0 when unset: a
 * zeroed renderer_options chooses nothing, and renderer_create refuses it, naming the
 * field. The runner sets every field from runner/params.def (params_to_renderer_options),
 * the one place that says what the defaults are. */

/* G-buffer layouts (the deferred renderer; renderers/deferred.c documents each):
 *   fat        seed 000: three RGBA16F, view-space position, normal + emissive, diffuse + gloss
 *   curtis     seed 003: four RGBA16F, normal + depth, diffuse + specular, specular colour,
 *              one unused; position rebuilt from depth
 *   compact    seed 002's 96-bit layout
 *   spheremap  seed 004: view-space normal in two 8-bit channels (Lambert azimuthal),
 *              position from linear depth and frustum-corner rays
 *   reference  RGBA32F, position stored: the G-buffer that loses (almost) nothing */
typedef enum gbuffer_preset {
    GBUFFER_UNSET = 0,
    GBUFFER_CURTIS,
    GBUFFER_FAT,
    GBUFFER_COMPACT,
    GBUFFER_SPHEREMAP,
    GBUFFER_REFERENCE,
} gbuffer_preset;

/* Field by field over the preset (0: no override, as the preset has it). */
typedef enum gbuffer_position {
    GBUFFER_POSITION_PRESET = 0,
    GBUFFER_POSITION_STORED16,     /* view-space xyz in RGBA16F */
    GBUFFER_POSITION_STORED32,     /* view-space xyz in RGBA32F */
    GBUFFER_POSITION_DEPTH,        /* rebuilt from the depth buffer */
} gbuffer_position;

typedef enum gbuffer_normal {
    GBUFFER_NORMAL_PRESET = 0,
    GBUFFER_NORMAL_FLOAT16,        /* xyz in 16-bit floats */
    GBUFFER_NORMAL_FLOAT32,
    GBUFFER_NORMAL_UNORM10,        /* xyz * 0.5 + 0.5 in RGB10A2 */
    GBUFFER_NORMAL_SPHEREMAP8,     /* Lambert azimuthal in RG8 */
    GBUFFER_NORMAL_SPHEREMAP16,    /* Lambert azimuthal in RG16F */
} gbuffer_normal;

/* How deferred light passes find their pixels. */
typedef enum light_volume_mode {
    LIGHT_VOLUMES_UNSET = 0,
    LIGHT_VOLUMES_STENCIL,         /* seed 003: one two-sided stencil pass (inc/dec on depth
                                      fail), then the light on non-zero, and reset */
    LIGHT_VOLUMES_FULLSCREEN,      /* a full-screen pass per light */
    LIGHT_VOLUMES_VOLUME,          /* back faces, depth test GREATER, no stencil */
    LIGHT_VOLUMES_STENCIL_TWO_PASS,/* seed 000: clear to 1, front faces inc on depth fail,
                                      back faces dec, shade where 0 */
    LIGHT_VOLUMES_HULL,            /* seed 000 4.5.8's unoptimised hull: back faces, no depth
                                      test, no stencil: every pixel the hull covers */
    LIGHT_VOLUMES_SCISSOR,         /* a full-screen pass scissored to the light's projected
                                      screen rectangle */
} light_volume_mode;

/* Where forward-spml reads its lights from. */
typedef enum light_buffer_kind {
    LIGHT_BUFFER_UNSET = 0,
    LIGHT_BUFFER_UNIFORM,          /* seed 003's uniform block: GL_MAX_UNIFORM_BLOCK_SIZE / 80 */
    LIGHT_BUFFER_STORAGE,          /* one shader storage buffer: no limit of its own */
    LIGHT_BUFFER_AUTO,             /* uniform when the run's lights fit, storage beyond
                                      (what an error reference uses) */
} light_buffer_kind;

/* The float light accumulation's format (the manifest's `hdr`): every renderer that
 * draws accumulates into one target of it (renderers/base.h). */
typedef enum hdr_format {
    HDR_UNSET = 0,
    HDR_RGBA16F,                   /* 16-bit floats (seed 000 4.5.12's FP16 HDR) */
    HDR_RGBA32F,                   /* 32-bit floats: no rounding of additive passes to 11 bits */
} hdr_format;

/* deferred-lighting's light buffer (deferred_lighting.light_buffer): the format of its
 * diffuse and specular light targets. RGBA8 is Engel 2008's 8-bit buffer: light above
 * 1.0 clamps there, and the image shows it. */
typedef enum lpp_light_buffer_format {
    LPP_LIGHT_BUFFER_UNSET = 0,
    LPP_LIGHT_BUFFER_RGBA16F,
    LPP_LIGHT_BUFFER_RGBA8,
} lpp_light_buffer_format;

/* Anti-aliasing after the lighting (the manifest's `aa`): every renderer that draws. */
typedef enum aa_mode {
    AA_UNSET = 0,
    AA_NONE,                       /* no pass */
    AA_EDGE,                       /* seed 001 19.5.2's edge-detect blur (renderers/edge_aa.h) */
} aa_mode;

typedef struct renderer_options {
    int width, height;
    bool queries;              /* use timer / pipeline-statistics queries where the context has them */
    bool timer_query, pipeline_statistics;  /* what the context offers (from gl_info) */
    int max_uniform_block_size;   /* the context's limit, for forward-spml's light buffer */
    /* deferred */
    gbuffer_preset gbuffer;
    gbuffer_position gbuffer_position;
    gbuffer_normal gbuffer_normal;
    light_volume_mode light_volumes;
    bool separate_specular;    /* seed 001: diffuse and specular in separate targets */
    bool sky_stencil;          /* seed 001 19.7.2: the full-screen passes skip the pixels no
                                  surface covers by a stencil bit the G-buffer pass sets */
    /* shadows (every renderer; renderers/shadow.h): false = auto (spot and directional
     * lights with shadows = true cast them), true = the manifest's `shadows: off` */
    bool no_shadows;
    int shadow_map_size;       /* side of each shadow map in texels; 0: 1024 */
    /* forward-mpml */
    bool no_illumination_sets; /* draw every visible object for every light (seed 000 5.6) */
    bool directional_in_base;  /* the directional lights shaded in the base pass, not in
                                  passes of their own (forward.directional_in_base) */
    /* forward-spml's light buffer (forward.light_buffer) */
    light_buffer_kind light_buffer;
    /* forward-plus (tiles.*): tile side in pixels (8, 16 or 32); the index
     * buffer's capacity in entries per tile on average (0: enough for every light in
     * every tile, i.e. no list can overflow) */
    int tile_size;
    uint32_t max_lights_per_tile;   /* clustered: per cluster */
    /* clustered: exponential depth slices (clustered.slices, 1 to 64), and shading from the
     * G-buffer (clustered.shading: deferred; every deferred G-buffer option applies) */
    int clustered_slices;
    bool clustered_deferred;
    /* deferred-lighting (deferred_lighting.light_buffer), and its lights accumulated by the
     * tiled light lists instead of deferred's light volumes (deferred_lighting.lights) */
    lpp_light_buffer_format lpp_light_buffer;
    bool lpp_tiled;
    /* every renderer that draws: the light accumulation's format (hdr), and seed 000
     * 4.5.12's fog from depth (fog.*): off while fog_density is 0; on, a surface at view
     * depth z keeps exp(-fog_density z) of its light and takes the rest from fog_color */
    hdr_format hdr;
    float fog_density;
    float fog_color[3];
    /* every renderer that draws: anti-aliasing (aa), a post pass on the HDR image */
    aa_mode aa;
    /* every renderer that draws (msaa): samples per pixel of its HDR and depth targets;
     * 0 or 1: single-sampled (renderers/base.h) */
    int msaa;
} renderer_options;

struct renderer_estimate;

typedef struct renderer_impl {
    const char *name;
    const char *description;
    /* The manifest keys whose value changes its output beyond those every run reads
     * (runner/params.def readers "*"), space-separated; a group name stands for its keys
     * ("gbuffer": gbuffer.*). A sweep folds the runs of a renderer that differ only in
     * keys it does not read; docs/manifest.md's "read by" is made from these. */
    const char *reads;
    void *(*create)(const renderer_options *opts, char *err, size_t errlen);
    bool (*prepare)(void *self, const struct scene *s, char *err, size_t errlen);
    void (*draw)(void *self, const struct scene *s, frame_stats *out);
    /* After the frame's sync point: fills GPU times and query counts of that frame.
     * Optional (NULL: the object begins with a renderer_base, renderers/base.h, and its
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
     * (runner/memory.c): a model, no GL call. */
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
/* The bytes of one shadow map layer at the default size (renderers/shadow.h). */
uint64_t renderer_shadow_layer_bytes(void);
/* The depth slices clustered.slices slices_y makes of s's camera (its light grid's
 * depth, renderers/shading.h), and whether the planes proj11, znear, zfar hold them
 * (false with the message the grid gives at prepare, naming kind). */
uint32_t renderer_cluster_slices(const struct scene *s, int slices_y);
bool renderer_cluster_slices_ok(const char *kind, double proj11, double znear, double zfar,
                                int slices_y, char *err, size_t errlen);

/* What objects' materials of s write (opaque and alpha-tested ones: translucent objects
 * never reach the G-buffer, renderers/translucent.h). */
deferred_needs deferred_needs_of(const struct scene *s);

/* Whether the renderer `kind` with options o shades from a G-buffer: whether the design
 * that serves it (renderer_impl.variant) reads the gbuffer keys. */
bool renderer_uses_gbuffer(const char *kind, const renderer_options *o);
/* renderer_impl.gbuffer_layout of the design that serves kind with o; "" without one. */
const char *renderer_gbuffer_layout(const char *kind, const renderer_options *o);

