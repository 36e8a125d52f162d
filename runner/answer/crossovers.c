/* Where two configurations change places along the numeric parameters a sweep varies
 * (runner/answer/crossovers.h). */
#include "runner/answer/crossovers.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "results/mdtext.h"
#include "common/grow.h"

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

/* Whether r (a / b) lies below 1 (side -1) or above it (+1); 0 when not finite or 1. */
static int side_of(const ratio_ci *r)
{
    return !(isfinite(r->ratio) && r->ratio > 0) || r->ratio == 1 ? 0 : r->ratio < 1 ? -1 : 1;
}

/* Whether r's interval lies wholly on `side` of 1. */
static bool decided(const ratio_ci *r, int side)
{
    return side < 0 ? r->hi < 1 : r->lo > 1;
}

/* Whether the crossing co of a / b is one to report: the configuration faster below is
 * the fastest of all (lead[k]: the fastest at x[k]; NULL: unknown) at x[i] and the one
 * faster above at x[j], and the evidence holds: the ratio's interval lies on its side of
 * 1 at both x[i] and x[j], or two points each side are on their side (x[i-1] with x[i],
 * x[j+1] with x[j]). */
static bool worth_reporting(const ratio_ci *r, size_t n, const char *const *lead,
                            const ratio_crossover *co, const char *below, const char *above)
{
    if (!lead[co->i] || !lead[co->j] || strcmp(lead[co->i], below) != 0 ||
        strcmp(lead[co->j], above) != 0)
        return false;
    int s0 = side_of(&r[co->i]), s1 = side_of(&r[co->j]);
    if (decided(&r[co->i], s0) && decided(&r[co->j], s1))
        return true;
    return co->i > 0 && side_of(&r[co->i - 1]) == s0 && co->j + 1 < n &&
           side_of(&r[co->j + 1]) == s1;
}

/* Every crossing of a / b (ratios r at x[0..n), ascending) through 1 worth reporting,
 * named (a / b rising through 1 makes a the faster below the crossing); the others
 * counted in out->pruned. */
static bool push_crossings(const double *x, const ratio_ci *r, const char *const *lead,
                           size_t n, const char *axis, const char *group, const char *a,
                           const char *b, crossover_list *out)
{
    ratio_crossover co;
    for (size_t from = 0; n >= 2 && verdict_crossover(x, r, n, from, &co); from = co.j) {
        crossover_found f = {
            .axis = axis, .group = group,
            .below = co.dir > 0 ? a : b, .above = co.dir > 0 ? b : a,
            .x0 = x[co.i], .x1 = x[co.j], .x = co.x, .lo = co.lo, .hi = co.hi,
            .differs0 = summary_differs(&r[co.i]), .differs1 = summary_differs(&r[co.j]),
        };
        if (!worth_reporting(r, n, lead, &co, f.below, f.above))
            out->pruned++;
        else if (!push(out, &f))
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

/* The configuration with the least mean among a group's entries e[g0..g1) at x. */
static const char *leader_at(const run_result *runs, const entry *e, size_t g0, size_t g1,
                             double x)
{
    const entry *best = NULL;
    for (size_t k = g0; k < g1; k++)
        if (e[k].x == x && (!best || runs[e[k].run].mean < runs[best->run].mean))
            best = &e[k];
    return best ? best->cfg : NULL;
}

/* The crossings of configurations a and b (entries e[a0..a1) and e[b0..b1), each
 * ascending in x) at the x values both have; their group's entries are e[g0..g1). */
static bool pair_crossings(const run_result *runs, const entry *e, size_t g0, size_t g1,
                           size_t a0, size_t a1, size_t b0, size_t b1, const char *axis,
                           crossover_list *out)
{
    size_t cap = (a1 - a0) < (b1 - b0) ? a1 - a0 : b1 - b0;
    double *x = malloc((cap ? cap : 1) * sizeof *x);
    ratio_ci *r = malloc((cap ? cap : 1) * sizeof *r);
    const char **lead = malloc((cap ? cap : 1) * sizeof *lead);
    bool ok = x && r && lead;
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
                lead[n] = leader_at(runs, e, g0, g1, x[n]);
                n++;
            }
            i++;
            j++;
        }
    }
    ok = ok && push_crossings(x, r, lead, n, axis, e[a0].group, e[a0].cfg, e[b0].cfg, out);
    free(x);
    free(r);
    free(lead);
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
                ok = pair_crossings(runs, e, g0, g1, a0, a1, b0, b1, pl->header[axis],
                                    out);
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

/* The mean over its trials of run lv's metric at light count L; NAN where it drew none. */
static double level_mean(const levels *lv, double L)
{
    const double *at = lv->n ? bsearch(&L, lv->lights, lv->n, sizeof *lv->lights, by_double)
                             : NULL;
    double s = 0;
    size_t m = 0;
    for (size_t t = 0; at && t < lv->ntrials; t++) {
        double v = lv->mean[(size_t)(at - lv->lights) * lv->ntrials + t];
        if (isfinite(v))
            s += v, m++;
    }
    return m ? s / (double)m : NAN;
}

/* The configuration fastest at light count L among a point's nr runs (those with
 * have[k]): the least mean over the trials. */
