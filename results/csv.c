/* Tidy CSV writer. See csv.h.
 *
 * Format: RFC 4180 fields and quoting, but rows end with LF ("\n"), not CRLF:
 * every reader we care about (pandas, R, Python's csv, awk) accepts LF, and
 * LF keeps the files diff- and grep-friendly. The header row comes first.
 *
 * Numbers never depend on the locale: integers are formatted here, digit by
 * digit; floating-point numbers go through printf and, should the process ever
 * run under a locale whose decimal point is not '.', the separator is replaced.
 *
 * Output is collected in a buffer inside the writer and handed to stdio in
 * large blocks: a field costs no allocation and no stdio call. */
#include "results/csv.h"

#include <locale.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <errno.h>

#include "common/fsutil.h"
#include "common/grow.h"
#include "results/numfmt.h"

#define CSV_BUF_SIZE (64 * 1024)
#define CSV_MAX_DECIMALS 40

struct csv_writer {
    afile file;
    size_t ncols;
    size_t nfields;   /* fields written in the current row */
    size_t row;       /* rows ended so far, header included (for messages) */
    bool failed;      /* sticky: after the first error calls do nothing */
    char msg[256];
    size_t len;       /* bytes used in buf */
    char buf[CSV_BUF_SIZE];
};

/* >>output */

static void fail(csv_writer *w, const char *what)
{
    afile_fail_once(&w->file, "csv", &w->failed, w->msg, sizeof w->msg, what);
}

/* a write to the stream failed: errno says why */
static void fail_write(csv_writer *w)
{
    char m[160];
    snprintf(m, sizeof m, "write failed: %s", strerror(errno ? errno : EIO));
    fail(w, m);
}

static void flush_buf(csv_writer *w)
{
    if (w->len == 0 || w->failed)
        return;
    if (fwrite(w->buf, 1, w->len, w->file.fp) != w->len)
        fail_write(w);
    w->len = 0;
}

static void put(csv_writer *w, const char *p, size_t n)
{
    if (w->len + n > sizeof w->buf) {
        flush_buf(w);
        if (w->failed)
            return;
        if (n > sizeof w->buf) {
            if (fwrite(p, 1, n, w->file.fp) != n)
                fail_write(w);
            return;
        }
    }
    memcpy(w->buf + w->len, p, n);
    w->len += n;
}

static void put_char(csv_writer *w, char c)
{
    if (w->len == sizeof w->buf) {
        flush_buf(w);
        if (w->failed)
            return;
    }
    w->buf[w->len++] = c;
}

/* >>quoting */

/* Length of s, and whether it needs quotes (see csv_write_field). */
static bool needs_quotes(const char *s, size_t *len)
{
    bool q = false;
    size_t n = 0;
    for (const char *c = s; *c; c++, n++) {
        if (*c == ',' || *c == '"' || *c == '\r' || *c == '\n')
            q = true;
    }
    if (n > 0 && (s[0] == ' ' || s[0] == '\t' || s[n - 1] == ' ' || s[n - 1] == '\t'))
        q = true;
    *len = n;
    return q;
}

void csv_write_field(FILE *fp, const char *s)
{
    size_t n;
    if (s == NULL)
        return;
    if (!needs_quotes(s, &n)) {
        fwrite(s, 1, n, fp);
        return;
    }
    putc('"', fp);
    for (const char *c = s; *c; c++) {
        if (*c == '"')
            putc('"', fp);
        putc(*c, fp);
    }
    putc('"', fp);
}

static void put_field_text(csv_writer *w, const char *s)
{
    size_t n;
    if (!needs_quotes(s, &n)) {
        put(w, s, n);
        return;
    }
    put_char(w, '"');
    const char *run = s;
    for (const char *c = s; *c; c++) {
        if (*c == '"') {
            put(w, run, (size_t)(c - run + 1)); /* up to and including the quote */
            put_char(w, '"');
            run = c + 1;
        }
    }
    put(w, run, strlen(run));
    put_char(w, '"');
}

