/* OUT/summary.json: the ranked table and the crossovers for scripts
 * (runner/answer/summary_json.h; the schema is docs/summary-json.md). */
#define _GNU_SOURCE   /* open_memstream */
#include "runner/answer/summary_json.h"

#include "runner/answer/device_note.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/fsutil.h"
#include "results/jsonout.h"
#include "runner/folder/output.h"
#include "runner/answer/point_verdict.h"
#include "runner/answer/device_note.h"

static bool bookkeeping(const char *name)
{
    return strcmp(name, "index") == 0 || strcmp(name, "run_id") == 0 ||
           strcmp(name, "shard") == 0 || strcmp(name, "folded") == 0;
}

/* summary.csv's rows by run id, and the unit of each of its columns (NULL: not a
 * measure), made once for every run's trial_results. */
typedef struct trial_rows {
    csv_index ix;
    const char **unit;
} trial_rows;

/* Each trial of run `id`, in summary.csv's order: {"trial", "status", "measures": {every
 * measured column of summary.csv that has a value: its number}}. */
static void trial_results(FILE *fp, const csv_table *sm, const trial_rows *tr, const char *id)
{
    const csv_index *ix = &tr->ix;
    size_t first, n = csv_index_find(ix, id, &first);
    int tcol = csv_col(sm, "trial"), scol = csv_col(sm, "status");
    fputs("[", fp);
    for (size_t k = 0; k < n; k++) {
        size_t r = ix->item[first + k].row;
        char *end;
        long trial = strtol(csv_get(sm, r, tcol), &end, 10);
        fputs(k ? ", {\"trial\": " : "{\"trial\": ", fp);
        if (*end == '\0' && end != csv_get(sm, r, tcol))
            fprintf(fp, "%ld", trial);
        else
            fputs("null", fp);
        fputs(", \"status\": ", fp);
        json_string(fp, csv_get(sm, r, scol));
        fputs(", \"measures\": {", fp);
        bool mf = true;
        for (size_t c = 0; c < sm->ncols; c++) {
            double x = strtod(sm->rows[r][c], &end);
            if (tr->unit[c] && *sm->rows[r][c] && *end == '\0' &&
                isfinite(x))
                json_member_number(fp, &mf, sm->header[c], x);
        }
        fputs("}}", fp);
    }
    fputs("]", fp);
}

static void run_object(FILE *fp, const summary_view *v, const trial_rows *tr,
                       const summary_point *p, size_t i)
{
    const run_result *x = &v->runs[p->runs[i]];
    const run_result *fastest = &v->runs[p->runs[0]];
    bool ok = isfinite(x->mean), fok = isfinite(fastest->mean);
    bool first = true;
    fputs("{", fp);
    json_key(fp, &first, "rank");
    if (ok)
        fprintf(fp, "%zu", i + 1);
    else
        fputs("null", fp);
    json_member_string(fp, &first, "run_id", x->id);
    json_member_string(fp, &first, "renderer", x->renderer);
    json_member_string(fp, &first, "configuration", v->rcfg[p->runs[i]]);
    json_member_string(fp, &first, "status", x->status);
    json_member_string(fp, &first, "metric", x->metric[0] ? x->metric : NULL);
    json_member_number(fp, &first, "mean_us", x->mean);
    json_member_number(fp, &first, "ci95_us", x->half);
    ratio_ci r = {NAN, NAN, NAN, 0, true};
    const char *differs = NULL;
    if (ok && fok && x != fastest) {
        summary_paired_ratio(x, fastest, &r);
        differs = summary_differs(&r);
    } else if (ok && x == fastest) {
        r.ratio = 1;
    }
    json_member_number(fp, &first, "x_fastest", r.ratio);
    json_member_number(fp, &first, "x_fastest_lo", r.lo);
    json_member_number(fp, &first, "x_fastest_hi", r.hi);
    json_member_string(fp, &first, "differs", differs);
    json_member_number(fp, &first, "wall_mean_us", x->wall_mean);
    json_member_number(fp, &first, "wall_ci95_us", x->wall_half);
    json_member_number(fp, &first, "p99_us", x->p99_us);
    json_member_number(fp, &first, "fps_1pct_low", x->low1_fps);
    json_member_number(fp, &first, "image_rmse", x->rmse);
    json_key(fp, &first, "trials");
    fprintf(fp, "%zu", x->trials);
    json_key(fp, &first, "trials_ok");
    fprintf(fp, "%zu", x->trials_ok);
    json_key(fp, &first, "parameters");
    fputs("{", fp);
    long row = v->prow[p->runs[i]];
    bool pf = true;
    for (size_t c = 0; row >= 0 && c < v->pl->ncols; c++) {
        if (bookkeeping(v->pl->header[c]))
            continue;
        json_key(fp, &pf, v->pl->header[c]);
        json_typed(fp, v->pl->rows[row][c]);
    }
    fputs("}, \"trial_results\": ", fp);
    trial_results(fp, v->sm, tr, x->id);
    fputs("}", fp);
}

