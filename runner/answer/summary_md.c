#include "runner/answer/summary_md.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "results/mdtext.h"
#include "results/csvread.h"
#include "common/fsutil.h"
#include "runner/answer/crossovers.h"
#include "runner/answer/device_note.h"
#include "runner/answer/summary_bound.h"
#include "runner/manifest/params.h"
#include "runner/answer/point_verdict.h"
#include "runner/answer/summary_json.h"
#include "runner/answer/summary_long.h"

typedef summary_point point;

static const run_result *rank_base;
static int by_frametime(const void *pa, const void *pb)
{
    const run_result *a = &rank_base[*(const size_t *)pa], *b = &rank_base[*(const size_t *)pb];
    bool oka = isfinite(a->mean), okb = isfinite(b->mean);
    if (oka != okb)
        return oka ? -1 : 1;
    if (oka && a->mean != b->mean)
        return a->mean < b->mean ? -1 : 1;
    /* stable: pl order */
    size_t ia = *(const size_t *)pa, ib = *(const size_t *)pb;
    return ia < ib ? -1 : ia > ib;
}

static char *label_of(const csv_table *pl, long row, const bool *varies)
{
    size_t cap = 256, len = 0;
    char *s = malloc(cap);
    if (!s)
        return NULL;
    s[0] = 0;
    for (size_t c = 0; row >= 0 && c < pl->ncols; c++) {
        if (!varies[c])
            continue;
        size_t need = strlen(pl->header[c]) + strlen(pl->rows[row][c]) + 4;
        if (len + need >= cap) {
            cap = (len + need) * 2;
            char *t = realloc(s, cap);
            if (!t) {
                free(s);
                return NULL;
            }
            s = t;
        }
        len += (size_t)snprintf(s + len, cap - len, "%s%s=%s", len ? ", " : "",
                                pl->header[c], pl->rows[row][c]);
    }
    if (!len)
        snprintf(s, cap, "%s", row >= 0 ? "all runs" : "runs not in plan.csv");
    return s;
}

/* "renderer" or "renderer v1/v2": the renderer and its values of the swept
 * parameters only it reads. */
static char *config_of(const csv_table *pl, long row, const bool *cvaries, const char *rname)
{
    size_t cap = strlen(rname) + 2, len;
    for (size_t c = 0; row >= 0 && c < pl->ncols; c++)
        if (cvaries[c])
            cap += strlen(pl->rows[row][c]) + 1;
    char *s = malloc(cap);
    if (!s)
        return NULL;
    len = (size_t)snprintf(s, cap, "%s", rname);
    bool first = true;
    for (size_t c = 0; row >= 0 && c < pl->ncols; c++) {
        const param *pd = cvaries[c] ? summary_config_column(pl->header[c]) : NULL;
        if (!pd || !param_read_by(pd, rname))
            continue;
        len += (size_t)snprintf(s + len, cap - len, "%s%s", first ? " " : "/", pl->rows[row][c]);
        first = false;
    }
    return s;
}

/* ---- formatting */

static int decimals_for(double ms)
{
    double a = fabs(ms);
    return a < 1 ? 4 : a < 10 ? 3 : a < 100 ? 2 : 1;
}

static void fmt_ms(char *dst, size_t len, double us, int dec)
{
    if (isfinite(us))
        snprintf(dst, len, "%.*f", dec, us / 1000);
    else
        snprintf(dst, len, "-");
}

typedef struct cells {
    char rank[24], mean[32], ci[32], wall[64], ratio[48], sig[16], p99[32], low[32], rmse[32];
    char reach[48], evals[32], coverage[32];
} cells;

/* A table cell: the printf of its values where they are finite (`have`), else "-". */
__attribute__((format(printf, 4, 5)))
static void cell(char *out, size_t len, bool have, const char *fmt, ...)
{
    if (!have) {
        snprintf(out, len, "-");
        return;
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out, len, fmt, ap);
    va_end(ap);
}

