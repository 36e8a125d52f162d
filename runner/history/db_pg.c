/* The history's PostgreSQL backend (runner/history/history_db.h) through libpq: a
 * team's shared history, the same schema as SQLite's. Concurrent adds: each is one
 * transaction that first takes a transaction-scoped advisory lock, so two adds (and two
 * first adds that both make the tables) run one after the other; the primary keys make
 * a folder added twice add nothing twice. */
#include "runner/history/history_db.h"

#include <libpq-fe.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the advisory lock's key: "SSH1" (shadesweep history) */
#define HISTORY_LOCK_KEY 0x53534831

typedef struct pg_db {
    hdb base;
    PGconn *conn;
} pg_db;

/* libpq's message on one line, without its trailing newline */
static void pg_message(const char *m, char *err, size_t errlen)
{
    snprintf(err, errlen, "postgresql: %s", m && *m ? m : "unknown error");
    for (char *p = err; *p; p++)
        if (*p == '\t')
            *p = ' ';
        else if (*p == '\n')
            *p = p[1] ? ' ' : '\0';
}

static bool pg_exec(hdb *h, const char *sql, const char *const *params, int nparams,
                    hdb_result *res, char *err, size_t errlen)
{
    pg_db *p = (pg_db *)h;
    if (res)
        *res = (hdb_result){0};
    PGresult *r = PQexecParams(p->conn, sql, nparams, NULL, params, NULL, NULL, 0);
    ExecStatusType st = PQresultStatus(r);
    bool ok = st == PGRES_COMMAND_OK || st == PGRES_TUPLES_OK;
    if (!ok)
        pg_message(PQresultErrorMessage(r), err, errlen);
    if (ok && res && st == PGRES_TUPLES_OK) {
        res->nrows = (size_t)PQntuples(r);
        res->ncols = (size_t)PQnfields(r);
        res->cell = calloc(res->nrows * res->ncols + 1, sizeof *res->cell);
        ok = res->cell != NULL;
        for (size_t i = 0; ok && i < res->nrows; i++)
            for (size_t j = 0; j < res->ncols; j++)
                if (!PQgetisnull(r, (int)i, (int)j))
                    res->cell[i * res->ncols + j] = strdup(PQgetvalue(r, (int)i, (int)j));
        if (!ok)
            snprintf(err, errlen, "postgresql: out of memory");
    }
    PQclear(r);
    if (!ok && res)
        hdb_result_free(res);
    return ok;
}

static bool pg_begin(hdb *h, char *err, size_t errlen)
{
    char sql[64];
    snprintf(sql, sizeof sql, "SELECT pg_advisory_xact_lock(%d)", HISTORY_LOCK_KEY);
    return pg_exec(h, "BEGIN", NULL, 0, NULL, err, errlen) &&
           pg_exec(h, sql, NULL, 0, NULL, err, errlen);
}

static void pg_quiet(void *arg, const char *message)
{
    (void)arg;
    (void)message;
}

static void pg_close(hdb *h)
{
    pg_db *p = (pg_db *)h;
    PQfinish(p->conn);
    free(p);
}

static const hdb_ops pg_ops = {pg_exec, pg_begin, pg_close};

bool hdb_open_pg(const char *url, hdb **out, char *err, size_t errlen)
{
    *out = NULL;
    pg_db *p = calloc(1, sizeof *p);
    if (!p) {
        snprintf(err, errlen, "postgresql: out of memory");
        return false;
    }
    p->base = (hdb){&pg_ops, "postgresql"};
    p->conn = PQconnectdb(url);
    if (PQstatus(p->conn) != CONNECTION_OK) {
        pg_message(PQerrorMessage(p->conn), err, errlen);
        pg_close(&p->base);
        return false;
    }
    /* the server's notices (a table that already exists) are not the user's business */
    PQsetNoticeProcessor(p->conn, pg_quiet, NULL);
    *out = &p->base;
    return true;
}
