/* shadesweep compare: a regression gate.
 *
 * compare BASE NEW: the runs two output folders share (by run id). Each run's value
 * per trial is its metric (summary.csv `metric_us`: measure.metric), and the change is
 * the ratio NEW / BASE with its 95% interval from the trials (results/verdict.h): the
 * ratio of geometric means with Welch's interval on the logs, since two folders
 * measured at different times are independent samples. Verdicts at a relative
 * threshold T: slower when the whole interval lies above 1 + T, faster when below
 * 1 / (1 + T), same when inside [1 / (1 + T), 1 + T], undecided otherwise; fewer than
 * 3 trials a side give no verdict. With 5 runs or more the verdicts are on ratios
 * corrected for the common change (the machine's drift: results/drift.h) where its
 * interval excludes 1, the raw ratios beside them.
 * compare --exe (two builds, in rounds, paired), the output and the exit status:
 * the comment above cmd_compare below. */
#define _DEFAULT_SOURCE
#include "runner/answer/commands.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "results/csv.h"
#include "results/drift.h"
#include "common/fsutil.h"
#include "results/jsonout.h"
#include "runner/manifest/diag.h"
#include "runner/manifest/hash.h"
#include "runner/manifest/manifest.h"
#include "runner/answer/clock_check.h"
#include "runner/answer/device_note.h"
#include "runner/answer/run_model.h"
#include "runner/manifest/sweep_axis.h"
#include "runner/folder/trials.h"

static const char compare_usage[] =
    "usage: shadesweep compare [OPTIONS] BASE NEW\n"
    "       shadesweep compare --exe OTHER [OPTIONS] MANIFEST\n"
    "  the runs two output folders share (by run id): NEW / BASE of the metric that\n"
    "  decides (measure.metric), with its 95% interval over the trials, and a verdict\n"
    "  per run: slower, faster, same, undecided (the interval straddles the threshold)\n"
    "  or no verdict (fewer than 3 trials); with 5 runs or more, on the ratios divided\n"
    "  by their common change (the machine's drift: the median NEW / BASE) where its\n"
    "  interval excludes 1, the raw ratios beside them\n"
    "  --threshold P%      a change within P% is `same` (default 5%)\n"
    "  --allow-missing     a BASE run missing or failed in NEW does not fail the gate\n"
    "  --csv FILE          also write one CSV row per run\n"
    "  --md FILE           also write the markdown table to FILE\n"
    "  --json              JSON on stdout instead of the markdown (schema\n"
    "                      shadesweep-compare, version 1: docs/summary-json.md)\n"
    "  --exe OTHER         run MANIFEST with the shadesweep OTHER (BASE) and with this\n"
    "                      build (NEW) in interleaved rounds, then compare them paired\n"
    "  --base-manifest M   with --exe: OTHER runs M (its run ids must be MANIFEST's)\n"
    "  -o DIR              with --exe: the folders DIR/base and DIR/new\n"
    "                      (default out/<name>-compare)\n"
    "  --force             with --exe: replace DIR's folders of an earlier comparison\n"
    "exit status: 0 no run slower, none missing; 1 some run slower, or a BASE run\n"
    "failed or missing in NEW; 2 bad input\n";

typedef struct pair {
    const run_result *a, *b;   /* BASE, NEW */
    ratio_ci raw;              /* NEW / BASE as measured */
    ratio_ci r;                /* NEW / BASE the verdict is on: raw / the common change
                                * where that was applied (results/drift.h), else raw */
    verdict v;
    clock_check clk;           /* the GPU clocks of both sides (NVML; clock_check.h) */
} pair;

static bool parse_threshold(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || errno)
        return false;
    if (*end == '%')
        end++;
    if (*end || !(v >= 0 && v <= 1e6))
        return false;
    *out = v / 100;
    return true;
}

static void fmt_ms(char *dst, size_t len, double us, double ci_us)
{
    if (!isfinite(us)) {
        snprintf(dst, len, "-");
        return;
    }
    double a = fabs(us / 1000);
    int dec = a < 1 ? 4 : a < 10 ? 3 : a < 100 ? 2 : 1;
    if (isfinite(ci_us))
        snprintf(dst, len, "%.*f ± %.*f", dec, us / 1000, dec, ci_us / 1000);
    else
        snprintf(dst, len, "%.*f", dec, us / 1000);
}

