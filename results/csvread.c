#include "results/csvread.h"

#include "results/csv.h"
#include "common/fsutil.h"
#include "common/grow.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char **copy_fields(const csv_record *r)
{
    char **f = calloc(r->n ? r->n : 1, sizeof *f);
    for (size_t i = 0; f && i < r->n; i++)
        if (!(f[i] = strdup(r->field[i]))) {
            while (i--)
                free(f[i]);
            free(f);
            return NULL;
        }
    return f;
}

/* The whole file in memory, then csv_next_record (results/csv.c, the one parser of
 * the CSV shadesweep writes) record by record. */
bool csv_read(const char *path, csv_table *t, char *err, size_t errlen)
{
    memset(t, 0, sizeof *t);
    char *text;
    size_t len, pos = 0, cap = 0, line = 0;   /* the record, from 1 (the header) */
    int e;
    if (!(text = fs_read_all(path, 0, &len, &e))) {
        snprintf(err, errlen, "%s: %s", path, strerror(e));
        return false;
    }
    csv_record r = {0};
    const char *why = NULL;
    int k;
    while (!why && (k = csv_next_record(text, len, &pos, &r)) > 0) {
        line++;
        if (!t->header) {
            t->ncols = r.n;
            if (!(t->header = copy_fields(&r)))
                why = "out of memory";
        } else if (r.n != t->ncols) {
            why = "a row whose field count differs from the header's";
        } else {
            if (!GROW(t->rows, cap, t->nrows + 1, 64)) {
                why = "out of memory";
                break;
            }
            if (!(t->rows[t->nrows] = copy_fields(&r)))
                why = "out of memory";
            else
                t->nrows++;
        }
    }
    if (!why && k < 0) {
        line++;
        why = "a malformed or cut-off row";
    }
    if (!why && !t->header) {
        line = 1;
        why = "empty (no header)";
    }
    csv_record_free(&r);
    free(text);
    if (why) {
        snprintf(err, errlen, "%s:%zu: %s", path, line, why);
        csv_table_free(t);
        return false;
    }
    return true;
}

void csv_table_free(csv_table *t)
{
    for (size_t r = 0; r < t->nrows; r++) {
        for (size_t c = 0; c < t->ncols; c++)
            free(t->rows[r][c]);
        free(t->rows[r]);
    }
    free(t->rows);
    for (size_t c = 0; t->header && c < t->ncols; c++)
        free(t->header[c]);
    free(t->header);
    memset(t, 0, sizeof *t);
}

int csv_col(const csv_table *t, const char *name)
{
    for (size_t c = 0; c < t->ncols; c++)
        if (strcmp(t->header[c], name) == 0)
            return (int)c;
    return -1;
}

const char *csv_get(const csv_table *t, size_t r, int c)
{
    if (c < 0 || (size_t)c >= t->ncols || r >= t->nrows)
        return "";
    return t->rows[r][c];
}

double csv_num(const csv_table *t, size_t r, int c)
{
    const char *s = csv_get(t, r, c);
    if (!*s)
        return NAN;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end)
        return NAN;
    return v;
}

static int by_key(const void *a, const void *b)
{
    const struct csv_index_key *x = a, *y = b;
    int c = strcmp(x->key, y->key);
    return c ? c : (x->row > y->row) - (x->row < y->row);
}

bool csv_index_build(csv_index *ix, const csv_table *t, const char *column)
{
    int c = csv_col(t, column);
    ix->n = c >= 0 ? t->nrows : 0;
    ix->item = malloc((ix->n ? ix->n : 1) * sizeof *ix->item);
    if (!ix->item)
        return false;
    for (size_t r = 0; r < ix->n; r++)
        ix->item[r] = (struct csv_index_key){t->rows[r][c], r};
    qsort(ix->item, ix->n, sizeof *ix->item, by_key);
    return true;
}

size_t csv_index_find(const csv_index *ix, const char *key, size_t *first)
{
    size_t lo = 0, hi = ix->n;   /* the first item whose key is not below `key` */
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (strcmp(ix->item[mid].key, key) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    *first = lo;
    size_t n = 0;
    while (lo + n < ix->n && strcmp(ix->item[lo + n].key, key) == 0)
        n++;
    return n;
}

void csv_index_free(csv_index *ix)
{
    free(ix->item);
    ix->item = NULL;
    ix->n = 0;
}
