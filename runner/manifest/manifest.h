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
#include "runner/manifest/diag.h"
#include "scenes/lights.h"
#include "scenes/scene.h"

/* The manifest changed from the command line (run, list, validate):
 *
 *   --set KEY=VALUE     KEY: VALUE as if written in the manifest (repeatable, applied
 *                       in order). VALUE is YAML (`--set 'lights.count={start: 0,
 *                       step: 8, every: 1, max: 64}'`); KEY is a dotted key of
 *                       docs/manifest.md, `sweep.KEY` (an axis) or `sweep`. The key is
 *                       replaced wherever the manifest has it: `--set lights.count=64`
 *                       on a manifest that sweeps lights.count makes it fixed (the axis
 *                       is gone), `--set 'sweep.lights.count=[16, 64]'` sweeps a key the
 *                       manifest sets in place, `--set 'sweep={...}'` replaces the
 *                       whole sweep (its keys removed in place). On a sweep of
 *                       blocks `sweep.KEY` is refused (`--set 'sweep=[{...}, ...]'`
 *                       replaces the list, the keys in place kept as the base) and
 *                       `--set KEY=V` removes KEY from every block (a block left
 *                       empty is the base point once). A value replaces
 *                       the whole key: `--set gbuffer=fat` drops the manifest's
 *                       gbuffer.normal, `--set gbuffer.preset=fat` keeps it.
 *   --renderer LIST     only the runs of these renderers (comma-separated), as if the
 *                       manifest's `renderers` listed only those of its own that LIST
 *                       names, in its order.
 *
 * Both go through the manifest's own validation (overrides.c grafts each
 * --set's YAML onto the manifest's tree before it is read), so a bad value gets the
 * manifest's message, located at "MANIFEST: --set KEY=VALUE" instead of a line; the
 * run ids are those of the same manifest written out. Both are part of the manifest
 * hash (a folder resumes and merges only with the same ones) and meta.yaml records
 * them verbatim. */
typedef struct manifest_overrides {
    size_t nsets;
    const char *const *sets;   /* "KEY=VALUE", verbatim, in command-line order */
    const char *renderers;     /* --renderer's list, verbatim; NULL: every renderer */
} manifest_overrides;

/* The command line's checks of one argument, before any manifest is read: a --set
 * without '=' or with an empty or malformed KEY; a --renderer list with a name that is
 * not a renderer or an empty name. False with a one-line message in err. */
bool override_check_set(const char *arg, char *err, size_t errlen);
bool override_check_renderers(const char *list, char *err, size_t errlen);

typedef enum span_kind { SPAN_SECONDS = 0, SPAN_FRAMES } span_kind;
typedef struct span {          /* {seconds: x} or {frames: n} */
    span_kind kind;
    double seconds;
    uint32_t frames;
} span;

typedef enum run_clock { RUN_CLOCK_WALL = 0, RUN_CLOCK_FIXED } run_clock;
typedef enum run_sync { RUN_SYNC_FINISH = 0, RUN_SYNC_FENCE } run_sync;
/* `schedule`: the trials of a sweep point's runs in rounds, or each run's back to back */
typedef enum run_schedule { RUN_SCHEDULE_INTERLEAVED = 0, RUN_SCHEDULE_SEQUENTIAL } run_schedule;
/* `measure.metric`: what ranks, compares and decides (runner/cli/schedule.c resolves auto) */
typedef enum run_metric {
    RUN_METRIC_AUTO = 0, RUN_METRIC_WALL, RUN_METRIC_CPU, RUN_METRIC_GPU
} run_metric;
/* `measure.rasterizer`: llvmpipe's threads in a trial's process (runner/trial/run.c) */
typedef enum run_rasterizer {
    RUN_RASTERIZER_AUTO = 0, RUN_RASTERIZER_THREADED, RUN_RASTERIZER_SINGLE
} run_rasterizer;
/* `translucency`, `shading.model` and `environment.light` (the names: runner/manifest/params.c) */
typedef enum run_translucency {
    RUN_TRANSLUCENCY_BLEND = 0, RUN_TRANSLUCENCY_OPAQUE
} run_translucency;
typedef enum run_shading_model {
    RUN_SHADING_MODEL_SCENE = 0, RUN_SHADING_MODEL_PHONG, RUN_SHADING_MODEL_PBR
} run_shading_model;
typedef enum run_environment {
    RUN_ENVIRONMENT_NONE = 0, RUN_ENVIRONMENT_SKY, RUN_ENVIRONMENT_SCENE
} run_environment;
/* trials: auto: rounds until measure.precision or measure.budget, within these */
#define TRIALS_AUTO_MIN 3
#define TRIALS_AUTO_MAX 30

#define MAX_SCREENSHOTS 16

/* Everything that defines one run (one point of the sweep grid x renderer): the
 * fields are declared by runner/manifest/params.def, one entry per manifest key. */
#define SHADESWEEP_STRIP_PARENS(...) __VA_ARGS__
#define PARAM_META(path, type, flags, decl, shorthand, desc) SHADESWEEP_STRIP_PARENS decl
#define PARAM(path, type, flags, field, decl, def, lim, values, readers, ref, apply, desc) \
    SHADESWEEP_STRIP_PARENS decl
typedef struct run_params {
#include "runner/manifest/params.def"
} run_params;