#define NVERDICTS (VERDICT_UNDECIDED + 1)

/* count[v]: the pairs whose verdict is v */
static void count_verdicts(const pair *p, size_t np, size_t count[NVERDICTS])
{
    memset(count, 0, NVERDICTS * sizeof *count);
    for (size_t i = 0; i < np; i++)
        count[p[i].v]++;
}

/* The common change is beyond the threshold: the machine moved by more than it. */
static bool drift_beyond(const common_change *cc, double thr)
{
    return cc->applied && (cc->ratio > 1 + thr || cc->ratio < 1 / (1 + thr));
}

/* Above the table: the common change, whether the verdicts are corrected for it, and
 * the warning when the machine moved by more than the threshold. */
static void drift_md_lines(FILE *fp, const common_change *cc, double thr, bool paired)
{
    const char *between = paired ? "between the builds within the rounds" : "between the folders";
    if (!isfinite(cc->ratio))
        fprintf(fp, "Common change: not estimated: %zu run%s with an interval, the median "
                "needs %d (with fewer, one changed run would move it); verdicts on the raw "
                "ratios.\n\n", cc->n, cc->n == 1 ? "" : "s", DRIFT_MIN_RUNS);
    else
        fprintf(fp, "Common change %s (median of the %zu runs' NEW / BASE, robust to a few "
                "changed runs): %.4f (%.4f .. %.4f): %s.\n\n", between, cc->n, cc->ratio,
                cc->lo, cc->hi, cc->applied ? "verdicts on the ratios divided by it, the raw "
                "ratios beside them" : "its interval holds 1, no correction");
    if (drift_beyond(cc, thr))
        fprintf(fp, "**Warning:** the machine moved by %+.0f%% %s: verdicts are on ratios "
                "corrected for it.\n\n", (cc->ratio - 1) * 100, between);
}

/* compare --exe: round k's common change, the median over the runs of NEW / BASE in
 * that round (DRIFT_MIN_RUNS runs at least, else not printed), a number a round: what
 * the pairing leaves of the drift, since BASE and NEW of a round ran back to back. */
static void round_changes_line(FILE *fp, const pair *p, size_t np)
{
    size_t rounds = 0;
    for (size_t i = 0; i < np; i++)
        rounds = p[i].a->nvalues > rounds ? p[i].a->nvalues : rounds;
    double *l = malloc(2 * (np ? np : 1) * sizeof *l);
    if (!l || rounds == 0) {
        free(l);
        return;
    }
    bool any = false;
    for (size_t k = 0; k < rounds && k < 64; k++) {
        size_t m = 0;
        for (size_t i = 0; i < np; i++) {
            if (k >= p[i].a->nvalues || k >= p[i].b->nvalues)
                continue;
            double a = p[i].a->value[k], b = p[i].b->value[k];
            if (isfinite(a) && isfinite(b) && a > 0 && b > 0)
                l[m++] = log(b / a);
        }
        if (m < DRIFT_MIN_RUNS)
            continue;
        double med;
        verdict_median(l, m, l + np, &med);
        fprintf(fp, "%s round %zu %.4f", any ? "," : "Common change within each round (the "
                "median over the runs of NEW / BASE of that round; the pairing cancels the "
                "drift between rounds, these are what it leaves):", k + 1, exp(med));
        any = true;
    }
    if (any)
        fputs(".\n\n", fp);
    free(l);
}

/* Where either side has GPU clocks (NVML): each run's median SM clocks, the rounds
 * whose clocks differ by more than CLOCK_TOLERANCE, and GPU time raw and at BASE's
 * clock. Nothing without clocks (llvmpipe, other vendors). */
