#pragma once
/* What a frame and a renderer's plan report: the statistics of each pass of a frame
 * (frame_stats, pass_stats) and the passes, programs and targets prepare decided
 * (pass_plan). Below renderer.h, which includes it, so that gl/ (state.h, query.h,
 * target.h, program.h) fills them without the renderer interface. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define RENDERER_MAX_PASSES 32

/* Work and time of one pass in one frame. NAN where a measurement is unavailable. */
typedef struct pass_stats {
    const char *name;          /* static string */
    double gpu_us;             /* GL_TIME_ELAPSED */
    double cpu_us;             /* CPU time spent submitting the pass */
    uint64_t draw_calls;
    uint64_t dispatches;       /* compute dispatches (not in draw_calls) */
    uint64_t state_changes;
    double fragments;          /* GL_FRAGMENT_SHADER_INVOCATIONS */
    double samples;            /* GL_SAMPLES_PASSED of the pass's shading draws (not the
                                  stencil marks, shadow maps or depth pre-pass) */
    double per_sample_samples; /* msaa: of samples, those of draws shaded per sample (deferred's
                                  edge pixels); 0 elsewhere */
    double samples_shaded;     /* fragment shader runs in samples: samples at msaa 1 and in a
                                  single_sampled pass; with msaa N, (samples -
                                  per_sample_samples) / N + per_sample_samples (a pixel
                                  shaded once covers N samples) */
    bool shaded_counted;       /* samples_shaded is the renderer's own count (a compute
                                  pass that counts its shadings: visibility's shade) */
    bool single_sampled;       /* the pass draws into single-sampled targets whatever the
                                  run's msaa (the display resolve, edge AA): its samples are
                                  pixels */
    double primitives;         /* GL_PRIMITIVES_SUBMITTED */
    double scissor_pixels;     /* light_volumes scissor: the pass's scissor rectangles'
                                  area, summed over its lights; NAN elsewhere */
} pass_stats;

typedef struct frame_stats {
    size_t npasses;
    pass_stats pass[RENDERER_MAX_PASSES];
    pass_stats total;          /* sums over passes (NAN if any pass's value is NAN) */
    uint32_t lights_drawn;
    /* deferred with msaa > 1 (NAN elsewhere): the fraction of the output's pixels whose
     * samples differ (the edge-mark pass's samples / N / pixels), after collect */
    double edge_fraction;
    int msaa;                  /* samples per pixel of the frame's targets (0: 1) */
    /* Tiled and clustered renderers, filled by collect (NAN and 0 for the others):
     * over the frame's tiles (or clusters), the mean and largest light-list length,
     * and the light evaluations per shaded pixel (list length summed over the pixels
     * of the output / pixels: what the shading loop iterates). */
    uint32_t grid_cells;       /* tiles, or clusters */
    size_t grid_pass;          /* 1 + the index of the pass that built the grid; 0: none */
    double grid_lights_mean, grid_lights_max;
    double light_evals_per_pixel;
    uint64_t grid_covered;     /* pixels with geometry over the cells (each pixel's in one) */
    double light_struct_bytes; /* the light structures' bytes (light_grid_struct_bytes) */
    /* The tiles' translucent lists (tiled and clustered renderers whose cull builds them
     * because the scene has translucent objects; 0 and NAN otherwise): how many, and
     * their mean and largest length. The grid_* counters above stay the opaque lists'. */
    uint32_t translucent_lists;
    double translucent_lights_mean, translucent_lights_max;
    /* Non-empty when the frame could not be drawn as asked (a light list that would
     * not fit, tiled renderers): the run fails as failed:overflow with this message. */
    char overflow[160];
} frame_stats;

/* What renderer_prepare() decided: passes run and skipped (with why), programs
 * compiled, targets allocated. Recorded in meta.yaml. */
typedef struct pass_plan_entry {
    char name[32];
    bool run;
    char reason[96];           /* why it runs or why it was skipped */
} pass_plan_entry;

typedef struct target_plan_entry {
    char name[32];
    char format[24];
    int width, height;
    uint64_t bytes;
} target_plan_entry;

typedef struct pass_plan {
    size_t npasses;
    pass_plan_entry pass[RENDERER_MAX_PASSES];
    size_t nprograms;
    char program[RENDERER_MAX_PASSES][64];
    size_t ntargets;
    target_plan_entry target[16];
    char lighting[192];        /* the light features every program is compiled for, and
                                  those left out (renderer_base_describe; "" for null) */
    uint64_t gbuffer_bytes;    /* bytes of G-buffer targets (0 for forward / null) */
    uint64_t target_bytes;     /* all targets the renderer allocated */
} pass_plan;
