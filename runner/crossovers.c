/* Where two configurations change places along the numeric parameters a sweep varies
 * (runner/crossovers.h). */
#include "runner/crossovers.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "results/mdtext.h"
#include "results/grow.h"

/* The value of a plan cell on a numeric axis: a plain number, or a resolution WxH as
 * its pixel count. False for anything else ("volume", "seconds:0.3", ""). */
static bool axis_value(const char *s, double *out)
{
    char *end;
    double v = strtod(s, &end);
    if (end != s && isfinite(v)) {
        if (*end == '\0') {
            *out = v;
            return true;
        }
        if (*end == 'x') {
            char *end2;
            double h = strtod(end + 1, &end2);
            if (end2 != end + 1 && *end2 == '\0' && isfinite(h)) {
                *out = v * h;
                return true;
            }
        }
    }
    return false;
}

typedef struct entry {
    const char *group;   /* the other varying parameters' values */
    const char *cfg;     /* the configuration (renderer and its own keys) */
    double x;
    size_t run;
} entry;

static int by_group_cfg_x(const void *pa, const void *pb)
{
    const entry *a = pa, *b = pb;
    int c = strcmp(a->group, b->group);
    if (!c)
        c = strcmp(a->cfg, b->cfg);
    if (!c)
        c = a->x < b->x ? -1 : a->x > b->x;
    if (!c)
        c = a->run < b->run ? -1 : a->run > b->run;
    return c;
}

static bool push(crossover_list *l, const crossover_found *c)
{
    if (!GROW(l->item, l->cap, l->n + 1, 16))
        return false;
    l->item[l->n++] = *c;
    return true;
}

/* Every crossing of a / b (ratios r at x[0..n), ascending) through 1, named: a / b
 * rising through 1 makes a the faster below the crossing. */
static bool push_crossings(const double *x, const ratio_ci *r, size_t n, const char *axis,
                           const char *group, const char *a, const char *b,
                           crossover_list *out)
{
    ratio_crossover co;
    for (size_t from = 0; n >= 2 && verdict_crossover(x, r, n, from, &co); from = co.j) {
        crossover_found f = {
            .axis = axis, .group = group,
            .below = co.dir > 0 ? a : b, .above = co.dir > 0 ? b : a,
            .x0 = x[co.i], .x1 = x[co.j], .x = co.x, .lo = co.lo, .hi = co.hi,
            .differs0 = summary_differs(&r[co.i]), .differs1 = summary_differs(&r[co.j]),
        };
        if (!push(out, &f))
            return false;
    }
    return true;
}

/* "k=v, k=v" of the varying columns but `axis`, for one plan row. */
static char *group_of(const csv_table *pl, long row, const bool *varies, size_t axis)
{
    size_t cap = 2;
    for (size_t c = 0; row >= 0 && c < pl->ncols; c++)
        if (varies[c] && c != axis)
            cap += strlen(pl->header[c]) + strlen(pl->rows[row][c]) + 3;
    char *s = malloc(cap);
    if (!s)
        return NULL;
    size_t len = 0;
    s[0] = '\0';
    for (size_t c = 0; row >= 0 && c < pl->ncols; c++)
        if (varies[c] && c != axis)
            len += (size_t)snprintf(s + len, cap - len, "%s%s=%s", len ? ", " : "",
                                    pl->header[c], pl->rows[row][c]);
    return s;
}

/* The crossings of configurations a and b (entries e[a0..a1) and e[b0..b1), each
 * ascending in x) at the x values both have. */
static bool pair_crossings(const run_result *runs, const entry *e, size_t a0, size_t a1,
                           size_t b0, size_t b1, const char *axis, crossover_list *out)
{
    size_t cap = (a1 - a0) < (b1 - b0) ? a1 - a0 : b1 - b0;
    double *x = malloc((cap ? cap : 1) * sizeof *x);
    ratio_ci *r = malloc((cap ? cap : 1) * sizeof *r);
    bool ok = x && r;
    size_t n = 0;
    for (size_t i = a0, j = b0; ok && i < a1 && j < b1;) {
        if (e[i].x < e[j].x) {
            i++;
        } else if (e[j].x < e[i].x) {
            j++;
        } else {
            if (!n || e[i].x > x[n - 1]) {   /* the first run of a repeated x */
                x[n] = e[i].x;
                summary_paired_ratio(&runs[e[i].run], &runs[e[j].run], &r[n]);
                n++;
            }
            i++;
            j++;
        }
    }
    ok = ok && push_crossings(x, r, n, axis, e[a0].group, e[a0].cfg, e[b0].cfg, out);
    free(x);
    free(r);
    return ok;
}

