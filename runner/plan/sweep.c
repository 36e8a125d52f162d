/* From an experiment to its runs (manifest.h): the cartesian product of the sweep
 * axes times the renderers, run ids, shards, and the plan as `shadesweep list`
 * prints it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "results/jsonout.h"
#include "runner/manifest/hash.h"
#include "runner/manifest/manifest_parse.h"
#include "runner/plan/plan_check.h"
#include "runner/manifest/sweep_axis.h"

#define PLAN_MAX_RUNS 100000u
#define SHARD_MAX 100000u

/* The id: the first 12 hex digits of FNV-1a 64 over "key=value\n" per pair, for
 * the parameters not at their default (params.def: so a new key leaves every
 * existing id as it was). */
static void run_id(const run_params *p, char id[13])
{
    param_kv kv[PARAM_KV_MAX];
    size_t n = run_params_kv(p, kv, PARAM_KV_MAX);
    uint64_t h = FNV1A64_OFFSET_BASIS;
    for (size_t i = 0; i < n; i++) {
        if (!kv[i].in_id || kv[i].is_default)
            continue;
        h = fnv1a64_update(h, kv[i].key, strlen(kv[i].key));
        h = fnv1a64_update(h, "=", 1);
        h = fnv1a64_update(h, kv[i].value, strlen(kv[i].value));
        h = fnv1a64_update(h, "\n", 1);
    }
    hash_hex(h, 12, id);
}

#define NO_VALUE ((size_t)-1)

/* The plan's grid points: each block's product of its axes times the renderers, the
 * blocks in turn; start[b] is block b's first point, start[nblocks] all of them. */
typedef struct grid {
    const experiment *e;
    size_t nblocks;
    size_t *start;
} grid;

/* The block of point k (binary search: a list of many blocks stays n log n); *local:
 * k's index in it. */
static size_t block_of(const grid *g, size_t k, size_t *local)
{
    size_t b = 0;   /* the last block that starts at or before k */
    for (size_t n = g->nblocks; n > 1;) {
        size_t half = n / 2;
        b += g->start[b + half] <= k ? half : 0;
        n -= half;
    }
    *local = k - g->start[b];
    return b;
}

/* The value index of point `local` of block b on its axis a (renderers vary fastest,
 * then the block's last axis). */
static size_t block_value_of(const experiment *e, size_t b, size_t local, size_t a)
{
    size_t q = local / e->nrenderers;
    for (size_t x = sweep_block_end(e, b); x-- > a + 1;)
        q /= e->axes[x].nvalues;
    return q % e->axes[a].nvalues;
}

/* The value index of point k on axis a; NO_VALUE when a is another block's axis (k
 * takes the base value). */
static size_t axis_value_of(const grid *g, size_t k, size_t a)
{
    size_t local, b = block_of(g, k, &local);
    if (a < sweep_block_first(g->e, b) || a >= sweep_block_end(g->e, b))
        return NO_VALUE;
    return block_value_of(g->e, b, local, a);
}

/* The parameters of point k as the sweep makes them: the base, its block's values,
 * its renderer. */
static void point_params(const grid *g, size_t k, run_params *p)
{
    const experiment *e = g->e;
    size_t local, b = block_of(g, k, &local);
    *p = e->base;
    for (size_t a = sweep_block_first(e, b); a < sweep_block_end(e, b); a++) {
        const struct sweep_axis *ax = &e->axes[a];
        size_t v = block_value_of(e, b, local, a);
        memcpy((char *)p + ax->off, (const char *)&ax->values[v] + ax->off, ax->size);
    }
    snprintf(p->renderer, sizeof p->renderer, "%s", e->renderers[k % e->nrenderers]);
}

typedef struct id_ref {
    const char *id;
    size_t index;
} id_ref;

static int id_ref_cmp(const void *x, const void *y)
{
    const id_ref *a = x, *b = y;
    int c = strcmp(a->id, b->id);
    if (c != 0)
        return c;
    return a->index < b->index ? -1 : a->index > b->index;
}

static int id_ref_cmp_index(const void *x, const void *y)
{
    const id_ref *a = x, *b = y;
    return a->index < b->index ? -1 : a->index > b->index;
}

/* Two runs of one block with one id are one point of the grid twice (a value
 * repeated in an axis, or two values with one canonical text, like 0.5 and 0.50):
 * reported once per repeated value, at that value, naming the first pair of runs it
 * makes. A run of a later block that is an earlier block's is no error: fold() folds
 * it. */
