/* The parameter table (runner/manifest/params.def made into data) and what is computed from
 * it alone: canonical text, which renderers read a key, the renderer options. The
 * bottom of the manifest code: it calls none of it (params_defaults.c, which parses
 * the defaults, and params_print.c sit above the parser). */
#include "runner/manifest/params.h"

#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/renderer.h"
#include "runner/manifest/hash.h"

/* A bounded string builder (manifest_parse.h), at the bottom: every layer uses it. */
void mf_sb_add(sbuf *b, const char *fmt, ...)
{
    if (b->len + 1 >= b->cap)
        return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(b->s + b->len, b->cap - b->len, fmt, ap);
    va_end(ap);
    if (n > 0)
        b->len = b->len + (size_t)n < b->cap ? b->len + (size_t)n : b->cap - 1;
}

/* Enumerations are stored through their int representation. */
_Static_assert(sizeof(run_clock) == sizeof(int), "enum size");
_Static_assert(sizeof(run_sync) == sizeof(int), "enum size");
_Static_assert(sizeof(light_placement) == sizeof(int), "enum size");
_Static_assert(sizeof(rng_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(attenuation_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(run_schedule) == sizeof(int), "enum size");
_Static_assert(sizeof(run_metric) == sizeof(int), "enum size");

static const char *const clock_names[] = {"wall", "fixed", NULL};
static const char *const sync_names[] = {"finish", "fence", NULL};
/* light placements: light_placement_names of scenes/lights.h */
static const char *const rng_names[] = {"msvc", "pcg32", "mt19937", NULL};
static const char *const attenuation_names[] = {"inverse-square", "linear-range", "quadratic",
                                                "windowed", NULL};
static const char *const translucency_names[] = {[RUN_TRANSLUCENCY_BLEND] = "blend",
                                                 [RUN_TRANSLUCENCY_OPAQUE] = "opaque", NULL};
static const char *const shading_model_names[] = {[RUN_SHADING_MODEL_SCENE] = "scene",
                                                  [RUN_SHADING_MODEL_PHONG] = "phong",
                                                  [RUN_SHADING_MODEL_PBR] = "pbr", NULL};
/* light_sizing (scenes/lights.h), exposure_mode and tonemap_kind (scenes/scene.h) */
static const char *const light_sizing_names[] = {"radius", "range-from-intensity",
                                                 "intensity-from-range", NULL};
static const char *const exposure_mode_names[] = {"none", "auto", "fixed", NULL};
static const char *const tonemap_names[] = {"none", "pbr-neutral", NULL};
static const char *const environment_names[] = {[RUN_ENVIRONMENT_NONE] = "none",
                                                [RUN_ENVIRONMENT_SKY] = "sky",
                                                [RUN_ENVIRONMENT_SCENE] = "scene", NULL};
static const char *const schedule_names[] = {"interleaved", "sequential", NULL};
static const char *const metric_names[] = {"auto", "wall", "cpu", "gpu", NULL};
static const char *const rasterizer_names[] = {"auto", "threaded", "single", NULL};
/* The renderers' enums' names: renderers/keys.h declares them, renderer.c holds them. */

#define RP(f) .off = offsetof(run_params, f), .size = sizeof(((run_params *)0)->f)
#define RP_SPAN(a, b)                                                                         \
    .off = offsetof(run_params, a),                                                           \
    .size = offsetof(run_params, b) + sizeof(((run_params *)0)->b) - offsetof(run_params, a)
#define LIM(lo, hi) .min = (lo), .max = (hi)
#define LIMF(lo, hi, flo, fhi) .min = (lo), .max = (hi), .fmin = (flo), .fmax = (fhi)

const param params_table[PARAMS_N] = {
#define PARAM_META(path_, type_, flags_, decl, shorthand_, desc)                             \
    {.path = path_, .type = type_, .flags = flags_, .shorthand = shorthand_,                \
     .description = desc},
#define PARAM(path_, type_, flags_, field, decl, def_, lim, values_, readers_, ref_, apply,   \
              desc)                                                                         \
    {.path = path_, .type = type_, .flags = flags_, field, .def = def_, lim,                \
     .values = values_, .readers = readers_, .ref = ref_, .description = desc},
#include "runner/manifest/params.def"
};

const param *param_find(const char *path)
{
    for (size_t i = 0; i < NPARAMS; i++)
        if (strcmp(params_table[i].path, path) == 0)
            return &params_table[i];
    return NULL;
}

bool path_parent_is(const char *path, const char *parent)
{
    const char *dot = strrchr(path, '.');
    size_t plen = dot ? (size_t)(dot - path) : 0;
    return strlen(parent) == plen && strncmp(path, parent, plen) == 0;
}

const char *path_leaf(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot ? dot + 1 : path;
}

const char *param_column(const param *pd)
{
    return pd->type == PT_RENDERERS ? "renderer" : pd->path;
}

/* >>text */

/* fmt_double and fmt_float are pure and called for every number of every run of a
 * plan (ids, sweep points), 17 and 9 snprintf/strtod pairs each: a small cache of
 * recent values, keyed by the value's bits, makes a large plan's repeated values
 * (most of them: the base's) cost a lookup. Per thread, so that no caller shares it. */
typedef struct fmt_memo {
    uint64_t bits;
    bool used, found;
    char text[40];
} fmt_memo;

#define FMT_MEMO_N 512

static fmt_memo *fmt_memo_slot(fmt_memo *memo, uint64_t bits, bool *hit)
{
    uint64_t h = (bits ^ (bits >> 29)) * UINT64_C(0xbf58476d1ce4e5b9);
    fmt_memo *m = &memo[(h >> 40) % FMT_MEMO_N];
    *hit = m->used && m->bits == bits;
    return m;
}

static bool reads_back_double(const char *t, double v)
{
    return strtod(t, NULL) == v;
}

static bool reads_back_float(const char *t, double v)
{
    return strtof(t, NULL) == (float)v;
}

/* The shortest %.*g text, up to max_prec digits, that reads_back as the same
 * value, memoised in memo by the value's bits. A value no text reads back as
 * (NaN) leaves out as it was. */
static void fmt_shortest(fmt_memo *memo, uint64_t bits, double v, int max_prec,
                         bool (*reads_back)(const char *, double), char *out, size_t len)
{
    bool hit;
    fmt_memo *m = fmt_memo_slot(memo, bits, &hit);
    if (!hit) {
        char t[40];
        size_t best = SIZE_MAX;
        *m = (fmt_memo){.bits = bits, .used = true};
        for (int prec = 1; prec <= max_prec; prec++) {
            snprintf(t, sizeof t, "%.*g", prec, v);
            if (reads_back(t, v) && strlen(t) < best) {
                best = strlen(t);
                snprintf(m->text, sizeof m->text, "%s", t);
                m->found = true;
            }
        }
    }
    if (m->found)
        snprintf(out, len, "%s", m->text);
}

/* The shortest %.*g text that reads back as the same value (10 is "10", not
 * "1e+01"; 1e9 is "1e+09"; 0.1 is "0.1"). A value no text reads back as (NaN)
 * leaves out as it was. */
void params_fmt_double(double v, char *out, size_t len)
{
    static _Thread_local fmt_memo memo[FMT_MEMO_N];
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    fmt_shortest(memo, bits, v, 17, reads_back_double, out, len);
}

void params_fmt_float(float v, char *out, size_t len)
{
    static _Thread_local fmt_memo memo[FMT_MEMO_N];
    uint32_t b32;
    memcpy(&b32, &v, sizeof b32);
    fmt_shortest(memo, b32, (double)v, 9, reads_back_float, out, len);
}

/* >>kv */

void param_format(const param *pd, const run_params *p, char *out, size_t len)
{
    const char *at = (const char *)p + pd->off;
    char a[32];
    out[0] = '\0';
    switch (pd->type) {
    case PT_SCENE:
        if (!p->scene_file[0]) {
            snprintf(out, len, "%s", p->scene);
        } else {
            /* a file scene by its content, not its name: a renamed copy is the same run,
             * an edited file a new one */
            char sc[32] = "";
            if (p->scene_scale == 0)
                snprintf(sc, sizeof sc, "fit");
            else if (p->scene_scale != 1)
                params_fmt_float(p->scene_scale, sc, sizeof sc);
            /* what file scenes had before each new default (scale 1, camera orbit, light
             * bounds model) stays out of the text so that their ids hold; the new
             * defaults (fit, auto, around) are written, so a run of them never takes the
             * id of the old one's results */
            bool cam = strcmp(p->scene_camera, "orbit") != 0;
            snprintf(out, len, "file:%s%s%s%s%s%s%s", p->scene_hash, sc[0] ? ",scale:" : "", sc,
                     p->scene_up == SCENE_UP_Z ? ",up:z" : "", cam ? ",camera:" : "",
                     cam ? p->scene_camera : "", p->scene_around ? ",light_bounds:around" : "");
        }
        break;
    case PT_RENDERERS:
        snprintf(out, len, "%s", p->renderer);
        break;
    case PT_RENDERER:
        snprintf(out, len, "%.31s", at);
        break;
    case PT_RESOLUTION:
        snprintf(out, len, "%dx%d", p->width, p->height);
        break;
    case PT_UINT: {
        uint32_t u;
        memcpy(&u, at, sizeof u);
        if (u == 0 && (pd->flags & PF_AUTO))
            snprintf(out, len, "auto");
        else
            snprintf(out, len, "%" PRIu32, u);
        break;
    }
    case PT_NUMBER:
        if (pd->flags & PF_FLOAT) {
            float f;
            memcpy(&f, at, sizeof f);
            if (isnan(f))
                snprintf(out, len, "scene");   /* PF_SCENE_DEFAULT */
            else
                params_fmt_float(f, out, len);
        } else {
            double v;
            memcpy(&v, at, sizeof v);
            params_fmt_double(v, out, len);
        }
        break;
    case PT_VEC3: {
        float v[3];
        char y[32], z[32];
        memcpy(v, at, sizeof v);
        if (isnan(v[0])) {
            snprintf(out, len, "scene");
        } else {
            params_fmt_float(v[0], a, sizeof a);
            params_fmt_float(v[1], y, sizeof y);
            params_fmt_float(v[2], z, sizeof z);
            snprintf(out, len, "%s,%s,%s", a, y, z);
        }
        break;
    }
    case PT_ENUM: {
        int i;
        memcpy(&i, at, sizeof i);
        int n = 0;
        while (pd->values[n])
            n++;
        snprintf(out, len, "%s", i >= 0 && i < n ? pd->values[i] : "?");
        break;
    }
    case PT_BOOL: {
        bool b;
        memcpy(&b, at, sizeof b);
        snprintf(out, len, "%s", b ? "true" : "false");
        break;
    }
    case PT_SPAN: {
        span s;
        memcpy(&s, at, sizeof s);
        if (s.kind == SPAN_FRAMES) {
            snprintf(out, len, "frames:%" PRIu32, s.frames);
        } else {
            params_fmt_double(s.seconds, a, sizeof a);
            snprintf(out, len, "seconds:%s", a);
        }
        break;
    }
    case PT_COUNT: {
        light_count lc;
        memcpy(&lc, at, sizeof lc);
        if (!lc.growth && lc.start == LIGHT_COUNT_ALL) {
            snprintf(out, len, "all");
        } else if (lc.growth) {
            params_fmt_double(lc.every, a, sizeof a);
            snprintf(out, len, "start:%" PRIu32 ",step:%" PRIu32 ",every:%s,max:%" PRIu32,
                     lc.start, lc.step, a, lc.max);
        } else {
            snprintf(out, len, "%" PRIu32, lc.start);
        }
        break;
    }
    case PT_TIMES: {
        /* Comma-separated; a list too long for the column is named by its count and
         * hash instead, so that two different lists never share a text. */
        char all[MAX_SCREENSHOTS * 32 + 1];
        sbuf b = {all, sizeof all, 0};
        all[0] = '\0';
        size_t count;
        memcpy(&count, at, sizeof count);
        const double *times = (const double *)(at + sizeof(size_t));
        size_t n = count < MAX_SCREENSHOTS ? count : MAX_SCREENSHOTS;
        for (size_t i = 0; i < n; i++) {
            params_fmt_double(times[i], a, sizeof a);
            mf_sb_add(&b, "%s%s", i ? "," : "", a);
        }
        if (b.len < len) {
            snprintf(out, len, "%s", all);
        } else {
            char h[17];
            hash_hex(fnv1a64(all, b.len), 16, h);
            snprintf(out, len, "times:%zu,fnv:%s", n, h);
        }
        break;
    }
    case PT_SCHEMA:
    case PT_NAME:
    case PT_TEXT:
    case PT_GROUP:
    case PT_SWEEP:
        break;
    }
}

/* >>readers */

bool param_every_run_reads(const param *pd)
{
    return pd->readers && strcmp(pd->readers, "*") == 0;
}

bool param_read_by(const param *pd, const char *name)
{
    if (param_every_run_reads(pd))
        return true;
    const renderer_impl *r = renderer_kind_find(name);
    return r && renderer_reads(r->reads, pd->path);
}

void param_readers_text(const param *pd, char *out, size_t len)
{
    size_t n = 0;
    out[0] = '\0';
    if (param_every_run_reads(pd)) {
        snprintf(out, len, "*");
        return;
    }
    for (size_t i = 0; i < renderer_kind_count() && n < len; i++) {
        const renderer_impl *r = renderer_kind_at(i);
        if (renderer_reads(r->reads, pd->path))
            n += (size_t)snprintf(out + n, len - n, "%s%s", n ? " " : "", r->name);
    }
}

bool param_read_by_run(const param *pd, const run_params *p)
{
    if (param_read_by(pd, p->renderer))
        return true;
    return p->error_renderer[0] && pd->ref && strcmp(pd->ref, "inherit") == 0 &&
           param_read_by(pd, p->error_renderer);
}

void params_to_renderer_options(const run_params *p, renderer_options *o)
{
#define PARAM(path, type, flags, field, decl, def, lim, values, readers, ref, apply, desc) apply;
#include "runner/manifest/params.def"
}

bool params_rasterizer_single(const run_params *p)
{
    const char *env = getenv("LP_NUM_THREADS");   /* the trial's once run.c has set it */
    if (p->rasterizer == RUN_RASTERIZER_SINGLE)
        return true;
    if (env)
        return strtol(env, NULL, 10) == 0;
    return p->rasterizer == RUN_RASTERIZER_AUTO &&
           (p->metric == RUN_METRIC_AUTO || p->metric == RUN_METRIC_CPU);
}
