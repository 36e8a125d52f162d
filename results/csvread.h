#pragma once
/* Reading the CSV files shadesweep writes (RFC 4180: quoted fields, doubled quotes,
 * CR LF or LF), whole, into memory: summary.csv and plan.csv for the end-of-run
 * table and `compare`. */
#include <stdbool.h>
#include <stddef.h>

typedef struct csv_table {
    size_t ncols, nrows;
    char **header;          /* ncols names */
    char ***rows;           /* nrows x ncols fields */
} csv_table;

/* False with "PATH:LINE: why" in err (no such file, empty, a row whose field count
 * differs from the header's, a malformed or cut-off row: csv_next_record's rules). */
bool csv_read(const char *path, csv_table *t, char *err, size_t errlen);
void csv_table_free(csv_table *t);
/* Column index of name, or -1. */
int csv_col(const csv_table *t, const char *name);
/* Field of row r in column c; "" when c < 0. */
const char *csv_get(const csv_table *t, size_t r, int c);
/* The field as a number; NAN when empty or not a number. */
double csv_num(const csv_table *t, size_t r, int c);

/* The rows of a table sorted by one column's text, for look-ups by id. */
typedef struct csv_index {
    struct csv_index_key {
        const char *key;
        size_t row;
    } *item;
    size_t n;
} csv_index;

/* False when out of memory. A table without the column gives an empty index. */
bool csv_index_build(csv_index *ix, const csv_table *t, const char *column);
/* The rows whose column is `key`, in file order: *first indexes ix->item; returns how
 * many (0: none). */
size_t csv_index_find(const csv_index *ix, const char *key, size_t *first);
void csv_index_free(csv_index *ix);