static bool check_duplicates(const grid *gr, const plan *p, diag_list *diags)
{
    const experiment *e = gr->e;
    if (p->nruns < 2)
        return true;
    size_t nvals = 0, ndup = 0;
    for (size_t a = 0; a < e->naxes; a++)
        nvals += e->axes[a].nvalues;
    id_ref *refs = malloc(p->nruns * sizeof *refs);
    id_ref *dups = malloc(p->nruns * sizeof *dups);   /* .index: the repeat; .id: unused */
    size_t *firsts = malloc(p->nruns * sizeof *firsts);
    bool *reported = calloc(nvals ? nvals : 1, sizeof *reported);
    bool ok = refs && dups && firsts && reported;
    if (!ok) {
        diag_add(diags, e->path, 0, 0, "", "expected a plan that fits in memory, found no memory left");
        goto done;
    }
    for (size_t i = 0; i < p->nruns; i++)
        refs[i] = (id_ref){p->runs[i].id, i};
    qsort(refs, p->nruns, sizeof *refs, id_ref_cmp);
    /* in each group of one id and block, the first run (lowest index) is the original */
    size_t local;
    for (size_t i = 1, g = 0; i < p->nruns; i++) {
        if (strcmp(refs[i].id, refs[g].id) != 0 ||
            block_of(gr, refs[i].index, &local) != block_of(gr, refs[g].index, &local)) {
            g = i;
            continue;
        }
        firsts[refs[i].index] = refs[g].index;
        dups[ndup++] = (id_ref){refs[i].id, refs[i].index};
    }
    qsort(dups, ndup, sizeof *dups, id_ref_cmp_index);
    for (size_t i = 0; i < ndup; i++) {
        ok = false;
        size_t again = dups[i].index, first = firsts[again];
        /* the axis where the two runs take different values; the later value repeats */
        size_t a = 0, base = 0, v = 0;
        for (; a < e->naxes; base += e->axes[a].nvalues, a++) {
            size_t va = axis_value_of(gr, first, a), vb = axis_value_of(gr, again, a);
            if (va != vb) {
                v = va > vb ? va : vb;
                break;
            }
        }
        if (a == e->naxes) {   /* not a repeated value: two different points, one id */
            diag_add(diags, e->path, 0, 0, "sweep",
                     "expected a distinct id per run, found run %zu with the id of run %zu (%s)",
                     again, first, dups[i].id);
        } else if (!reported[base + v]) {
            reported[base + v] = true;
            const struct sweep_axis *ax = &e->axes[a];
            char key[200];
            mf_axis_key(e, a, key, sizeof key);
            snprintf(key + strlen(key), sizeof key - strlen(key), "[%zu]", v);
            overrides_diag(diags, e, e->path, ax->line[v], ax->col[v], key,
                           "expected a distinct sweep point, found run %zu the same as run "
                           "%zu (id %s)", again, first, dups[i].id);
        }
    }
done:
    free(refs);
    free(dups);
    free(firsts);
    free(reported);
    return ok;
}

/* A swept key must change what some run measures: one that none of the renderers
 * reads (nor an error reference that inherits it) would only repeat runs. */
static bool check_axes_read(const experiment *e, diag_list *diags)
{
    bool ok = true;
    for (size_t a = 0; a < e->naxes; a++) {
        const struct sweep_axis *ax = &e->axes[a];
        const param *pd = param_find(ax->path);
        if (!pd)
            continue;
        bool read = false;
        run_params probe = e->base;
        for (size_t r = 0; r < e->nrenderers && !read; r++) {
            snprintf(probe.renderer, sizeof probe.renderer, "%s", e->renderers[r]);
            read = param_read_by_run(pd, &probe);
        }
        if (read)
            continue;
        char key[200], list[512] = "", readers[256];
        param_readers_text(pd, readers, sizeof readers);
        size_t len = 0;
        for (size_t r = 0; r < e->nrenderers; r++)
            len += (size_t)snprintf(list + len, len < sizeof list ? sizeof list - len : 0, "%s%s",
                                    r ? ", " : "", e->renderers[r]);
        mf_axis_key(e, a, key, sizeof key);
        overrides_diag(diags, e, e->path, ax->line ? ax->line[0] : 0,
                       ax->col ? ax->col[0] : 0, key, "expected a key one of the renderers "
                       "reads (%s is read by %s), found none of %s", ax->path, readers,
                       list);
        ok = false;
    }
    return ok;
}

static int id_ref_cmp_first(const void *x, const void *y)
{
    return id_ref_cmp(x, y);
}