/* >>numbers */

/* Writes v in decimal at the end of buf[0..24); returns the first character. */
static char *format_u64(uint64_t v, char *end)
{
    char *p = end;
    do {
        *--p = (char)('0' + v % 10);
        v /= 10;
    } while (v != 0);
    return p;
}

static bool is_c_number_text(const char *s)
{
    for (; *s; s++) {
        char c = *s;
        if (!((c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e' ||
              c == 'E'))
            return false;
    }
    return true;
}

/* >>api */

static bool begin_field(csv_writer *w)
{
    if (w == NULL || w->failed)
        return false;
    if (w->nfields > 0)
        put_char(w, ',');
    w->nfields++;
    return true;
}

csv_writer *csv_open(const char *final_path, const char *const *columns, size_t ncols,
                     char *err, size_t errlen)
{
    if (columns == NULL || ncols == 0) {
        snprintf(err, errlen, "%s: bug: a CSV file needs at least one column",
                 final_path ? final_path : "csv");
        return NULL;
    }
    for (size_t i = 0; i < ncols; i++) {
        if (columns[i] == NULL || columns[i][0] == '\0') {
            snprintf(err, errlen, "%s: bug: column %zu has no name",
                     final_path ? final_path : "csv", i);
            return NULL;
        }
    }
    csv_writer *w = malloc(sizeof *w);
    if (w == NULL) {
        snprintf(err, errlen, "%s: out of memory", final_path ? final_path : "csv");
        return NULL;
    }
    w->ncols = ncols;
    w->nfields = 0;
    w->row = 0;
    w->failed = false;
    w->msg[0] = '\0';
    w->len = 0;
    if (!afile_open(&w->file, final_path, err, errlen)) {
        free(w);
        return NULL;
    }
    for (size_t i = 0; i < ncols; i++)
        csv_str(w, columns[i]);
    csv_end_row(w);
    return w;
}

void csv_str(csv_writer *w, const char *s)
{
    if (!begin_field(w))
        return;
    if (s != NULL)
        put_field_text(w, s);
}

void csv_i64(csv_writer *w, int64_t v)
{
    if (!begin_field(w))
        return;
    char tmp[24];
    char *end = tmp + sizeof tmp;
    uint64_t mag = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
    char *p = format_u64(mag, end);
    if (v < 0)
        *--p = '-';
    put(w, p, (size_t)(end - p));
}

void csv_u64(csv_writer *w, uint64_t v)
{
    if (!begin_field(w))
        return;
    char tmp[24];
    char *end = tmp + sizeof tmp;
    char *p = format_u64(v, end);
    put(w, p, (size_t)(end - p));
}

/* Writes the non-finite forms; true when v was non-finite. */
static bool put_nonfinite(csv_writer *w, double v)
{
    if (isnan(v))
        return true; /* missing: empty field */
    if (isinf(v)) {
        if (v > 0)
            put(w, "inf", 3);
        else
            put(w, "-inf", 4);
        return true;
    }
    return false;
}

void csv_f64(csv_writer *w, double v, int decimals)
{
    if (!begin_field(w) || put_nonfinite(w, v))
        return;
    if (decimals < 0)
        decimals = 0;
    if (decimals > CSV_MAX_DECIMALS)
        decimals = CSV_MAX_DECIMALS;
    char s[320 + CSV_MAX_DECIMALS + 8]; /* DBL_MAX has 309 integer digits */
    int n = snprintf(s, sizeof s, "%.*f", decimals, v);
    if (n < 0 || (size_t)n >= sizeof s) {
        fail(w, "bug: number does not fit its buffer");
        return;
    }
    if (!is_c_number_text(s))
        num_c_decimal_point(s);
    put(w, s, strlen(s));
}

void csv_g(csv_writer *w, double v)
{
    if (!begin_field(w) || put_nonfinite(w, v))
        return;
    char s[340];   /* any finite double in plain decimals (num_plain) */
    num_plain(v, s, sizeof s);
    put(w, s, strlen(s));
}

void csv_empty(csv_writer *w)
{
    begin_field(w);
}

bool csv_end_row(csv_writer *w)
{
    if (w == NULL || w->failed)
        return false;
    if (w->nfields != w->ncols) {
        char m[160];
        snprintf(m, sizeof m, "bug: row %zu has %zu fields, the header has %zu", w->row,
                 w->nfields, w->ncols);
        fail(w, m);
        return false;
    }
    put_char(w, '\n');
    w->nfields = 0;
    w->row++;
    return !w->failed;
}

bool csv_commit(csv_writer *w, char *err, size_t errlen)
{
    if (w == NULL) {
        snprintf(err, errlen, "bug: csv_commit(NULL)");
        return false;
    }
    if (!w->failed && w->nfields != 0) {
        char m[160];
        snprintf(m, sizeof m, "bug: row %zu not ended (%zu of %zu fields)", w->row, w->nfields,
                 w->ncols);
        fail(w, m);
    }
    flush_buf(w);
    bool ok = afile_finish(&w->file, w->failed, w->msg, err, errlen);
    free(w);
    return ok;
}

void csv_join(csv_writer *w, struct afile_set *s)
{
    if (w)
        w->file.set = s;
}

void csv_abort(csv_writer *w)
{
    if (w == NULL)
        return;
    afile_abort(&w->file);
    free(w);
}

/* >>input (csv.h: csv_next_record) */

static bool rec_reserve(csv_record *r, size_t nbytes, size_t nfields)
{
    return GROW(r->buf, r->bufcap, nbytes, 256) && GROW(r->field, r->cap, nfields, 16);
}

int csv_next_record(const char *text, size_t len, size_t *pos, csv_record *r)
{
    size_t i = *pos;
    r->n = 0;
    if (i >= len)
        return 0;
    /* A field never grows when unquoted: the record's bytes bound the buffer. */
    size_t end = i;
    bool inq = false;
    while (end < len && (inq || text[end] != '\n')) {
        if (text[end] == '"')
            inq = !inq;
        end++;
    }
    if (end >= len)
        return -1;   /* no line end: cut off (or an unterminated quote) */
    if (!rec_reserve(r, end - i + 1, 1))
        return -1;
    /* Field starts are offsets into buf until the record is complete. */
    size_t o = 0, nf = 0;
    size_t *starts = NULL, cap = 0;
    int rc = 1;
    for (;;) {
        if (!GROW(starts, cap, nf + 1, 16)) {
            rc = -1;
            break;
        }
        starts[nf++] = o;
        if (i < end && text[i] == '"') {
            i++;
            for (;;) {
                if (i >= end) {
                    rc = -1;
                    break;
                }
                if (text[i] == '"') {
                    if (i + 1 < end && text[i + 1] == '"') {
                        r->buf[o++] = '"';
                        i += 2;
                        continue;
                    }
                    i++;
                    break;
                }
                r->buf[o++] = text[i++];
            }
            if (rc < 0)
                break;
            if (i < end && text[i] != ',' && !(text[i] == '\r' && i + 1 == end)) {
                rc = -1;
                break;
            }
        } else {
            while (i < end && text[i] != ',' && !(text[i] == '\r' && i + 1 == end)) {
                if (text[i] == '"') {
                    rc = -1;
                    break;
                }
                r->buf[o++] = text[i++];
            }
            if (rc < 0)
                break;
        }
        r->buf[o++] = 0;
        if (i < end && text[i] == ',') {
            i++;
            continue;
        }
        break;
    }
    if (rc > 0 && !rec_reserve(r, 0, nf))
        rc = -1;
    if (rc > 0) {
        for (size_t k = 0; k < nf; k++)
            r->field[k] = r->buf + starts[k];
        r->n = nf;
        *pos = end + 1;
    }
    free(starts);
    return rc;
}

void csv_record_free(csv_record *r)
{
    free(r->field);
    free(r->buf);
    memset(r, 0, sizeof *r);
}
