/* OUT/summary_long.csv: summary.csv in long form, the swept keys typed
 * (runner/answer/summary_long.h). */
#include "runner/answer/summary_long.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "results/csv.h"
#include "common/fsutil.h"
#include "runner/folder/output.h"

/* ---- typed cells --------------------------------------------------------------------- */

/* The whole of s is one number (finite unless `inf_ok`). */
static bool number_of(const char *s, bool inf_ok, double *v)
{
    char *end;
    *v = strtod(s, &end);
    return *s && end != s && *end == '\0' && !isnan(*v) && (inf_ok || isfinite(*v));
}

/* plan.csv's span text: "frames:N" or "seconds:S". */
static bool span_of(const char *s, bool *frames, double *v)
{
    *frames = strncmp(s, "frames:", 7) == 0;
    if (*frames)
        return number_of(s + 7, false, v);
    return strncmp(s, "seconds:", 8) == 0 && number_of(s + 8, false, v);
}

/* "WxH" */
static bool resolution_of(const char *s, long *w, long *h)
{
    char *x, *end;
    if (*s < '0' || *s > '9')
        return false;
    *w = strtol(s, &x, 10);
    if (*x != 'x' || x[1] < '0' || x[1] > '9')
        return false;
    *h = strtol(x + 1, &end, 10);
    return *end == '\0';
}

typedef enum key_kind { KEY_TEXT, KEY_NUMBER, KEY_SPAN, KEY_RESOLUTION } key_kind;

static bool is_kind(const char *s, key_kind k)
{
    double v;
    bool frames;
    long w, h;
    switch (k) {
    case KEY_NUMBER: return number_of(s, false, &v);
    case KEY_SPAN: return span_of(s, &frames, &v);
    case KEY_RESOLUTION: return resolution_of(s, &w, &h);
    default: return true;
    }
}

/* How a plan column's cells read: every non-empty cell of the one kind, else text. */
static key_kind kind_of(const csv_table *pl, size_t c)
{
    static const key_kind typed[] = {KEY_NUMBER, KEY_SPAN, KEY_RESOLUTION};
    for (size_t k = 0; k < sizeof typed / sizeof typed[0]; k++) {
        bool all = true, any = false;
        for (size_t r = 0; r < pl->nrows && all; r++) {
            const char *s = pl->rows[r][c];
            any = any || *s;
            all = !*s || is_kind(s, typed[k]);
        }
        if (all && any)
            return typed[k];
    }
    return KEY_TEXT;
}

/* The key's cells of plan row `row` (-1: not in the plan, every cell empty). */
static void key_cells(csv_writer *w, const csv_table *pl, long row, size_t c, key_kind k)
{
    const char *s = row >= 0 ? pl->rows[row][c] : "";
    double v;
    bool frames = false, ok;
    long width, height;
    switch (k) {
    case KEY_NUMBER:
        if (number_of(s, false, &v))
            csv_g(w, v);
        else
            csv_empty(w);
        break;
    case KEY_SPAN:
        ok = span_of(s, &frames, &v);
        if (ok && frames)
            csv_g(w, v);
        else
            csv_empty(w);
        if (ok && !frames)
            csv_g(w, v);
        else
            csv_empty(w);
        break;
    case KEY_RESOLUTION:
        csv_str(w, s);
        if (resolution_of(s, &width, &height)) {
            csv_i64(w, width);
            csv_i64(w, height);
        } else {
            csv_empty(w);
            csv_empty(w);
        }
        break;
    default:
        csv_str(w, s);
    }
}

/* ---- the table ----------------------------------------------------------------------- */

static const char *const head[] = {"experiment", "run_id", "renderer", "scene"};
static const char *const tail[] = {"trial", "status", "measure", "unit", "value"};
#define NHEAD (sizeof head / sizeof head[0])
#define NTAIL (sizeof tail / sizeof tail[0])

/* a + b, allocated; NULL when out of memory */
static char *joined(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    char *s = malloc(la + lb + 1);
    if (s) {
        memcpy(s, a, la);
        memcpy(s + la, b, lb + 1);
    }
    return s;
}

static bool not_a_key(const char *name)
{
    static const char *const own[] = {"index", "run_id", "shard", "folded", "renderer",
                                      "scene"};
    for (size_t i = 0; i < sizeof own / sizeof own[0]; i++)
        if (strcmp(name, own[i]) == 0)
            return true;
    return false;
}

typedef struct key_col {
    size_t col;
    key_kind kind;
} key_col;

