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
