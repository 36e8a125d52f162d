/* `shadesweep ratios`: the trial-level statistics of results/verdict.c for other
 * programs. The Python report asks here for every ratio, significance and crossover it
 * prints, so that the ranking, summary.md, compare, the crossovers and the report's
 * claims come from one statistics module and cannot disagree on the same data.
 * The request lines, their JSON answers and the errors: the comment above
 * cmd_ratios below. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "results/csvread.h"
#include "common/grow.h"
#include "results/jsonout.h"
#include "results/verdict.h"
#include "runner/answer/commands.h"
#include "runner/answer/device_note.h"
#include "runner/answer/run_model.h"

typedef struct folder_data {
    char *path;
    bool ok;
    char err[600];
    run_result *runs;
    size_t nruns;
    csv_table plan;
    bool has_plan;
} folder_data;

typedef struct cache {
    folder_data *f;
    size_t n, cap;
} cache;

static folder_data *folder_get(cache *c, const char *path)
{
    for (size_t i = 0; i < c->n; i++)
        if (strcmp(c->f[i].path, path) == 0)
            return &c->f[i];
    if (!GROW(c->f, c->cap, c->n + 1, 8))
        return NULL;
    folder_data *d = &c->f[c->n];
    memset(d, 0, sizeof *d);
    if (!(d->path = strdup(path)))
        return NULL;
    c->n++;
    char file[4200];
    snprintf(file, sizeof file, "%s/summary.csv", path);
    d->ok = summary_load_runs(file, &d->runs, &d->nruns, d->err, sizeof d->err);
    snprintf(file, sizeof file, "%s/plan.csv", path);
    char perr[200];
    d->has_plan = d->ok && csv_read(file, &d->plan, perr, sizeof perr);
    return d;
}

static void cache_free(cache *c)
{
    for (size_t i = 0; i < c->n; i++) {
        free(c->f[i].path);
        summary_free_runs(c->f[i].runs, c->f[i].nruns);
        if (c->f[i].has_plan)
            csv_table_free(&c->f[i].plan);
    }
    free(c->f);
}

/* One run of one folder, or NULL with *why set. */
static const run_result *find_run(cache *c, const char *folder, const char *id,
                                  folder_data **fd, char *why, size_t whylen)
{
    folder_data *d = folder_get(c, folder);
    if (!d) {
        snprintf(why, whylen, "out of memory");
        return NULL;
    }
    *fd = d;
    if (!d->ok) {
        snprintf(why, whylen, "%s", d->err);
        return NULL;
    }
    for (size_t i = 0; i < d->nruns; i++)
        if (strcmp(d->runs[i].id, id) == 0)
            return &d->runs[i];
    snprintf(why, whylen, "%s/summary.csv: no run %s", folder, id);
    return NULL;
}

typedef struct pair_result {
    const run_result *a, *b;
    ratio_ci r;
} pair_result;

/* The ratio of f[0] f[1] (A) to f[2] f[3] (B). False with *why. */
static bool pair_of(cache *c, char **f, pair_result *out, char *why, size_t whylen)
{
    folder_data *da, *db;
    out->a = find_run(c, f[0], f[1], &da, why, whylen);
    out->b = out->a ? find_run(c, f[2], f[3], &db, why, whylen) : NULL;
    if (!out->b)
        return false;
    if (strcmp(out->a->metric, out->b->metric) != 0) {
        snprintf(why, whylen, "runs %s and %s were measured by different metrics (%s, %s)",
                 out->a->id, out->b->id, out->a->metric[0] ? out->a->metric : "none",
                 out->b->metric[0] ? out->b->metric : "none");
        return false;
    }
    if (da == db && da->has_plan && summary_same_point(&da->plan, f[1], f[3]))
        summary_paired_ratio(out->a, out->b, &out->r);
    else
        verdict_unpaired_ratio(out->a->value, out->a->nvalues, out->b->value,
                               out->b->nvalues, &out->r);
    return true;
}

static void print_error(const char *why)
{
    fputs("{\"error\": ", stdout);
    json_string(stdout, why);
    fputs("}\n", stdout);
}

static void print_side(const char *k, const run_result *x, bool *first)
{
    char name[16];
    snprintf(name, sizeof name, "%s_mean_us", k);
    json_member_number(stdout, first, name, x->mean);
    snprintf(name, sizeof name, "%s_ci95_us", k);
    json_member_number(stdout, first, name, x->half);
    snprintf(name, sizeof name, "%s_trials", k);
    json_member_number(stdout, first, name, (double)x->trials_ok);
}

