/* The parameter table (runner/params.def made into data) and what is computed from
 * it alone: canonical text and run_params_kv, which renderers read a key, the error
 * reference's parameters, the renderer options and `shadesweep params`. */
#include "runner/params.h"

#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/renderer.h"
#include "results/jsonout.h"
#include "runner/hash.h"
#include "runner/manifest_internal.h"

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
/* The renderers' enums (renderers/keys.h): each value's text at its enumerator. */
#define KEY_ENUM(type, names, values)                                                         \
    _Static_assert(sizeof(type) == sizeof(int), "enum size");                                 \
    static const char *const names[] = {values NULL};
#define V(text, e) [e] = text,
#define VX(e)
#include "runner/params.def"
#undef V
#undef VX

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
#include "runner/params.def"
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

/* What `shadesweep: 2` changes (issue 36): a file scene shown as a viewer shows it,
 * its lights sized by what they light. Every other default is schema 1's. */
static const struct {
    const char *path, *value;
} params_schema2[] = {
    {"lights.attenuation", "windowed"},
    {"lights.sizing", "range-from-intensity"},
    {"exposure.mode", "auto"},
    {"tonemap", "pbr-neutral"},
    {"environment.light", "scene"},
};

/* A key's schema-2 default, or NULL where it is schema 1's. */
static const char *schema2_default(const char *path)
{
    for (size_t i = 0; i < sizeof params_schema2 / sizeof *params_schema2; i++)
        if (strcmp(params_schema2[i].path, path) == 0)
            return params_schema2[i].value;
    return NULL;
}

/* The canonical text of every parameter's default ("" for those without one). */
static const char (*default_texts(void))[160]
{
    static char text[PARAMS_N][160];
    static bool done;
    if (!done) {
        run_params d;
        params_defaults(&d);
        for (size_t i = 0; i < NPARAMS; i++)
            if (params_table[i].size && params_table[i].def)
                param_format(&params_table[i], &d, text[i], sizeof text[i]);
        done = true;
    }
    return (const char (*)[160])text;
}

