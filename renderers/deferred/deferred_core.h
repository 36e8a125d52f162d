#pragma once
/* What deferred (deferred.c) and tiled-deferred (tiled/tiled_deferred.c, and clustered
 * with clustered.shading: deferred) share: the object's common part, the pass plan's
 * common entries, the G-buffer (its layout's targets and programs, and the G-buffer pass),
 * the light and fog targets, the passes after the lighting (fog, sky, translucent,
 * msaa-resolve, edge-aa, resolve), describe, destroy and the accessors tests use. A
 * renderer of this family (the design: docs/notes/deferred.md) is
 *
 *     create     deferred_core_create (the options both check), its own checks first
 *     prepare    deferred_prepare_scene (the scene, the layout, the common plan), its own
 *                plan entries, deferred_make_targets, deferred_compile_gbuffer, its own
 *                programs, deferred_compile_fog, translucent_prepare,
 *                deferred_prepare_edge_aa, deferred_prepare_end
 *     draw       deferred_frame_begin (shadows, gbuffer), its own lighting into the light
 *                target, deferred_frame_end (fog ... resolve)
 *     collect    its own, with renderer_base_collect */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/frame/base.h"
#include "renderers/deferred/gbuffer_layout.h"
#include "renderers/gl/state.h"
#include "renderers/gl/target.h"
#include "renderers/renderer.h"
#include "renderers/frame/translucent.h"
#include "scenes/scene.h"

enum {
    DEFERRED_MAX_PASSES = 14,          /* shadows gbuffer [edges] ambient directional point
                                         spot compose fog sky translucent [msaa-resolve]
                                         edge-aa resolve */
    DEFERRED_VARIANTS = 32,           /* material map bits and the alpha test */
    DEFERRED_LIGHT_TYPES = 3,
};

typedef enum deferred_pass {
    PASS_SHADOWS,                    /* renderers/frame/shadow.h */
    PASS_GBUFFER,
    PASS_AMBIENT,
    PASS_DIRECTIONAL,
    PASS_POINT,
    PASS_SPOT,
    PASS_COMPOSE,
    PASS_SKY,
    PASS_RESOLVE,
    PASS_TILED,                      /* tiled-deferred: ambient and every light, one dispatch */
    PASS_FOG,                        /* fog.density > 0: deferred_fog.frag after the lights */
    PASS_TRANSLUCENT,                /* MATERIAL_BLEND objects, forward, after the sky */
    PASS_EDGES,                      /* msaa > 1: edge_mark.frag sets EDGE_BIT */
    PASS_MSAA,                       /* msaa > 1: renderer_base_msaa_resolve_pass */
    PASS_TLISTS,                     /* not a pass: the tiled pass's translucent lists */
    PASS_MATERIAL,                   /* deferred-lighting: the second geometry pass */
    PASS_COARSE,                     /* tiles.levels: 2: the big tiles' dispatch (coarse.c) */
    PASS_COUNT
} deferred_pass;

typedef struct deferred_renderer {
    renderer_base b;                 /* first: name ("deferred", "tiled-deferred",
                                        "clustered"), options, size, caches, queries */
    bool tiled;                      /* tiled-deferred: PASS_TILED instead of the light passes */
    bool lpp;                        /* deferred-lighting (deferred.c): the light pre-pass's
                                        G-buffer and light buffer, and PASS_MATERIAL */

    /* >>made by prepare */
    bool prepared;                   /* (the scene on the GPU, the frontend and the shadow
                                        maps are the base's: renderer_base_scene) */
    deferred_needs needs;
    deferred_layout layout;
    translucent_pass translucent;    /* MATERIAL_BLEND objects after the sky (translucent.h) */
    bool translucency;               /* the scene has translucent objects */
    gl_target gbuf[DEFERRED_MAX_ATTACHMENTS];
    gl_target specular;              /* separate_specular: light.specular */
    gl_target depth_sampled;         /* position from depth: the G-buffer's depth, copied */
    gl_framebuffer fb_gbuffer, fb_light, fb_compose;
    gl_framebuffer fb_fog;           /* the light target alone (fog reads depth) */
    /* deferred-lighting: the light buffer (deferred_lighting.light_buffer's format), the
     * light passes' framebuffer (both + depth); fb_light is the material pass's */
    gl_target lbuf_diffuse, lbuf_specular;
    gl_framebuffer fb_lbuf;
    GLuint fog_program;
    bool unclipped;                  /* full-screen passes draw the unclipped triangle */
    unsigned variants;               /* bit v: some object's material is of map variant v */
    unsigned light_types;            /* bit t: some light of the scene is of type t */
    uint32_t count[DEFERRED_LIGHT_TYPES];   /* the scene's lights of each type */
    uint32_t nobjects;
    bool run[PASS_COUNT];
    char reason[PASS_COUNT][96];
    GLuint gbuffer_program[DEFERRED_VARIANTS];
} deferred_renderer;

// >>create and release

/* calloc(size) (the renderer's object, which starts with a deferred_renderer), the
 * G-buffer options and light_volumes checked, the base initialised. NULL with a message.
 * lpp: deferred-lighting's object (set before anything reads it). */
deferred_renderer *deferred_core_create(const char *name, size_t size, bool tiled, bool lpp,
                                        const renderer_options *opts, char *err, size_t errlen);
/* What prepare made (the common part); a zeroed object is fine. */
void deferred_core_release(deferred_renderer *r);
/* release, the base, the object. */
void deferred_core_destroy(deferred_renderer *r);

// >>prepare