static void make_cells(const run_result *x, const run_result *fastest, size_t rank, cells *o)
{
    memset(o, 0, sizeof *o);
    bool ok = isfinite(x->mean);
    snprintf(o->rank, sizeof o->rank, "%s", ok ? "" : "-");
    if (ok)
        snprintf(o->rank, sizeof o->rank, "%zu", rank);
    int dec = decimals_for(x->mean / 1000);
    fmt_ms(o->mean, sizeof o->mean, x->mean, dec);
    fmt_ms(o->ci, sizeof o->ci, x->half, dec);
    char wm[24], wc[24];
    int wdec = decimals_for(x->wall_mean / 1000);
    fmt_ms(wm, sizeof wm, x->wall_mean, wdec);
    fmt_ms(wc, sizeof wc, x->wall_half, wdec);
    snprintf(o->wall, sizeof o->wall, "%s ± %s", wm, wc);
    if (!ok || !fastest) {
        snprintf(o->ratio, sizeof o->ratio, "-");
        snprintf(o->sig, sizeof o->sig, "-");
    } else if (x == fastest) {
        snprintf(o->ratio, sizeof o->ratio, "1.00x");
        snprintf(o->sig, sizeof o->sig, "-");
    } else {
        ratio_ci r;
        summary_paired_ratio(x, fastest, &r);
        if (isfinite(r.lo))
            snprintf(o->ratio, sizeof o->ratio, "%.2fx (%.2f-%.2f)", r.ratio, r.lo, r.hi);
        else if (isfinite(r.ratio))
            snprintf(o->ratio, sizeof o->ratio, "%.2fx", r.ratio);
        else
            snprintf(o->ratio, sizeof o->ratio, "%.2fx", x->mean / fastest->mean);
        snprintf(o->sig, sizeof o->sig, "%s", summary_differs(&r));
    }
    fmt_ms(o->p99, sizeof o->p99, x->p99_us, decimals_for(x->p99_us / 1000));
    cell(o->low, sizeof o->low, isfinite(x->low1_fps), "%.1f", x->low1_fps);
    cell(o->rmse, sizeof o->rmse, isfinite(x->rmse), "%.4g", x->rmse);
    cell(o->reach, sizeof o->reach, isfinite(x->reach_mean) && isfinite(x->lights),
         "%.2f of %.0f", x->reach_mean, x->lights);
    cell(o->evals, sizeof o->evals, isfinite(x->evals), "%.2f", x->evals);
    cell(o->coverage, sizeof o->coverage, isfinite(x->coverage), "%.1f%%", 100 * x->coverage);
}

static const char md_intro[] =
    "Per sweep point (the runs whose parameters are equal but for the renderer and the "
    "keys only some renderers read, whose values follow the renderer's name), the "
    "configurations ranked by the mean over their ok trials of the metric that decides "
    "(named in each table: cpu is the process's CPU time per frame over all its threads, "
    "wall the frame time, gpu GL_TIME_ELAPSED; measure.metric), ± the half-width of its "
    "95% t interval over the trials (each trial is a process of its own: the unit of "
    "replication). `x fastest` is the geometric mean of the per-round ratios to the "
    "fastest (round k ran trial k of each configuration, back to back in a random order) "
    "with its 95% interval; `differs` is yes when that interval excludes 1, n/a with "
    "fewer than 3 paired trials. Wall frame time is shown beside the metric; p99 is the mean "
    "of the trials' 99th-percentile frame time and `1% low` the FPS at that frame time "
    "(1e6 / p99 us: the slowest 1% of frames run at this rate or below); RMSE is the "
    "largest image error against the reference where the manifest measures it. The "
    "workload beside them: `lights a pixel` is how many of the run's lights reach a "
    "covered pixel's surface, on average (the same for every renderer of a point: the "
    "scene's own figure, counted in the first measured frame), `evals a pixel` the light "
    "evaluations the renderer's shading loops make a covered pixel (renderers with light "
    "lists only; above `lights a pixel` by what culling lets through in vain), `coverage` "
    "the fraction of the screen the scene covers. `trials` counts the ok ones and names a "
    "partial run's status (`partial:<reason>`: some trials ok, the first other failed so); "
    "a run with no ok trial shows its failure in place of its time. Under each table, "
    "`Verdict:` names the fastest, those that tie with it (their `x fastest` interval holds "
    "1) and the next.\n";

/* Prints s left-aligned in a field of `width` columns (UTF-8 aware for "±"). */
static void tcell(FILE *fp, const char *s, int width)
{
    int cols = 0;
    for (const unsigned char *q = (const unsigned char *)s; *q; q++)
        cols += (*q & 0xC0) != 0x80;
    fprintf(fp, "%s%*s", s, width > cols ? width - cols : 0, "");
}

#define TERM_MAX_POINTS 8
#define TERM_MAX_ROWS 12

static void term_header(FILE *t, bool with_point, int cfg_width, const char *metric)
{
    char m[32];
    snprintf(m, sizeof m, "%s ms", metric);
    fputs("  ", t);
    tcell(t, "#", 4);
    tcell(t, "renderer", cfg_width);
    tcell(t, m, 20);
    tcell(t, "x fastest", 24);
    tcell(t, "differs", 8);
    tcell(t, "p99 ms", 9);
    tcell(t, "1% low fps", 11);
    tcell(t, "rmse", 10);
    if (with_point)
        fputs("point", t);
    fputs("\n", t);
}

