/* The bound of a run: rates, work and the division (results/bound.h). */
#include "results/bound.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const bound_resource_names[BOUND_NRESOURCES] = {"bytes", "fill", "alu", "draws",
                                                            "dispatches"};

static const device_figure *figure(const device_profile *p, const char *name)
{
    for (size_t i = 0; i < p->nfigures; i++)
        if (strcmp(p->figure[i].name, name) == 0 && isfinite(p->figure[i].median) &&
            p->figure[i].median > 0)
            return &p->figure[i];
    return NULL;
}

/* The figure's median (NAN when absent), its relative spread folded into *spread. */
static double use(const device_profile *p, const char *name, double *spread)
{
    const device_figure *f = figure(p, name);
    if (!f)
        return NAN;
    if (isfinite(f->spread) && f->spread / f->median > *spread)
        *spread = f->spread / f->median;
    return f->median;
}

/* The larger of two figures, either of which may be absent. */
static double peak(const device_profile *p, const char *a, const char *b, double *spread)
{
    double x = use(p, a, spread), y = use(p, b, spread);
    return isnan(x) ? y : isnan(y) ? x : fmax(x, y);
}

bool bound_rates_of(const device_profile *p, const char *format, int samples, bound_rates *r)
{
    memset(r, 0, sizeof *r);
    r->bandwidth_gbps = peak(p, "bandwidth_copy", "bandwidth_texture_read", &r->spread);
    r->alu_gflops = peak(p, "alu_fragment", "alu_compute", &r->spread);
    r->draw_us = use(p, "draw_us", &r->spread);
    r->dispatch_us = use(p, "dispatch_us", &r->spread);
    char want[3][48];
    snprintf(want[0], sizeof want[0], "fill_%.24s_%dx", format ? format : "rgba8",
             samples > 1 ? 4 : 1);
    snprintf(want[1], sizeof want[1], "fill_%.24s_1x", format ? format : "rgba8");
    snprintf(want[2], sizeof want[2], "fill_rgba8_1x");
    r->fill_gsps = NAN;
    for (size_t i = 0; i < 3 && isnan(r->fill_gsps); i++)
        if (figure(p, want[i])) {
            r->fill_gsps = use(p, want[i], &r->spread);
            memcpy(r->fill_figure, want[i], sizeof r->fill_figure);
        }
    return !(isnan(r->bandwidth_gbps) && isnan(r->alu_gflops) && isnan(r->draw_us) &&
             isnan(r->dispatch_us) && isnan(r->fill_gsps));
}

/* work / rate in microseconds: rate in G-units a second (1e3 units a microsecond) */
static double per_rate(double work, double giga_per_s)
{
    return isfinite(work) && isfinite(giga_per_s) && giga_per_s > 0 ? work / (giga_per_s * 1e3)
                                                                     : NAN;
}

void bound_compute(const bound_rates *r, const bound_work *w, double measured_us,
                   bound_result *out)
{
    out->us[BOUND_BYTES] = per_rate(w->bytes, r->bandwidth_gbps);
    out->us[BOUND_FILL] = per_rate(w->samples, r->fill_gsps);
    out->us[BOUND_ALU] = per_rate(w->evaluations * BOUND_FLOPS_PER_EVALUATION, r->alu_gflops);
    /* a state change is charged nothing beyond its draw: the runs count every change
     * (blend, depth, stencil, a program), the probe times a program switch, and most
     * changes cost far less; charged so, stencil light volumes' bounds rose above their
     * measured times (a bound is a floor: what the work cannot take less than) */
    out->us[BOUND_DRAWS] =
        isfinite(w->draws) && isfinite(r->draw_us) ? w->draws * r->draw_us : NAN;
    out->us[BOUND_DISPATCHES] = isfinite(w->dispatches) && isfinite(r->dispatch_us)
                                    ? w->dispatches * r->dispatch_us : NAN;
    out->bound_us = NAN;
    out->limiter = -1;
    for (int i = 0; i < BOUND_NRESOURCES; i++)
        if (isfinite(out->us[i]) && (out->limiter < 0 || out->us[i] > out->bound_us)) {
            out->bound_us = out->us[i];
            out->limiter = i;
        }
    bool both = isfinite(out->bound_us) && isfinite(measured_us) && measured_us > 0;
    out->pct = both ? 100.0 * out->bound_us / measured_us : NAN;
    out->model_error = both && out->bound_us > measured_us;
}

const char *bound_row_text(const bound_row *rows, size_t nrows, const char *name)
{
    for (size_t k = 0; k < nrows; k++)
        for (size_t i = 0; i < rows[k].n; i++)
            if (strcmp(rows[k].names[i], name) == 0 && rows[k].values[i] &&
                rows[k].values[i][0])
                return rows[k].values[i];
    return NULL;
}

double bound_row_number(const bound_row *rows, size_t nrows, const char *name)
{
    const char *s = bound_row_text(rows, nrows, name);
    char *end;
    double v = s ? strtod(s, &end) : NAN;
    return s && end != s && *end == '\0' ? v : NAN;
}

void bound_work_of_row(const bound_row *rows, size_t nrows, bound_work *w,
                       double *measured_us, const char **format, int *samples)
{
    double gw = bound_row_number(rows, nrows, "gbuffer_write_bytes_mean");
    double gr = bound_row_number(rows, nrows, "gbuffer_read_bytes_mean");
    w->bytes = isfinite(gw) && isfinite(gr) ? gw + gr : NAN;
    w->samples = bound_row_number(rows, nrows, "samples_shaded_mean");
    if (isnan(w->samples))
        w->samples = bound_row_number(rows, nrows, "samples_mean");
    /* evaluations a frame: per covered pixel x covered pixels (coverage x width x height) */
    w->evaluations = bound_row_number(rows, nrows, "light_evals_per_pixel") *
                     bound_row_number(rows, nrows, "coverage") *
                     bound_row_number(rows, nrows, "width") *
                     bound_row_number(rows, nrows, "height");
    w->draws = bound_row_number(rows, nrows, "draw_calls_mean");
    w->dispatches = bound_row_number(rows, nrows, "dispatches_mean");
    *measured_us = bound_row_number(rows, nrows, "frametime_mean_us");
    const char *hdr = bound_row_text(rows, nrows, "hdr");
    *format = hdr ? hdr : "rgba8";
    double msaa = bound_row_number(rows, nrows, "msaa");
    *samples = isfinite(msaa) && msaa > 1 ? (int)msaa : 1;
}