static bool push_string(crossover_list *l, char *s);

/* The crossings along one axis column. */
static bool along(const run_result *runs, size_t nruns, const csv_table *pl, const long *prow,
                  const bool *varies, char *const *rcfg, size_t axis, crossover_list *out)
{
    entry *e = malloc((nruns ? nruns : 1) * sizeof *e);
    if (!e)
        return false;
    size_t n = 0;
    bool ok = true;
    for (size_t r = 0; ok && r < nruns; r++) {
        double x;
        if (prow[r] < 0 || !isfinite(runs[r].mean) ||
            !axis_value(pl->rows[prow[r]][axis], &x))
            continue;
        char *g = group_of(pl, prow[r], varies, axis);
        if (!g || !push_string(out, g)) {
            free(g);
            ok = false;
            break;
        }
        e[n++] = (entry){out->strings[out->nstrings - 1], rcfg[r], x, r};
    }
    qsort(e, n, sizeof *e, by_group_cfg_x);
    /* per group, each pair of configurations */
    for (size_t g0 = 0, g1; ok && g0 < n; g0 = g1) {
        for (g1 = g0; g1 < n && strcmp(e[g1].group, e[g0].group) == 0; g1++)
            ;
        for (size_t a0 = g0, a1; ok && a0 < g1; a0 = a1) {
            for (a1 = a0; a1 < g1 && strcmp(e[a1].cfg, e[a0].cfg) == 0; a1++)
                ;
            for (size_t b0 = a1, b1; ok && b0 < g1; b0 = b1) {
                for (b1 = b0; b1 < g1 && strcmp(e[b1].cfg, e[b0].cfg) == 0; b1++)
                    ;
                ok = pair_crossings(runs, e, a0, a1, b0, b1, pl->header[axis], out);
            }
        }
    }
    free(e);
    return ok;
}

/* Keeps s (owned by l from here). */
static bool push_string(crossover_list *l, char *s)
{
    if (!GROW(l->strings, l->capstrings, l->nstrings + 1, 16))
        return false;
    l->strings[l->nstrings++] = s;
    return true;
}

/* A seed names a random draw: a label, not a quantity to interpolate along. */
static bool is_label(const char *name)
{
    size_t n = strlen(name);
    return strcmp(name, "seed") == 0 || (n > 5 && strcmp(name + n - 5, ".seed") == 0);
}

bool crossovers_find(const run_result *runs, size_t nruns, const csv_table *pl,
                     const long *prow, const bool *varies, char *const *rcfg,
                     crossover_list *out)
{
    memset(out, 0, sizeof *out);
    bool ok = true;
    for (size_t c = 0; ok && c < pl->ncols; c++) {
        if (!varies[c] || is_label(pl->header[c]))
            continue;
        /* an axis when every planned run's value on it is numeric */
        bool numeric = true;
        for (size_t r = 0; numeric && r < nruns; r++) {
            double x;
            numeric = prow[r] < 0 || axis_value(pl->rows[prow[r]][c], &x);
        }
        if (!numeric)
            continue;
        out->axes++;
        ok = along(runs, nruns, pl, prow, varies, rcfg, c, out);
    }
    return ok;
}

/* ---- lights that grow over time within a run */

/* A run's metric per trial and light count: mean[level * ntrials + (trial - 1)], the
 * mean of the metric's frames.csv column over the frames drawn at that count. */
typedef struct levels {
    double *lights;   /* ascending, distinct */
    size_t n, ntrials;
    double *mean;
} levels;

static int by_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return a < b ? -1 : a > b;
}

static const char *frame_column(const char *metric)
{
    return strcmp(metric, "cpu") == 0 ? "cpu_us" : strcmp(metric, "gpu") == 0 ? "gpu_us"
                                                                              : "frametime_us";
}

