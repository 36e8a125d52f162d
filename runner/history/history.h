#pragma once
/* `shadesweep history`: a results history with change points (issue 41, item 2).
 * history_cmd.c parses the options, history_add.c puts output folders into the
 * database (history_db.h), history_show.c finds and prints the change points
 * (results/changepoint.h). docs/notes/history.md. */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "results/changepoint.h"
#include "runner/history/history_db.h"

/* `shadesweep history add|show|check ...`; argv[0] is "history". Exit status: 0, 1
 * (check: a change point is a regression), 2 (bad input or a database error). */
int cmd_history(int argc, char **argv);

/* Every run of output folder dir, with its trials and provenance, into db in one
 * transaction; what was already there is kept and not added again. *runs and *trials:
 * how many were new. False with a message in err. */
bool history_add_folder(hdb *db, const char *dir, size_t *runs, size_t *trials, char *err,
                        size_t errlen);

typedef struct history_query {
    const char *run;           /* only this run id (NULL: all) */
    const char *renderer;      /* only this renderer's runs (NULL: all) */
    const char *metric;        /* wall, cpu, gpu, all, or NULL: each run's own */
    cp_options cp;
    bool drift;                /* remove the sweeps' common drift first */
} history_query;

/* The change points of db's series as the query asks: the table on out (NULL: none),
 * JSON into json (NULL: none). *regressions: how many are slower. False on a database
 * error, with a message in err. */
bool history_show(hdb *db, const char *where, const history_query *q, FILE *out, FILE *json,
                  size_t *regressions, char *err, size_t errlen);
