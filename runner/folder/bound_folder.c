/* The bound of a folder's runs (runner/folder/bound_folder.h). */
#include "runner/folder/bound_folder.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "results/csv.h"
#include "runner/folder/meta_read.h"

const char folder_bound_no_profile[] =
    "No bound: this folder has no profile of the hardware it ran on (`shadesweep probe` "
    "makes one; later runs copy it in)";

bool folder_bound_open(folder_bound *fb, const char *dir, const char *profile)
{
    memset(fb, 0, sizeof *fb);
    char path[4200], err[4400];
    snprintf(path, sizeof path, "%s/plan.csv", dir);
    if (csv_read(path, &fb->plan, err, sizeof err) &&
        !csv_index_build(&fb->plan_ix, &fb->plan, "run_id"))
        memset(&fb->plan_ix, 0, sizeof fb->plan_ix);
    if (!profile) {
        snprintf(path, sizeof path, "%s/device.yaml", dir);
        profile = path;
        FILE *f = fopen(path, "r");
        if (!f) {
            snprintf(fb->why, sizeof fb->why, "%s", folder_bound_no_profile);
            return false;
        }
        fclose(f);
    }
    fb->have = meta_read_profile(profile, &fb->prof, fb->why, sizeof fb->why);
    return fb->have;
}

void folder_bound_close(folder_bound *fb)
{
    csv_index_free(&fb->plan_ix);
    csv_table_free(&fb->plan);
}

/* The work, measured time and rates of one summary.csv row; false without rates. */
static bool row_work(const folder_bound *fb, const char *const *names,
                     const char *const *values, size_t n, bound_work *w, double *measured,
                     bound_rates *rates)
{
    bound_row rows[2] = {{names, values, n}, {0}};
    size_t nrows = 1;
    const char *id = bound_row_text(rows, 1, "run_id");
    size_t first;
    if (id && csv_index_find(&fb->plan_ix, id, &first)) {
        rows[1].names = (const char *const *)fb->plan.header;
        rows[1].values = (const char *const *)fb->plan.rows[fb->plan_ix.item[first].row];
        rows[1].n = fb->plan.ncols;
        nrows = 2;
    }
    const char *format;
    int samples;
    bound_work_of_row(rows, nrows, w, measured, &format, &samples);
    return fb->have && bound_rates_of(&fb->prof, format, samples, rates);
}

bool folder_bound_rates(const folder_bound *fb, const char *id, bound_rates *r)
{
    const char *const names[] = {"run_id"};
    const char *const values[] = {id};
    bound_work w;
    double measured;
    return row_work(fb, names, values, 1, &w, &measured, r);
}

void folder_bound_row(const folder_bound *fb, const char *const *names,
                      const char *const *values, size_t n, bound_result *res,
                      double *measured_us)
{
    bound_work w;
    bound_rates r;
    if (!row_work(fb, names, values, n, &w, measured_us, &r))
        memset(&r, 0xff, sizeof r);   /* every rate NAN: every time NAN */
    bound_compute(&r, &w, *measured_us, res);
}

run_bound *folder_bound_runs(const folder_bound *fb, const csv_table *t, size_t *n)
{
    *n = 0;
    run_bound *out = t->nrows ? calloc(t->nrows, sizeof *out) : NULL;
    double(*sum)[8] = t->nrows ? calloc(t->nrows, sizeof *sum) : NULL;
    bound_rates *rates = t->nrows ? calloc(t->nrows, sizeof *rates) : NULL;
    bool *has = t->nrows ? calloc(t->nrows, sizeof *has) : NULL;
    if (!out || !sum || !rates || !has) {
        free(out), free(sum), free(rates), free(has);
        return NULL;
    }
    int cid = csv_col(t, "run_id"), cr = csv_col(t, "renderer"), cs = csv_col(t, "status");
    for (size_t r = 0; r < t->nrows; r++) {
        const char *id = csv_get(t, r, cid);
        size_t k = 0;
        while (k < *n && strcmp(out[k].id, id) != 0)
            k++;
        if (k == *n) {
            snprintf(out[k].id, sizeof out[k].id, "%s", id);
            snprintf(out[k].renderer, sizeof out[k].renderer, "%s", csv_get(t, r, cr));
            (*n)++;
        }
        if (cs >= 0 && strcmp(csv_get(t, r, cs), "ok") != 0)
            continue;
        bound_work w;
        double measured;
        has[k] = row_work(fb, (const char *const *)t->header, (const char *const *)t->rows[r],
                          t->ncols, &w, &measured, &rates[k]) || has[k];
        const double v[] = {w.bytes, w.samples, w.evaluations, w.draws, w.dispatches,
                            measured, 1};
        for (size_t i = 0; i < 7; i++)
            sum[k][i] += v[i];   /* a NAN stays NAN: that work is not counted */
    }
    for (size_t k = 0; k < *n; k++) {
        double c = sum[k][6];
        bound_work w = {sum[k][0] / c, sum[k][1] / c, sum[k][2] / c, sum[k][3] / c,
                        sum[k][4] / c};
        out[k].measured_us = c > 0 ? sum[k][5] / c : NAN;
        if (!has[k] || c == 0)
            memset(&rates[k], 0xff, sizeof rates[k]);
        bound_compute(&rates[k], &w, out[k].measured_us, &out[k].b);
    }
    free(sum), free(rates), free(has);
    return out;
}

bool folder_bound_fill_summary(const char *dir, const folder_bound *fb, char *err,
                               size_t errlen)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/summary.csv", dir);
    csv_table t;
    if (!csv_read(path, &t, err, errlen))
        return false;
    int cb = csv_col(&t, "bound_us"), cl = csv_col(&t, "limiter"), cp = csv_col(&t, "bound_pct");
    if (cb < 0 || cl < 0 || cp < 0) {
        csv_table_free(&t);
        return true;
    }
    csv_writer *w = csv_open(path, (const char *const *)t.header, t.ncols, err, errlen);
    for (size_t r = 0; w && r < t.nrows; r++) {
        bound_result b;
        double measured;
        folder_bound_row(fb, (const char *const *)t.header, (const char *const *)t.rows[r],
                         t.ncols, &b, &measured);
        for (int c = 0; c < (int)t.ncols; c++) {
            if (c == cb)
                csv_f64(w, b.bound_us, 3);
            else if (c == cl)
                csv_str(w, b.limiter >= 0 ? bound_resource_names[b.limiter] : "");
            else if (c == cp)
                csv_f64(w, b.pct, 1);
            else
                csv_str(w, t.rows[r][c]);
        }
        csv_end_row(w);
    }
    bool ok = w && csv_commit(w, err, errlen);
    csv_table_free(&t);
    return ok;
}