/* The sweep point of a run: the hash of the canonical text of every parameter that
 * every run reads (params.def readers "*") but the renderer. Runs that share it differ
 * only in their renderer and the keys only some renderers read: they are ranked
 * together (runner/answer/run_model.c's rule), and the schedule runs them in rounds. */
static uint64_t point_hash(const run_params *rp)
{
    uint64_t h = FNV1A64_OFFSET_BASIS;
    char text[4096];
    for (size_t i = 0; i < NPARAMS; i++) {
        const param *pd = &params_table[i];
        if (!pd->size || !param_every_run_reads(pd) ||
            strcmp(pd->path, "renderers") == 0)
            continue;
        param_format(pd, rp, text, sizeof text);
        h = fnv1a64_update(h, pd->path, strlen(pd->path) + 1);
        h = fnv1a64_update(h, text, strlen(text) + 1);
    }
    return h;
}

/* Numbers the sweep points in order of their first run (sorted by hash: n log n for
 * the largest plans), and deals them to the shards: a shard holds whole points, so
 * that the runs ranked together are measured together. */
static bool assign_points(plan *p, unsigned nshards)
{
    size_t *first = malloc((p->nruns ? p->nruns : 1) * sizeof *first);
    if (!first || !plan_first_of_key(p, point_hash, NULL, first)) {
        free(first);
        return false;
    }
    size_t npoints = 0;
    for (size_t k = 0; k < p->nruns; k++) {
        run_spec *r = &p->runs[k];
        r->group = first[k] == k ? npoints++ : p->runs[first[k]].group;
        r->shard = (unsigned)(r->group % nshards) + 1;
    }
    p->ngroups = npoints;
    free(first);
    return true;
}

/* Resets what each run's renderer does not read to its default, then keeps the
 * first run of each id: the others are folded into it. Ids, indices and shards are
 * assigned to the runs that remain, in plan order. */
static bool fold(plan *p, const grid *gr, unsigned nshards, diag_list *diags)
{
    run_params d;
    params_defaults(&d);
    for (size_t k = 0; k < p->nruns; k++) {
        run_spec *r = &p->runs[k];
        r->index = k;   /* scratch: the raw run it came from */
        run_params raw = r->p;
        bool reset = false;
        for (size_t i = 0; i < NPARAMS; i++) {
            const param *pd = &params_table[i];
            if (pd->size && !param_read_by_run(pd, &raw) &&
                memcmp((char *)&r->p + pd->off, (const char *)&d + pd->off, pd->size) != 0) {
                memcpy((char *)&r->p + pd->off, (const char *)&d + pd->off, pd->size);
                reset = true;
            }
        }
        if (reset)   /* else the id plan_expand gave it, of these same parameters */
            run_id(&r->p, r->id);
    }
    id_ref *refs = malloc((p->nruns ? p->nruns : 1) * sizeof *refs);
    size_t *first_of = malloc((p->nruns ? p->nruns : 1) * sizeof *first_of);
    run_params *raw = malloc((p->nruns ? p->nruns : 1) * sizeof *raw);
    if (!refs || !first_of || !raw) {
        free(refs);
        free(first_of);
        free(raw);
        diag_add(diags, p->exp->path, 0, 0, "", "expected a plan that fits in memory, found no memory left");
        return false;
    }
    for (size_t k = 0; k < p->nruns; k++)
        refs[k] = (id_ref){p->runs[k].id, k};
    qsort(refs, p->nruns, sizeof *refs, id_ref_cmp_first);
    size_t nfolded = 0;
    for (size_t i = 0, g = 0; i < p->nruns; i++) {
        if (strcmp(refs[i].id, refs[g].id) != 0)
            g = i;
        first_of[refs[i].index] = refs[g].index;
        nfolded += i != g;
    }
    /* the raw parameters of every point, for the folds' record */
    for (size_t k = 0; k < p->nruns; k++)
        point_params(gr, k, &raw[k]);
    plan_fold *folds = nfolded ? calloc(nfolded, sizeof *folds) : NULL;
    size_t *new_index = malloc((p->nruns ? p->nruns : 1) * sizeof *new_index);
    bool ok = (!nfolded || folds) && new_index;
    if (ok) {
        size_t n = 0, f = 0;
        for (size_t k = 0; k < p->nruns; k++) {
            if (first_of[k] == k) {
                new_index[k] = n;
                p->runs[n] = p->runs[k];
                p->runs[n].index = n;
                p->runs[n].point = k;
                p->runs[n].folded = 0;
                n++;
            } else {
                size_t into = new_index[first_of[k]];
                p->runs[into].folded++;
                folds[f++] = (plan_fold){.point = k, .into = into, .p = raw[k]};
            }
        }
        p->nruns = n;
        p->nfolded = f;
        p->folds = folds;
        ok = assign_points(p, nshards);
    }
    if (!ok) {
        free(folds);
        diag_add(diags, p->exp->path, 0, 0, "", "expected a plan that fits in memory, found no memory left");
    }
    free(new_index);
    free(refs);
    free(first_of);
    free(raw);
    return ok;
}