static void print_ratio_fields(const ratio_ci *r, bool *first)
{
    json_member_number(stdout, first, "ratio", r->ratio);
    json_member_number(stdout, first, "lo", r->lo);
    json_member_number(stdout, first, "hi", r->hi);
    json_member_string(stdout, first, "differs", summary_differs(r));
}

static void answer_ratio(cache *c, char **f)
{
    pair_result p;
    char why[700];
    if (!pair_of(c, f, &p, why, sizeof why)) {
        print_error(why);
        return;
    }
    bool first = true;
    fputs("{", stdout);
    json_member_string(stdout, &first, "a", p.a->id);
    json_member_string(stdout, &first, "b", p.b->id);
    json_member_string(stdout, &first, "metric", p.a->metric);
    json_key(stdout, &first, "paired");
    fputs(p.r.paired ? "true" : "false", stdout);
    json_member_number(stdout, &first, "n", (double)p.r.n);
    print_ratio_fields(&p.r, &first);
    print_side("a", p.a, &first);
    print_side("b", p.b, &first);
    fputs("}\n", stdout);
}

static void answer_run(cache *c, char **f)
{
    folder_data *d;
    char why[700];
    const run_result *x = find_run(c, f[0], f[1], &d, why, sizeof why);
    if (!x) {
        print_error(why);
        return;
    }
    bool first = true;
    fputs("{", stdout);
    json_member_string(stdout, &first, "id", x->id);
    json_member_string(stdout, &first, "metric", x->metric);
    json_member_number(stdout, &first, "mean_us", x->mean);
    json_member_number(stdout, &first, "ci95_us", x->half);
    json_member_number(stdout, &first, "trials", (double)x->trials_ok);
    fputs("}\n", stdout);
}

/* The folder's device (runner/answer/device_note.h): what the report says of it. */
static void answer_device(cache *c, char **f)
{
    folder_data *d = folder_get(c, f[0]);
    if (!d || !d->ok) {
        print_error(d ? d->err : "out of memory");
        return;
    }
    device_note dn;
    device_note_of(f[0], d->runs, d->nruns, &dn);
    bool first = true;
    fputs("{", stdout);
    json_key(stdout, &first, "software_rasterizer");
    fputs(dn.nsoftware ? "true" : "false", stdout);
    json_member_number(stdout, &first, "devices", (double)dn.ndevices);
    json_member_string(stdout, &first, "note", dn.line[0] ? dn.line : NULL);
    fputs("}\n", stdout);
}

static void answer_crossover(cache *c, char **f, size_t npts)
{
    double *x = calloc(npts ? npts : 1, sizeof *x);
    ratio_ci *r = calloc(npts ? npts : 1, sizeof *r);
    if (!x || !r) {
        free(x);
        free(r);
        print_error("out of memory");
        return;
    }
    char why[700];
    for (size_t k = 0; k < npts; k++) {
        pair_result p;
        char *end;
        x[k] = strtod(f[5 * k], &end);
        if (end == f[5 * k] || *end || !isfinite(x[k]) || (k && !(x[k] > x[k - 1]))) {
            snprintf(why, sizeof why, "crossover: point %zu: '%s' is not a number above "
                     "the point before", k + 1, f[5 * k]);
            print_error(why);
            free(x);
            free(r);
            return;
        }
        if (!pair_of(c, f + 5 * k + 1, &p, why, sizeof why)) {
            print_error(why);
            free(x);
            free(r);
            return;
        }
        r[k] = p.r;
    }
    fputs("{\"crossings\": [", stdout);
    ratio_crossover co;
    size_t from = 0;
    for (bool first = true; verdict_crossover(x, r, npts, from, &co); first = false) {
        printf("%s{\"i\": %zu, \"j\": %zu, \"dir\": %d, \"x\": ", first ? "" : ", ", co.i,
               co.j, co.dir);
        json_number(stdout, co.x);
        fputs(", \"lo\": ", stdout);
        json_number(stdout, co.lo);
        fputs(", \"hi\": ", stdout);
        json_number(stdout, co.hi);
        fputs("}", stdout);
        from = co.j;
    }
    fputs("], \"ratios\": [", stdout);
    for (size_t k = 0; k < npts; k++) {
        bool first = true;
        fputs(k ? ", {" : "{", stdout);
        print_ratio_fields(&r[k], &first);
        fputs("}", stdout);
    }
    fputs("]}\n", stdout);
    free(x);
    free(r);
}

