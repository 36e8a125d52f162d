#pragma once
/* What every renderer that draws (deferred, tiled-deferred and the forward family)
 * embeds as its first member: the options and output size, the output framebuffer,
 * the state cache, the program cache, the per-pass queries, and the bracketing and
 * collection of passes. A renderer is then its own passes plus this.
 * The calls in a frame's order, the targets, MSAA and fog: the comment above
 * struct renderer_base below. */
#include <stdbool.h>
#include <stddef.h>

#include "renderers/frame/frontend.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/query.h"
#include "renderers/gl/state.h"
#include "renderers/gl/target.h"
#include "renderers/renderer.h"
#include "renderers/frame/scene_gpu.h"
#include "renderers/frame/shadow.h"

enum { RENDERER_BASE_MAX_PASSES = 16 };

struct scene;

/* aa: edge's state (made and run by renderers/frame/edge_aa.h, released with the base's
 * targets, its output the display when it runs). */
typedef struct edge_aa {
    bool run;                        /* opts.aa == AA_EDGE and prepared */
    bool gbuffer_normals;            /* normals from the G-buffer, else from depth */
    gl_target out;                   /* "hdr.aa" */
    gl_framebuffer fb;               /* out alone */
    GLuint program;                  /* in the base's program cache */
    /* msaa > 1: the multisampled depth blitted to one sample a pixel ("depth.aa"), what
     * the edge test reads; normals then come from it, not from the G-buffer */
    gl_target depth1;
    gl_framebuffer depth_read, depth_draw;
} edge_aa;

/*     renderer_base_init      at create: records the output framebuffer (the draw
 *                             framebuffer bound now), the context's uniform block limit
 *                             when opts does not give it, makes the caches and (with
 *                             opts.queries) max_passes pass queries
 *     renderer_base_size      at prepare: the output size (opts, or the scene's), refused
 *                             when the scene is posed for another size
 *     renderer_base_scene     at prepare: the scene on the GPU, the frontend and the
 *                             shadow maps (below), what every renderer draws from
 *     renderer_base_begin_frame   every frame: the state cache invalidated (every frame
 *                             counts alike), the frame's passes reset, the frontend
 *                             built and the Frame block uploaded for the scene's pose
 *     renderer_base_shadow_pass   the "shadows" pass, when some light casts shadows
 *     renderer_base_pass_begin / _end   around each pass: the pass gets the next index
 *                             of frame_stats.pass, its queries and the cache's counts
 *                             (draws, dispatches, state changes); GPU time and fragments
 *                             are NAN until collect
 *     renderer_base_collect   after the frame's sync point: the queries' results
 *     renderer_base_destroy   what init made; a zeroed base is fine
 *
 * The targets every renderer shades into are the base's, so that all of them follow
 * the run's options alike: renderer_base_targets makes hdr (the float light
 * accumulation in opts.hdr's format: RGBA16F or RGBA32F, at the output's size) and
 * depth (depth24-stencil8 at that size), renderer_base_read_hdr reads hdr back for
 * every renderer's read_hdr; renderer_base_hdr_target makes another target like hdr
 * (deferred's light.specular). A compute pass that
 * image-stores into the HDR target binds it with renderer_base_hdr_image_format and
 * compiles its shader with renderer_base_hdr_define (the image's format qualifier; no
 * define for RGBA16F, so the default's programs are what they always were).
 *
 * MSAA (opts.msaa > 1, the manifest's `msaa`): renderer_base_init refuses a count above
 * the context's min(GL_MAX_SAMPLES, GL_MAX_COLOR_TEXTURE_SAMPLES,
 * GL_MAX_DEPTH_TEXTURE_SAMPLES) (renderer_base_msaa_check, before anything renders);
 * renderer_base_targets then makes hdr and depth multisampled (GL_TEXTURE_2D_MULTISAMPLE,
 * renderer_base_hdr_target too) plus hdr_resolved, single-sampled in the HDR format.
 * renderer_base_msaa_resolve_pass, after the renderer's last shading pass and before
 * the display resolve, is the pass "msaa-resolve": a blit of hdr into hdr_resolved,
 * i.e. the samples averaged in linear HDR (before the clamp to the display, so a bright
 * sample is not clipped before it is averaged). renderer_base_display (what
 * scene_gpu_resolve reads) and renderer_base_read_hdr use hdr_resolved; aa: edge then
 * runs after msaa-resolve, on hdr_resolved and a single-sampled copy of the depth
 * (edge_aa.h). At msaa 1
 * none of this exists: no pass, no target, the same programs and images as before.
 *
 * Fog (seed 000 4.5.12, opts.fog_*): renderer_base_fog says whether it is on; each
 * program compiled with the "FOG" define (fog.inc.glsl) gets the run's fog once from
 * renderer_base_fog_uniform. */