/* A fresh program cache, the size, the scene's variants, light counts and layout, the
 * scene on the GPU (renderer_base_scene) and the plan entries both renderers share
 * (shadows, gbuffer, compose, fog, sky, resolve, msaa-resolve). False with a message. */
bool deferred_prepare_scene(deferred_renderer *r, const scene *s, char *err, size_t errlen);
/* Sets plan entry p: whether it runs, and why (printf format). */
void deferred_plan(deferred_renderer *r, deferred_pass p, bool run, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* The G-buffer's, light, compose and fog targets and framebuffers (depth.sampled for
 * position from depth, when not tiled). */
bool deferred_make_targets(deferred_renderer *r, char *err, size_t errlen);
/* gbuffer.frag in every map variant present. */
bool deferred_compile_gbuffer(deferred_renderer *r, char *err, size_t errlen);
/* One program; the defines are the layout's (ld, may be NULL) plus extra (NULL-ended). */
bool deferred_build_program(deferred_renderer *r, const char *display, const char *vertex,
                            const char *fragment, const deferred_layout_defs *ld,
                            const char *const *extra, GLuint *program, char *err,
                            size_t errlen);
/* deferred_build_program, and with msaa > 1 two variants over the multisampled G-buffer
 * (GB_MSAA): *pixel reads sample 0 (shaded once per pixel, off the edges) and *sample
 * (when not NULL) reads gl_SampleID (per sample, on the edges). Single-sampled: *pixel
 * alone, with exactly deferred_build_program's defines. */
bool deferred_build_msaa(deferred_renderer *r, const char *display, const char *vertex,
                         const char *fragment, const deferred_layout_defs *ld,
                         const char *const *extra, GLuint *pixel, GLuint *sample, char *err,
                         size_t errlen);
/* The samples' positions in the pixel (GL_SAMPLE_POSITION of the multisampled framebuffer
 * fbo) into program's vec2[8] at location loc: edge_rule.inc, position from depth. */
void deferred_set_sample_positions(deferred_renderer *r, GLuint fbo, GLuint program, GLint loc);
/* The fog pass's program, when it runs. */
bool deferred_compile_fog(deferred_renderer *r, char *err, size_t errlen);
/* aa: edge (edge_aa.h), its normals from this G-buffer. */
bool deferred_prepare_edge_aa(deferred_renderer *r, char *err, size_t errlen);
/* The translucent plan entry; prepared. */
void deferred_prepare_end(deferred_renderer *r);

// >>per frame

void deferred_pass_begin(deferred_renderer *r, frame_stats *out, deferred_pass p);
void deferred_pass_end(deferred_renderer *r, frame_stats *out);
/* The map variant (bit 0 diffuse, 1 gloss, 2 normal, 3 emissive map, 4 alpha test) of a
 * material: the index of gbuffer_program (and deferred-lighting's material programs). */
unsigned deferred_material_variant(const scene_material *m);
/* The G-buffer attachments (and the depth to sample, for position from depth) bound. */
void deferred_bind_gbuffer_textures(deferred_renderer *r);
/* One full-screen draw. */
void deferred_fullscreen(deferred_renderer *r);
/* out's passes and lights reset; when prepared (false otherwise: nothing drawn) the
 * frame begun, the shadows pass and the gbuffer pass. */
bool deferred_frame_begin(deferred_renderer *r, const scene *s, frame_stats *out);
/* After the lighting, whose result is in framebuffer hdr_fbo: fog, sky, translucent,
 * msaa-resolve, edge-aa and resolve. */
void deferred_frame_end(deferred_renderer *r, const scene *s, frame_stats *out, GLuint hdr_fbo);

// >>the entries both renderers use as they are

void deferred_describe(const void *self, pass_plan *out);
bool deferred_read_hdr(void *self, float *rgba, int width, int height);
/* renderer_impl.own_bytes of a G-buffer renderer: the layout's bytes per sample (64 when
 * the layout does not build: the widest preset's bound) and, with separate_specular,
 * the specular target's. */
uint64_t deferred_gbuffer_own_bytes(const renderer_estimate *e);
/* renderer_impl.draws_per_light of the light-volume designs: each light's volume and
 * its stencil mark. */
uint64_t deferred_draws_per_light(const renderer_estimate *e);
/* renderer_impl.traffic: deferred_gbuffer_traffic of the layout prepare built. */
gbuffer_traffic deferred_traffic(const void *self, const frame_stats *fs);

/* For tests: self is what a deferred_core renderer's create returned. The layout
 * renderer_prepare chose (NULL before a successful prepare). */
const deferred_layout *deferred_gbuffer_layout(const void *self);
/* The float target (the run's hdr format) the frame's light is accumulated in (the one
 * resolved), and the G-buffer attachment k (NULL past the layout's attachments). */
const gl_target *deferred_hdr_target(const void *self);
const gl_target *deferred_gbuffer_target(const void *self, int k);
/* The shared depth-stencil target (what the G-buffer pass left in it). */
const gl_target *deferred_depth_target(const void *self);
/* The renderer's state cache (gl/state.h), e.g. to switch on gl_state_set_force. */
struct gl_state *deferred_state_cache(void *self);
/* light_volumes scissor (deferred_lights.c; tests ask it too): the screen rectangle
 * {x, y, width, height} (GL's window coordinates, whole pixels, clipped to the w x h
 * screen) that holds the projection of
 * light `light`'s volume (the box around its mesh in the volume's own frame, a little
 * larger than the mesh); the whole screen when the box reaches the eye's plane. Returns
 * its area in pixels (0: off screen). */
int64_t deferred_scissor_rect(const struct scene *s, uint32_t light, int w, int h, int rect[4]);