size_t run_params_kv(const run_params *p, param_kv *out, size_t max)
{
    const char (*defaults)[160] = default_texts();
    size_t k = 0;
    for (size_t i = 0; i < NPARAMS && k < max; i++) {
        const param *pd = &params_table[i];
        if (pd->size == 0)
            continue;
        out[k].key = param_column(pd);
        out[k].in_id = !(pd->flags & PF_NOT_IN_ID);
        param_format(pd, p, out[k].value, sizeof out[k].value);
        /* without a default (scene, renderer, duration, error.reference.renderer), only
         * the empty text: a reference renderer not named */
        out[k].is_default = pd->def ? strcmp(out[k].value, defaults[i]) == 0 : !out[k].value[0];
        k++;
    }
    return k;
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

void params_reference(const run_params *p, run_params *ref)
{
    run_params d;
    params_defaults(&d);
    *ref = *p;
    for (size_t i = 0; i < NPARAMS; i++) {
        const param *pd = &params_table[i];
        if (pd->size && pd->ref && strcmp(pd->ref, "default") == 0)
            memcpy((char *)ref + pd->off, (const char *)&d + pd->off, pd->size);
    }
    for (size_t i = 0; i < NPARAMS; i++) {
        const param *pd = &params_table[i];
        if (!pd->size || !pd->ref || strncmp(pd->ref, "sets:", 5) != 0)
            continue;
        const param *t = param_find(pd->ref + 5);
        if (t && t->size == pd->size)   /* tests/unit/test_params.c checks every one */
            memcpy((char *)ref + t->off, (const char *)p + pd->off, pd->size);
    }
    ref->error_renderer[0] = '\0';   /* the reference is compared with nothing */
    ref->nerror_at = 0;
}

void params_to_renderer_options(const run_params *p, renderer_options *o)
{
#define PARAM(path, type, flags, field, decl, def, lim, values, readers, ref, apply, desc) apply;
#include "runner/params.def"
}

/* >>print */

static const char *type_name(const param *pd)
{
    switch (pd->type) {
    case PT_SCHEMA: return "schema";
    case PT_NAME: return "name";
    case PT_TEXT: return "text";
    case PT_SCENE: return "scene";
    case PT_RENDERERS: return "renderer list";
    case PT_RESOLUTION: return "resolution";
    case PT_UINT: return "integer";
    case PT_NUMBER: return "number";
    case PT_ENUM: return "enum";
    case PT_BOOL: return "bool";
    case PT_SPAN: return "span";
    case PT_COUNT: return "light count";
    case PT_TIMES: return "times";
    case PT_RENDERER: return "renderer";
    case PT_VEC3: return "vec3";
    case PT_GROUP: return "group";
    case PT_SWEEP: return "sweep";
    }
    return "?";
}

/* Markdown cells: a | in text would end the cell. */
static void md_cell(FILE *out, const char *s)
{
    for (; *s; s++) {
        if (*s == '|')
            fputs("\\|", out);
        else
            fputc(*s, out);
    }
}

static void print_bash(FILE *out)
{
    fputs("# bash completion for shadesweep; generated by `shadesweep params --bash`\n"
          "# from runner/params.def (tests/cli/params.sh fails when it is stale).\n"
          "# Install: source it, or copy it to /usr/share/bash-completion/completions/shadesweep\n"
          "_shadesweep() {\n"
          "  local cur=${COMP_WORDS[COMP_CWORD]} cmd=${COMP_WORDS[1]}\n"
          "  local prev=${COMP_WORDS[COMP_CWORD-1]}\n"
          "  local commands=\"run validate list info merge params columns report compare\"\n"
          "  local keys=\"",
          out);
    for (size_t i = 0; i < NPARAMS; i++)
        if (params_table[i].type != PT_SCHEMA)
            fprintf(out, "%s%s", i ? " " : "", params_table[i].path);
    fputs("\"\n"
          "  local sweepable=\"", out);
    bool first = true;
    for (size_t i = 0; i < NPARAMS; i++)
        if (params_table[i].flags & PF_SWEEP) {
            fprintf(out, "%s%s", first ? "" : " ", params_table[i].path);
            first = false;
        }
    fputs("\"\n"
          "  local renderers=\"", out);
    for (size_t i = 0; i < renderer_kind_count(); i++)
        fprintf(out, "%s%s", i ? " " : "", renderer_kind_at(i)->name);
    fputs("\"\n"
          "  if [ \"$COMP_CWORD\" -eq 1 ]; then\n"
          "    COMPREPLY=($(compgen -W \"$commands --help --version\" -- \"$cur\")); return\n"
          "  fi\n"
          "  case $prev in\n"
          "    -o|--out) COMPREPLY=($(compgen -d -- \"$cur\")); return ;;\n"
          "    --backend) COMPREPLY=($(compgen -W \"egl osmesa\" -- \"$cur\")); return ;;\n"
          "    --set) compopt -o nospace 2>/dev/null\n"
          "      COMPREPLY=($(compgen -S = -W \"$keys $(printf 'sweep.%s ' $sweepable)\" -- \"$cur\")); return ;;\n"
          "    --renderer) COMPREPLY=($(compgen -W \"$renderers\" -- \"$cur\")); return ;;\n"
          "  esac\n"
          "  local opts\n"
          "  case $cmd in\n"
          "    run) opts=\"-o --out --force --resume --retry-failed --backend --device --shard "
          "--debug-gl --scale --smoke --set --renderer --help\" ;;\n"
          "    list) opts=\"--shard --smoke --scale --set --renderer --json --help\" ;;\n"
          "    info) opts=\"--backend --device --help\" ;;\n"
          "    merge) opts=\"-o --out --force --allow-mixed-builds --help\" ;;\n"
          "    validate) opts=\"--set --renderer --gl --no-gl --backend --device --help\" ;;\n"
          "    params) opts=\"--markdown --bash --help\"\n"
          "      COMPREPLY=($(compgen -W \"$opts $keys\" -- \"$cur\")); return ;;\n"
          "    columns) opts=\"--markdown --help\" ;;\n"
          "    compare) opts=\"--threshold --csv --md --help\" ;;\n"
          "    report) opts=\"--help\" ;;\n"
          "  esac\n"
          "  if [[ $cur == -* ]]; then\n"
          "    COMPREPLY=($(compgen -W \"$opts\" -- \"$cur\"))\n"
          "  elif [ \"$cmd\" = run ] || [ \"$cmd\" = validate ] || [ \"$cmd\" = list ]; then\n"
          "    COMPREPLY=($(compgen -f -X '!*.y*ml' -- \"$cur\") $(compgen -d -- \"$cur\"))\n"
          "  else\n"
          "    COMPREPLY=($(compgen -d -- \"$cur\"))\n"
          "  fi\n"
          "}\n"
          "# the sweepable keys, for scripts that build manifests: $sweepable\n"
          "complete -F _shadesweep shadesweep\n",
          out);
}

/* One key of `params --json`: the text's fields; the default typed (null when none),
 * the readers an array (["*"]: every run). */
static void print_json_key(FILE *out, const param *pd, bool first_key, const char *def,
                           const char *accepts, const char *readers, const char *ref)
{
    bool first = true;
    fputs(first_key ? "\n  {" : ",\n  {", out);
    json_member_string(out, &first, "key", pd->path);
    json_member_string(out, &first, "type", type_name(pd));
    json_key(out, &first, "default");
    if (pd->size && pd->def)
        json_typed(out, def);
    else
        fputs("null", out);
    json_key(out, &first, "required");
    fputs(pd->flags & PF_REQUIRED ? "true" : "false", out);
    json_member_string(out, &first, "accepts", accepts);
    json_key(out, &first, "sweep");
    fputs(pd->flags & PF_SWEEP ? "true" : "false", out);
    json_key(out, &first, "read_by");
    json_words(out, readers);
    json_member_string(out, &first, "reference", *ref ? ref : NULL);
    json_member_string(out, &first, "description", pd->description);
    fputs("}", out);
}

void params_print(FILE *out, params_format f)
{
    if (f == PARAMS_BASH) {
        print_bash(out);
        return;
    }
    const char (*defaults)[160] = default_texts();
    if (f == PARAMS_MARKDOWN)
        fputs("# Manifest keys (schemas 1 and 2)\n\n"
              "Generated by `shadesweep params --markdown` from `runner/params.def`; "
              "tests/cli/params.sh fails when this file is stale. A key at its default "
              "is left out of the run id, so a default never changes within a schema "
              "version. *Read by* names the renderers whose output depends on the key "
              "(`*`: every run); a sweep folds runs that differ only in keys their "
              "renderer does not read. *Reference* says what the error reference does "
              "with it: renders with the run's value (inherit), with the default, or "
              "takes this key as its own value of another. `run`, `list` and `validate` "
              "take `--set KEY=VALUE` to set a key as if written in the manifest (VALUE "
              "is YAML; `--set 'sweep.KEY=[A, B]'` sweeps it) and `--renderer R[,R...]` to "
              "keep only those renderers; see `shadesweep run --help`. A manifest of "
              "`shadesweep: 2` has other defaults for a few keys (the *default* column "
              "says `schema 2:`): lights sized by what they light, auto exposure and a "
              "tone mapper; its runs' ids name those keys, since an id leaves out a key "
              "only at its schema-1 default.\n\n"
              "| key | type | default | accepts | sweep | read by | reference | description |\n"
              "|---|---|---|---|---|---|---|---|\n",
              out);
    if (f == PARAMS_JSON)
        fputs("{\"schema\": \"shadesweep-params\", \"version\": 1, \"keys\": [", out);
    for (size_t i = 0; i < NPARAMS; i++) {
        const param *pd = &params_table[i];
        char accepts[1024];
        mf_expect(pd, accepts, sizeof accepts);
        const char *def = pd->size && pd->def ? defaults[i]
                          : (pd->flags & PF_REQUIRED) ? "(required)" : "";
        char readers[256] = "";
        if (pd->size)
            param_readers_text(pd, readers, sizeof readers);
        const char *ref = pd->size && pd->ref ? pd->ref : "";
        bool sweep = pd->flags & PF_SWEEP;
        if (f == PARAMS_JSON) {
            print_json_key(out, pd, i == 0, def, accepts, readers, ref);
        } else if (f == PARAMS_MARKDOWN) {
            fputs("| `", out);
            md_cell(out, pd->path);
            fprintf(out, "` | %s | ", type_name(pd));
            md_cell(out, def);
            if (schema2_default(pd->path)) {
                fputs("; schema 2: ", out);
                md_cell(out, schema2_default(pd->path));
            }
            fputs(" | ", out);
            md_cell(out, accepts);
            fprintf(out, " | %s | ", sweep ? "yes" : "");
            md_cell(out, readers);
            fputs(" | ", out);
            md_cell(out, ref);
            fputs(" | ", out);
            md_cell(out, pd->description);
            fputs(" |\n", out);
        } else {
            fprintf(out, "%s  (%s%s)\n", pd->path, type_name(pd), sweep ? ", sweepable" : "");
            if (*def)
                fprintf(out, "    default:   %s\n", def);
            if (schema2_default(pd->path))
                fprintf(out, "    schema 2:  %s\n", schema2_default(pd->path));
            fprintf(out, "    accepts:   %s\n", accepts);
            if (*readers)
                fprintf(out, "    read by:   %s\n", readers);
            if (*ref)
                fprintf(out, "    reference: %s\n", ref);
            fprintf(out, "    %s\n\n", pd->description);
        }
    }
    if (f == PARAMS_JSON)
        fputs("\n]}\n", out);
}

/* The table's defaults go through the same validation as any value: a default
 * that fails its own parameter is a bug, caught by every load. */
bool params_apply_defaults(vctx *c, run_params *dst)
{
    bool ok = true;
    for (size_t i = 0; i < NPARAMS && ok; i++) {
        const param *pd = &params_table[i];
        if (!pd->def)
            continue;
        diag_list scratch = {0};
        ydoc *doc = NULL;
        vctx dc = {.file = "<default>", .d = &scratch, .e = c->e};
        ok = ydoc_load(dc.file, pd->def, strlen(pd->def), &doc, &scratch) &&
             mf_parse_value(&dc, pd, doc->root, pd->path, dst) && dc.nerr == 0;
        if (!ok)
            diag_add(c->d, c->file, 0, 0, "", "bug: the default of %s (%s) does not validate",
                     pd->path, pd->def);
        ydoc_free(doc);
        diag_free(&scratch);
    }
    return ok;
}

bool params_apply_schema_defaults(vctx *c, unsigned schema, run_params *dst)
{
    bool ok = true;
    for (size_t i = 0; schema == 2 && ok && i < sizeof params_schema2 / sizeof *params_schema2;
         i++) {
        const param *pd = param_find(params_schema2[i].path);
        diag_list scratch = {0};
        ydoc *doc = NULL;
        vctx dc = {.file = "<schema 2>", .d = &scratch, .e = c->e};
        const char *v = params_schema2[i].value;
        ok = pd && ydoc_load(dc.file, v, strlen(v), &doc, &scratch) &&
             mf_parse_value(&dc, pd, doc->root, pd->path, dst) && dc.nerr == 0;
        if (!ok)
            diag_add(c->d, c->file, 0, 0, "", "bug: schema 2's default of %s (%s) does not "
                     "validate", params_schema2[i].path, v);
        ydoc_free(doc);
        diag_free(&scratch);
    }
    return ok;
}

unsigned params_schema_of(const ynode *root)
{
    if (!root || root->kind != YNODE_MAPPING)
        return 1;
    for (size_t i = 0; i < root->n; i++) {
        const ynode *k = root->pairs[i].key, *v = root->pairs[i].value;
        if (k->kind == YNODE_SCALAR && strcmp(k->text, "shadesweep") == 0)
            return v->kind == YNODE_SCALAR && ynode_plain(v) && strcmp(v->text, "2") == 0 ? 2
                                                                                       : 1;
    }
    return 1;
}

bool params_defaults(run_params *out)
{
    static run_params d;
    static int state;   /* 0: not yet, 1: made, -1: a default does not validate (a bug) */
    if (state == 0) {
        diag_list scratch = {0};
        experiment e = {0};
        vctx c = {.file = "<default>", .d = &scratch, .e = &e};
        memset(&d, 0, sizeof d);
        state = params_apply_defaults(&c, &d) ? 1 : -1;
        free(e.renderers);
        free(e.description);
        diag_free(&scratch);
    }
    *out = d;
    return state == 1;
}
