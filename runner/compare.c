/* shadesweep compare BASE NEW: a regression gate over two output folders.
 *
 * The runs both folders' summary.csv hold (by run id), each one's mean frame time
 * and its standard error from its trials' batch means (stats_pool_trials), the
 * change NEW - BASE with its 95% confidence interval by Welch's t-test, and a
 * verdict at a relative threshold T: slower when NEW > BASE x (1 + T), faster when
 * NEW < BASE / (1 + T) (so that swapping the folders swaps the verdicts), each only
 * when the change is significant; same otherwise.
 * Markdown on stdout (and --md FILE), one CSV row per run with --csv FILE.
 * Exit 1 when any run is slower. */
#include "runner/commands.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "results/csv.h"
#include "results/fsutil.h"
#include "runner/summary_md.h"

static const char compare_usage[] =
    "usage: shadesweep compare [OPTIONS] BASE NEW\n"
    "  the runs two output folders share (by run id): the change of mean frame time\n"
    "  with its 95% CI (Welch's t on the trials' batch means) and a verdict per run\n"
    "  --threshold P%   a change smaller than P% of BASE's mean is `same` (default 5%)\n"
    "  --csv FILE       also write one CSV row per run\n"
    "  --md FILE        also write the markdown table to FILE\n"
    "exit status: 0 no run significantly slower; 1 some run is; 2 bad input\n";

typedef enum verdict { V_SAME, V_SLOWER, V_FASTER, V_NA } verdict;
static const char *const verdict_names[] = {"same", "slower", "faster", "n/a"};

