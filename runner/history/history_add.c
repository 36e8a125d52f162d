/* `history add`: an output folder's runs into the history (runner/history/history.h).
 * From summary.csv each trial's values (frame time, CPU time, GPU time, the metric
 * that decides) and status; from each run's meta.yaml the provenance (the build's
 * commit and dirty flag, the manifest's hash, the GL device strings, the host, the
 * sweep point, the trials' start). The sweep's date is its earliest trial start, and
 * its key a hash of host, manifest hash, experiment and date: the same folder added
 * twice is the same sweep, whose rows are then already there. */
#define _DEFAULT_SOURCE
#include "runner/history/history.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "results/csvread.h"
#include "runner/folder/meta_read.h"
#include "runner/manifest/hash.h"

enum { F_LEN = 256 };

/* The sweep's provenance: from the first run whose meta.yaml has it */
typedef struct sweep_info {
    char date[64], hash[F_LEN], commit[F_LEN], dirty[16], host[2 * F_LEN + 4];
    char device[3 * F_LEN + 8];
    char experiment[F_LEN], folder[PATH_MAX];
} sweep_info;

static void read_provenance(const char *run_dir, sweep_info *s)
{
    char v[3][F_LEN];
    if (!s->hash[0] && meta_read_block(run_dir, "manifest", (const char *[]){"hash"}, 1,
                                       v[0], F_LEN))
        snprintf(s->hash, sizeof s->hash, "%s", v[0]);
    if (!s->commit[0] && meta_read_block(run_dir, "shadesweep",
                                         (const char *[]){"commit", "dirty"}, 2, v[0], F_LEN)) {
        snprintf(s->commit, sizeof s->commit, "%s", v[0]);
        snprintf(s->dirty, sizeof s->dirty, "%s", strcmp(v[1], "true") == 0 ? "1" : "0");
    }
    if (!s->host[0] && meta_read_block(run_dir, "host", (const char *[]){"hostname", "cpu"},
                                       2, v[0], F_LEN) && v[0][0])
        snprintf(s->host, sizeof s->host, "%s (%s)", v[0], v[1]);
    if (!s->device[0] &&
        meta_read_block(run_dir, "gl", (const char *[]){"vendor", "renderer", "version"}, 3,
                        v[0], F_LEN) && v[1][0])
        snprintf(s->device, sizeof s->device, "%s | %s | %s", v[0], v[1], v[2]);
}

/* a field as a parameter: NULL (SQL NULL) when empty */
static const char *opt(const char *s)
{
    return s && *s ? s : NULL;
}

/* one INSERT ... ON CONFLICT DO NOTHING RETURNING 1: *added += whether it was new */
static bool insert(hdb *db, const char *sql, const char *const *p, int n, size_t *added,
                   char *err, size_t errlen)
{
    hdb_result r;
    if (!db->ops->exec(db, sql, p, n, &r, err, errlen))
        return false;
    if (added)
        *added += r.nrows;
    hdb_result_free(&r);
    return true;
}

/* The runs of table t in order of first appearance: ids[k] = the row of run k's first */
static size_t distinct_runs(const csv_table *t, int c_id, size_t *first)
{
    size_t n = 0;
    for (size_t r = 0; r < t->nrows; r++) {
        size_t k = 0;
        while (k < n && strcmp(csv_get(t, first[k], c_id), csv_get(t, r, c_id)) != 0)
            k++;
        if (k == n)
            first[n++] = r;
    }
    return n;
}