static void clocks_md(FILE *fp, const pair *p, size_t np, bool paired)
{
    size_t any = 0, flagged = 0;
    for (size_t i = 0; i < np; i++) {
        any += p[i].clk.any;
        flagged += p[i].clk.nflagged > 0;
    }
    if (!any)
        return;
    fprintf(fp, "\n**GPU clocks** (NVML, each trial's median SM clock): %zu of %zu run%s %s "
            "clocks more than %g%% apart%s. GPU time at BASE's clock is each trial's GPU time "
            "x its clock / BASE's median clock: what it would be if the time scaled with the "
            "SM clock (a pass bound by memory does not; the raw ratio is beside it).\n\n"
            "| run | renderer | BASE SM (MHz) | NEW SM (MHz) | GPU NEW / BASE | at BASE's "
            "clock | clocks apart |\n|---|---|---|---|---|---|---|\n", flagged, np,
            np == 1 ? "" : "s", paired ? "had rounds with" : "ran at", CLOCK_TOLERANCE * 100,
            paired ? " (a round's two trials ran minutes apart)" : "");
    for (size_t i = 0; i < np; i++) {
        const clock_check *c = &p[i].clk;
        char apart[160] = "-";
        if (c->nflagged && paired) {
            int len = snprintf(apart, sizeof apart, "round%s", c->nflagged == 1 ? "" : "s");
            for (size_t k = 0; k < c->nflagged && k < CLOCK_MAX_FLAGGED && len < 140; k++)
                len += snprintf(apart + len, sizeof apart - (size_t)len, "%s %u", k ? "," : "",
                                c->flagged[k]);
            if (c->nflagged > CLOCK_MAX_FLAGGED)
                snprintf(apart + len, sizeof apart - (size_t)len, " and %zu more",
                         c->nflagged - CLOCK_MAX_FLAGGED);
        } else if (c->nflagged) {
            snprintf(apart, sizeof apart, "**%+.1f%%**", (c->new_mhz / c->base_mhz - 1) * 100);
        }
        char g[32] = "-", gn[32] = "-";
        if (isfinite(c->gpu.ratio))
            snprintf(g, sizeof g, "%.4f", c->gpu.ratio);
        if (isfinite(c->gpu_norm.ratio))
            snprintf(gn, sizeof gn, "%.4f", c->gpu_norm.ratio);
        fprintf(fp, "| %s | %s | %.0f | %.0f | %s | %s | %s |\n", p[i].a->id, p[i].a->renderer,
                c->base_mhz, c->new_mhz, g, gn, apart);
    }
}

/* dn[0], dn[1]: the devices of BASE and NEW (device_note.h) */
static void write_md(FILE *fp, const char *base, const char *new_, double thr, bool paired,
                     const pair *p, size_t np, size_t only_base, size_t only_new,
                     const device_note *dn, const common_change *cc)
{
    size_t count[NVERDICTS];
    count_verdicts(p, np, count);
    const char *metric = np ? p[0].a->metric : "wall";
    fprintf(fp, "# compare: `%s` -> `%s`\n\n", base, new_);
    fprintf(fp, "Each trial is a process of its own; a run's value per trial is its mean %s "
            "time per frame (measure.metric). NEW / BASE is %s with its 95%% interval. A run "
            "is **slower** when the whole interval lies above %g (a change of more than "
            "%g%%), **faster** when it lies below 1/%g, `same` when it lies within "
            "[1/%g, %g], `undecided` when it straddles a threshold (more trials would "
            "decide), and has no verdict with fewer than 3 trials a side. Times in ms, ± the "
            "half-width of the 95%% interval over the trials.\n\n", metric,
            paired ? "the geometric mean of the per-round ratios (BASE and NEW ran trial k "
                     "in the same round)"
                   : "the ratio of geometric means (Welch's interval on the logs: two "
                     "folders measured at different times are independent)",
            1 + thr, thr * 100, 1 + thr, 1 + thr, 1 + thr);
    bool same = strcmp(dn[0].line, dn[1].line) == 0;   /* one line for both */
    for (int k = same; k < 2; k++)
        if (dn[k].line[0])
            fprintf(fp, "**Device of %s:** %s.\n\n", same ? "BASE and NEW" : k ? "NEW" : "BASE",
                    dn[k].line);
    drift_md_lines(fp, cc, thr, paired);
    if (paired)
        round_changes_line(fp, p, np);
    fprintf(fp, "| run | renderer | BASE (ms) | NEW (ms) | NEW / BASE | 95%% interval | %strials "
                "| verdict |\n|---|---|---|---|---|---|---|---|%s\n",
            cc->applied ? "raw NEW / BASE | raw interval | " : "", cc->applied ? "---|---|" : "");
    for (size_t i = 0; i < np; i++) {
        char a[64], b[64], ch[32] = "-", ci[64] = "-";
        fmt_ms(a, sizeof a, p[i].a->mean, p[i].a->half);
        fmt_ms(b, sizeof b, p[i].b->mean, p[i].b->half);
        if (isfinite(p[i].r.ratio))
            snprintf(ch, sizeof ch, "%.4f", p[i].r.ratio);
        if (isfinite(p[i].r.lo))
            snprintf(ci, sizeof ci, "%.4f .. %.4f", p[i].r.lo, p[i].r.hi);
        char raw[96] = "";
        if (cc->applied)
            snprintf(raw, sizeof raw, "%.4f | %.4f .. %.4f | ", p[i].raw.ratio, p[i].raw.lo,
                     p[i].raw.hi);
        const char *v = verdict_name(p[i].v);
        bool bold = p[i].v == VERDICT_SLOWER || p[i].v == VERDICT_FASTER;
        fprintf(fp, "| %s | %s | %s | %s | %s | %s | %s%zu | %s%s%s |\n", p[i].a->id,
                p[i].a->renderer, trials_status_measured(p[i].a->status) ? a : p[i].a->status,
                trials_status_measured(p[i].b->status) ? b : p[i].b->status, ch, ci, raw, p[i].r.n,
                bold ? "**" : "", v, bold ? "**" : "");
    }
    fprintf(fp, "\n%zu run%s in common: %zu slower, %zu faster, %zu same, %zu undecided, %zu "
            "without a verdict (failed, or fewer than 3 trials); %zu only in BASE, %zu only "
            "in NEW.\n", np, np == 1 ? "" : "s", count[VERDICT_SLOWER], count[VERDICT_FASTER],
            count[VERDICT_SAME], count[VERDICT_UNDECIDED], count[VERDICT_NONE], only_base,
            only_new);
    clocks_md(fp, p, np, paired);
}