/* The plan's varying keys, and the header they make with summary_long's own columns. */
static bool layout(const csv_table *pl, key_col *keys, size_t *nkeys, char **names,
                   size_t *nnames)
{
    size_t n = 0, k = 0;
    bool ok = true;
    for (size_t i = 0; i < NHEAD; i++)
        ok = ok && (names[n++] = strdup(head[i])) != NULL;
    for (size_t c = 0; ok && c < pl->ncols; c++) {
        bool varies = false;
        for (size_t r = 1; r < pl->nrows && !varies; r++)
            varies = strcmp(pl->rows[r][c], pl->rows[0][c]) != 0;
        if (!varies || not_a_key(pl->header[c]))
            continue;
        keys[k] = (key_col){c, kind_of(pl, c)};
        const char *h = pl->header[c];
        if (keys[k].kind == KEY_SPAN) {
            ok = (names[n++] = joined(h, "_frames")) != NULL &&
                 (names[n++] = joined(h, "_s")) != NULL;
        } else {
            ok = (names[n++] = strdup(h)) != NULL;
            if (ok && keys[k].kind == KEY_RESOLUTION)
                ok = (names[n++] = strdup("width_px")) != NULL &&
                     (names[n++] = strdup("height_px")) != NULL;
        }
        k++;
    }
    for (size_t i = 0; ok && i < NTAIL; i++)
        ok = (names[n++] = strdup(tail[i])) != NULL;
    *nkeys = k;
    *nnames = n;
    return ok;
}

/* One trial's rows: a row per measured value of summary.csv row r; own[] are
 * summary.csv's columns of head[], then of trial and status; unit[] its columns' units
 * (NULL: not a measure). */
static void trial_rows(csv_writer *w, const csv_table *pl, const csv_table *sm, size_t r,
                       const int *own, const char *const *unit_of, long prow,
                       const key_col *keys, size_t nkeys)
{
    for (size_t c = 0; c < sm->ncols; c++) {
        const char *unit = unit_of[c];
        double v;
        if (!unit || !number_of(sm->rows[r][c], true, &v))
            continue;
        for (size_t i = 0; i < NHEAD; i++)
            csv_str(w, csv_get(sm, r, own[i]));
        for (size_t k = 0; k < nkeys; k++)
            key_cells(w, pl, prow, keys[k].col, keys[k].kind);
        csv_str(w, csv_get(sm, r, own[NHEAD]));       /* trial */
        csv_str(w, csv_get(sm, r, own[NHEAD + 1]));   /* status */
        csv_str(w, sm->header[c]);
        csv_str(w, unit);
        csv_g(w, v);
        csv_end_row(w);
    }
}

bool summary_long_write(const char *out_dir, const csv_table *pl, const csv_table *sm,
                        afile_set *set, char *err, size_t errlen)
{
    size_t cap = 9 + 3 * pl->ncols;
    key_col *keys = malloc((pl->ncols ? pl->ncols : 1) * sizeof *keys);
    char **names = calloc(cap, sizeof *names);
    const char **unit = summary_units_of(sm);
    csv_index ix = {0};
    size_t nkeys = 0, nnames = 0;
    bool ok = keys && names && unit && layout(pl, keys, &nkeys, names, &nnames) &&
              csv_index_build(&ix, pl, "run_id");
    if (!ok) {
        snprintf(err, errlen, "out of memory");
    } else {
        char path[4200];
        snprintf(path, sizeof path, "%s/summary_long.csv", out_dir);
        csv_writer *w = csv_open(path, (const char *const *)names, nnames, err, errlen);
        csv_join(w, set);
        int own[NHEAD + 2], idcol = csv_col(sm, "run_id");
        for (size_t i = 0; i < NHEAD; i++)
            own[i] = csv_col(sm, head[i]);
        own[NHEAD] = csv_col(sm, "trial");
        own[NHEAD + 1] = csv_col(sm, "status");
        for (size_t r = 0; w && r < sm->nrows; r++) {
            size_t first;
            long prow = -1;
            if (csv_index_find(&ix, csv_get(sm, r, idcol), &first))
                prow = (long)ix.item[first].row;
            trial_rows(w, pl, sm, r, own, unit, prow, keys, nkeys);
        }
        ok = w && csv_commit(w, err, errlen);
    }
    csv_index_free(&ix);
    for (size_t i = 0; names && i < cap; i++)
        free(names[i]);
    free(names);
    free(keys);
    free(unit);
    return ok;
}