bool history_add_folder(hdb *db, const char *dir, size_t *runs, size_t *trials, char *err,
                        size_t errlen)
{
    *runs = *trials = 0;
    char path[PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/summary.csv", dir);
    csv_table t = {0};
    if (!csv_read(path, &t, err, errlen))
        return false;
    int c_id = csv_col(&t, "run_id"), c_r = csv_col(&t, "renderer"), c_k = csv_col(&t, "trial"),
        c_st = csv_col(&t, "status"), c_m = csv_col(&t, "metric"), c_e = csv_col(&t, "experiment");
    int c_v[4] = {csv_col(&t, "frametime_mean_us"), csv_col(&t, "cpu_mean_us"),
                  csv_col(&t, "gpu_mean_us"), csv_col(&t, "metric_us")};
    bool ok = c_id >= 0 && c_r >= 0 && c_k >= 0 && c_st >= 0 && c_v[0] >= 0;
    if (!ok)
        snprintf(err, errlen, "%s: not a shadesweep summary (run_id, renderer, trial, status "
                 "or frametime_mean_us missing)", path);
    size_t *first = ok ? calloc(t.nrows + 1, sizeof *first) : NULL;
    sweep_info s = {0};
    char (*point)[32] = ok ? calloc(t.nrows + 1, sizeof *point) : NULL;
    size_t nruns = 0;
    if (ok && (!first || !point)) {
        snprintf(err, errlen, "%s: out of memory", path);
        ok = false;
    }
    if (ok) {
        nruns = distinct_runs(&t, c_id, first);
        if (!realpath(dir, s.folder))
            snprintf(s.folder, sizeof s.folder, "%s", dir);
        snprintf(s.experiment, sizeof s.experiment, "%s", nruns ? csv_get(&t, 0, c_e) : "");
    }
    for (size_t k = 0; ok && k < nruns; k++) {
        char run_dir[PATH_MAX + 64], start[64];
        snprintf(run_dir, sizeof run_dir, "%s/runs/%s", dir, csv_get(&t, first[k], c_id));
        if (meta_read_first_start(run_dir, start, sizeof start) &&
            (!s.date[0] || strcmp(start, s.date) < 0))
            snprintf(s.date, sizeof s.date, "%s", start);
        read_provenance(run_dir, &s);
        meta_read_block(run_dir, "schedule", (const char *[]){"point"}, 1, point[k],
                        sizeof point[k]);
    }
    if (ok && !s.date[0]) {
        snprintf(err, errlen, "%s: no run has a trial with a start time (runs/*/meta.yaml): "
                 "nothing to date the sweep by", dir);
        ok = false;
    }
    char key[17] = "", added[32];
    if (ok) {
        uint64_t h = fnv1a64(s.host, strlen(s.host) + 1);
        h = fnv1a64_update(h, s.hash, strlen(s.hash) + 1);
        h = fnv1a64_update(h, s.experiment, strlen(s.experiment) + 1);
        h = fnv1a64_update(h, s.date, strlen(s.date) + 1);
        hash_hex(h, 16, key);
        time_t now = time(NULL);
        strftime(added, sizeof added, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
        ok = db->ops->begin(db, err, errlen);
    }
    bool in_tx = ok;
    ok = ok && hdb_schema(db, true, err, errlen);
    const char *sp[] = {key, s.date, s.folder, s.experiment, s.hash, s.commit,
                        s.dirty[0] ? s.dirty : "0", s.host, s.device, added};
    ok = ok && insert(db, "INSERT INTO sweeps (sweep, date, folder, experiment, "
                      "manifest_hash, commit_id, dirty, host, device, added) VALUES ($1, $2, "
                      "$3, $4, $5, $6, $7, $8, $9, $10) ON CONFLICT DO NOTHING RETURNING 1",
                      sp, 10, NULL, err, errlen);
    for (size_t k = 0; ok && k < nruns; k++) {
        const char *id = csv_get(&t, first[k], c_id), *status = "ok";
        for (size_t r = 0; r < t.nrows; r++)
            if (strcmp(csv_get(&t, r, c_id), id) == 0 && strcmp(csv_get(&t, r, c_st), "ok"))
                status = csv_get(&t, r, c_st);
        /* a folder written before summary.csv's `metric` was decided by wall time */
        const char *metric = c_m >= 0 ? csv_get(&t, first[k], c_m) : "wall";
        const char *rp[] = {key, id, csv_get(&t, first[k], c_r), opt(point[k]), metric, status};
        ok = insert(db, "INSERT INTO runs (sweep, run_id, renderer, point, metric, status) "
                    "VALUES ($1, $2, $3, $4, $5, $6) ON CONFLICT DO NOTHING RETURNING 1",
                    rp, 6, runs, err, errlen);
    }
    for (size_t r = 0; ok && r < t.nrows; r++) {
        const char *tp[] = {key, csv_get(&t, r, c_id), csv_get(&t, r, c_k),
                            csv_get(&t, r, c_st), opt(csv_get(&t, r, c_v[0])),
                            opt(csv_get(&t, r, c_v[1])), opt(csv_get(&t, r, c_v[2])),
                            opt(csv_get(&t, r, c_v[3]))};
        ok = insert(db, "INSERT INTO trials (sweep, run_id, trial, status, frame_us, cpu_us, "
                    "gpu_us, metric_us) VALUES ($1, $2, $3, $4, $5, $6, $7, $8) "
                    "ON CONFLICT DO NOTHING RETURNING 1", tp, 8, trials, err, errlen);
    }
    if (ok)
        ok = hdb_commit(db, err, errlen);
    else if (in_tx)
        hdb_rollback(db);
    free(first);
    free(point);
    csv_table_free(&t);
    return ok;
}
