#pragma once
/* Experiment manifests, schema 1 (DESIGN.md), parsed with libyaml.
 *
 * One parameter table (manifest.c) drives validation, sweep expansion, run ids,
 * plan.csv columns and `shadesweep list`: every key is checked for type and range,
 * unknown and duplicate keys are errors, and all errors are reported (diag.h). */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "renderers/renderer.h"
#include "runner/diag.h"
#include "scenes/lights.h"
#include "scenes/scene.h"

typedef enum span_kind { SPAN_SECONDS = 0, SPAN_FRAMES } span_kind;
typedef struct span {          /* {seconds: x} or {frames: n} */
    span_kind kind;
    double seconds;
    uint32_t frames;
} span;

typedef enum run_clock { RUN_CLOCK_WALL = 0, RUN_CLOCK_FIXED } run_clock;
typedef enum run_sync { RUN_SYNC_FINISH = 0, RUN_SYNC_FENCE } run_sync;

#define MAX_SCREENSHOTS 16

/* Everything that defines one run (one point of the sweep grid x renderer). */
typedef struct run_params {
    char scene[32];
    char renderer[32];
    int width, height;
    uint32_t trials;
    span warmup, duration;
    run_clock clock;
    double step;               /* seconds of scene time per frame with clock: fixed */
    run_sync sync;
    double timeout_s;          /* a run still going after this long is stopped; 0: automatic */
    gbuffer_preset gbuffer;    /* deferred */
    gbuffer_position gbuffer_position;
    gbuffer_normal gbuffer_normal;
    light_volume_mode light_volumes;
    bool separate_specular;
    bool illumination_sets;    /* forward-mpml */
    int shadows;               /* 0 auto, 1 off */
    camera_params camera;      /* NAN fields: the scene's own */
    light_params lights;
    bool out_frames, out_seconds;
    size_t nscreenshots;
    double screenshots[MAX_SCREENSHOTS];   /* schedule times, seconds */
    /* image error against a reference configuration (error_renderer "" : none) */
    char error_renderer[32];
    gbuffer_preset error_gbuffer;
    light_volume_mode error_light_volumes;
    size_t nerror_at;
    double error_at[MAX_SCREENSHOTS];      /* schedule times, seconds */
    double error_max_rmse;                 /* 0: no limit */
    bool error_save_images;
    /* >>helper-tiled keys */
    int light_buffer;                      /* forward.light_buffer: 0 uniform, 1 storage */
    int tile_size;                         /* tiles.size: index into 8, 16, 32 */
    uint32_t max_lights_per_tile;          /* tiles.max_lights_per_tile; 0: no budget */
    uint32_t clustered_slices;             /* clustered.slices */
    int clustered_shading;                 /* clustered.shading: 0 forward, 1 deferred */
    /* <<helper-tiled keys */
} run_params;

typedef struct experiment {
    char *path;                /* as given */
    char name[64];             /* [a-z0-9-]+ */
    char *description;         /* "" if absent */
    char hash[17];             /* FNV-1a 64 of the manifest's bytes, hex */
    double scale;              /* run --scale (1 when not given) */
    bool smoke;                /* run --smoke: experiment_make_smoke applied */
    run_params base;           /* the manifest's values with defaults, renderer = "" */
    size_t nrenderers;
    char (*renderers)[32];
    size_t naxes;              /* sweep axes in manifest order */
    struct sweep_axis *axes;   /* opaque: manifest.c */
} experiment;

typedef struct run_spec {
    size_t index;              /* position in the plan, from 0 */
    char id[13];               /* 12 hex digits: stable hash of the resolved parameters */
    unsigned shard;            /* 1..N for the --shard N given to plan_expand (1 without) */
    run_params p;
} run_spec;

typedef struct plan {
    const experiment *exp;
    size_t nruns;
    run_spec *runs;
} plan;

/* Parses and validates; on any error returns false with every problem in diags
 * (and *out = NULL). Nothing is written anywhere. */
bool manifest_load(const char *path, experiment **out, diag_list *diags);
/* The same for a manifest already in memory: data[0..len) are the file's bytes
 * (NULs included; data may be NULL when len is 0) and `name` stands for the path
 * in messages and in experiment.path. manifest_load reads the file and calls it. */
bool manifest_load_mem(const char *name, const char *data, size_t len, experiment **out,
                       diag_list *diags);
void experiment_free(experiment *e);   /* NULL is fine */

/* The smoke variant of a manifest (`run --smoke`), for CI and for a quick look before
 * an overnight sweep: every run at 160x120 (or smaller if the manifest asks for
 * smaller), one trial, no warm-up, at most 2 s (or 120 frames) measured; sweeps of
 * resolution, trials, warm-up and duration collapse to that one value; screenshot
 * and error times past the end move to the middle of the run. The name gets
 * "-smoke" and the manifest hash changes with it, so a smoke folder never merges
 * with a full one. */
void experiment_make_smoke(experiment *e);

/* `run --scale S`: every resolution of the manifest (the base and a resolution sweep's
 * values) multiplied by S, rounded, each side at least 1; a paper's settings at a size
 * a slower machine renders in time. False with a message when S is not in (0, 16] or a
 * scaled side exceeds the largest allowed, or two swept resolutions become one. The
 * run ids follow the scaled resolutions; the output's sweep.yaml records the scale. */
bool experiment_scale_resolution(experiment *e, double scale, char *err, size_t errlen);

/* The cartesian product of the sweep axes (first axis varies slowest) times the
 * renderers (fastest), in that order. nshards >= 1 assigns run k to shard
 * (k mod nshards) + 1. Duplicate points are an error in diags. */
bool plan_expand(const experiment *e, unsigned nshards, plan *out, diag_list *diags);
void plan_free(plan *p);

/* The resolved parameters as (column, canonical text) pairs, in table order; the
 * run id hashes exactly those with in_id. Returns the number of pairs (<= max). */
typedef struct param_kv {
    const char *key;           /* dotted path, static */
    char value[96];
    bool in_id;                /* part of the run id (timeout is not: it changes no result) */
} param_kv;
size_t run_params_kv(const run_params *p, param_kv *out, size_t max);
#define PARAM_KV_MAX 64

/* "--shard I/N" parser: 1 <= I <= N. */
bool parse_shard(const char *s, unsigned *i, unsigned *n, char *err, size_t errlen);

/* `shadesweep list`: one line per run: id, then key=value for the renderer and each
 * swept parameter. Only runs of shard i (0 = all). */
void plan_print(const plan *p, unsigned shard, FILE *out);
