/* The history's SQLite backend (runner/history/history_db.h): a file beside the
 * results. Concurrent adds: each is one transaction that takes the write lock first
 * (BEGIN IMMEDIATE), and a busy database is waited for (busy timeout 60 s) rather than
 * failed. */
#include "runner/history/history_db.h"

#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct sqlite_db {
    hdb base;
    sqlite3 *db;
    char path[4096];
} sqlite_db;

static bool sq_exec(hdb *h, const char *sql, const char *const *params, int nparams,
                    hdb_result *res, char *err, size_t errlen)
{
    sqlite_db *s = (sqlite_db *)h;
    sqlite3_stmt *st = NULL;
    if (res)
        *res = (hdb_result){0};
    int rc = sqlite3_prepare_v2(s->db, sql, -1, &st, NULL);
    for (int i = 0; rc == SQLITE_OK && i < nparams; i++) {
        char name[16];
        snprintf(name, sizeof name, "$%d", i + 1);
        int k = sqlite3_bind_parameter_index(st, name);
        rc = !k ? SQLITE_RANGE
             : params[i] ? sqlite3_bind_text(st, k, params[i], -1, SQLITE_TRANSIENT)
                         : sqlite3_bind_null(st, k);
    }
    size_t cap = 0;
    while (rc == SQLITE_OK || rc == SQLITE_ROW) {
        rc = sqlite3_step(st);
        if (rc != SQLITE_ROW || !res)
            continue;
        size_t nc = (size_t)sqlite3_column_count(st);
        if ((res->nrows + 1) * nc > cap) {
            cap = cap ? 2 * cap : 64 * nc;
            char **c = realloc(res->cell, cap * sizeof *c);
            if (!c) {
                rc = SQLITE_NOMEM;
                break;
            }
            res->cell = c;
        }
        res->ncols = nc;
        for (size_t j = 0; j < nc; j++) {
            const unsigned char *t = sqlite3_column_text(st, (int)j);
            res->cell[res->nrows * nc + j] = t ? strdup((const char *)t) : NULL;
        }
        res->nrows++;
    }
    bool ok = rc == SQLITE_DONE;
    if (!ok)
        snprintf(err, errlen, "%s: %s", s->path, sqlite3_errmsg(s->db));
    sqlite3_finalize(st);
    if (!ok && res)
        hdb_result_free(res);
    return ok;
}

static bool sq_begin(hdb *h, char *err, size_t errlen)
{
    return sq_exec(h, "BEGIN IMMEDIATE", NULL, 0, NULL, err, errlen);
}

static void sq_close(hdb *h)
{
    sqlite_db *s = (sqlite_db *)h;
    sqlite3_close(s->db);
    free(s);
}

static const hdb_ops sqlite_ops = {sq_exec, sq_begin, sq_close};

bool hdb_open_sqlite(const char *path, bool create, hdb **out, char *err, size_t errlen)
{
    *out = NULL;
    sqlite_db *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(err, errlen, "%s: out of memory", path);
        return false;
    }
    s->base = (hdb){&sqlite_ops, "sqlite"};
    snprintf(s->path, sizeof s->path, "%s", path);
    int flags = SQLITE_OPEN_READWRITE | (create ? SQLITE_OPEN_CREATE : 0);
    if (sqlite3_open_v2(path, &s->db, flags, NULL) != SQLITE_OK) {
        snprintf(err, errlen, "%s: %s", path,
                 s->db ? sqlite3_errmsg(s->db) : "cannot open the database");
        sqlite3_close(s->db);
        free(s);
        return false;
    }
    sqlite3_busy_timeout(s->db, 60000);
    if (!sq_exec(&s->base, "PRAGMA foreign_keys = ON", NULL, 0, NULL, err, errlen)) {
        sq_close(&s->base);
        return false;
    }
    *out = &s->base;
    return true;
}