static const char usage[] =
    "usage: shadesweep ratios < REQUESTS\n"
    "  The trial-level statistics (results/verdict.c) for other programs: requests on\n"
    "  stdin, one a line, fields separated by tabs; one JSON object a line on stdout.\n"
    "    run FOLDER RUN     the run's mean metric_us over its trials, 95% interval\n"
    "    ratio FOLDER_A RUN_A FOLDER_B RUN_B\n"
    "      A / B of the runs' trial values (summary.csv metric_us), paired within one\n"
    "      folder's sweep point, else Welch on logs; its 95% interval and `differs`\n"
    "    crossover X1 FOLDER_A1 RUN_A1 FOLDER_B1 RUN_B1 X2 ...\n"
    "      where A / B crosses 1 along an axis (X ascending), with its interval\n"
    "    device FOLDER      whether a CPU rasterizer measured the folder's runs, how\n"
    "      many devices did, and the line summary.md says of them (null: none)\n"
    "exit status: 0 answered (a request about a missing run answers {\"error\": ...});\n"
    "2 a malformed request\n";

/* Requests on standard input, one a line, fields separated by tabs (folder names may
 * hold spaces); answers on standard output, one JSON object a line, in the order asked:
 *
 *   run FOLDER RUN
 *     the run's value, what ranks it: {"id", "metric", "mean_us", "ci95_us", "trials"},
 *     the mean over its ok trials and the half-width of the 95% t interval
 *   ratio FOLDER_A RUN_A FOLDER_B RUN_B
 *     A / B of the runs' trial values (summary.csv metric_us: what measure.metric
 *     chose): paired (the geometric mean of per-round ratios) when both are of one
 *     folder and one sweep point, whose trials ran in the same rounds; else Welch's
 *     interval on the logs. {"a", "b", "metric", "paired", "n", "ratio", "lo", "hi",
 *     "differs", "a_mean_us", "a_ci95_us", "a_trials", "b_mean_us", ...}
 *   crossover X1 FOLDER_A1 RUN_A1 FOLDER_B1 RUN_B1 X2 FOLDER_A2 ...
 *     where A / B crosses 1 along an axis whose value at point k is Xk (ascending):
 *     {"crossings": [{"i", "j", "dir", "x", "lo", "hi"}, ...]} (verdict_crossover), with
 *     "ratios": [{"ratio", "lo", "hi", "differs"}, ...] of each point.
 *   device FOLDER
 *     {"software_rasterizer", "devices", "note"}: summary.md's `Device:` line of the
 *     folder (runner/answer/device_note.h), null when it has none.
 *
 * A request naming a folder or run that is not there answers {"error": "..."} on its
 * line, and the others go on; a malformed line is a message on stderr and exit 2. A
 * number that is not finite is null. */
int cmd_ratios(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            fputs(usage, stdout);
            return 0;
        }
        fprintf(stderr, "shadesweep ratios: unexpected argument '%s' (the requests come "
                "on standard input; see --help)\n", argv[i]);
        return 2;
    }
    cache c = {0};
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    int status = 0;
    size_t lineno = 0;
    char **f = NULL;
    size_t fcap = 0;
    while (status == 0 && (len = getline(&line, &cap, stdin)) >= 0) {
        lineno++;
        while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r'))
            line[--len] = '\0';
        if (len == 0)
            continue;
        size_t nf = 0;
        for (char *s = line;; nf++) {
            if (!GROW(f, fcap, nf + 1, 16)) {
                fprintf(stderr, "shadesweep ratios: out of memory\n");
                status = 2;
                break;
            }
            f[nf] = s;
            char *tab = strchr(s, '\t');
            if (!tab) {
                nf++;
                break;
            }
            *tab = '\0';
            s = tab + 1;
        }
        if (status)
            break;
        if (strcmp(f[0], "run") == 0 && nf == 3) {
            answer_run(&c, f + 1);
        } else if (strcmp(f[0], "ratio") == 0 && nf == 5) {
            answer_ratio(&c, f + 1);
        } else if (strcmp(f[0], "device") == 0 && nf == 2) {
            answer_device(&c, f + 1);
        } else if (strcmp(f[0], "crossover") == 0 && nf >= 11 && (nf - 1) % 5 == 0) {
            answer_crossover(&c, f + 1, (nf - 1) / 5);
        } else {
            fprintf(stderr, "shadesweep ratios: line %zu: want 'run' and 2 fields, 'ratio' and 4, "
                    "'device' and 1, or 'crossover' and 5 fields a point (2 points or more), separated by "
                    "tabs\n", lineno);
            status = 2;
        }
        fflush(stdout);
    }
    free(f);
    free(line);
    cache_free(&c);
    if (status == 0 && (ferror(stdout) || fflush(stdout) != 0)) {
        fprintf(stderr, "shadesweep ratios: cannot write the answers\n");
        status = 2;
    }
    return status;
}
