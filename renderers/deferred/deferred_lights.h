#pragma once
/* What the two renderers over deferred's light passes share beyond deferred_core
 * (renderers/deferred/deferred_lights.c): deferred (deferred.c) and deferred-lighting
 * (deferred_lighting.c). Their object, the light passes of every light_volumes mode (the
 * MODES table), the lighting programs, and with msaa > 1 the edge pass and the two draw
 * classes (per sample on edge pixels, per pixel elsewhere). Not for other renderers. */
#include "renderers/deferred/deferred_core.h"
#include "renderers/gl/state.h"

struct scene;

typedef struct deferred {
    deferred_renderer d;             /* first: deferred_describe and the accessors read it */
    GLuint ambient_program, compose_program, mark_program;
    GLuint light_program[DEFERRED_LIGHT_TYPES];
    /* msaa > 1: the per-sample variants (edge pixels) and the edge-mark program */
    GLuint ambient_sample_program, compose_sample_program, edge_program;
    GLuint light_sample_program[DEFERRED_LIGHT_TYPES];
    /* deferred-lighting: the material pass's programs, per map variant */
    GLuint material_program[DEFERRED_VARIANTS];
    bool lbuf_cleared;               /* deferred-lighting: the light buffer cleared this frame */

    /* >>the last frame, for tests */
    uint64_t mark_draws[DEFERRED_LIGHT_TYPES], shade_draws[DEFERRED_LIGHT_TYPES];
    int64_t scissor_area;            /* light_volumes scissor: this pass's rectangles */
    size_t edges_pass;               /* msaa > 1: 1 + the edge pass's index; 0: none */
} deferred;

/* ONE + ONE: the light passes add up. */
extern const gls_blend DEFERRED_BLEND_ADD;

/* The lighting programs: ambient (not deferred-lighting's), edges (msaa), one per light
 * type that runs (its vertex shader by the mode; deferred-lighting's LIGHT_PREPASS
 * variant), the stencil modes' mark program, compose. */
bool deferred_compile_lighting(deferred *r, char *err, size_t errlen);
/* prepare's first steps: what the last prepare made released, then the scene's needs and
 * the common plan (deferred_prepare_scene); false, released, on failure. */
bool deferred_lights_prepare_begin(deferred *r, const struct scene *s, char *err,
                                   size_t errlen);
/* prepare's last steps, once the renderer has planned its passes: the targets, the
 * G-buffer and lighting programs, the renderer's own (`programs`, or NULL), fog,
 * translucent (its programs by `translucent`, translucent_compile over the renderer's
 * lists; NULL: without lists), edge-aa; false, released, on failure. */
bool deferred_lights_prepare_end(deferred *r, const struct scene *s,
                                 bool (*programs)(deferred *r, char *err, size_t errlen),
                                 bool (*translucent)(deferred *r, char *err, size_t errlen),
                                 char *err, size_t errlen);
/* The plan's light passes: a pass per light type the scene has. */
void deferred_plan_lights(deferred *r);
/* The programs prepare made, forgotten (the cache that owns them is remade). */
void deferred_forget_programs(deferred *r);
/* msaa > 1: the edge bit on every sample of the pixels whose samples differ. */
void deferred_edges_pass(deferred *r, frame_stats *out);
/* One full-screen draw per class with the pixel and sample programs (ambient, compose). */
void deferred_fullscreen_classes(deferred *r, GLuint pixel, GLuint sample);
/* deferred-lighting: the bound light buffer cleared to zero, once a frame. */
void deferred_clear_light_buffer(deferred *r);
/* draw's first steps: the last frame's counters for tests reset, deferred_frame_begin
 * (shadows, gbuffer), and with msaa > 1 the edge pass; false when the frame ends there. */
bool deferred_lights_frame_begin(deferred *r, const struct scene *s, frame_stats *out);
/* The passes of the lights the plan runs, directional, point, spot: directional full
 * screen, point and spot by the mode; into the light target, or deferred-lighting's light
 * buffer. */
void deferred_light_passes(deferred *r, const struct scene *s, frame_stats *out);
/* renderer_impl.collect of both: the base's counters and the msaa edge fraction. */
void deferred_collect(void *self, frame_stats *out);
