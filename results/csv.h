#pragma once
/* Tidy CSV writer: RFC 4180 quoting, C-locale numbers, header always present,
 * written under a temporary name and renamed when complete (see fsutil.h).
 *
 *   csv_writer *w = csv_open(path, cols, ncols, err, sizeof err);
 *   csv_str(w, "a,b"); csv_u64(w, 3); csv_f64(w, 1.5, 3); csv_end_row(w);
 *   csv_commit(w, err, sizeof err);   // or csv_abort(w)
 *
 * Missing numbers (NAN) are written as an empty field; +-Inf as "inf"/"-inf".
 * A row with the wrong number of fields is a bug: csv_end_row() returns false. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

typedef struct csv_writer csv_writer;

csv_writer *csv_open(const char *final_path, const char *const *columns, size_t ncols,
                     char *err, size_t errlen);
void csv_str(csv_writer *w, const char *s);        /* quoted only when needed */
void csv_i64(csv_writer *w, int64_t v);
void csv_u64(csv_writer *w, uint64_t v);
void csv_f64(csv_writer *w, double v, int decimals); /* %.{decimals}f; NAN -> empty */
void csv_g(csv_writer *w, double v);                 /* shortest round-trip, never an
                                                      * exponent (num_plain) */
void csv_empty(csv_writer *w);
bool csv_end_row(csv_writer *w);
bool csv_commit(csv_writer *w, char *err, size_t errlen); /* frees w */
void csv_abort(csv_writer *w);                             /* frees w; NULL is fine */
/* csv_commit then hands the file to s instead of renaming it (fsutil.h afile_set). */
struct afile_set;
void csv_join(csv_writer *w, struct afile_set *s);

/* The quoting rule on its own, for tests and for other writers:
 * writes s to fp, in double quotes (inner quotes doubled) when it contains
 * a comma, a quote, CR or LF, or leading/trailing space. */
void csv_write_field(FILE *fp, const char *s);

/* A reader for what the writer writes (and RFC 4180 generally, with LF or CRLF row
 * ends): one record at a time from text held in memory.
 *
 *   csv_record r = {0}; size_t pos = 0; int k;
 *   while ((k = csv_next_record(text, len, &pos, &r)) > 0) use(r.field, r.n);
 *   csv_record_free(&r);   // k < 0: malformed (see below)
 *
 * Returns 1 with a record, 0 at the end of the text, -1 for a record that is not
 * complete: an unterminated quote, a quote inside an unquoted field, text after a
 * closing quote, or a last row without its line end (a file cut off mid-row). */
typedef struct csv_record {
    char **field;      /* n NUL-terminated fields, valid until the next call */
    size_t n;
    size_t cap;
    char *buf;
    size_t bufcap;
} csv_record;
int csv_next_record(const char *text, size_t len, size_t *pos, csv_record *r);
void csv_record_free(csv_record *r);