/* The table as JSON (--json): what write_md says, for scripts; docs/summary-json.md. */
static void write_json(FILE *fp, const char *base, const char *new_, double thr, bool paired,
                       const pair *p, size_t np, size_t only_base, size_t only_new,
                       const device_note *dn, const common_change *cc)
{
    size_t count[NVERDICTS];
    count_verdicts(p, np, count);
    bool first = true;
    fputs("{", fp);
    json_member_string(fp, &first, "schema", "shadesweep-compare");
    json_member_number(fp, &first, "version", 1);
    json_member_string(fp, &first, "base", base);
    json_member_string(fp, &first, "new", new_);
    json_member_string(fp, &first, "metric", np ? p[0].a->metric : "wall");
    json_member_number(fp, &first, "threshold", thr);
    json_key(fp, &first, "paired");
    fputs(paired ? "true" : "false", fp);
    json_key(fp, &first, "common_change");
    fputs("{", fp);
    bool fc = true;
    json_member_number(fp, &fc, "ratio", cc->ratio);
    json_member_number(fp, &fc, "ratio_lo", cc->lo);
    json_member_number(fp, &fc, "ratio_hi", cc->hi);
    json_member_number(fp, &fc, "runs", (double)cc->n);
    json_key(fp, &fc, "applied");
    fputs(cc->applied ? "true" : "false", fp);
    json_key(fp, &fc, "beyond_threshold");
    fputs(drift_beyond(cc, thr) ? "true" : "false", fp);
    fputs("}", fp);
    json_key(fp, &first, "runs");
    fputs("[", fp);
    for (size_t i = 0; i < np; i++) {
        bool f = true;
        fputs(i ? ",\n  {" : "\n  {", fp);
        json_member_string(fp, &f, "run_id", p[i].a->id);
        json_member_string(fp, &f, "renderer", p[i].a->renderer);
        json_member_string(fp, &f, "base_status", p[i].a->status);
        json_member_string(fp, &f, "new_status", p[i].b->status);
        json_member_number(fp, &f, "base_mean_us", p[i].a->mean);
        json_member_number(fp, &f, "base_ci95_us", p[i].a->half);
        json_member_number(fp, &f, "new_mean_us", p[i].b->mean);
        json_member_number(fp, &f, "new_ci95_us", p[i].b->half);
        json_member_number(fp, &f, "ratio", p[i].r.ratio);
        json_member_number(fp, &f, "ratio_lo", p[i].r.lo);
        json_member_number(fp, &f, "ratio_hi", p[i].r.hi);
        json_member_number(fp, &f, "raw_ratio", p[i].raw.ratio);
        json_member_number(fp, &f, "raw_ratio_lo", p[i].raw.lo);
        json_member_number(fp, &f, "raw_ratio_hi", p[i].raw.hi);
        json_member_number(fp, &f, "trials", (double)p[i].r.n);
        json_member_string(fp, &f, "verdict", verdict_name(p[i].v));
        const clock_check *c = &p[i].clk;   /* NVML's clocks; null without */
        json_member_number(fp, &f, "base_sm_mhz", c->base_mhz);
        json_member_number(fp, &f, "new_sm_mhz", c->new_mhz);
        json_member_number(fp, &f, "clocks_apart", c->any ? (double)c->nflagged : NAN);
        json_member_number(fp, &f, "gpu_ratio", c->gpu.ratio);
        json_member_number(fp, &f, "gpu_ratio_at_base_clock", c->gpu_norm.ratio);
        fputs("}", fp);
    }
    fputs("]", fp);
    json_key(fp, &first, "counts");
    fputs("{", fp);
    bool f = true;
    for (int v = 0; v < NVERDICTS; v++)
        json_member_number(fp, &f, verdict_name((verdict)v), (double)count[v]);
    fputs("}", fp);
    json_member_number(fp, &first, "only_base", (double)only_base);
    json_member_number(fp, &first, "only_new", (double)only_new);
    json_member_string(fp, &first, "base_device", dn[0].line[0] ? dn[0].line : NULL);
    json_member_string(fp, &first, "new_device", dn[1].line[0] ? dn[1].line : NULL);
    fputs("}\n", fp);
}