/* False when the run has no frames.csv with the columns (outputs.frames: false). */
static bool read_levels(const char *out_dir, const run_result *x, levels *lv)
{
    memset(lv, 0, sizeof *lv);
    char path[4200], err[300];
    snprintf(path, sizeof path, "%s/runs/%s/frames.csv", out_dir, x->id);
    csv_table t;
    if (!x->nvalues || !csv_read(path, &t, err, sizeof err))
        return false;
    int ct = csv_col(&t, "trial"), cl = csv_col(&t, "lights");
    int cv = csv_col(&t, frame_column(x->metric));
    bool ok = ct >= 0 && cl >= 0 && cv >= 0 && t.nrows > 0;
    double *all = ok ? malloc(t.nrows * sizeof *all) : NULL;
    ok = ok && all;
    size_t n = 0;
    for (size_t r = 0; ok && r < t.nrows; r++) {
        double L = csv_num(&t, r, cl);
        if (isfinite(L))
            all[n++] = L;
    }
    if (ok && n) {
        qsort(all, n, sizeof *all, by_double);
        size_t u = 1;
        for (size_t i = 1; i < n; i++)
            if (all[i] != all[u - 1])
                all[u++] = all[i];
        lv->lights = all;
        lv->n = u;
        lv->ntrials = x->nvalues;
        lv->mean = calloc(u * lv->ntrials, sizeof *lv->mean);
        size_t *cnt = calloc(u * lv->ntrials, sizeof *cnt);
        ok = lv->mean && cnt;
        for (size_t r = 0; ok && r < t.nrows; r++) {
            double L = csv_num(&t, r, cl), k = csv_num(&t, r, ct), v = csv_num(&t, r, cv);
            if (!isfinite(L) || !isfinite(v) || !(k >= 1 && k <= (double)lv->ntrials))
                continue;
            const double *at = bsearch(&L, lv->lights, u, sizeof *lv->lights, by_double);
            size_t i = (size_t)(at - lv->lights) * lv->ntrials + (size_t)k - 1;
            lv->mean[i] += v;
            cnt[i]++;
        }
        for (size_t i = 0; ok && i < u * lv->ntrials; i++)
            lv->mean[i] = cnt[i] ? lv->mean[i] / (double)cnt[i] : NAN;
        free(cnt);
    } else {
        free(all);   /* lv holds nothing yet */
        ok = false;
    }
    csv_table_free(&t);
    if (!ok) {
        free(lv->lights);   /* `all`, when lv took it */
        free(lv->mean);
        memset(lv, 0, sizeof *lv);
    }
    return ok;
}

/* The crossings of a against b along the light counts both drew. */
static bool growth_pair(const levels *a, const levels *b, const char *ca, const char *cb,
                        const char *group, crossover_list *out)
{
    size_t cap = a->n < b->n ? a->n : b->n, nt = a->ntrials < b->ntrials ? a->ntrials
                                                                          : b->ntrials;
    double *x = malloc((cap ? cap : 1) * sizeof *x);
    ratio_ci *r = malloc((cap ? cap : 1) * sizeof *r);
    bool ok = x && r;
    size_t n = 0;
    for (size_t i = 0, j = 0; ok && i < a->n && j < b->n;) {
        if (a->lights[i] < b->lights[j]) {
            i++;
        } else if (b->lights[j] < a->lights[i]) {
            j++;
        } else {
            x[n] = a->lights[i];
            verdict_paired_ratio(a->mean + i * a->ntrials, b->mean + j * b->ntrials, nt, &r[n]);
            n += isfinite(r[n].ratio);
            i++;
            j++;
        }
    }
    ok = ok && push_crossings(x, r, n, "lights (growing over time)", group, ca, cb, out);
    free(x);
    free(r);
    return ok;
}

bool crossovers_growth(const char *out_dir, const run_result *runs, const summary_point *pts,
                       size_t npts, const csv_table *pl, const long *prow,
                       char *const *rcfg, crossover_list *out)
{
    int cc = csv_col(pl, "lights.count");
    bool ok = true;
    for (size_t k = 0; ok && cc >= 0 && k < npts; k++) {
        const summary_point *p = &pts[k];
        if (p->nruns < 2 || prow[p->runs[0]] < 0 ||
            strncmp(pl->rows[prow[p->runs[0]]][cc], "start:", 6) != 0)
            continue;   /* a fixed light count: nothing grows */
        levels *lv = calloc(p->nruns, sizeof *lv);
        bool *have = calloc(p->nruns, sizeof *have);
        ok = lv && have;
        for (size_t i = 0; ok && i < p->nruns; i++)
            have[i] = isfinite(runs[p->runs[i]].mean) &&
                      read_levels(out_dir, &runs[p->runs[i]], &lv[i]);
        out->axes += ok;
        const char *group = strcmp(p->label, "all runs") == 0 ? "" : p->label;
        /* pairs in name order, as along a swept key */
        for (size_t i = 0; ok && i < p->nruns; i++)
            for (size_t j = 0; ok && j < p->nruns; j++) {
                const char *ci = rcfg[p->runs[i]], *cj = rcfg[p->runs[j]];
                if (have[i] && have[j] && strcmp(ci, cj) < 0)
                    ok = growth_pair(&lv[i], &lv[j], ci, cj, group, out);
            }
        for (size_t i = 0; lv && i < p->nruns; i++) {
            free(lv[i].lights);
            free(lv[i].mean);
        }
        free(lv);
        free(have);
    }
    return ok;
}