static const char *growth_leader(const levels *lv, const bool *have, const char *const *cfg,
                                 size_t nr, double L)
{
    const char *best = NULL;
    double bv = INFINITY;
    for (size_t k = 0; k < nr; k++) {
        double v = have[k] ? level_mean(&lv[k], L) : NAN;
        if (v < bv)
            bv = v, best = cfg[k];
    }
    return best;
}

/* The crossings of runs ia against ib of a point (lv, have, cfg: its nr runs) along the
 * light counts both drew. */
static bool growth_pair(const levels *lv, const bool *have, const char *const *cfg,
                        size_t nr, size_t ia, size_t ib, const char *group,
                        crossover_list *out)
{
    const levels *a = &lv[ia], *b = &lv[ib];
    size_t cap = a->n < b->n ? a->n : b->n, nt = a->ntrials < b->ntrials ? a->ntrials
                                                                          : b->ntrials;
    double *x = malloc((cap ? cap : 1) * sizeof *x);
    ratio_ci *r = malloc((cap ? cap : 1) * sizeof *r);
    const char **lead = malloc((cap ? cap : 1) * sizeof *lead);
    bool ok = x && r && lead;
    size_t n = 0;
    for (size_t i = 0, j = 0; ok && i < a->n && j < b->n;) {
        if (a->lights[i] < b->lights[j]) {
            i++;
        } else if (b->lights[j] < a->lights[i]) {
            j++;
        } else {
            x[n] = a->lights[i];
            verdict_paired_ratio(a->mean + i * a->ntrials, b->mean + j * b->ntrials, nt, &r[n]);
            lead[n] = growth_leader(lv, have, cfg, nr, x[n]);
            n += isfinite(r[n].ratio);
            i++;
            j++;
        }
    }
    ok = ok && push_crossings(x, r, lead, n, "lights (growing over time)", group, cfg[ia],
                              cfg[ib], out);
    free(x);
    free(r);
    free(lead);
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
        const char **cfg = calloc(p->nruns, sizeof *cfg);
        ok = lv && have && cfg;
        for (size_t i = 0; ok && i < p->nruns; i++) {
            have[i] = isfinite(runs[p->runs[i]].mean) &&
                      read_levels(out_dir, &runs[p->runs[i]], &lv[i]);
            cfg[i] = rcfg[p->runs[i]];
        }
        out->axes += ok;
        const char *group = strcmp(p->label, "all runs") == 0 ? "" : p->label;
        /* pairs in name order, as along a swept key */
        for (size_t i = 0; ok && i < p->nruns; i++)
            for (size_t j = 0; ok && j < p->nruns; j++)
                if (have[i] && have[j] && strcmp(cfg[i], cfg[j]) < 0)
                    ok = growth_pair(lv, have, cfg, p->nruns, i, j, group, out);
        for (size_t i = 0; lv && i < p->nruns; i++) {
            free(lv[i].lights);
            free(lv[i].mean);
        }
        free(lv);
        free(have);
        free(cfg);
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
    char pruned[160] = "";
    if (l->pruned)
        snprintf(pruned, sizeof pruned, " %zu other crossing%s of configurations that do "
                 "not lead, or with too little evidence, %s left out.", l->pruned,
                 l->pruned == 1 ? "" : "s", l->pruned == 1 ? "is" : "are");
    if (!l->n) {
        fprintf(fp, "None: along the numeric parameters the sweep varies, the fastest "
                "configuration does not change.%s\n", pruned);
        return;
    }
    fputs("Along each numeric parameter the sweep varies (the others held, as named), and "
          "along the light count where it grows within a run (`lights (growing over "
          "time)`: per trial, the mean of the metric over the frames drawn at each count; "
          "needs frames.csv), where the fastest configuration changes: the ratio of the "
          "two leaders' paired trial values at each value (as `x fastest`), its log "
          "interpolated linearly in the log of the parameter between the last value where "
          "the first is the fastest of all and the next where the second is (linearly from "
          "0), to where it crosses 1; the 95% interval is where the ratio's interval "
          "bounds cross 1, `?` where one does not within the values run. `differs` at the "
          "two values says whether each ratio's interval excludes 1 there. A crossing is "
          "kept when both intervals exclude 1 or two values each side agree, and is never "
          "placed beyond the values run. An estimate between measured values, not a "
          "measurement.", fp);
    fprintf(fp, "%s\n\n", pruned);
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

void crossovers_print(FILE *out, const crossover_list *l)
{
    for (size_t i = 0; i < l->n; i++) {
        const crossover_found *c = &l->item[i];
        xtext t;
        texts(c, &t);
        char ci[96];
        if (isfinite(c->lo) || isfinite(c->hi))
            snprintf(ci, sizeof ci, "95%%: %s to %s", t.lo, t.hi);
        else
            snprintf(ci, sizeof ci, "no interval: %s", strcmp(c->differs0, "n/a") == 0
                     ? "fewer than 3 trials" : "the bounds do not cross within the values run");
        fprintf(out, "crossover: %s is the fastest below %s ~%s (%s), %s above%s%s%s\n",
                c->below, c->axis, t.x, ci, c->above, c->group[0] ? " (" : "",
                c->group, c->group[0] ? ")" : "");
    }
    if (l->axes && !l->n)
        fprintf(out, "crossovers: none: along the numeric parameters the sweep varies, the "
                "fastest configuration does not change\n");
}