static bool write_csv(const char *path, const pair *p, size_t np, char *err, size_t errlen)
{
    static const char *const cols[] = {
        "run_id", "renderer", "metric", "base_mean_us", "base_ci95_us", "new_mean_us",
        "new_ci95_us", "ratio", "ratio_lo", "ratio_hi", "paired", "trials", "verdict",
    };
    csv_writer *w = csv_open(path, cols, sizeof cols / sizeof cols[0], err, errlen);
    if (!w)
        return false;
    for (size_t i = 0; i < np; i++) {
        csv_str(w, p[i].a->id);
        csv_str(w, p[i].a->renderer);
        csv_str(w, p[i].a->metric);
        csv_f64(w, p[i].a->mean, 3);
        csv_f64(w, p[i].a->half, 3);
        csv_f64(w, p[i].b->mean, 3);
        csv_f64(w, p[i].b->half, 3);
        csv_f64(w, p[i].r.ratio, 6);
        csv_f64(w, p[i].r.lo, 6);
        csv_f64(w, p[i].r.hi, 6);
        csv_u64(w, p[i].r.paired ? 1 : 0);
        csv_u64(w, p[i].r.n);
        csv_str(w, verdict_name(p[i].v));
        csv_end_row(w);
    }
    return csv_commit(w, err, errlen);
}

/* The common change over the pairs' raw ratios, each pair's ratio corrected for it
 * (results/drift.h), and the verdicts. */
static void drift_apply(pair *p, size_t np, double thr, common_change *cc)
{
    ratio_ci *raw = malloc((np ? np : 1) * sizeof *raw);
    if (raw) {
        for (size_t i = 0; i < np; i++)
            raw[i] = p[i].raw;
        drift_common_change(raw, np, cc);
        free(raw);
    } else {
        *cc = (common_change){.ratio = NAN, .lo = NAN, .hi = NAN};
    }
    for (size_t i = 0; i < np; i++) {
        drift_correct(&p[i].raw, cc, &p[i].r);
        p[i].v = verdict_of(&p[i].r, thr);
    }
}

