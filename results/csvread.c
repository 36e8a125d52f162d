#include "results/csvread.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct growbuf {
    char *s;
    size_t n, cap;
} growbuf;

static bool gb_put(growbuf *b, char c)
{
    if (b->n + 1 >= b->cap) {
        size_t cap = b->cap ? b->cap * 2 : 64;
        char *s = realloc(b->s, cap);
        if (!s)
            return false;
        b->s = s;
        b->cap = cap;
    }
    b->s[b->n++] = c;
    b->s[b->n] = 0;
    return true;
}

typedef struct fieldlist {
    char **f;
    size_t n, cap;
} fieldlist;

static bool fl_push(fieldlist *l, const char *s, size_t len)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? l->cap * 2 : 16;
        char **f = realloc(l->f, cap * sizeof *f);
        if (!f)
            return false;
        l->f = f;
        l->cap = cap;
    }
    char *d = malloc(len + 1);
    if (!d)
        return false;
    memcpy(d, s ? s : "", len);
    d[len] = 0;
    l->f[l->n++] = d;
    return true;
}

static void fl_free(fieldlist *l)
{
    for (size_t i = 0; i < l->n; i++)
        free(l->f[i]);
    free(l->f);
    memset(l, 0, sizeof *l);
}

static bool add_row(csv_table *t, fieldlist *row, size_t *cap)
{
    if (t->nrows == *cap) {
        size_t c = *cap ? *cap * 2 : 64;
        char ***r = realloc(t->rows, c * sizeof *r);
        if (!r)
            return false;
        t->rows = r;
        *cap = c;
    }
    while (row->n < t->ncols)
        if (!fl_push(row, "", 0))
            return false;
    t->rows[t->nrows++] = row->f;
    memset(row, 0, sizeof *row);
    return true;
}

bool csv_read(const char *path, csv_table *t, char *err, size_t errlen)
{
    memset(t, 0, sizeof *t);
    FILE *fp = fopen(path, "rb");
    if (!fp) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return false;
    }
    growbuf field = {0};
    fieldlist row = {0};
    size_t cap = 0, line = 1;
    bool ok = true, quoted = false, have_header = false, any = false, row_started = false;
    int c;
    const char *why = NULL;
    for (;;) {
        c = getc(fp);
        if (quoted) {
            if (c == EOF) {
                why = "unterminated quoted field";
                break;
            }
            if (c == '"') {
                int d = getc(fp);
                if (d == '"') {
                    ok = gb_put(&field, '"');
                } else {
                    quoted = false;
                    if (d != EOF)
                        ungetc(d, fp);
                }
            } else {
                if (c == '\n')
                    line++;
                ok = gb_put(&field, (char)c);
            }
            if (!ok)
                break;
            continue;
        }
        if (c == '"' && field.n == 0) {
            quoted = true;
            row_started = true;
            continue;
        }
        if (c == ',' || c == '\n' || c == EOF) {
            if (c == EOF && !row_started && field.n == 0)
                break;
            if (!(ok = fl_push(&row, field.s, field.n)))
                break;
            field.n = 0;
            if (field.s)
                field.s[0] = 0;
            if (c == ',') {
                row_started = true;
                continue;
            }
            /* end of a row */
            if (!have_header) {
                t->header = row.f;
                t->ncols = row.n;
                memset(&row, 0, sizeof row);
                have_header = true;
            } else if (row.n > t->ncols) {
                why = "a row has more fields than the header";
                break;
            } else if (!(ok = add_row(t, &row, &cap))) {
                break;
            }
            any = true;
            row_started = false;
            line++;
            if (c == EOF)
                break;
            continue;
        }
        if (c == '\r') {
            int d = getc(fp);
            if (d == '\n') {
                ungetc(d, fp);
                continue;
            }
            if (d != EOF)
                ungetc(d, fp);
        }
        row_started = true;
        if (!(ok = gb_put(&field, (char)c)))
            break;
    }
    fclose(fp);
    free(field.s);
    fl_free(&row);
    if (!ok)
        why = "out of memory";
    else if (!why && !any)
        why = "empty (no header)";
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
    for (size_t c = 0; c < t->ncols; c++)
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
