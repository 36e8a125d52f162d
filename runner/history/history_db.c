/* The history database's schema, its version and the backend chosen by URL
 * (runner/history/history_db.h). The schema, version 1 (docs/notes/history.md):
 *   shadesweep_history (version)          one row: the schema's version
 *   sweeps (sweep key, date, folder, provenance)   one per output folder's sweep
 *   runs (sweep, run_id, renderer, point, metric, status)
 *   trials (sweep, run_id, trial, status, frame_us, cpu_us, gpu_us, metric_us)
 * Primary keys make a second add of the same folder add nothing (ON CONFLICT DO
 * NOTHING, in SQLite since 3.24 and in PostgreSQL since 9.5). */
#include "runner/history/history_db.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const schema_sql[] = {
    "CREATE TABLE IF NOT EXISTS shadesweep_history (version INTEGER NOT NULL)",
    "CREATE TABLE IF NOT EXISTS sweeps (sweep TEXT PRIMARY KEY, date TEXT NOT NULL, "
    "folder TEXT NOT NULL, experiment TEXT NOT NULL, manifest_hash TEXT NOT NULL, "
    "commit_id TEXT NOT NULL, dirty INTEGER NOT NULL, host TEXT NOT NULL, "
    "device TEXT NOT NULL, added TEXT NOT NULL)",
    "CREATE TABLE IF NOT EXISTS runs (sweep TEXT NOT NULL REFERENCES sweeps (sweep), "
    "run_id TEXT NOT NULL, renderer TEXT NOT NULL, point INTEGER, metric TEXT NOT NULL, "
    "status TEXT NOT NULL, PRIMARY KEY (sweep, run_id))",
    "CREATE TABLE IF NOT EXISTS trials (sweep TEXT NOT NULL, run_id TEXT NOT NULL, "
    "trial INTEGER NOT NULL, status TEXT NOT NULL, frame_us DOUBLE PRECISION, "
    "cpu_us DOUBLE PRECISION, gpu_us DOUBLE PRECISION, metric_us DOUBLE PRECISION, "
    "PRIMARY KEY (sweep, run_id, trial), "
    "FOREIGN KEY (sweep, run_id) REFERENCES runs (sweep, run_id))",
    "CREATE INDEX IF NOT EXISTS sweeps_date ON sweeps (date)",
};

bool hdb_open(const char *url, bool create, hdb **out, char *err, size_t errlen)
{
    if (strncmp(url, "postgresql://", 13) == 0 || strncmp(url, "postgres://", 11) == 0)
        return hdb_open_pg(url, out, err, errlen);
    return hdb_open_sqlite(url, create, out, err, errlen);
}

bool hdb_schema(hdb *db, bool create, char *err, size_t errlen)
{
    for (size_t i = 0; create && i < sizeof schema_sql / sizeof *schema_sql; i++)
        if (!db->ops->exec(db, schema_sql[i], NULL, 0, NULL, err, errlen))
            return false;
    hdb_result r = {0};
    if (!db->ops->exec(db, "SELECT version FROM shadesweep_history", NULL, 0, &r, err,
                       errlen))
        return false;
    bool ok = true;
    if (r.nrows == 0 && create) {
        char v[16];
        snprintf(v, sizeof v, "%d", HISTORY_SCHEMA_VERSION);
        const char *p[] = {v};
        ok = db->ops->exec(db, "INSERT INTO shadesweep_history (version) VALUES ($1)", p, 1,
                           NULL, err, errlen);
    } else if (r.nrows != 1 || !r.cell[0] || atoi(r.cell[0]) != HISTORY_SCHEMA_VERSION) {
        snprintf(err, errlen,
                 "the database has schema version %s, this shadesweep reads and writes "
                 "version %d (a history of another version is not converted)",
                 r.nrows == 1 && r.cell[0] ? r.cell[0] : r.nrows ? "(several)" : "(none)",
                 HISTORY_SCHEMA_VERSION);
        ok = false;
    }
    hdb_result_free(&r);
    return ok;
}

bool hdb_commit(hdb *db, char *err, size_t errlen)
{
    return db->ops->exec(db, "COMMIT", NULL, 0, NULL, err, errlen);
}

void hdb_rollback(hdb *db)
{
    char err[256];
    db->ops->exec(db, "ROLLBACK", NULL, 0, NULL, err, sizeof err);
}

void hdb_result_free(hdb_result *r)
{
    for (size_t i = 0; r->cell && i < r->nrows * r->ncols; i++)
        free(r->cell[i]);
    free(r->cell);
    *r = (hdb_result){0};
}