typedef struct renderer_base {
    const char *name;                /* "deferred": prefixes messages */
    renderer_options opts;
    bool stochastic;                 /* lights.culling: stochastic, set at create by a design
                                        that culls so (light_grid_culling_option): every
                                        program gets STOCHASTIC (lighting.inc) */
    int width, height;               /* the output's size (opts, or the scene's) */
    GLuint output_fbo;               /* the draw framebuffer bound at creation */
    gl_state *st;
    gl_program_cache *programs;
    gl_pass_queries *queries;        /* NULL without opts.queries */
    GLuint coverage_buffer;          /* renderer_base_coverage's counter, made at first use */
    size_t max_passes;
    /* >>made by renderer_base_scene at prepare */
    scene_gpu *gpu;                  /* the scene's meshes, textures and Frame block */
    frontend fe;                     /* per frame: visible objects, lights, their sets */
    shadow_maps shadows;             /* the shadow-map plan, and the pool when it runs */
    char light_types_define[32];     /* the programs' common defines (lighting.inc): the */
    char attenuations_define[32];    /* scene's light types and attenuations */
    char lighting[192];              /* the pass plan's line about them */
    /* >>made by renderer_base_targets at prepare */
    gl_target hdr;                   /* the light accumulation, opts.hdr's format */
    gl_target depth;                 /* depth24-stencil8 */
    int samples;                     /* 1, or opts.msaa: the samples of hdr and depth (after
                                        renderer_base_targets what the driver gave, which
                                        may be more: llvmpipe gives 4 for 2) */
    gl_target hdr_resolved;          /* samples > 1: hdr averaged (msaa-resolve) */
    gl_framebuffer msaa_read, msaa_draw;   /* samples > 1: the blit's hdr -> hdr_resolved */
    edge_aa aa;                      /* aa: edge (edge_aa.h): its pass, target, program */
    /* >>the last frame, for tests */
    size_t npasses;
    gls_counts pass_counts[RENDERER_BASE_MAX_PASSES];
} renderer_base;

/* False with "NAME: out of memory"; renderer_base_destroy is then still right. */
bool renderer_base_init(renderer_base *b, const char *name, const renderer_options *opts,
                        size_t max_passes, char *err, size_t errlen);
void renderer_base_destroy(renderer_base *b);
/* Sets width and height; false with a message when s is posed for another size. */
bool renderer_base_size(renderer_base *b, const struct scene *s, char *err, size_t errlen);
/* The programs built (gl_program_cache_describe) and the lighting line into out. */
void renderer_base_describe(const renderer_base *b, pass_plan *out);
/* What every renderer needs of a scene, made at prepare: the shadow-map plan
 * (shadow_maps_plan: which lights get maps, or why none), the frontend (frontend_init;
 * illumination sets only when illumination_sets, i.e. forward-mpml; no shadow sets
 * when no map is drawn), the scene on the GPU (scene_gpu_create) and, when the plan
 * runs, the shadow pool and its depth program. False with "NAME: ..."; what it made
 * is released by renderer_base_release_scene (a second call releases first). */
bool renderer_base_scene(renderer_base *b, const struct scene *s, bool illumination_sets,
                         char *err, size_t errlen);
void renderer_base_release_scene(renderer_base *b);
/* Every frame, first: the state cache invalidated (every frame counts alike), the
 * frame's passes reset, and with a scene (s non-NULL, after renderer_base_scene) the
 * frontend built for s's pose and the Frame block uploaded. */
void renderer_base_begin_frame(renderer_base *b, const struct scene *s, frame_stats *out);
/* The pass "shadows" when the plan runs it (renderers/frame/shadow.h: one depth draw per
 * object of each shadowed light's casting set, no samples counted); nothing otherwise. */
void renderer_base_shadow_pass(renderer_base *b, const struct scene *s, frame_stats *out);
void renderer_base_pass_begin(renderer_base *b, frame_stats *out, const char *name);
void renderer_base_pass_end(renderer_base *b, frame_stats *out);
void renderer_base_collect(renderer_base *b, frame_stats *out);
/* Within a pass: false before draws that shade nothing (stencil marks, shadow maps, a
 * depth pre-pass), true after them; pass_stats.samples (GL_SAMPLES_PASSED) counts the
 * pass's other draws. A pass starts counting; without queries it does nothing. */