static bool load(const char *dir, run_result **runs, size_t *n)
{
    char path[4200], err[600];
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "shadesweep compare: %s: %s\n", dir,
                fs_exists(dir) ? "not a folder" : "no such folder");
        return false;
    }
    snprintf(path, sizeof path, "%s/summary.csv", dir);
    if (!fs_exists(path)) {
        fprintf(stderr, "shadesweep compare: %s: not a shadesweep output folder (no summary.csv)\n",
                dir);
        return false;
    }
    if (!summary_load_runs(path, runs, n, err, sizeof err)) {
        fprintf(stderr, "shadesweep compare: %s\n", err);
        return false;
    }
    return true;
}

typedef struct compare_opts {
    double thr;
    bool paired, allow_missing, json;
    const char *csv_path, *md_path;
} compare_opts;

static int compare_folders(const char *base, const char *new_, const compare_opts *co)
{
    run_result *ra = NULL, *rb = NULL;
    size_t na = 0, nb = 0;
    int rc = 2;
    pair *p = NULL;
    if (!load(base, &ra, &na) || !load(new_, &rb, &nb))
        goto done;
    p = calloc(na ? na : 1, sizeof *p);
    if (!p) {
        fprintf(stderr, "shadesweep compare: out of memory\n");
        goto done;
    }
    size_t np = 0, missing = 0, broke = 0;
    for (size_t i = 0; i < na; i++) {
        size_t j = 0;
        while (j < nb && strcmp(ra[i].id, rb[j].id) != 0)
            j++;
        if (j == nb) {
            missing++;
            fprintf(stderr, "shadesweep compare: run %s (%s) of BASE is not in NEW\n", ra[i].id,
                    ra[i].renderer);
            continue;
        }
        if (ra[i].metric[0] && rb[j].metric[0] && strcmp(ra[i].metric, rb[j].metric) != 0) {
            fprintf(stderr, "shadesweep compare: run %s: BASE was ranked by %s time, NEW by "
                    "%s: not comparable (measure.metric)\n", ra[i].id, ra[i].metric,
                    rb[j].metric);
            goto done;
        }
        pair *x = &p[np++];
        x->a = &ra[i];
        x->b = &rb[j];
        if (co->paired)
            summary_paired_ratio(x->b, x->a, &x->r);
        else
            verdict_unpaired_ratio(x->b->value, x->b->nvalues, x->a->value, x->a->nvalues,
                                   &x->r);
        x->raw = x->r;
        clock_check_pair(x->a, x->b, co->paired, &x->clk);
        if (strcmp(x->b->status, "ok") != 0 && strcmp(x->a->status, "ok") == 0) {
            broke++;
            fprintf(stderr, "shadesweep compare: run %s (%s) failed in NEW (%s), not in BASE\n",
                    x->a->id, x->a->renderer, x->b->status);
        }
    }
    if (np == 0) {
        fprintf(stderr, "shadesweep compare: %s and %s have no run in common (no run id in "
                "both summary.csv files)\n", base, new_);
        goto done;
    }
    common_change cc;
    drift_apply(p, np, co->thr, &cc);
    device_note dn[2];
    device_note_of(base, ra, na, &dn[0]);
    device_note_of(new_, rb, nb, &dn[1]);
    char err[600];
    if (co->csv_path && !write_csv(co->csv_path, p, np, err, sizeof err)) {
        fprintf(stderr, "shadesweep compare: %s\n", err);
        goto done;
    }
    if (co->md_path) {
        afile f;
        if (!afile_open(&f, co->md_path, err, sizeof err)) {
            fprintf(stderr, "shadesweep compare: %s\n", err);
            goto done;
        }
        write_md(f.fp, base, new_, co->thr, co->paired, p, np, missing, nb - np, dn, &cc);
        if (!afile_commit(&f, err, sizeof err)) {
            fprintf(stderr, "shadesweep compare: %s\n", err);
            goto done;
        }
    }
    (co->json ? write_json : write_md)(stdout, base, new_, co->thr, co->paired, p, np, missing,
                                       nb - np, dn, &cc);
    rc = 0;
    for (size_t i = 0; i < np; i++)
        if (p[i].v == VERDICT_SLOWER)
            rc = 1;
    if (!co->allow_missing && (missing || broke)) {
        fprintf(stderr, "shadesweep compare: %zu run%s of BASE missing in NEW, %zu failed in "
                "NEW only (--allow-missing to accept)\n", missing, missing == 1 ? "" : "s",
                broke);
        rc = 1;
    }
done:
    free(p);
    summary_free_runs(ra, na);
    summary_free_runs(rb, nb);
    return rc;
}