bool plan_expand(const experiment *e, unsigned nshards, plan *out, diag_list *diags)
{
    *out = (plan){.exp = e};
    if (nshards < 1) {
        diag_add(diags, e->path, 0, 0, "", "expected at least 1 shard, found %u", nshards);
        return false;
    }
    if (e->nrenderers == 0) {
        diag_add(diags, e->path, 0, 0, "renderers", "expected at least one renderer, found none");
        return false;
    }
    grid g = {.e = e, .nblocks = sweep_nblocks(e)};
    g.start = malloc((g.nblocks + 1) * sizeof *g.start);
    if (!g.start) {
        diag_add(diags, e->path, 0, 0, "", "expected a plan that fits in memory, found no memory left");
        return false;
    }
    size_t total = 0;
    for (size_t b = 0; b < g.nblocks; b++) {
        g.start[b] = total;
        size_t n = e->nrenderers;
        for (size_t a = sweep_block_first(e, b); a < sweep_block_end(e, b); a++) {
            if (e->axes[a].nvalues == 0 || n > PLAN_MAX_RUNS / e->axes[a].nvalues) {
                overrides_diag(diags, e, e->path, e->axes[a].line ? e->axes[a].line[0] : 0,
                               e->axes[a].col ? e->axes[a].col[0] : 0, "sweep",
                               "expected at most %u runs, found more at axis %s",
                               PLAN_MAX_RUNS, e->axes[a].path);
                free(g.start);
                return false;
            }
            n *= e->axes[a].nvalues;
        }
        total += n;   /* blocks of at most PLAN_MAX_RUNS each: no overflow */
    }
    g.start[g.nblocks] = total;
    if (total > PLAN_MAX_RUNS) {
        diag_add(diags, e->path, 0, 0, "sweep", "expected at most %u runs, found %zu",
                 PLAN_MAX_RUNS, total);
        free(g.start);
        return false;
    }

    run_spec *runs = calloc(total, sizeof *runs);
    if (!runs) {
        diag_add(diags, e->path, 0, 0, "", "expected a plan that fits in memory, found no memory left");
        free(g.start);
        return false;
    }
    for (size_t k = 0; k < total; k++) {
        run_spec *r = &runs[k];
        r->index = r->point = k;
        point_params(&g, k, &r->p);
        run_id(&r->p, r->id);   /* as swept: a repeated value is a duplicate */
    }
    out->npoints = out->nruns = total;
    out->runs = runs;
    bool ok = check_duplicates(&g, out, diags) && check_axes_read(e, diags) &&
              fold(out, &g, nshards, diags);
    free(g.start);
    if (!ok)
        plan_free(out);
    return ok;
}

void plan_free(plan *p)
{
    if (!p)
        return;
    free(p->runs);
    free(p->folds);
    p->runs = NULL;
    p->folds = NULL;
    p->nruns = p->npoints = p->nfolded = 0;
}

/* Digits only, no sign, no spaces, at most 6 of them (100000 has 6). */
static bool parse_count_part(const char *s, size_t len, unsigned *out)
{
    if (len == 0 || len > 6)
        return false;
    unsigned v = 0;
    for (size_t i = 0; i < len; i++) {
        if (s[i] < '0' || s[i] > '9')
            return false;
        v = v * 10 + (unsigned)(s[i] - '0');
    }
    *out = v;
    return true;
}

