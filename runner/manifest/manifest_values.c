/* Manifest values: integers, numbers, booleans and strings out of YAML scalars, and
 * one parser per parameter type (the one path for keys in place, sweep values and
 * defaults). */
#include "runner/manifest/manifest_parse.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/renderer.h"
#include "runner/manifest/hash.h"
#include "runner/manifest/sweep_axis.h"
#include "scenes/scene.h"

/* >>scalars */

/* Text a string parameter can take: any non-empty scalar without a non-string
 * tag and without NUL bytes. */
bool mf_stringish(const ynode *n)
{
    return n && n->kind == YNODE_SCALAR && mf_tag_ok(n) && !ynode_empty(n) &&
           strlen(n->text) == n->len;
}

/* A plain scalar that is a decimal integer: [-+]?[0-9]+. Negative or too large
 * for 64 bits is out of every range here, so those read as "not an integer". */
bool mf_get_uint(const ynode *n, uint64_t *out)
{
    if (!ynode_plain(n))
        return false;
    const char *s = n->text;
    bool neg = *s == '-';
    if (*s == '-' || *s == '+')
        s++;
    if (!*s)
        return false;
    uint64_t v = 0;
    for (; *s; s++) {
        if (*s < '0' || *s > '9')
            return false;
        unsigned dgt = (unsigned)(*s - '0');
        if (v > (UINT64_MAX - dgt) / 10)
            return false;
        v = v * 10 + dgt;
    }
    if (neg && v != 0)
        return false;
    *out = v;
    return true;
}

static bool all_digits(const char *s, const char *end)
{
    if (s == end)
        return false;
    for (; s < end; s++)
        if (*s < '0' || *s > '9')
            return false;
    return true;
}

/* A plain scalar that is a YAML 1.2 core-schema number:
 * [-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?, or [-+]?.inf or .nan in
 * their three spellings. *finite is false for those and for overflow (1e999). */
bool mf_get_number(const ynode *n, double *out, bool *finite)
{
    if (!ynode_plain(n))
        return false;
    const char *s = n->text, *p = s;
    if (*p == '-' || *p == '+')
        p++;
    static const char *const specials[] = {".inf", ".Inf", ".INF", ".nan", ".NaN", ".NAN", NULL};
    for (size_t i = 0; specials[i]; i++)
        if (strcmp(p, specials[i]) == 0 && (i < 3 || p == s)) {
            *finite = false;
            *out = i < 3 ? (s[0] == '-' ? -INFINITY : INFINITY) : NAN;
            return true;
        }
    const char *q = p;
    while (*q >= '0' && *q <= '9')
        q++;
    bool int_part = q > p;
    if (*q == '.') {
        const char *frac = ++q;
        while (*q >= '0' && *q <= '9')
            q++;
        if (!int_part && q == frac)
            return false;
    } else if (!int_part) {
        return false;
    }
    if (*q == 'e' || *q == 'E') {
        q++;
        if (*q == '-' || *q == '+')
            q++;
        if (!all_digits(q, q + strlen(q)))
            return false;
        q += strlen(q);
    }
    if (*q)
        return false;
    errno = 0;
    double v = strtod(s, NULL);
    *finite = isfinite(v);
    *out = v == 0 ? 0.0 : v;   /* -0 reads as 0: one canonical text */
    return true;
}

/* >>values */