void crossovers_free(crossover_list *l)
{
    for (size_t i = 0; i < l->nstrings; i++)
        free(l->strings[i]);
    free(l->strings);
    free(l->item);
    memset(l, 0, sizeof *l);
}

static void fmt_x(char *dst, size_t len, double v)
{
    if (!isfinite(v))
        snprintf(dst, len, "?");
    else if (fabs(v) >= 100 || v == floor(v))
        snprintf(dst, len, "%.0f", v);
    else
        snprintf(dst, len, "%.3g", v);
}

typedef struct xtext {
    char x0[32], x1[32], x[32], lo[32], hi[32];
} xtext;

static void texts(const crossover_found *c, xtext *t)
{
    fmt_x(t->x0, sizeof t->x0, c->x0);
    fmt_x(t->x1, sizeof t->x1, c->x1);
    fmt_x(t->x, sizeof t->x, c->x);
    fmt_x(t->lo, sizeof t->lo, c->lo);
    fmt_x(t->hi, sizeof t->hi, c->hi);
}

void crossovers_write_md(FILE *fp, const crossover_list *l)
{
    fputs("\n## Crossovers\n\n", fp);
    if (!l->axes) {
        fputs("No numeric parameter varies across the sweep points (a resolution counts as "
              "its pixels; a seed is a label), and no light count grows within a run: "
              "nothing to cross along.\n", fp);
        return;
    }
    if (!l->n) {
        fputs("None: along the numeric parameters the sweep varies, no two configurations "
              "change places.\n", fp);
        return;
    }
    fputs("Along each numeric parameter the sweep varies (the others held, as named), and "
          "along the light count where it grows within a run (`lights (growing over "
          "time)`: per trial, the mean of the metric over the frames drawn at each count; "
          "needs frames.csv), where two configurations change places: the ratio of their paired trial values at each "
          "value (as `x fastest`), its log interpolated linearly in the log of the parameter "
          "between the last value where the first is faster and the next where the second "
          "is (linearly from 0), to where it crosses 1; the 95% interval is where the "
          "ratio's interval bounds cross 1, `?` where one does not within the values run. "
          "`differs` at the two values says whether each ratio's interval excludes 1 there. "
          "An estimate between measured values, not a measurement.\n\n", fp);
    fputs("| along | where | faster below | faster above | between | crossing | 95% interval "
          "| differs below / above |\n|---|---|---|---|---|---|---|---|\n", fp);
    for (size_t i = 0; i < l->n; i++) {
        const crossover_found *c = &l->item[i];
        xtext t;
        texts(c, &t);
        /* names and values from result files: escaped (results/mdtext.h) */
        const char *cell[4] = {c->axis, c->group[0] ? c->group : "-", c->below, c->above};
        for (int k = 0; k < 4; k++) {
            fputs("| ", fp);
            md_put(fp, cell[k]);
            fputs(" ", fp);
        }
        fprintf(fp, "| %s-%s | ~%s | %s to %s | %s / %s |\n", t.x0, t.x1, t.x, t.lo, t.hi,
                c->differs0, c->differs1);
    }
}

void crossovers_print(FILE *out, const crossover_list *l, size_t max)
{
    for (size_t i = 0; i < l->n && i < max; i++) {
        const crossover_found *c = &l->item[i];
        xtext t;
        texts(c, &t);
        char ci[96];
        if (isfinite(c->lo) || isfinite(c->hi))
            snprintf(ci, sizeof ci, "95%%: %s to %s", t.lo, t.hi);
        else
            snprintf(ci, sizeof ci, "no interval: %s", strcmp(c->differs0, "n/a") == 0
                     ? "fewer than 3 trials" : "the bounds do not cross within the values run");
        fprintf(out, "crossover: %s is faster below %s ~%s (%s), %s above%s%s%s\n",
                c->below, c->axis, t.x, ci, c->above, c->group[0] ? " (" : "",
                c->group, c->group[0] ? ")" : "");
    }
    if (l->n > max)
        fprintf(out, "... %zu more crossovers\n", l->n - max);
    if (l->axes && !l->n)
        fprintf(out, "crossovers: none: along the numeric parameters the sweep varies, no two "
                "configurations change places\n");
}
