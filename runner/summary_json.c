/* OUT/summary.json: the ranked table and the crossovers for scripts
 * (runner/summary_json.h; the schema is docs/summary-json.md). */
#define _GNU_SOURCE   /* open_memstream */
#include "runner/summary_json.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "results/fsutil.h"
#include "results/jsonout.h"

/* A plan cell as JSON: a number when the whole cell is one, true / false, else a string. */
static void cell(FILE *fp, const char *s)
{
    if (strcmp(s, "true") == 0 || strcmp(s, "false") == 0) {
        fputs(s, fp);
        return;
    }
    char *end;
    double v = strtod(s, &end);
    if (*s && end != s && *end == '\0' && isfinite(v))
        json_number(fp, v);
    else
        json_string(fp, s);
}

static bool bookkeeping(const char *name)
{
    return strcmp(name, "index") == 0 || strcmp(name, "run_id") == 0 ||
           strcmp(name, "shard") == 0 || strcmp(name, "folded") == 0;
}

static void key(FILE *fp, const char *k, bool *first)
{
    fputs(*first ? "" : ", ", fp);
    *first = false;
    json_string(fp, k);
    fputs(": ", fp);
}

static void num_field(FILE *fp, const char *k, double v, bool *first)
{
    key(fp, k, first);
    json_number(fp, v);
}

static void str_field(FILE *fp, const char *k, const char *v, bool *first)
{
    key(fp, k, first);
    if (v)
        json_string(fp, v);
    else
        fputs("null", fp);
}

static void run_object(FILE *fp, const summary_view *v, const summary_point *p, size_t i)
{
    const run_result *x = &v->runs[p->runs[i]];
    const run_result *fastest = &v->runs[p->runs[0]];
    bool ok = isfinite(x->mean), fok = isfinite(fastest->mean);
    bool first = true;
    fputs("{", fp);
    key(fp, "rank", &first);
    if (ok)
        fprintf(fp, "%zu", i + 1);
    else
        fputs("null", fp);
    str_field(fp, "run_id", x->id, &first);
    str_field(fp, "renderer", x->renderer, &first);
    str_field(fp, "configuration", v->rcfg[p->runs[i]], &first);
    str_field(fp, "status", x->status, &first);
    str_field(fp, "metric", x->metric[0] ? x->metric : NULL, &first);
    num_field(fp, "mean_us", x->mean, &first);
    num_field(fp, "ci95_us", x->half, &first);
    ratio_ci r = {NAN, NAN, NAN, 0, true};
    const char *differs = NULL;
    if (ok && fok && x != fastest) {
        summary_paired_ratio(x, fastest, &r);
        differs = summary_differs(&r);
    } else if (ok && x == fastest) {
        r.ratio = 1;
    }
    num_field(fp, "x_fastest", r.ratio, &first);
    num_field(fp, "x_fastest_lo", r.lo, &first);
    num_field(fp, "x_fastest_hi", r.hi, &first);
    str_field(fp, "differs", differs, &first);
    num_field(fp, "wall_mean_us", x->wall_mean, &first);
    num_field(fp, "wall_ci95_us", x->wall_half, &first);
    num_field(fp, "p99_us", x->p99_us, &first);
    num_field(fp, "fps_1pct_low", x->low1_fps, &first);
    num_field(fp, "image_rmse", x->rmse, &first);
    key(fp, "trials", &first);
    fprintf(fp, "%zu", x->trials);
    key(fp, "trials_ok", &first);
    fprintf(fp, "%zu", x->trials_ok);
    key(fp, "parameters", &first);
    fputs("{", fp);
    long row = v->prow[p->runs[i]];
    bool pf = true;
    for (size_t c = 0; row >= 0 && c < v->pl->ncols; c++) {
        if (bookkeeping(v->pl->header[c]))
            continue;
        key(fp, v->pl->header[c], &pf);
        cell(fp, v->pl->rows[row][c]);
    }
    fputs("}}", fp);
}

static void point_object(FILE *fp, const summary_view *v, const summary_point *p)
{
    fputs("{\"label\": ", fp);
    json_string(fp, p->label);
    fputs(", \"parameters\": {", fp);
    long row = p->nruns ? v->prow[p->runs[0]] : -1;
    bool first = true;
    for (size_t c = 0; row >= 0 && c < v->pl->ncols; c++)
        if (v->varies[c]) {
            key(fp, v->pl->header[c], &first);
            cell(fp, v->pl->rows[row][c]);
        }
    fputs("}, \"runs\": [", fp);
    for (size_t i = 0; i < p->nruns; i++) {
        fputs(i ? ",\n      " : "\n      ", fp);
        run_object(fp, v, p, i);
    }
    fputs("]}", fp);
}

static void crossover_object(FILE *fp, const crossover_found *c)
{
    bool first = true;
    fputs("{", fp);
    str_field(fp, "along", c->axis, &first);
    str_field(fp, "where", c->group, &first);
    str_field(fp, "faster_below", c->below, &first);
    str_field(fp, "faster_above", c->above, &first);
    num_field(fp, "between_lo", c->x0, &first);
    num_field(fp, "between_hi", c->x1, &first);
    num_field(fp, "x", c->x, &first);
    num_field(fp, "x_lo", c->lo, &first);
    num_field(fp, "x_hi", c->hi, &first);
    str_field(fp, "differs_below", c->differs0, &first);
    str_field(fp, "differs_above", c->differs1, &first);
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
    summary_warnings(v->runs, v->nruns, m, "");
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

bool summary_json_write(const char *out_dir, const summary_view *v, char *err, size_t errlen)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/summary.json", out_dir);
    afile f;
    if (!afile_open(&f, path, err, errlen))
        return false;
    FILE *fp = f.fp;
    fprintf(fp, "{\"schema\": \"shadesweep-summary\", \"version\": %d,\n  \"experiment\": ",
            SUMMARY_JSON_VERSION);
    json_string(fp, v->experiment);
    fputs(",\n  \"metric\": ", fp);
    json_string(fp, v->nruns && v->runs[0].metric[0] ? v->runs[0].metric : "wall");
    fputs(",\n  \"points\": [", fp);
    for (size_t k = 0; k < v->npoints; k++) {
        fputs(k ? ",\n    " : "\n    ", fp);
        point_object(fp, v, &v->points[k]);
    }
    fputs(v->npoints ? "\n  ],\n  \"crossovers\": [" : "],\n  \"crossovers\": [", fp);
    for (size_t i = 0; i < v->cx->n; i++) {
        fputs(i ? ",\n    " : "\n    ", fp);
        crossover_object(fp, &v->cx->item[i]);
    }
    fputs(v->cx->n ? "\n  ],\n  \"warnings\": " : "],\n  \"warnings\": ", fp);
    if (!warnings_array(fp, v)) {
        afile_abort(&f);
        snprintf(err, errlen, "out of memory");
        return false;
    }
    fputs("\n}\n", fp);
    return afile_commit(&f, err, errlen);
}