typedef struct pair {
    const run_result *a, *b;
    welch_result w;
    bool have;                 /* a Welch result */
    double rel, rel_ci;        /* change / BASE mean, its CI half-width / BASE mean */
    verdict v;
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

static double ci_of(const mean_estimate *m)
{
    return m->se * stats_t975_real(m->dof);
}

static void write_md(FILE *fp, const char *base, const char *new_, double thr, const pair *p,
                     size_t np, size_t only_base, size_t only_new)
{
    size_t count[4] = {0};
    for (size_t i = 0; i < np; i++)
        count[p[i].v]++;
    fprintf(fp, "# compare: `%s` -> `%s`\n\n", base, new_);
    fprintf(fp, "A run is **slower** when its mean frame time grew by more than %g%% of BASE's "
            "(NEW > BASE x %g), **faster** when it fell below BASE / %g, and Welch's t-test on "
            "the trials' batch means finds the change significant at 5%% (two-sided); "
            "otherwise `same`. Frame times in ms, ± the half-width of the 95%% confidence "
            "interval.\n\n", thr * 100, 1 + thr, 1 + thr);
    fprintf(fp, "| run | renderer | BASE | NEW | change | 95%% CI of the change | verdict |\n"
                "|---|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < np; i++) {
        char a[64], b[64], ch[32] = "-", ci[64] = "-";
        fmt_ms(a, sizeof a, p[i].a->ft.mean, ci_of(&p[i].a->ft));
        fmt_ms(b, sizeof b, p[i].b->ft.mean, ci_of(&p[i].b->ft));
        if (isfinite(p[i].rel))
            snprintf(ch, sizeof ch, "%+.2f%%", p[i].rel * 100);
        if (p[i].have && isfinite(p[i].rel_ci))
            snprintf(ci, sizeof ci, "%+.2f%% .. %+.2f%%", (p[i].rel - p[i].rel_ci) * 100,
                     (p[i].rel + p[i].rel_ci) * 100);
        const char *v = verdict_names[p[i].v];
        bool bold = p[i].v == V_SLOWER || p[i].v == V_FASTER;
        fprintf(fp, "| %s | %s | %s | %s | %s | %s | %s%s%s |\n", p[i].a->id, p[i].a->renderer,
                strcmp(p[i].a->status, "ok") ? p[i].a->status : a,
                strcmp(p[i].b->status, "ok") ? p[i].b->status : b, ch, ci, bold ? "**" : "", v,
                bold ? "**" : "");
    }
    fprintf(fp, "\n%zu run%s in common: %zu slower, %zu faster, %zu same, %zu n/a (failed or "
            "without a CI); %zu only in BASE, %zu only in NEW.\n", np, np == 1 ? "" : "s",
            count[V_SLOWER], count[V_FASTER], count[V_SAME], count[V_NA], only_base, only_new);
}

static bool write_csv(const char *path, const pair *p, size_t np, char *err, size_t errlen)
{
    static const char *const cols[] = {
        "run_id", "renderer", "base_mean_us", "base_ci95_us", "new_mean_us", "new_ci95_us",
        "change_us", "change_ci95_us", "change_rel", "change_ci95_rel", "welch_dof",
        "significant", "verdict",
    };
    csv_writer *w = csv_open(path, cols, sizeof cols / sizeof cols[0], err, errlen);
    if (!w)
        return false;
    for (size_t i = 0; i < np; i++) {
        csv_str(w, p[i].a->id);
        csv_str(w, p[i].a->renderer);
        csv_f64(w, p[i].a->ft.mean, 3);
        csv_f64(w, ci_of(&p[i].a->ft), 3);
        csv_f64(w, p[i].b->ft.mean, 3);
        csv_f64(w, ci_of(&p[i].b->ft), 3);
        csv_f64(w, p[i].w.diff, 3);
        csv_f64(w, p[i].have ? p[i].w.ci95 : NAN, 3);
        csv_f64(w, p[i].rel, 6);
        csv_f64(w, p[i].have ? p[i].rel_ci : NAN, 6);
        csv_f64(w, p[i].have ? p[i].w.dof : NAN, 2);
        if (p[i].have)
            csv_u64(w, p[i].w.significant ? 1 : 0);
        else
            csv_empty(w);
        csv_str(w, verdict_names[p[i].v]);
        csv_end_row(w);
    }
    return csv_commit(w, err, errlen);
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

int cmd_compare(int argc, char **argv)
{
    enum { OPT_THRESHOLD = 1000, OPT_CSV, OPT_MD, OPT_HELP };
    static const struct option longopts[] = {
        {"threshold", required_argument, NULL, OPT_THRESHOLD},
        {"csv", required_argument, NULL, OPT_CSV},
        {"md", required_argument, NULL, OPT_MD},
        {"help", no_argument, NULL, OPT_HELP},
        {NULL, 0, NULL, 0},
    };
    double thr = 0.05;
    const char *csv_path = NULL, *md_path = NULL;
    optind = 1;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":h", longopts, NULL)) != -1) {
        switch (c) {
        case OPT_THRESHOLD:
            if (!parse_threshold(optarg, &thr)) {
                fprintf(stderr, "shadesweep compare: --threshold: expected a percentage "
                        "0..1000000 (e.g. 5%%), found '%s'\n", optarg);
                return 2;
            }
            break;
        case OPT_CSV: csv_path = optarg; break;
        case OPT_MD: md_path = optarg; break;
        case 'h':
        case OPT_HELP: fputs(compare_usage, stdout); return 0;
        default:
            fprintf(stderr, "shadesweep compare: %s: %s\n%s", argv[optind - 1],
                    c == ':' ? "option needs a value" : "unknown option", compare_usage);
            return 2;
        }
    }
    if (argc - optind != 2) {
        fprintf(stderr, "shadesweep compare: expected two output folders, BASE and NEW\n%s",
                compare_usage);
        return 2;
    }
    const char *base = argv[optind], *new_ = argv[optind + 1];
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
    size_t np = 0;
    for (size_t i = 0; i < na; i++)
        for (size_t j = 0; j < nb; j++)
            if (strcmp(ra[i].id, rb[j].id) == 0) {
                pair *x = &p[np++];
                x->a = &ra[i];
                x->b = &rb[j];
                x->have = stats_welch(&x->a->ft, &x->b->ft, &x->w);
                x->rel = x->a->ft.mean > 0 ? x->w.diff / x->a->ft.mean : NAN;
                x->rel_ci = x->have && x->a->ft.mean > 0 ? x->w.ci95 / x->a->ft.mean : NAN;
                if (!x->have || !isfinite(x->rel))
                    x->v = V_NA;
                else if (x->w.significant && x->rel > thr)
                    x->v = V_SLOWER;
                else if (x->w.significant && x->rel < 1 / (1 + thr) - 1)
                    x->v = V_FASTER;
                else
                    x->v = V_SAME;
                break;
            }
    if (np == 0) {
        fprintf(stderr, "shadesweep compare: %s and %s have no run in common (no run id in "
                "both summary.csv files)\n", base, new_);
        goto done;
    }
    char err[600];
    if (csv_path && !write_csv(csv_path, p, np, err, sizeof err)) {
        fprintf(stderr, "shadesweep compare: %s\n", err);
        goto done;
    }
    if (md_path) {
        afile f;
        if (!afile_open(&f, md_path, err, sizeof err)) {
            fprintf(stderr, "shadesweep compare: %s\n", err);
            goto done;
        }
        write_md(f.fp, base, new_, thr, p, np, na - np, nb - np);
        if (!afile_commit(&f, err, sizeof err)) {
            fprintf(stderr, "shadesweep compare: %s\n", err);
            goto done;
        }
    }
    write_md(stdout, base, new_, thr, p, np, na - np, nb - np);
    rc = 0;
    for (size_t i = 0; i < np; i++)
        if (p[i].v == V_SLOWER)
            rc = 1;
done:
    free(p);
    free(ra);
    free(rb);
    return rc;
}