void renderer_base_shading(renderer_base *b, bool on);
/* Within a pass (msaa): the shading draws from now on shade per sample (true) or per
 * pixel (false, what every pass starts with); pass_stats.per_sample_samples counts the
 * former's samples apart. */
void renderer_base_per_sample(renderer_base *b, bool on);
/* Within a pass: it draws into single-sampled targets whatever opts.msaa (the display
 * resolve, edge AA), so its samples are pixels (pass_stats.single_sampled). */
void renderer_base_single_sampled(frame_stats *out);
/* The state cache's counts of pass i of the last frame, or NULL past its passes. */
const gls_counts *renderer_base_pass_counts(const renderer_base *b, size_t pass);

// >>targets and fog

/* The msaa refusal of renderer_base_init, on given limits (so that a test can pass a
 * limit the context does not have): msaa 0 or 1 is single-sampled; otherwise it must be
 * 2, 4 or 8 and at most every limit. False with "NAME: msaa N: ..." naming the limits. */
bool renderer_base_msaa_check(const char *name, int msaa, int max_samples, int max_color,
                              int max_depth, char *err, size_t errlen);

/* opts.hdr as a target format (GLT_FORMAT_RGBA16F or GLT_FORMAT_RGBA32F), as an image
 * unit format (GL_RGBA16F, GL_RGBA32F), and as the shader define of an image store's
 * format qualifier ("HDR_RGBA32F", or NULL for RGBA16F). */
gl_format renderer_base_hdr_format(const renderer_base *b);
GLenum renderer_base_hdr_image_format(const renderer_base *b);
const char *renderer_base_hdr_define(const renderer_base *b);
/* Creates t, named name, in the HDR format at width x height (renderer_base_size
 * first); false with gl_target_create's message. */
bool renderer_base_hdr_target(const renderer_base *b, gl_target *t, const char *name, char *err,
                              size_t errlen);
/* The renderer's own targets, at width x height (renderer_base_size first): hdr
 * (renderer_base_hdr_target, named hdr_name) and depth ("depth", depth24-stencil8).
 * False with gl_target_create's message; renderer_base_release_targets (which
 * renderer_base_destroy calls too) undoes it, as often as wanted. */
bool renderer_base_targets(renderer_base *b, const char *hdr_name, char *err, size_t errlen);
void renderer_base_release_targets(renderer_base *b);
/* What edge_aa_prepare made (renderer_base_release_targets calls it); a zeroed one is
 * fine. */
void renderer_base_release_aa(edge_aa *e);
/* The HDR image the resolve clamps into the output and read_hdr reads: with aa: edge
 * the edge pass's "hdr.aa", with msaa > 1 "hdr.resolved", else hdr. */
const gl_target *renderer_base_display(const renderer_base *b);
/* renderer_impl.read_hdr of every renderer: renderer_base_display's target of the last
 * frame as RGBA floats, row 0 at the bottom; false when there is none or it is not
 * width x height. */
bool renderer_base_read_hdr(const renderer_base *b, float *rgba, int width, int height);
/* The pixels of the last frame drawn where any sample of the depth target is nearer
 * than the far plane (coverage.comp: a dispatch and a read-back of one word, between
 * frames). False with a message when there is no depth target (not prepared) or the
 * program cannot be made. The state cache is invalidated: its next use sets again. */
bool renderer_base_coverage(renderer_base *b, uint64_t *covered, char *err, size_t errlen);
/* The lights of s (posed for the last frame drawn: lights[0 .. nlights_active)) that
 * reach each pixel's surface in the depth target (lights_reaching.comp: the nearest
 * sample with geometry unprojected through s->proj; point and spot lights within their
 * range, spots inside their cone, directional lights always), into counts (width x
 * height, GL's rows: row 0 at the bottom); UINT32_MAX where no sample has geometry.
 * Between frames, as renderer_base_coverage; false with a message as it. */
bool renderer_base_lights_reaching(renderer_base *b, const struct scene *s, uint32_t *counts,
                                   char *err, size_t errlen);
/* samples > 1: the pass "msaa-resolve" (a blit of hdr into hdr_resolved, in the HDR
 * format); nothing at all when single-sampled. After the last pass that shades into hdr,
 * before the display resolve. */
void renderer_base_msaa_resolve_pass(renderer_base *b, frame_stats *out);

/* Fog is on: opts.fog_density > 0. */
bool renderer_base_fog(const renderer_base *b);
/* The run's fog (colour, density) into a FOG program's u_fog (LOC_FOG), with direct state
 * access (nothing bound); nothing while fog is off or for program 0. */
void renderer_base_fog_uniform(const renderer_base *b, GLuint program);