/* ---- compare --exe */

/* exe run [--force|--resume] --round k -o dir manifest; its exit status (-1: did not
 * run or died). stdout goes to the log as well: the summary tables are not ours. */
static int run_round(const char *exe, unsigned round, bool first, bool force, const char *dir,
                     const char *manifest, const char *log)
{
    char rbuf[16];
    snprintf(rbuf, sizeof rbuf, "%u", round);
    const char *argv[10];
    int n = 0;
    argv[n++] = exe;
    argv[n++] = "run";
    if (!first)
        argv[n++] = "--resume";
    else if (force)
        argv[n++] = "--force";
    argv[n++] = "--round";
    argv[n++] = rbuf;
    argv[n++] = "-o";
    argv[n++] = dir;
    argv[n++] = manifest;
    argv[n] = NULL;
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        FILE *f = fopen(log, "a");
        if (f) {
            dup2(fileno(f), STDOUT_FILENO);
            dup2(fileno(f), STDERR_FILENO);
        }
        execv(exe, (char *const *)argv);
        fprintf(stderr, "cannot run %s: %s\n", exe, strerror(errno));
        _exit(127);
    }
    int st;
    while (waitpid(pid, &st, 0) < 0)
        if (errno != EINTR)
            return -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* This program's own path, for the NEW side. */
static bool self_exe(char *out, size_t len)
{
    ssize_t n = readlink("/proc/self/exe", out, len - 1);
    if (n <= 0)
        return false;
    out[n] = 0;
    return true;
}

static int compare_exe(const char *other, const char *base_manifest, const char *manifest,
                       const char *out, bool force, const compare_opts *co)
{
    char self[4096];
    if (access(other, X_OK) != 0) {
        fprintf(stderr, "shadesweep compare: --exe %s: %s\n", other, strerror(errno));
        return 2;
    }
    if (!self_exe(self, sizeof self)) {
        fprintf(stderr, "shadesweep compare: cannot find this program's path\n");
        return 2;
    }
    diag_list d = {0};
    experiment *e = NULL;
    bool ok = manifest_load(manifest, &e, &d);
    diag_print(&d, stderr);
    diag_free(&d);
    if (!ok)
        return 2;
    uint32_t trials = e->base.trials, seed = e->base.schedule_seed;
    char name[80];
    snprintf(name, sizeof name, "%s", e->name);
    bool swept = false;
    for (size_t a = 0; a < e->naxes; a++)
        swept |= strcmp(e->axes[a].path, "trials") == 0;
    experiment_free(e);
    if (swept || trials < 3) {
        fprintf(stderr, "shadesweep compare --exe: expected a manifest with one fixed `trials` "
                "of 3 or more (the rounds both builds run), found %s\n",
                swept ? "trials swept" : trials == 0 ? "trials: auto" : "fewer than 3");
        return 2;
    }
    char dir[4096], bdir[4200], ndir[4200], blog[4300], nlog[4300];
    if (out)
        snprintf(dir, sizeof dir, "%s", out);
    else
        snprintf(dir, sizeof dir, "out/%s-compare", name);
    snprintf(bdir, sizeof bdir, "%s/base", dir);
    snprintf(ndir, sizeof ndir, "%s/new", dir);
    snprintf(blog, sizeof blog, "%s/base.log", dir);
    snprintf(nlog, sizeof nlog, "%s/new.log", dir);
    char err[600];
    if (!fs_mkdirs(dir, err, sizeof err)) {
        fprintf(stderr, "shadesweep compare: %s\n", err);
        return 2;
    }
    if (force) {
        unlink(blog);
        unlink(nlog);
    }
    for (unsigned k = 1; k <= trials; k++) {
        /* which build goes first in this round: seeded, recorded on stderr */
        uint64_t key[2] = {seed, k};
        bool base_first = (fnv1a64(key, sizeof key) >> 17) & 1;
        fprintf(stderr, "compare: round %u of %u: %s first\n", k, trials,
                base_first ? "BASE" : "NEW");
        for (int side = 0; side < 2; side++) {
            bool is_base = (side == 0) == base_first;
            int rc = run_round(is_base ? other : self, k, k == 1, force,
                               is_base ? bdir : ndir,
                               is_base && base_manifest ? base_manifest : manifest,
                               is_base ? blog : nlog);
            if (rc < 0 || rc > 1) {
                fprintf(stderr, "shadesweep compare: %s round %u failed (exit %d): see %s\n",
                        is_base ? "BASE" : "NEW", k, rc, is_base ? blog : nlog);
                return 2;
            }
        }
    }
    compare_opts paired = *co;
    paired.paired = true;
    return compare_folders(bdir, ndir, &paired);
}

