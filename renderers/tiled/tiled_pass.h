#pragma once
/* The tiled (or clustered) light pass over a G-buffer, which two renderers run:
 * tiled-deferred (tiled_deferred.c, and clustered with clustered.shading: deferred) shades
 * ambient, emissive and the lights into the HDR target; deferred-lighting with
 * deferred_lighting.lights: tiled (deferred_lighting.c) accumulates the lights alone into
 * its light buffer (LIGHT_PREPASS: diffuse and specular light in two images, as
 * deferred_light.frag's LIGHT_PREPASS sums them), which its material pass reads. One
 * compute dispatch (tiled_deferred.comp) over the light grid (grid.h) culls each tile's
 * (or cluster's) lights and shades its pixels; tiled_deferred.c's header has the design,
 * MSAA included (edge pixels found by deferred's rule, per sample there).
 *
 * The renderer's object holds a tiled_pass beside its deferred_renderer; prepare calls
 * tiled_pass_plan (after deferred_prepare_scene), tiled_pass_buffers, then (after the
 * targets) tiled_pass_compile; draw calls tiled_pass_run after the G-buffer pass; collect
 * calls tiled_pass_collect. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/deferred/deferred_core.h"
#include "renderers/tiled/grid.h"

typedef struct tiled_pass {
    light_grid g;                    /* tiles, or clusters (g.slices_y) */
    GLuint program;                  /* tiled_deferred.comp */
    GLuint edges;                    /* msaa > 1: the dispatch's edge-pixel count */
    uint32_t edge_pixels;            /* msaa > 1: the last frame's, after collect */
    char msaa_define[24];
    size_t index;                    /* msaa > 1: 1 + the pass's index this frame; 0: none */
    uint32_t nlights;                /* the scene's lights (tiled_pass_plan) */
} tiled_pass;

/* At prepare, after deferred_prepare_scene: the grid sized for d's scene (culled when it
 * has point or spot lights) and the plan's entries of the pass (tiled, translucent-lists,
 * and why ambient, the light passes and edges do not run). False with a message. */
bool tiled_pass_plan(tiled_pass *t, deferred_renderer *d, const scene *s, char *err,
                     size_t errlen);
/* The grid's buffers for the scene plan saw and, with msaa > 1, the edge counter; false
 * with a message. */
bool tiled_pass_buffers(tiled_pass *t, deferred_renderer *d, char *err, size_t errlen);
/* tiled_deferred.comp with the grid's, the samples', the output images', the shadows' and
 * the layout's defines (after the targets: the sample positions); false with a message. */
bool tiled_pass_compile(tiled_pass *t, deferred_renderer *d, char *err, size_t errlen);
/* What buffers and compile made; a zeroed pass is fine (the options stay). */
void tiled_pass_release(tiled_pass *t);
/* The pass: the frame's visible lights into the grid, then the dispatch into the HDR
 * target (tiled-deferred) or the light buffer (deferred-lighting). */
void tiled_pass_run(tiled_pass *t, deferred_renderer *d, const scene *s, frame_stats *out);
/* After the sync point: the grid's counters (when culled) and the base's; with msaa > 1
 * the pass's samples from the edge count. */
void tiled_pass_collect(tiled_pass *t, deferred_renderer *d, frame_stats *out);
