/* `shadesweep history add|show|check`: the options, the database's default place,
 * and the exit status (runner/history/history.h). */
#define _DEFAULT_SOURCE
#include "runner/history/history.h"

#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <libgen.h>
#include <stdlib.h>
#include <string.h>

static const char history_usage[] =
    "usage: shadesweep history add [--db URL] OUT...\n"
    "       shadesweep history show [OPTIONS]\n"
    "       shadesweep history check [OPTIONS]\n"
    "  add: every run of each output folder, its trials' values (frame, CPU and GPU\n"
    "  time) and provenance (commit, dirty flag, device, manifest hash, run id, renderer,\n"
    "  sweep point, date, host) into the history; a folder added again adds nothing\n"
    "  show: the change points of each run's series over the sweeps in date order\n"
    "  (E-divisive means with a t-test, as Apache Otava; the sweeps' common drift\n"
    "  removed first); check: the same, exit status 1 when one is a regression\n"
    "  --db URL            the history: a SQLite file (default: history.sqlite beside\n"
    "                      the first OUT, in its parent folder; show and check:\n"
    "                      out/history.sqlite) or postgresql://... (libpq's URI)\n"
    "  --run ID            only this run's series\n"
    "  --renderer R        only this renderer's runs\n"
    "  --metric M          wall, cpu, gpu or all (default: each run's own, summary.csv's\n"
    "                      `metric`)\n"
    "  --min-change P%     the smallest relative change reported (default 5%)\n"
    "  --max-pvalue P      the t-test's threshold (default 0.001)\n"
    "  --no-drift          do not remove the sweeps' common drift\n"
    "  --json FILE         also write the change points as JSON (- : stdout, instead of\n"
    "                      the table)\n"
    "exit status: 0 no regression (add: all added); 1 check found a regression;\n"
    "2 bad input or a database error\n";

static bool parse_fraction(const char *s, bool percent, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || errno)
        return false;
    if (percent && *end == '%')
        end++;
    if (*end || !(v >= 0) || !(percent ? v <= 1e6 : v <= 1))
        return false;
    *out = percent ? v / 100 : v;
    return true;
}

static int add(const char *db_url, int n, char **dirs)
{
    char def[PATH_MAX], err[1024];
    if (!db_url) {   /* beside the results: the first folder's parent */
        char copy[PATH_MAX];
        snprintf(copy, sizeof copy, "%s", dirs[0]);
        snprintf(def, sizeof def, "%s/history.sqlite", dirname(copy));
        db_url = def;
    }
    hdb *db;
    if (!hdb_open(db_url, true, &db, err, sizeof err)) {
        fprintf(stderr, "shadesweep history: %s\n", err);
        return 2;
    }
    int rc = 0;
    for (int i = 0; i < n; i++) {
        size_t runs, trials;
        if (!history_add_folder(db, dirs[i], &runs, &trials, err, sizeof err)) {
            fprintf(stderr, "shadesweep history add: %s\n", err);
            rc = 2;
            continue;
        }
        printf("%s: %zu runs and %zu trials added to %s%s\n", dirs[i], runs, trials,
               strcmp(db->kind, "sqlite") == 0 ? db_url : "the PostgreSQL history",
               runs + trials ? "" : " (all there already)");
    }
    db->ops->close(db);
    return rc;
}

int cmd_history(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        fputs(history_usage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const char *sub = argv[1];
    bool is_add = strcmp(sub, "add") == 0, is_check = strcmp(sub, "check") == 0;
    if (!is_add && !is_check && strcmp(sub, "show") != 0) {
        fprintf(stderr, "shadesweep history: unknown subcommand '%s' (add, show, check)\n\n%s",
                sub, history_usage);
        return 2;
    }
    enum { O_DB = 256, O_RUN, O_RENDERER, O_METRIC, O_MIN, O_P, O_NODRIFT, O_JSON };
    static const struct option opts[] = {
        {"db", required_argument, NULL, O_DB},           {"run", required_argument, NULL, O_RUN},
        {"renderer", required_argument, NULL, O_RENDERER},
        {"metric", required_argument, NULL, O_METRIC},
        {"min-change", required_argument, NULL, O_MIN},
        {"max-pvalue", required_argument, NULL, O_P},    {"no-drift", no_argument, NULL, O_NODRIFT},
        {"json", required_argument, NULL, O_JSON},       {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    history_query q = {.cp = changepoint_defaults(), .drift = true};
    const char *db_url = NULL, *json_path = NULL;
    optind = 1;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc - 1, argv + 1, "h", opts, NULL)) != -1) {
        const char *a = optarg;
        bool bad = false;
        switch (c) {
        case O_DB: db_url = a; break;
        case O_RUN: q.run = a; break;
        case O_RENDERER: q.renderer = a; break;
        case O_METRIC:
            q.metric = a;
            bad = strcmp(a, "wall") && strcmp(a, "cpu") && strcmp(a, "gpu") && strcmp(a, "all");
            break;
        case O_MIN: bad = !parse_fraction(a, true, &q.cp.min_magnitude); break;
        case O_P: bad = !parse_fraction(a, false, &q.cp.max_pvalue) || q.cp.max_pvalue == 0; break;
        case O_NODRIFT: q.drift = false; break;
        case O_JSON: json_path = a; break;
        case 'h': fputs(history_usage, stdout); return 0;
        default:
            fprintf(stderr, "shadesweep history %s: unknown or incomplete option '%s'\n", sub,
                    argv[optind]);
            return 2;
        }
        if (bad) {
            fprintf(stderr, "shadesweep history %s: bad value '%s' for --%s\n", sub, a,
                    opts[c - O_DB].name);
            return 2;
        }
    }
    int nargs = argc - 1 - optind;
    char **args = argv + 1 + optind;
    if (is_add != (nargs > 0) || (is_add && (q.run || q.renderer || q.metric || json_path))) {
        fprintf(stderr, is_add ? "shadesweep history add: expected output folders (and only "
                                 "--db)\n"
                               : "shadesweep history %s: unexpected argument '%s'\n",
                sub, nargs ? args[0] : "");
        return 2;
    }
    if (q.run && q.renderer) {
        fprintf(stderr, "shadesweep history %s: --run or --renderer, not both\n", sub);
        return 2;
    }
    if (is_add)
        return add(db_url, nargs, args);
    if (!db_url)
        db_url = "out/history.sqlite";
    char err[1024];
    hdb *db;
    if (!hdb_open(db_url, false, &db, err, sizeof err)) {
        fprintf(stderr, "shadesweep history %s: %s\n", sub, err);
        return 2;
    }
    FILE *js = NULL;
    bool to_stdout = json_path && strcmp(json_path, "-") == 0;
    if (json_path && !to_stdout && !(js = fopen(json_path, "w"))) {
        fprintf(stderr, "shadesweep history %s: %s: %s\n", sub, json_path, strerror(errno));
        db->ops->close(db);
        return 2;
    }
    size_t reg = 0;
    const char *where = strcmp(db->kind, "sqlite") == 0 ? db_url : "postgresql";
    bool ok = history_show(db, where, &q, to_stdout ? NULL : stdout, to_stdout ? stdout : js,
                           &reg, err, sizeof err);
    db->ops->close(db);
    if (js && fclose(js) != 0 && ok) {
        snprintf(err, sizeof err, "%s: %s", json_path, strerror(errno));
        ok = false;
    }
    if (!ok) {
        fprintf(stderr, "shadesweep history %s: %s\n", sub, err);
        return 2;
    }
    return is_check && reg ? 1 : 0;
}
