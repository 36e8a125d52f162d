#pragma once
/* Internal to the runner: the parameter table that runner/manifest/params.def defines, and
 * what is computed from it (canonical text, defaults, which renderers read a key,
 * the error reference's parameters, the renderer options, `shadesweep params`).
 * manifest.h is the public side. */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include "renderers/renderer.h"
#include "runner/manifest/manifest.h"

#define MAX_SIDE 32768
#define MAX_LIGHTS 1000000u
#define MAX_EVERY 604800.0
#define MAX_AXIS_VALUES 10000

/* A bounded string builder: appends what fits, always NUL-terminated. */
typedef struct sbuf {
    char *s;
    size_t cap, len;
} sbuf;
void mf_sb_add(sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

typedef enum ptype {
    PT_SCHEMA,       /* the integer 1 */
    PT_NAME,         /* [a-z0-9-]{1,63} -> experiment.name */
    PT_TEXT,         /* any string -> experiment.description */
    PT_SCENE,        /* a catalog name -> char[32] */
    PT_RENDERERS,    /* non-empty sequence of unique renderer names -> experiment.renderers */
    PT_RESOLUTION,   /* "WxH" -> int width, height */
    PT_UINT,         /* integer min..max -> uint32_t */
    PT_NUMBER,       /* finite number in range -> double, or float with PF_FLOAT */
    PT_ENUM,         /* one of values[] -> int (the index) */
    PT_BOOL,         /* true | false -> bool */
    PT_SPAN,         /* {seconds: min..max} | {frames: fmin..fmax} -> span */
    PT_COUNT,        /* integer 0..MAX_LIGHTS | {start, step, every, max} -> light_count */
    PT_TIMES,        /* sequence of numbers >= 0, at most MAX_SCREENSHOTS -> size_t n, double[] */
    PT_RENDERER,     /* one renderer name -> char[32] */
    PT_VEC3,         /* [x, y, z] finite numbers, or `scene` (PF_SCENE_DEFAULT) -> float[3] */
    PT_GROUP,        /* a mapping of the parameters whose path continues this one */
    PT_SWEEP,        /* parameter path -> non-empty sequence of its values */
} ptype;

enum {
    PF_REQUIRED = 1u << 0,
    PF_SWEEP = 1u << 1,        /* may be a key of `sweep` */
    PF_MIN_OPEN = 1u << 2,     /* PT_NUMBER, PT_SPAN seconds: value > min rather than >= */
    PF_FLOAT = 1u << 3,        /* PT_NUMBER stored as float */
    PF_NOT_IN_ID = 1u << 4,    /* recorded, but changes no result: not part of the run id */
    PF_SCENE_DEFAULT = 1u << 5,/* PT_NUMBER (float), PT_VEC3: `scene` (stored as NAN) keeps
                                  the scene's own value */
    PF_AUTO = 1u << 6,         /* PT_UINT: `auto` is a value too, stored as 0 */
};

typedef struct param {
    const char *path;          /* dotted */
    ptype type;
    unsigned flags;
    const char *def;           /* the default as YAML text, validated like any value; NULL: none */
    double min, max;           /* PT_UINT, PT_NUMBER, PT_SPAN seconds, PT_TIMES items */
    double fmin, fmax;         /* PT_SPAN frames */
    const char *const *values; /* PT_ENUM, NULL-terminated; the index is the stored value */
    size_t off, size;          /* where it lives in run_params; size 0: not a run parameter */
    const char *shorthand;     /* PT_GROUP: the member a plain scalar sets (`gbuffer: fat`) */
    const char *readers;       /* renderers that read it, space-separated; "*": every run */
    const char *ref;           /* the error reference: "inherit" (the run's value),
                                  "default", or "sets:PATH" (its value of PATH) */
    const char *description;
} param;

/* Entries of params.def, a compile-time constant (arrays per parameter need no VLA). */
enum {
    PARAMS_N = 0
#define PARAM_META(path, type, flags, decl, shorthand, desc) +1
#define PARAM(path, type, flags, field, decl, def, lim, values, readers, ref, apply, desc) +1
#include "runner/manifest/params.def"
};
#define NPARAMS ((size_t)PARAMS_N)
extern const param params_table[PARAMS_N];

const param *param_find(const char *path);
/* The part of a path before its last dot ("" for a top-level key), and after. */
bool path_parent_is(const char *path, const char *parent);
const char *path_leaf(const char *path);

/* Canonical numbers: the shortest %g text that reads back as the same value. */
void params_fmt_double(double v, char *out, size_t len);
void params_fmt_float(float v, char *out, size_t len);
/* The canonical text of a run parameter (what run ids hash and plan.csv holds). */
void param_format(const param *pd, const run_params *p, char *out, size_t len);
/* The column a parameter has in plan.csv and run_params_kv. */
const char *param_column(const param *pd);

/* params_defaults.c: a key's schema-2 default (NULL where it is schema 1's), and the
 * canonical text of each parameter's default, by table index ("" for those without). */
const char *params_schema2_default(const char *path);
const char (*params_default_texts(void))[160];

/* Every parameter at its default (those without one zeroed): the table's defaults
 * validate at every manifest load, so this cannot fail after one has loaded. */
bool params_defaults(run_params *out);
/* Whether the output of a run with this renderer depends on the parameter. */
bool param_read_by(const param *pd, const char *name);
/* The key is read by every run (params.def readers "*"). */
bool param_every_run_reads(const param *pd);
/* "*", or the renderers that read the key, space-separated in registry order ("": none). */
void param_readers_text(const param *pd, char *out, size_t len);
/* Whether run p reads the parameter: its renderer does, or its error reference
 * does and inherits the run's value. */
bool param_read_by_run(const param *pd, const run_params *p);
/* measure.rasterizer resolved against this process's environment: true when a trial of
 * p runs llvmpipe single-threaded (LP_NUM_THREADS=0, which runner/trial/run.c sets in the
 * trial's process; the environment's own LP_NUM_THREADS is kept unless p says single). */
bool params_rasterizer_single(const run_params *p);
/* The parameters the error reference of run p renders with (renderer included). */
void params_reference(const run_params *p, run_params *ref);
/* The renderer options of params.def's `apply` column (the context's fields are
 * the caller's). */
void params_to_renderer_options(const run_params *p, renderer_options *o);

/* `shadesweep params`: every key, as a table (text), as markdown (docs/manifest.md),
 * as a bash completion script or as JSON (the text's fields, typed). */
typedef enum params_format { PARAMS_TEXT, PARAMS_MARKDOWN, PARAMS_BASH, PARAMS_JSON } params_format;
void params_print(FILE *out, params_format f);
