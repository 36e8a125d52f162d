#pragma once
/* The results history's database (issue 41, item 2): one interface, two backends:
 * SQLite, a file (the default; db_sqlite.c), and PostgreSQL through libpq for a team's
 * shared history (db_pg.c), with the same schema and the same SQL: parameters $1, $2, ...
 * bound as text, results as text. history_db.c opens either by its URL and keeps the
 * schema and its version; docs/notes/history.md. */
#include <stdbool.h>
#include <stddef.h>

/* The schema this build reads and writes; a database of another version is refused. */
#define HISTORY_SCHEMA_VERSION 1

typedef struct hdb_result {
    size_t nrows, ncols;
    char **cell;               /* cell[r * ncols + c]; NULL: SQL NULL */
} hdb_result;

typedef struct hdb hdb;
typedef struct hdb_ops {
    /* One statement with nparams text parameters (NULL: SQL NULL); its rows into *res
     * when res is not NULL. False with the database's message in err. */
    bool (*exec)(hdb *db, const char *sql, const char *const *params, int nparams,
                 hdb_result *res, char *err, size_t errlen);
    /* A transaction that writes: SQLite takes the write lock at once (BEGIN IMMEDIATE,
     * under the busy timeout), PostgreSQL serializes on an advisory lock. */
    bool (*begin)(hdb *db, char *err, size_t errlen);
    void (*close)(hdb *db);
} hdb_ops;

struct hdb {
    const hdb_ops *ops;
    const char *kind;          /* "sqlite" or "postgresql" */
};

/* url: postgresql://... or postgres://... (libpq's URI), else the path of a SQLite file,
 * created when missing only where `create`. False with a message naming the database. */
bool hdb_open(const char *url, bool create, hdb **out, char *err, size_t errlen);
bool hdb_open_sqlite(const char *path, bool create, hdb **out, char *err, size_t errlen);
bool hdb_open_pg(const char *url, hdb **out, char *err, size_t errlen);

/* Inside a transaction: the schema's tables made where missing (when create) and its
 * version checked: another version is refused with a message naming both. */
bool hdb_schema(hdb *db, bool create, char *err, size_t errlen);

bool hdb_commit(hdb *db, char *err, size_t errlen);
void hdb_rollback(hdb *db);

void hdb_result_free(hdb_result *r);