typedef struct experiment {
    char *path;                /* as given */
    unsigned schema;           /* `shadesweep:` 1 or 2 (params_schema_defaults) */
    char name[64];             /* [a-z0-9-]+ */
    char *description;         /* "" if absent */
    char hash[17];             /* FNV-1a 64 of the manifest's bytes, hex (and of --set,
                                * --renderer, --smoke and --scale where given) */
    char *text;                /* the manifest's bytes, NUL-terminated (meta.yaml keeps them) */
    size_t nsets;
    char **sets;               /* --set KEY=VALUE, verbatim, in order (manifest_overrides, above) */
    char *renderer_filter;     /* --renderer's list, verbatim; NULL: none */
    double scale;              /* run --scale (1 when not given) */
    bool smoke;                /* run --smoke: experiment_make_smoke applied */
    run_params base;           /* the manifest's values with defaults, renderer = "" */
    size_t nrenderers;
    char (*renderers)[32];
    size_t naxes;              /* sweep axes in manifest order (every block's) */
    struct sweep_axis *axes;   /* opaque: manifest.c */
    size_t nblocks;            /* `sweep:` a list of blocks: their number (0: a mapping, */
    size_t *block_first;       /* one product); block b is axes [first[b], first[b+1]) */
} experiment;

typedef struct run_spec {
    size_t index;              /* position in the plan, from 0 */
    size_t point;              /* its point of the sweep grid x renderers, from 0 */
    size_t folded;             /* other grid points that are this same run (see plan_expand) */
    char id[13];               /* 12 hex digits: stable hash of the resolved parameters */
    size_t group;              /* its sweep point (plan.ngroups), from 0: the runs ranked
                                * together and scheduled in rounds together */
    unsigned shard;            /* 1..N for the --shard N given to plan_expand (1 without):
                                * whole sweep points go to one shard */
    run_params p;
} run_spec;

/* A grid point folded into an earlier run: it differs from it only in parameters
 * its renderer does not read (params.def's readers), so it would measure the same. */
typedef struct plan_fold {
    size_t point;              /* its grid point */
    size_t into;               /* the index of the run it is */
    run_params p;              /* its parameters as the sweep made them */
} plan_fold;

typedef struct plan {
    const experiment *exp;
    size_t npoints;            /* grid points x renderers */
    size_t nruns;              /* distinct runs: npoints - nfolded */
    run_spec *runs;
    size_t nfolded;
    plan_fold *folds;
    size_t ngroups;            /* sweep points (run_spec.group) */
} plan;

/* Parses and validates; on any error returns false with every problem in diags
 * (and *out = NULL). Nothing is written anywhere. */
bool manifest_load(const char *path, experiment **out, diag_list *diags);
/* The same for a manifest already in memory: data[0..len) are the file's bytes
 * (NULs included; data may be NULL when len is 0) and `name` stands for the path
 * in messages and in experiment.path. manifest_load reads the file and calls it. */
bool manifest_load_mem(const char *name, const char *data, size_t len, experiment **out,
                       diag_list *diags);
/* manifest_load with the command line's --set and --renderer (manifest_overrides, above);
 * ov NULL: none. */
bool manifest_load_with(const char *path, const manifest_overrides *ov, experiment **out,
                        diag_list *diags);
void experiment_free(experiment *e);   /* NULL is fine */

/* The smoke variant of a manifest (`run --smoke`), for CI and for a quick look before
 * an overnight sweep: every run at 160x120 (or smaller if the manifest asks for
 * smaller), one trial, no warm-up, at most 2 s (or 120 frames) measured, and a
 * draw_limit of 2 s over its priming and measured frames together (a frame that is
 * slow stops the run early; a draw_limit the manifest sets is kept); sweeps of
 * resolution, trials, warm-up, duration and
 * draw_limit collapse to that one value; screenshot
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
 * renderers (fastest), in that order, each distinct configuration once (a sweep of
 * blocks: each block's product in turn, a run an earlier block made folded into it): a
 * parameter the run's renderer does not read (and its error reference does not
 * inherit) is reset to its default, and a point that is then an earlier run is
 * folded into it (plan.folds). nshards >= 1 assigns run k to shard
 * (k mod nshards) + 1. Duplicate points (a value repeated in an axis) and a swept
 * key that none of the renderers reads are errors in diags. */
bool plan_expand(const experiment *e, unsigned nshards, plan *out, diag_list *diags);
void plan_free(plan *p);

/* The resolved parameters as (column, canonical text) pairs, in table order; the
 * run id hashes exactly those with in_id. Returns the number of pairs (<= max). */
typedef struct param_kv {
    const char *key;           /* dotted path, static */
    char value[160];
    bool in_id;                /* can be part of the run id (timeout is not: it changes no result) */
    bool is_default;           /* at its default: left out of the run id (params.def) */
} param_kv;
size_t run_params_kv(const run_params *p, param_kv *out, size_t max);
/* The number of run parameters in params.def: an array of PARAM_KV_MAX pairs always
 * holds every one (a compile-time constant, so no run can have more). */
enum {
    PARAM_KV_MAX = 0
#define PARAM(path, type, flags, field, decl, def, lim, values, readers, ref, apply, desc) +1
#include "runner/manifest/params.def"
};

/* "--shard I/N" parser: 1 <= I <= N. */
bool parse_shard(const char *s, unsigned *i, unsigned *n, char *err, size_t errlen);

/* `shadesweep list`: one line per run: id, then key=value for the renderer and each
 * swept parameter. Only runs of shard i (0 = all). */
void plan_print(const plan *p, unsigned shard, FILE *out);
/* `shadesweep list --json`: {"experiment", "runs": [{"run_id", "index", "shard", "point",
 * "parameters": {every key: its value, typed}}], "folded": [{"into", "parameters"}]}. */
void plan_print_json(const plan *p, unsigned shard, FILE *out);