void mf_err(vctx *c, const ynode *at, const char *key, const char *fmt, ...)
{
    char msg[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    overrides_diag(c->d, c->e, c->file, at->line, at->col, key, "%s", msg);
    c->nerr++;
}

/* The usual message: "expected <what the parameter takes>, found <the node>". */
bool mf_bad(vctx *c, const param *pd, const ynode *n, const char *key)
{
    char e[512], f[128];
    mf_err(c, n, key, "expected %s, found %s", mf_expect(pd, e, sizeof e),
        mf_found(n, mf_wants_string(pd), f, sizeof f));
    return false;
}

bool mf_parse_uint_in(vctx *c, const ynode *n, const char *key, uint64_t min, uint64_t max,
                          const char *note, uint64_t *out)
{
    uint64_t v;
    if (!mf_get_uint(n, &v) || v < min || v > max) {
        char f[128];
        mf_err(c, n, key, "expected an integer %" PRIu64 "..%" PRIu64 "%s, found %s", min, max, note,
            mf_found(n, false, f, sizeof f));
        return false;
    }
    *out = v;
    return true;
}

bool mf_parse_number_in(vctx *c, const ynode *n, const char *key, double min, double max,
                            unsigned flags, double *out)
{
    double v;
    bool finite;
    char e[128], f[128];
    sbuf b = {e, sizeof e, 0};
    mf_range_number(&b, min, max, flags & PF_MIN_OPEN);
    if (flags & PF_SCENE_DEFAULT)
        mf_sb_add(&b, ", or scene");
    if (!mf_get_number(n, &v, &finite)) {
        mf_err(c, n, key, "expected %s, found %s", e, mf_found(n, false, f, sizeof f));
        return false;
    }
    if (!finite) {
        mf_err(c, n, key, "expected a finite number, found %s", mf_found(n, false, f, sizeof f));
        return false;
    }
    if (flags & PF_FLOAT)
        v = (double)(float)v;  /* what will be stored is what is checked */
    if (((flags & PF_MIN_OPEN) ? v <= min : v < min) || v > max) {
        mf_err(c, n, key, "expected %s, found %s", e, mf_found(n, false, f, sizeof f));
        return false;
    }
    *out = v;
    return true;
}

/* Checks the keys of a mapping against names[0..nnames): an unknown key, a key
 * that is not a scalar and a second occurrence are errors. vals[i] (and keys[i])
 * get the first occurrence of names[i], NULL if absent. Returns false if any key
 * was wrong. */
bool mf_map_keys(vctx *c, const ynode *map, const char *prefix, const char *const *names,
                     size_t nnames, const ynode **keys, const ynode **vals)
{
    bool ok = true;
    for (size_t i = 0; i < nnames; i++)
        keys[i] = vals[i] = NULL;
    for (size_t p = 0; p < map->n; p++) {
        const ynode *k = map->pairs[p].key;
        char f[128];
        if (k->kind != YNODE_SCALAR) {
            mf_err(c, k, prefix, "expected a key, found %s", mf_found(k, true, f, sizeof f));
            ok = false;
            continue;
        }
        size_t i = 0;
        while (i < nnames && strcmp(names[i], k->text) != 0)
            i++;
        char path[256];
        sbuf pb = {path, sizeof path, 0};
        mf_sb_add(&pb, "%s%s", prefix, prefix[0] ? "." : "");
        mf_escape_text(&pb, k->text, k->len);
        if (i == nnames) {
            char list[1024];
            sbuf lb = {list, sizeof list, 0};
            list[0] = '\0';
            for (size_t j = 0; j < nnames; j++)
                mf_sb_add(&lb, "%s%s", j ? ", " : "", names[j]);
            mf_err(c, k, path, "expected one of %s, found %s", list, mf_found(k, true, f, sizeof f));
            ok = false;
        } else if (keys[i]) {
            mf_err(c, k, path, "expected a key used once, found a second '%s' (first at %d:%d)",
                names[i], keys[i]->line, keys[i]->col);
            ok = false;
        } else {
            keys[i] = k;
            vals[i] = map->pairs[p].value;
        }
    }
    return ok;
}

/* A mapping whose keys are the table's parameters under `prefix` ("" at the top). */
void mf_parse_group(vctx *c, const char *prefix, const ynode *map, run_params *dst)
{
    size_t idx[NPARAMS], nk = 0;
    const char *names[NPARAMS];
    for (size_t i = 0; i < NPARAMS; i++)
        if (path_parent_is(params_table[i].path, prefix)) {
            idx[nk] = i;
            names[nk++] = path_leaf(params_table[i].path);
        }
    const ynode *keys[NPARAMS], *vals[NPARAMS];
    mf_map_keys(c, map, prefix, names, nk, keys, vals);
    for (size_t j = 0; j < nk; j++) {
        if (!keys[j])
            continue;
        c->set_key[idx[j]] = keys[j];
        c->set_val[idx[j]] = vals[j];
        mf_parse_value(c, &params_table[idx[j]], vals[j], params_table[idx[j]].path, dst);
    }
}

static bool parse_span(vctx *c, const param *pd, const ynode *n, const char *key, span *out)
{
    if (n->kind != YNODE_MAPPING)
        return mf_bad(c, pd, n, key);
    static const char *const names[] = {"seconds", "frames"};
    const ynode *keys[2], *vals[2];
    bool keys_ok = mf_map_keys(c, n, key, names, 2, keys, vals);
    char e[64], sub[160];
    if (vals[0] && vals[1]) {
        mf_err(c, n, key, "expected %s, found both seconds and frames", mf_expect(pd, e, sizeof e));
        return false;
    }
    if (!vals[0] && !vals[1]) {
        if (keys_ok)
            mf_bad(c, pd, n, key);
        return false;
    }
    if (vals[0]) {
        double v;
        snprintf(sub, sizeof sub, "%s.seconds", key);
        if (!mf_parse_number_in(c, vals[0], sub, pd->min, pd->max, pd->flags, &v))
            return false;
        *out = (span){.kind = SPAN_SECONDS, .seconds = v};
    } else {
        uint64_t v;
        snprintf(sub, sizeof sub, "%s.frames", key);
        if (!mf_parse_uint_in(c, vals[1], sub, (uint64_t)pd->fmin, (uint64_t)pd->fmax, "", &v))
            return false;
        *out = (span){.kind = SPAN_FRAMES, .frames = (uint32_t)v};
    }
    return keys_ok;
}

static bool parse_count(vctx *c, const param *pd, const ynode *n, const char *key,
                        light_count *out)
{
    if (n->kind == YNODE_SCALAR) {
        uint64_t v;
        if (ynode_plain(n) && strcmp(n->text, "all") == 0) {
            *out = (light_count){.growth = false, .start = LIGHT_COUNT_ALL,
                                 .max = LIGHT_COUNT_ALL};
            return true;
        }
        if (!mf_get_uint(n, &v) || v > MAX_LIGHTS)
            return mf_bad(c, pd, n, key);
        *out = (light_count){.growth = false, .start = (uint32_t)v, .max = (uint32_t)v};
        return true;
    }
    if (n->kind != YNODE_MAPPING)
        return mf_bad(c, pd, n, key);

    static const char *const names[] = {"start", "step", "every", "max"};
    const ynode *keys[4], *vals[4];
    bool ok = mf_map_keys(c, n, key, names, 4, keys, vals);
    char sub[4][160];
    for (size_t i = 0; i < 4; i++) {
        snprintf(sub[i], sizeof sub[i], "%s.%s", key, names[i]);
        if (!vals[i]) {
            mf_err(c, n, sub[i], "expected %s, found nothing",
                i == 2 ? "a number > 0 and <= 604800" : "an integer 0..1000000");
            ok = false;
        }
    }
    uint64_t start = 0, step = 0, max = 0;
    double every = 0;
    bool have_start = vals[0] && mf_parse_uint_in(c, vals[0], sub[0], 0, MAX_LIGHTS, "", &start);
    if (vals[1] && !mf_parse_uint_in(c, vals[1], sub[1], 0, MAX_LIGHTS, "", &step))
        ok = false;
    if (vals[2] && !mf_parse_number_in(c, vals[2], sub[2], 0, MAX_EVERY, PF_MIN_OPEN, &every))
        ok = false;
    if (vals[3] &&
        !mf_parse_uint_in(c, vals[3], sub[3], have_start ? start : 0, MAX_LIGHTS,
                       have_start ? " (at least start)" : "", &max))
        ok = false;
    if (!ok || !have_start)
        return false;
    *out = (light_count){.growth = true, .start = (uint32_t)start, .step = (uint32_t)step,
                         .max = (uint32_t)max, .every = every};
    return true;
}

static bool parse_times(vctx *c, const param *pd, const ynode *n, const char *key,
                        run_params *dst)
{
    if (n->kind != YNODE_SEQUENCE)
        return mf_bad(c, pd, n, key);
    if (n->n > MAX_SCREENSHOTS) {
        char e[128];
        mf_err(c, n, key, "expected %s, found %zu times", mf_expect(pd, e, sizeof e), n->n);
        return false;
    }
    /* a size_t count followed by MAX_SCREENSHOTS doubles at pd->off (RP_SPAN) */
    size_t *count = (size_t *)((char *)dst + pd->off);
    double *times = (double *)((char *)dst + pd->off + sizeof(size_t));
    bool ok = true;
    for (size_t i = 0; i < n->n; i++) {
        char sub[160];
        snprintf(sub, sizeof sub, "%s[%zu]", key, i);
        if (!mf_parse_number_in(c, n->items[i], sub, pd->min, pd->max, 0, &times[i]))
            ok = false;
    }
    if (ok)
        *count = n->n;
    return ok;
}

static bool parse_renderers(vctx *c, const param *pd, const ynode *n, const char *key)
{
    if (n->kind != YNODE_SEQUENCE || n->n == 0)
        return mf_bad(c, pd, n, key);
    experiment *e = c->e;
    free(e->renderers);
    e->nrenderers = 0;
    e->renderers = calloc(n->n, sizeof *e->renderers);
    if (!e->renderers) {
        mf_err(c, n, key, "expected a sequence that fits in memory, found no memory left");
        return false;
    }
    bool ok = true;
    for (size_t i = 0; i < n->n; i++) {
        const ynode *it = n->items[i];
        char sub[160], f[128];
        snprintf(sub, sizeof sub, "%s[%zu]", key, i);
        const renderer_impl *impl = mf_stringish(it) ? renderer_kind_find(it->text) : NULL;
        if (!impl || strlen(impl->name) >= sizeof e->renderers[0]) {
            char list[512];
            sbuf lb = {list, sizeof list, 0};
            mf_list_renderers(&lb);
            mf_err(c, it, sub, "expected %s, found %s", list, mf_found(it, true, f, sizeof f));
            ok = false;
            continue;
        }
        const ynode *first = NULL;
        for (size_t j = 0; j < i && !first; j++)
            if (n->items[j]->kind == YNODE_SCALAR && strcmp(n->items[j]->text, it->text) == 0)
                first = n->items[j];
        if (first) {
            mf_err(c, it, sub, "expected a renderer listed once, found a second '%s' (first at %d:%d)",
                impl->name, first->line, first->col);
            ok = false;
            continue;
        }
        strcpy(e->renderers[e->nrenderers++], impl->name);
    }
    return ok;
}

static bool parse_resolution(vctx *c, const param *pd, const ynode *n, const char *key,
                             run_params *dst)
{
    if (!mf_stringish(n))
        return mf_bad(c, pd, n, key);
    const char *s = n->text, *x = strchr(s, 'x');
    if (!x || !all_digits(s, x) || !all_digits(x + 1, s + n->len) || x - s > 9 ||
        (s + n->len) - (x + 1) > 9)
        return mf_bad(c, pd, n, key);
    long w = strtol(s, NULL, 10), h = strtol(x + 1, NULL, 10);
    if (w < 1 || w > MAX_SIDE || h < 1 || h > MAX_SIDE)
        return mf_bad(c, pd, n, key);
    dst->width = (int)w;
    dst->height = (int)h;
    return true;
}

static bool parse_name(vctx *c, const param *pd, const ynode *n, const char *key)
{
    if (!mf_stringish(n) || n->len == 0 || n->len > 63)
        return mf_bad(c, pd, n, key);
    for (const char *s = n->text; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') || *s == '-'))
            return mf_bad(c, pd, n, key);
    strcpy(c->e->name, n->text);
    return true;
}

static bool parse_text(vctx *c, const param *pd, const ynode *n, const char *key)
{
    /* an explicitly empty string ("") is a string too */
    bool empty_quoted = n->kind == YNODE_SCALAR && n->len == 0 && n->style != YSTYLE_PLAIN;
    if (!mf_stringish(n) && !empty_quoted)
        return mf_bad(c, pd, n, key);
    char *d = strdup(n->text);
    if (!d) {
        mf_err(c, n, key, "expected a string that fits in memory, found no memory left");
        return false;
    }
    free(c->e->description);
    c->e->description = d;
    return true;
}

/* An optional key of a file scene whose value is one of two words: *second says whether
 * it is b (left as it is when the key is absent); false with the message otherwise. */
static bool either_word(vctx *c, const ynode *v, const char *key, const char *a,
                        const char *b, bool *second)
{
    if (!v)
        return true;
    if (ynode_plain(v) && (strcmp(v->text, a) == 0 || strcmp(v->text, b) == 0)) {
        *second = strcmp(v->text, b) == 0;
        return true;
    }
    char f[128];
    mf_err(c, v, key, "expected one of %s, %s, found %s", a, b, mf_found(v, true, f, sizeof f));
    return false;
}

/* `scene: {file: PATH, scale, up, camera, allow_outside, light_bounds}`: the file is
 * opened and checked here (scene_file_check: no GL), so that validate and run refuse a
 * bad file before any output exists; its content hash goes into the run id instead of
 * its path. */
static bool parse_scene_file(vctx *c, const param *pd, const ynode *n, const char *key,
                             run_params *dst)
{
    static const char *const names[] = {"file", "scale", "up", "camera", "allow_outside",
                                        "light_bounds", "max_image_bytes", "max_triangles",
                                        "max_vertices"};
    enum { NAMES = sizeof names / sizeof names[0] };
    const ynode *keys[NAMES], *vals[NAMES];
    bool ok = mf_map_keys(c, n, key, names, NAMES, keys, vals);
    char sub[NAMES][160], f[128];
    for (size_t i = 0; i < NAMES; i++)
        snprintf(sub[i], sizeof sub[i], "%s.%s", key, names[i]);
    if (!vals[0]) {
        mf_err(c, n, sub[0], "expected a path to a glTF 2.0 (.gltf, .glb) or OBJ file, found nothing");
        return false;
    }
    if (!mf_stringish(vals[0])) {
        mf_err(c, vals[0], sub[0], "expected a path to a glTF 2.0 (.gltf, .glb) or OBJ file, found %s",
            mf_found(vals[0], true, f, sizeof f));
        return false;
    }
    /* fit (the default) is stored as 0, which no number may be */
    double scale = 0;
    bool finite;
    if (!vals[1] || (ynode_plain(vals[1]) && strcmp(vals[1]->text, "fit") == 0)) {
        /* fit */
    } else if (!mf_get_number(vals[1], &scale, &finite)) {
        mf_err(c, vals[1], sub[1], "expected fit or a number > 0 and <= 1e+09, found %s",
            mf_found(vals[1], false, f, sizeof f));
        ok = false;
    } else if (!mf_parse_number_in(c, vals[1], sub[1], 0, 1e9, PF_MIN_OPEN | PF_FLOAT, &scale)) {
        ok = false;
    }
    bool up_z = false;
    ok &= either_word(c, vals[2], sub[2], "y", "z", &up_z);
    int up = up_z ? SCENE_UP_Z : SCENE_UP_Y;
    const char *camera = "auto";
    if (vals[3]) {
        if (!mf_stringish(vals[3]) || vals[3]->len >= sizeof dst->scene_camera) {
            mf_err(c, vals[3], sub[3], "expected auto, orbit or the name of one of the file's cameras "
                "(at most %zu bytes), found %s", sizeof dst->scene_camera - 1,
                mf_found(vals[3], true, f, sizeof f));
            ok = false;
        } else {
            camera = vals[3]->text;
        }
    }
    /* files the scene references may lie outside its folder: not part of the id (the
     * content hash is) */
    bool outside = false, model = false;
    ok &= either_word(c, vals[4], sub[4], "false", "true", &outside);
    ok &= either_word(c, vals[5], sub[5], "around", "model", &model);
    bool around = !model;
    /* limits on what the file may cost to load: not part of the id either (a limit
     * changes nothing that is measured); 0 stands for the default */
    uint64_t limit[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++)
        if (vals[6 + k])
            ok &= mf_parse_uint_in(c, vals[6 + k], sub[6 + k], 1, (uint64_t)1 << 53, "", &limit[k]);
    if (!ok)
        return false;
    /* relative to the manifest's folder */
    const char *given = vals[0]->text;
    const char *slash = strrchr(c->file, '/');
    int dirlen = given[0] != '/' && slash ? (int)(slash - c->file) : 0;
    int need = dirlen ? snprintf(dst->scene_file, sizeof dst->scene_file, "%.*s/%s", dirlen,
                                 c->file, given)
                      : snprintf(dst->scene_file, sizeof dst->scene_file, "%s", given);
    if (need < 0 || (size_t)need >= sizeof dst->scene_file) {
        mf_err(c, vals[0], sub[0], "expected a path of at most %zu bytes, found %d",
            sizeof dst->scene_file - 1, need);
        dst->scene_file[0] = '\0';
        return false;
    }
    scene_file_options o = {.path = dst->scene_file, .scale = (float)scale, .fit = scale == 0,
                            .up = (scene_up)up, .camera = camera, .allow_outside = outside,
                            .lights_around = around, .max_image_bytes = limit[0],
                            .max_triangles = limit[1], .max_vertices = limit[2]};
    scene_file_info info;
    char msg[1024];
    if (!scene_file_check(&o, &info, msg, sizeof msg)) {
        mf_err(c, vals[0], sub[0], "expected a scene file that loads, found %s", msg);
        dst->scene_file[0] = '\0';
        return false;
    }
    if (info.nnot_rendered) {   /* once a file, where the manifest is read */
        fprintf(stderr, "%s: warning: scene.file: %s: read but not rendered:", c->file, given);
        for (uint32_t i = 0; i < info.nnot_rendered; i++)
            fprintf(stderr, "%s %s", i ? ";" : "", info.not_rendered[i]);
        fputc('\n', stderr);
    }
    const char *base = strrchr(given, '/');
    snprintf(dst->scene, sizeof dst->scene, "%.63s", base ? base + 1 : given);
    dst->scene_scale = (float)scale;
    dst->scene_up = up;
    snprintf(dst->scene_camera, sizeof dst->scene_camera, "%s", camera);
    dst->scene_outside = outside;
    dst->scene_around = around;
    dst->scene_max_image_bytes = limit[0];
    dst->scene_max_triangles = limit[1];
    dst->scene_max_vertices = limit[2];
    hash_hex(info.hash, 16, dst->scene_hash);
    return true;
}

/* A parsed value into its parameter's bytes: true. */
static bool store(char *at, const void *v, size_t size)
{
    memcpy(at, v, size);
    return true;
}

/* Validates n as parameter pd; a run parameter's value goes into dst (at pd->off),
 * the experiment's own (name, renderers...) into c->e. The one path for keys in
 * place, sweep values and defaults. */
bool mf_parse_value(vctx *c, const param *pd, const ynode *n, const char *key,
                    run_params *dst)
{
    char *at = (char *)dst + pd->off;
    if (n->kind == YNODE_SCALAR && !mf_tag_ok(n))
        return mf_bad(c, pd, n, key);
    switch (pd->type) {
    case PT_SCHEMA: {
        uint64_t v;
        if (!mf_get_uint(n, &v) || (v != 1 && v != 2))
            return mf_bad(c, pd, n, key);
        c->e->schema = (unsigned)v;
        return true;
    }
    case PT_NAME:
        return parse_name(c, pd, n, key);
    case PT_TEXT:
        return parse_text(c, pd, n, key);
    case PT_SCENE:
        if (n->kind == YNODE_MAPPING)
            return parse_scene_file(c, pd, n, key, dst);
        if (!mf_stringish(n) || !scene_catalog_find(n->text) || n->len >= sizeof dst->scene)
            return mf_bad(c, pd, n, key);
        strcpy(dst->scene, n->text);
        return true;
    case PT_RENDERERS:
        return parse_renderers(c, pd, n, key);
    case PT_RENDERER:
        if (!mf_stringish(n) || !renderer_kind_find(n->text) || n->len >= 32)
            return mf_bad(c, pd, n, key);
        return store(at, n->text, n->len + 1);
    case PT_RESOLUTION:
        return parse_resolution(c, pd, n, key, dst);
    case PT_UINT: {
        uint64_t v;
        if ((pd->flags & PF_AUTO) && ynode_plain(n) && strcmp(n->text, "auto") == 0) {
            uint32_t zero = 0;
            return store(at, &zero, sizeof zero);
        }
        if (!mf_parse_uint_in(c, n, key, (uint64_t)pd->min, (uint64_t)pd->max,
                           pd->flags & PF_AUTO ? ", or auto" : "", &v))
            return false;
        uint32_t u = (uint32_t)v;
        return store(at, &u, sizeof u);
    }
    case PT_NUMBER: {
        double v;
        if ((pd->flags & PF_SCENE_DEFAULT) && ynode_plain(n) && strcmp(n->text, "scene") == 0) {
            float f = NAN;   /* PF_SCENE_DEFAULT numbers are floats */
            return store(at, &f, sizeof f);
        }
        if (!mf_parse_number_in(c, n, key, pd->min, pd->max, pd->flags, &v))
            return false;
        if (pd->flags & PF_FLOAT) {
            float f = (float)v;
            memcpy(at, &f, sizeof f);
        } else {
            memcpy(at, &v, sizeof v);
        }
        return true;
    }
    case PT_VEC3: {
        float v[3] = {NAN, NAN, NAN};
        if ((pd->flags & PF_SCENE_DEFAULT) && ynode_plain(n) && strcmp(n->text, "scene") == 0)
            return store(at, v, sizeof v);
        if (n->kind != YNODE_SEQUENCE || n->n != 3)
            return mf_bad(c, pd, n, key);
        for (size_t i = 0; i < 3; i++) {
            char k[160];
            double d;
            snprintf(k, sizeof k, "%s[%zu]", key, i);
            if (!mf_parse_number_in(c, n->items[i], k, pd->min, pd->max, PF_FLOAT, &d))
                return false;
            v[i] = (float)d;
        }
        return store(at, v, sizeof v);
    }
    case PT_ENUM:
        if (mf_stringish(n))
            for (int i = 0; pd->values[i]; i++)
                if (strcmp(pd->values[i], n->text) == 0)
                    return store(at, &i, sizeof i);
        return mf_bad(c, pd, n, key);
    case PT_BOOL: {
        bool t = ynode_plain(n) && strcmp(n->text, "true") == 0;
        bool f = ynode_plain(n) && strcmp(n->text, "false") == 0;
        if (!t && !f)
            return mf_bad(c, pd, n, key);
        return store(at, &t, sizeof t);
    }
    case PT_SPAN: {
        span s;
        return parse_span(c, pd, n, key, &s) && store(at, &s, sizeof s);
    }
    case PT_COUNT: {
        light_count lc;
        return parse_count(c, pd, n, key, &lc) && store(at, &lc, sizeof lc);
    }
    case PT_TIMES:
        return parse_times(c, pd, n, key, dst);
    case PT_GROUP:
        if (n->kind == YNODE_SCALAR && pd->shorthand) {
            const param *member = param_find(pd->shorthand);
            return mf_parse_value(c, member, n, key, dst);
        }
        if (n->kind != YNODE_MAPPING)
            return mf_bad(c, pd, n, key);
        mf_parse_group(c, pd->path, n, dst);
        return true;
    case PT_SWEEP:
        return mf_parse_sweep(c, pd, n);
    }
    return false;
}