static void point_object(FILE *fp, const summary_view *v, const trial_rows *tr,
                         const summary_point *p)
{
    fputs("{\"label\": ", fp);
    json_string(fp, p->label);
    char said[1024];
    fputs(", \"verdict\": ", fp);
    if (point_verdict(v->runs, p, v->rcfg, said, sizeof said))
        json_string(fp, said);
    else
        fputs("null", fp);
    fputs(", \"parameters\": {", fp);
    long row = p->nruns ? v->prow[p->runs[0]] : -1;
    bool first = true;
    for (size_t c = 0; row >= 0 && c < v->pl->ncols; c++)
        if (v->varies[c]) {
            json_key(fp, &first, v->pl->header[c]);
            json_typed(fp, v->pl->rows[row][c]);
        }
    fputs("}, \"runs\": [", fp);
    for (size_t i = 0; i < p->nruns; i++) {
        fputs(i ? ",\n      " : "\n      ", fp);
        run_object(fp, v, tr, p, i);
    }
    fputs("]}", fp);
}

static void crossover_object(FILE *fp, const crossover_found *c)
{
    bool first = true;
    fputs("{", fp);
    json_member_string(fp, &first, "along", c->axis);
    json_member_string(fp, &first, "where", c->group);
    json_member_string(fp, &first, "faster_below", c->below);
    json_member_string(fp, &first, "faster_above", c->above);
    json_member_number(fp, &first, "between_lo", c->x0);
    json_member_number(fp, &first, "between_hi", c->x1);
    json_member_number(fp, &first, "x", c->x);
    json_member_number(fp, &first, "x_lo", c->lo);
    json_member_number(fp, &first, "x_hi", c->hi);
    json_member_string(fp, &first, "differs_below", c->differs0);
    json_member_string(fp, &first, "differs_above", c->differs1);
    fputs("}", fp);
}

/* The warnings' lines (summary_warnings) as a JSON array of strings. */
static bool warnings_array(FILE *fp, const summary_view *v)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (!m)
        return false;
    summary_warnings(v->runs, v->nruns, m, "", false);
    if (fclose(m) != 0) {
        free(buf);
        return false;
    }
    fputs("[", fp);
    bool first = true;
    for (char *line = buf, *nl; line && *line; line = nl ? nl + 1 : NULL) {
        nl = strchr(line, '\n');
        if (nl)
            *nl = '\0';
        fputs(first ? "\n    " : ",\n    ", fp);
        first = false;
        json_string(fp, line);
    }
    fputs(first ? "]" : "\n  ]", fp);
    free(buf);
    return true;
}

bool summary_json_write(const char *out_dir, const summary_view *v, afile_set *set, char *err,
                        size_t errlen)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/summary.json", out_dir);
    trial_rows tr = {.unit = summary_units_of(v->sm)};
    if (!tr.unit || !csv_index_build(&tr.ix, v->sm, "run_id")) {
        free(tr.unit);
        snprintf(err, errlen, "out of memory");
        return false;
    }
    afile f;
    if (!afile_open(&f, path, err, errlen)) {
        csv_index_free(&tr.ix);
        free(tr.unit);
        return false;
    }
    f.set = set;
    FILE *fp = f.fp;
    fprintf(fp, "{\"schema\": \"shadesweep-summary\", \"version\": %d,\n  \"experiment\": ",
            SUMMARY_JSON_VERSION);
    json_string(fp, v->experiment);
    fputs(",\n  \"metric\": ", fp);
    json_string(fp, v->nruns && v->runs[0].metric[0] ? v->runs[0].metric : "wall");
    /* the device, when a CPU rasterizer measured the runs (runner/answer/device_note.h) */
    fputs(",\n  \"device\": {", fp);
    bool df = true;
    json_key(fp, &df, "software_rasterizer");
    fputs(v->device->nsoftware ? "true" : "false", fp);
    json_member_number(fp, &df, "devices", (double)v->device->ndevices);
    json_member_string(fp, &df, "note", v->device->line[0] ? v->device->line : NULL);
    fputs("}", fp);
    fputs(",\n  \"units\": {", fp);   /* of the measures of trial_results */
    bool uf = true;
    for (size_t c = 0; c < v->sm->ncols; c++)
        if (tr.unit[c])
            json_member_string(fp, &uf, v->sm->header[c], tr.unit[c]);
    fputs("},\n  \"points\": [", fp);
    for (size_t k = 0; k < v->npoints; k++) {
        fputs(k ? ",\n    " : "\n    ", fp);
        point_object(fp, v, &tr, &v->points[k]);
    }
    fputs(v->npoints ? "\n  ],\n  \"crossovers\": [" : "],\n  \"crossovers\": [", fp);
    for (size_t i = 0; i < v->cx->n; i++) {
        fputs(i ? ",\n    " : "\n    ", fp);
        crossover_object(fp, &v->cx->item[i]);
    }
    fputs(v->cx->n ? "\n  ],\n  \"warnings\": " : "],\n  \"warnings\": ", fp);
    csv_index_free(&tr.ix);
    free(tr.unit);
    if (!warnings_array(fp, v)) {
        afile_abort(&f);
        snprintf(err, errlen, "out of memory");
        return false;
    }
    fputs("\n}\n", fp);
    return afile_commit(&f, err, errlen);
}