static bool table_write(const char *out_dir, FILE *terminal, char *err, size_t errlen)
{
    afile_set set = {0};   /* summary.json, summary_long.csv, summary.md: renamed together */
    char path[4200];
    snprintf(path, sizeof path, "%s/summary.csv", out_dir);
    run_result *runs = NULL;
    size_t nruns = 0;
    if (!summary_load_runs(path, &runs, &nruns, err, errlen))
        return false;
    csv_table pl, sm;   /* plan.csv; summary.csv as text, for the files for scripts */
    if (!csv_read(path, &sm, err, errlen)) {
        summary_free_runs(runs, nruns);
        return false;
    }
    snprintf(path, sizeof path, "%s/plan.csv", out_dir);
    if (!csv_read(path, &pl, err, errlen)) {
        csv_table_free(&sm);
        summary_free_runs(runs, nruns);
        return false;
    }
    size_t nalloc = nruns ? nruns : 1;
    bool *varies = calloc(pl.ncols ? pl.ncols : 1, sizeof *varies);
    long *prow = calloc(nalloc, sizeof *prow);
    point *pts = calloc(nalloc, sizeof *pts);
    size_t *idx = calloc(nalloc, sizeof *idx), *all = calloc(nalloc, sizeof *all);
    char **rlabel = calloc(nalloc, sizeof *rlabel);
    bool *done = calloc(nalloc, sizeof *done);
    size_t npts = 0;
    csv_index pix = {0};   /* plan rows by run id: a look-up each, not a scan */
    bool ok = varies && prow && pts && idx && all && rlabel && done &&
              csv_index_build(&pix, &pl, "run_id");
    for (size_t r = 0; ok && r < nruns; r++) {
        size_t first;
        prow[r] = csv_index_find(&pix, runs[r].id, &first) ? (long)pix.item[first].row : -1;
    }
    csv_index_free(&pix);
    /* a parameter varies when two runs of this summary differ in it */
    bool *cvaries = calloc(pl.ncols ? pl.ncols : 1, sizeof *cvaries);
    char **rcfg = calloc(nalloc, sizeof *rcfg);
    ok = ok && cvaries && rcfg;
    for (size_t c = 0; ok && c < pl.ncols; c++) {
        if (summary_meta_column(pl.header[c]))
            continue;
        bool v = false;
        for (size_t r = 1; r < nruns && !v; r++)
            if (prow[r] >= 0 && prow[0] >= 0 &&
                strcmp(pl.rows[prow[r]][c], pl.rows[prow[0]][c]) != 0)
                v = true;
        if (summary_config_column(pl.header[c]))
            cvaries[c] = v;
        else
            varies[c] = v;
    }
    for (size_t r = 0; ok && r < nruns; r++) {
        ok = (rlabel[r] = label_of(&pl, prow[r], varies)) != NULL &&
             (rcfg[r] = config_of(&pl, prow[r], cvaries, runs[r].renderer)) != NULL;
    }
    /* the points in order of first appearance; each point's runs ranked */
    size_t *next = idx;
    bool single = nruns > 1;   /* every point has one run: one renderer */
    for (size_t r = 0; ok && r < nruns; r++) {
        if (done[r])
            continue;
        point *p = &pts[npts++];
        p->runs = next;
        for (size_t q = r; q < nruns; q++)
            if (!done[q] && summary_same_row(&pl, prow[r], prow[q])) {
                done[q] = true;
                next[p->nruns++] = q;
            }
        next += p->nruns;
        single = single && p->nruns == 1;
        rank_base = runs;
        qsort(p->runs, p->nruns, sizeof *p->runs, by_frametime);
        p->label = rlabel[r];
    }
    if (!ok) {
        snprintf(err, errlen, "out of memory");
        goto out;
    }
    /* One renderer: the points' runs ranked against each other in one table. */
    point one = {.label = "every run (one renderer: the sweep points ranked)", .runs = all,
                 .nruns = nruns};
    for (size_t r = 0; r < nruns; r++)
        all[r] = r;
    rank_base = runs;
    qsort(all, nruns, sizeof *all, by_frametime);
    point *shown = single ? &one : pts;
    int cfg_width = 14;   /* the renderer column: the longest configuration, + 2 */
    for (size_t r = 0; r < nruns; r++)
        if ((int)strlen(rcfg[r]) + 2 > cfg_width)
            cfg_width = (int)strlen(rcfg[r]) + 2;
    size_t nshown = single ? 1 : npts;

    char mdpath[4200];
    snprintf(mdpath, sizeof mdpath, "%s/summary.md", out_dir);
    afile f;
    if (!(ok = afile_open(&f, mdpath, err, errlen)))
        goto out;
    f.set = &set;
    const char *exp = nruns ? runs[0].experiment : "";
    /* every name below comes from result files: escaped (results/mdtext.h) */
    fputs("# ", f.fp);
    md_put(f.fp, *exp ? exp : out_dir);
    fputs(": the renderers ranked per sweep point\n\n", f.fp);
    fputs(md_intro, f.fp);
    /* on a CPU rasterizer, or across devices: said before any table (device_note.h) */
    device_note dn;
    device_note_of(out_dir, runs, nruns, &dn);
    if (dn.line[0]) {
        fputs("\n**Device:** ", f.fp);
        md_put(f.fp, dn.line);
        fputs(".\n", f.fp);
    }
    if (terminal)
        fprintf(terminal, "\n%s: %zu run%s, %zu sweep point%s; %s time per frame, ms: mean ± "
                "95%% CI over the trials\n", *exp ? exp : out_dir, nruns, nruns == 1 ? "" : "s",
                npts, npts == 1 ? "" : "s", nruns && runs[0].metric[0] ? runs[0].metric : "wall");
    if (!nruns)
        fputs("\nNo run has results yet.\n", f.fp);
    for (size_t k = 0; k < nshown; k++) {
        point *p = &shown[k];
        const run_result *fastest = &runs[p->runs[0]];
        if (!isfinite(fastest->mean))
            fastest = NULL;
        const char *metric = "wall";
        for (size_t i = 0; i < p->nruns; i++)
            if (runs[p->runs[i]].metric[0]) {
                metric = runs[p->runs[i]].metric;
                break;
            }
        fputs("\n## ", f.fp);
        md_put(f.fp, p->label);
        fputs("\n\nRanked by ", f.fp);
        md_put(f.fp, metric);
        fprintf(f.fp, " time per frame.\n\n| rank | renderer |%s run | ", single ? " point |" : "");
        md_put(f.fp, metric);
        fprintf(f.fp, " (ms) | x fastest | differs | wall (ms) | "
                "p99 (ms) | 1%% low (FPS) | RMSE | lights a pixel | evals a pixel | coverage | "
                "trials |\n"
                "|---|---|%s---|---|---|---|---|---|---|---|---|---|---|---|\n", single ? "---|" : "");
        bool term = terminal && k < TERM_MAX_POINTS;
        if (term) {
            fprintf(terminal, "%s\n", p->label);
            term_header(terminal, single, cfg_width, metric);
        }
        for (size_t i = 0; i < p->nruns; i++) {
            const run_result *x = &runs[p->runs[i]];
            cells c;
            make_cells(x, fastest, i + 1, &c);
            char ft[160], trials[160];
            if (isfinite(x->mean))
                snprintf(ft, sizeof ft, "%s ± %s", c.mean, c.ci);
            else
                snprintf(ft, sizeof ft, "%s", x->status);
            snprintf(trials, sizeof trials, "%zu of %zu ok%s%s", x->trials_ok, x->trials,
                     isfinite(x->mean) && strcmp(x->status, "ok") ? ", " : "",
                     isfinite(x->mean) && strcmp(x->status, "ok") ? x->status : "");
            fprintf(f.fp, "| %s | ", c.rank);
            md_put(f.fp, rcfg[p->runs[i]]);
            fputs(" |", f.fp);
            if (single) {
                fputs(" ", f.fp);
                md_put(f.fp, rlabel[p->runs[i]]);
                fputs(" |", f.fp);
            }
            fputs(" ", f.fp);
            md_put(f.fp, x->id);
            fputs(" | ", f.fp);
            md_put(f.fp, ft);
            fprintf(f.fp, " | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", c.ratio,
                    c.sig, c.wall, c.p99, c.low, c.rmse, c.reach, c.evals, c.coverage, trials);
            if (term && i < TERM_MAX_ROWS) {
                fputs("  ", terminal);
                tcell(terminal, c.rank, 4);
                tcell(terminal, rcfg[p->runs[i]], cfg_width);
                tcell(terminal, ft, 20);
                tcell(terminal, c.ratio, 24);
                tcell(terminal, c.sig, 8);
                tcell(terminal, c.p99, 9);
                tcell(terminal, c.low, 11);
                tcell(terminal, c.rmse, 10);
                fprintf(terminal, "%s\n", single ? rlabel[p->runs[i]] : "");
            }
        }
        if (term && p->nruns > TERM_MAX_ROWS)
            fprintf(terminal, "  ... %zu more\n", p->nruns - TERM_MAX_ROWS);
        char said[1024];
        if (point_verdict(runs, p, rcfg, said, sizeof said)) {
            fputs("\nVerdict: ", f.fp);
            md_put(f.fp, said);
            fputs(".\n", f.fp);
        }
    }
    if (terminal && nshown > TERM_MAX_POINTS)
        fprintf(terminal, "... %zu more sweep points\n", nshown - TERM_MAX_POINTS);
    /* where two configurations change places along a numeric parameter */
    crossover_list cx;
    if (!crossovers_find(runs, nruns, &pl, prow, varies, rcfg, &cx) ||
        !crossovers_growth(out_dir, runs, pts, npts, &pl, prow, rcfg, &cx)) {
        crossovers_free(&cx);
        afile_abort(&f);
        snprintf(err, errlen, "out of memory");
        ok = false;
        goto out;
    }
    crossovers_write_md(f.fp, &cx);
    /* the same for scripts */
    summary_view view = {exp, runs, nruns, &pl, &sm, prow, varies, rcfg, shown, nshown, &cx,
                         &dn};
    if (!summary_json_write(out_dir, &view, &set, err, errlen) ||
        !summary_long_write(out_dir, &pl, &sm, &set, err, errlen)) {
        crossovers_free(&cx);
        afile_abort(&f);
        ok = false;
        goto out;
    }
    summary_bound_md(f.fp, out_dir, &sm);   /* each run's bound and limiter */
    /* what makes these verdicts doubtful, named per trial */
    fputs("\n## Warnings\n\n", f.fp);
    if (!summary_warnings(runs, nruns, f.fp, "- ", true))
        fputs("None: no trial is an outlier among its run's, none ran on a busy machine, "
              "no run's workload is brute force.\n", f.fp);
    if (terminal)
        summary_warnings(runs, nruns, terminal, "warning: ", false);
    ok = afile_commit(&f, err, errlen) && afile_set_commit(&set, err, errlen);
    if (ok && terminal) {
        fprintf(terminal, "ranked: %s (the definitions are there)\n", mdpath);
        if (dn.line[0])   /* above the answer, which stays last (crossovers.sh) */
            fprintf(terminal, "device: %s\n", dn.line);
        /* the answer: who wins at each point, then along the swept axes, last */
        point_verdicts_print(terminal, runs, shown, nshown, rcfg);
        crossovers_print(terminal, &cx);
    }
    crossovers_free(&cx);
out:
    afile_set_abort(&set);   /* what a failure left uncommitted */
    for (size_t r = 0; rlabel && r < nruns; r++)
        free(rlabel[r]);
    free(rlabel);
    for (size_t r = 0; rcfg && r < nruns; r++)
        free(rcfg[r]);
    free(rcfg);
    free(cvaries);
    free(done);
    free(idx);
    free(all);
    free(pts);
    free(prow);
    free(varies);
    csv_table_free(&pl);
    csv_table_free(&sm);
    summary_free_runs(runs, nruns);
    return ok;
}

/* On a failure the summaries of an earlier run, resume or merge would stay beside a
 * summary.csv that has other runs: they are removed (the next --resume writes them
 * again), and the message names each, or each one that stays stale. */
bool summary_table_write(const char *out_dir, FILE *terminal, char *err, size_t errlen)
{
    if (table_write(out_dir, terminal, err, errlen))
        return true;
    static const char *const derived[] = {"summary.md", "summary.json", "summary_long.csv"};
    char removed[128] = "", stale[512] = "";
    for (size_t i = 0; i < sizeof derived / sizeof *derived; i++) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", out_dir, derived[i]);
        if (unlink(path) == 0)
            snprintf(removed + strlen(removed), sizeof removed - strlen(removed), "%s%s",
                     removed[0] ? ", " : "", derived[i]);
        else if (errno != ENOENT)
            snprintf(stale + strlen(stale), sizeof stale - strlen(stale),
                     "; %s is stale (cannot remove it: %s)", derived[i], strerror(errno));
    }
    size_t n = strlen(err);
    if (removed[0])
        snprintf(err + n, errlen - n, "; removed %s, which would describe other runs "
                 "than summary.csv", removed);
    n = strlen(err);
    snprintf(err + n, errlen - n, "%s", stale);
    return false;
}