/* compare --exe OTHER MANIFEST: one manifest measured by two builds, OTHER (BASE) and
 * this one (NEW), in rounds: round k runs trial k of every run with each build (`run
 * --round k`), the two builds in a seeded random order, so that trial k of BASE and of
 * NEW ran minutes apart at most and are compared paired (the geometric mean of the
 * per-round ratios). The gate for a change on a shared machine.
 *
 * Markdown on stdout (and --md FILE), one CSV row per run with --csv FILE.
 * Exit 1 when any run is slower, when a run of BASE failed or is missing in NEW
 * (unless --allow-missing), 2 on bad input. */
int cmd_compare(int argc, char **argv)
{
    enum { OPT_THRESHOLD = 1000, OPT_CSV, OPT_MD, OPT_HELP, OPT_EXE, OPT_BASE_MANIFEST,
           OPT_FORCE, OPT_ALLOW_MISSING, OPT_JSON };
    static const struct option longopts[] = {
        {"threshold", required_argument, NULL, OPT_THRESHOLD},
        {"csv", required_argument, NULL, OPT_CSV},
        {"md", required_argument, NULL, OPT_MD},
        {"help", no_argument, NULL, OPT_HELP},
        {"exe", required_argument, NULL, OPT_EXE},
        {"base-manifest", required_argument, NULL, OPT_BASE_MANIFEST},
        {"force", no_argument, NULL, OPT_FORCE},
        {"allow-missing", no_argument, NULL, OPT_ALLOW_MISSING},
        {"json", no_argument, NULL, OPT_JSON},
        {NULL, 0, NULL, 0},
    };
    compare_opts co = {.thr = 0.05};
    const char *exe = NULL, *base_manifest = NULL, *out = NULL;
    bool force = false;
    optind = 1;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":ho:", longopts, NULL)) != -1) {
        switch (c) {
        case OPT_THRESHOLD:
            if (!parse_threshold(optarg, &co.thr)) {
                fprintf(stderr, "shadesweep compare: --threshold: expected a percentage "
                        "0..1000000 (e.g. 5%%), found '%s'\n", optarg);
                return 2;
            }
            break;
        case OPT_CSV: co.csv_path = optarg; break;
        case OPT_MD: co.md_path = optarg; break;
        case OPT_EXE: exe = optarg; break;
        case OPT_BASE_MANIFEST: base_manifest = optarg; break;
        case OPT_FORCE: force = true; break;
        case OPT_ALLOW_MISSING: co.allow_missing = true; break;
        case OPT_JSON: co.json = true; break;
        case 'o': out = optarg; break;
        case 'h':
        case OPT_HELP: fputs(compare_usage, stdout); return 0;
        default:
            fprintf(stderr, "shadesweep compare: %s: %s\n%s", argv[optind - 1],
                    c == ':' ? "option needs a value" : "unknown option", compare_usage);
            return 2;
        }
    }
    if (exe) {
        if (argc - optind != 1) {
            fprintf(stderr, "shadesweep compare: --exe: expected one manifest\n%s",
                    compare_usage);
            return 2;
        }
        return compare_exe(exe, base_manifest, argv[optind], out, force, &co);
    }
    if (base_manifest || out || force) {
        fprintf(stderr, "shadesweep compare: --base-manifest, -o and --force: only with --exe\n");
        return 2;
    }
    if (argc - optind != 2) {
        fprintf(stderr, "shadesweep compare: expected two output folders, BASE and NEW\n%s",
                compare_usage);
        return 2;
    }
    return compare_folders(argv[optind], argv[optind + 1], &co);
}