bool parse_shard(const char *s, unsigned *i, unsigned *n, char *err, size_t errlen)
{
    const char *slash = s ? strchr(s, '/') : NULL;
    unsigned a, b;
    if (slash && parse_count_part(s, (size_t)(slash - s), &a) &&
        parse_count_part(slash + 1, strlen(slash + 1), &b) && a >= 1 && a <= b &&
        b <= SHARD_MAX) {
        *i = a;
        *n = b;
        return true;
    }
    if (err && errlen) {
        /* the value as given, escaped and cut to keep the message one short line */
        char shown[64];
        size_t k = 0;
        for (const char *q = s ? s : ""; *q && k + 5 < sizeof shown; q++) {
            unsigned char ch = (unsigned char)*q;
            if (ch < 0x20 || ch == 0x7f || ch == '\'' || ch == '\\')
                k += (size_t)snprintf(shown + k, sizeof shown - k, "\\x%02x", ch);
            else
                shown[k++] = (char)ch;
        }
        shown[k] = '\0';
        snprintf(err, errlen, "--shard: expected I/N with 1 <= I <= N <= %u, found '%s'",
                 SHARD_MAX, shown);
    }
    return false;
}

/* " key=value" for the renderer and each swept parameter of p; first[a]: axis a is
 * the first to sweep its key (a key several blocks sweep is printed once). */
static void print_point(const experiment *e, const bool *first, const run_params *p, FILE *out)
{
    param_kv kv[PARAM_KV_MAX];
    size_t n = run_params_kv(p, kv, PARAM_KV_MAX);
    fprintf(out, "renderer=%s", p->renderer);
    for (size_t a = 0; first && a < e->naxes; a++)
        for (size_t i = 0; i < n && first[a]; i++)
            if (strcmp(kv[i].key, e->axes[a].path) == 0)
                fprintf(out, " %s=%s", kv[i].key, kv[i].value);
}

static void json_params(const run_params *rp, FILE *out)
{
    param_kv kv[PARAM_KV_MAX];
    size_t n = run_params_kv(rp, kv, PARAM_KV_MAX);
    bool first = true;
    fputc('{', out);
    for (size_t i = 0; i < n; i++) {
        json_key(out, &first, kv[i].key);
        json_typed(out, kv[i].value);
    }
    fputc('}', out);
}

void plan_print_json(const plan *p, unsigned shard, FILE *out)
{
    fputs("{\"experiment\": ", out);
    json_string(out, p->exp->name);
    fputs(", \"runs\": [", out);
    bool any = false;
    for (size_t k = 0; k < p->nruns; k++) {
        const run_spec *r = &p->runs[k];
        if (shard != 0 && r->shard != shard)
            continue;
        fprintf(out, "%s\n  {\"run_id\": \"%s\", \"index\": %zu, \"shard\": %u, "
                "\"point\": %zu, \"parameters\": ", any ? "," : "", r->id, r->index, r->shard,
                r->group);
        json_params(&r->p, out);
        fputc('}', out);
        any = true;
    }
    fputs(any ? "\n], \"folded\": [" : "], \"folded\": [", out);
    any = false;
    for (size_t f = 0; f < p->nfolded; f++) {
        const run_spec *r = &p->runs[p->folds[f].into];
        if (shard != 0 && r->shard != shard)
            continue;
        fprintf(out, "%s\n  {\"into\": \"%s\", \"parameters\": ", any ? "," : "", r->id);
        json_params(&p->folds[f].p, out);
        fputc('}', out);
        any = true;
    }
    fputs(any ? "\n]}\n" : "]}\n", out);
}

void plan_print(const plan *p, unsigned shard, FILE *out)
{
    const experiment *e = p->exp;
    bool *first = calloc(e->naxes ? e->naxes : 1, sizeof *first);
    for (size_t a = 0; first && a < e->naxes; a++) {
        first[a] = true;
        for (size_t b = 0; b < a && first[a]; b++)
            first[a] = e->axes[b].off != e->axes[a].off;
    }
    for (size_t k = 0; k < p->nruns; k++) {
        const run_spec *r = &p->runs[k];
        if (shard != 0 && r->shard != shard)
            continue;
        fprintf(out, "%s  ", r->id);
        print_point(e, first, &r->p, out);
        fputc('\n', out);
    }
    /* Folded points after the runs, as comments: what the sweep asked for that is
     * already one of the runs above. */
    size_t shown = 0;
    for (size_t f = 0; f < p->nfolded; f++) {
        const run_spec *r = &p->runs[p->folds[f].into];
        if (shard != 0 && r->shard != shard)
            continue;
        if (shown++ == 0)
            fprintf(out, "# %zu of %zu grid points folded into a run that measures the same "
                    "(they differ only in keys their renderer does not read):\n",
                    p->nfolded, p->npoints);
        fprintf(out, "#   ");
        print_point(e, first, &p->folds[f].p, out);
        fprintf(out, " -> %s\n", r->id);
    }
    free(first);
}
