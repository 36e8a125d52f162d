#include "runner/folder/output.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/fsutil.h"
#include "results/device_profile.h"
#include "results/numfmt.h"
#include "results/yamlout.h"
#include "runner/manifest/params.h"
#include "runner/manifest/yamldoc.h"
#include "runner/folder/meta_read.h"

/* The columns of results/metrics.def go in three slots (metrics.def: S1, S2, S3). */
const char *const summary_columns[] = {
    "experiment", "run_id", "renderer", "scene", "width", "height", "gbuffer",
    "lights_placement", "lights_rng", "lights_seed", "lights_count", "lights_radius",
    "trial", "frames", "measured_s", "fps_mean", "frametime_mean_us", "frametime_sd_us",
    "frametime_ci95_us", "frametime_p50_us", "frametime_p99_us", "fps_1pct_low",
#define METRIC_WANT S1
#include "results/metric_names.inc"
    "gbuffer_bytes",
    "image_rmse", "image_psnr_db", "image_max_abs", "nonfinite_pixels", "harness_us_mean",
    "ci1pct_after_s",
#define METRIC_WANT S2
#include "results/metric_names.inc"
    "image_edge_rmse", "image_edge_pixels",
#define METRIC_WANT S3
#include "results/metric_names.inc"
    /* the schedule (runner/cli/schedule.c): the trial's place in its round; what decides
     * (measure.metric resolved) and the trial's value of it */
    "order", "metric", "metric_us",
    /* the bound (runner/folder/bound_folder.h): empty here, filled for the folder's
     * summary.csv from its device.yaml */
    "bound_us", "limiter", "bound_pct",
    "status", "message",
};
const size_t summary_ncolumns = sizeof summary_columns / sizeof summary_columns[0];

/* The units of the measured columns above that results/metrics.def does not describe. */
static const struct {
    const char *column, *unit;
} summary_units[] = {
    {"lights_count", "lights"},  {"frames", "frames"},           {"measured_s", "s"},
    {"fps_mean", "1/s"},         {"frametime_mean_us", "us"},    {"frametime_sd_us", "us"},
    {"frametime_ci95_us", "us"}, {"frametime_p50_us", "us"},     {"frametime_p99_us", "us"},
    {"fps_1pct_low", "1/s"},     {"gbuffer_bytes", "bytes"},     {"image_rmse", "1"},
    {"image_psnr_db", "dB"},     {"image_max_abs", "1"},         {"nonfinite_pixels", "pixels"},
    {"harness_us_mean", "us"},   {"ci1pct_after_s", "s"},        {"image_edge_rmse", "1"},
    {"image_edge_pixels", "pixels"}, {"metric_us", "us"},
    {"bound_us", "us"},          {"bound_pct", "%"},
};

const char *summary_column_unit(const char *column)
{
    for (size_t i = 0; i < sizeof summary_units / sizeof summary_units[0]; i++)
        if (strcmp(summary_units[i].column, column) == 0)
            return summary_units[i].unit;
    for (size_t i = 0; i < metric_ndocs; i++)
        if (strcmp(metric_docs[i].summary, column) == 0)
            return metric_docs[i].unit;
    return NULL;
}

const char **summary_units_of(const csv_table *t)
{
    const char **unit = malloc((t->ncols ? t->ncols : 1) * sizeof *unit);
    for (size_t c = 0; unit && c < t->ncols; c++)
        unit[c] = summary_column_unit(t->header[c]);
    return unit;
}

const char *const frames_columns[] = {
    "run_id", "trial", "frame", "t_wall_s", "t_scene_s", "lights", "frametime_us",
#define METRIC_WANT_FRAMES
#include "results/metric_names.inc"
};
const size_t frames_ncolumns = sizeof frames_columns / sizeof frames_columns[0];
static const char *const seconds_columns[] = {
    "run_id", "trial", "second", "complete", "lights_min", "lights_max", "frames", "fps",
    "frametime_mean_us", "frametime_sd_us", "frametime_p50_us", "frametime_p99_us",
    "draw_calls_mean",
};
static const char *const convergence_columns[] = {
    "run_id", "trial", "elapsed_s", "frames", "frametime_mean_us", "frametime_ci95_us",
    "ci95_rel",
};
static const char *const errors_columns[] = {
    "run_id", "trial", "frame", "t_scene_s", "rmse", "psnr_db", "max_abs", "frac_over_1_255",
    "nonfinite", "edge_rmse", "edge_pixels",
};
static const char *const coverage_columns[] = {
    "run_id", "trial", "frame", "t_scene_s", "light", "coverage",
};
static const char *const lightgrid_columns[] = {
    "run_id", "trial", "frame", "t_scene_s", "lights", "cells",
};
static const char *const passes_columns[] = {
    "run_id", "trial", "frame", "pass", "gpu_us", "cpu_us", "draw_calls", "state_changes",
    "fragments", "samples", "primitives", "dispatches", "cell_lights_mean", "cell_lights_max",
    "light_evals_per_pixel", "scissor_pixels", "samples_shaded", "edge_fraction",
    /* whether gpu_us and cpu_us are the pass's own (0 on a software rasterizer: there
     * only the frame's total is; run_files.pass_times_frame_only) */
    "gpu_us_attributed", "cpu_us_attributed",
    /* the pass's bound from its counters and the device's cached profile (results/bound.h:
     * samples shaded, draws, dispatches), its limiter, and bound / gpu_us in % where the
     * pass's time is its own */
    "bound_us", "limiter", "bound_pct",
};
#define NCOLS(a) (sizeof(a) / sizeof((a)[0]))

static void join(char *dst, size_t len, const char *dir, const char *name)
{
    snprintf(dst, len, "%s/%s", dir, name);
}

bool output_write_plan(const char *out_dir, const plan *p, char *err, size_t errlen)
{
    char path[4096];
    join(path, sizeof path, out_dir, "plan.csv");
    param_kv kv[PARAM_KV_MAX];
    size_t nkv = p->nruns ? run_params_kv(&p->runs[0].p, kv, PARAM_KV_MAX) : 0;
    const char *cols[4 + PARAM_KV_MAX];
    cols[0] = "index";
    cols[1] = "run_id";
    cols[2] = "shard";
    cols[3] = "folded";   /* grid points folded into this run (runner/plan/sweep.c) */
    for (size_t i = 0; i < nkv; i++)
        cols[4 + i] = kv[i].key;
    csv_writer *w = csv_open(path, cols, 4 + nkv, err, errlen);
    if (!w)
        return false;
    for (size_t r = 0; r < p->nruns; r++) {
        const run_spec *s = &p->runs[r];
        run_params_kv(&s->p, kv, PARAM_KV_MAX);
        csv_u64(w, s->index);
        csv_str(w, s->id);
        csv_u64(w, s->shard);
        csv_u64(w, s->folded);
        for (size_t i = 0; i < nkv; i++)
            csv_str(w, kv[i].value);
        csv_end_row(w);
    }
    return csv_commit(w, err, errlen);
}

/* run_dir/name opened with its header (csv_open: a temporary name until committed). */
static csv_writer *open_in(const char *run_dir, const char *name, const char *const *columns,
                           size_t ncolumns, char *err, size_t errlen)
{
    char path[4096];
    join(path, sizeof path, run_dir, name);
    return csv_open(path, columns, ncolumns, err, errlen);
}

/* The cells every row of a run's per-trial files starts with: run_id, trial. */
static void row_start(csv_writer *w, const char *run_id, uint32_t trial)
{
    csv_str(w, run_id);
    csv_u64(w, trial);
}

/* ... and those of errors.csv, coverage.csv and lightgrid.csv: then frame, t_scene_s. */
static void frame_row_start(csv_writer *w, const char *run_id, uint32_t trial, uint32_t frame,
                            double t_scene)
{
    row_start(w, run_id, trial);
    csv_u64(w, frame);
    csv_f64(w, t_scene, 6);
}

bool run_files_open(run_files *f, const char *run_dir, const run_params *p, char *err,
                    size_t errlen)
{
    memset(f, 0, sizeof *f);
    if (p->out_frames) {
        if (!(f->frames = open_in(run_dir, "frames.csv", frames_columns, frames_ncolumns,
                                  err, errlen)) ||
            !(f->passes = open_in(run_dir, "passes.csv", passes_columns, NCOLS(passes_columns),
                                  err, errlen)))
            goto fail;
    }
    if (p->out_seconds) {
        if (!(f->seconds = open_in(run_dir, "seconds.csv", seconds_columns,
                                   NCOLS(seconds_columns), err, errlen)) ||
            !(f->convergence = open_in(run_dir, "convergence.csv", convergence_columns,
                                       NCOLS(convergence_columns), err, errlen)))
            goto fail;
    }
    return true;
fail:
    run_files_abort(f);
    return false;
}

/* passes.csv's bound columns of pass ps (empty without rates; bound_pct empty where the
 * pass's time is not its own) */
static void pass_bound(csv_writer *w, const run_files *f, const pass_stats *ps)
{
    bound_result b = {.bound_us = NAN, .limiter = -1, .pct = NAN};
    if (f->has_rates) {
        bound_work work = {.bytes = NAN, .samples = ps->samples_shaded, .evaluations = NAN,
                           .draws = (double)ps->draw_calls,
                           .dispatches = (double)ps->dispatches};
        bound_compute(&f->rates, &work, f->pass_times_frame_only ? NAN : ps->gpu_us, &b);
    }
    csv_f64(w, b.bound_us, 3);
    if (b.limiter >= 0)
        csv_str(w, bound_resource_names[b.limiter]);
    else
        csv_empty(w);
    csv_f64(w, b.pct, 1);
}

void run_files_frame(run_files *f, const char *run_id, uint32_t trial, const frame_record *r,
                     const frame_stats *fs)
{
    if (!f->frames)
        return;
    csv_writer *w = f->frames;
    row_start(w, run_id, trial);
    csv_u64(w, r->frame);
    csv_f64(w, r->t_wall_s, 6);
    csv_f64(w, r->t_scene_s, 6);
    csv_u64(w, r->lights);
    csv_f64(w, r->frametime_us, 3);
    metrics_write_frame(w, r);   /* results/metrics.def */
    csv_end_row(w);

    for (size_t i = 0; i < fs->npasses; i++) {
        const pass_stats *ps = &fs->pass[i];
        w = f->passes;
        row_start(w, run_id, trial);
        csv_u64(w, r->frame);
        csv_str(w, ps->name);
        csv_f64(w, ps->gpu_us, 3);
        csv_f64(w, ps->cpu_us, 3);
        csv_u64(w, ps->draw_calls);
        csv_u64(w, ps->state_changes);
        csv_f64(w, ps->fragments, 0);
        csv_f64(w, ps->samples, 0);
        csv_f64(w, ps->primitives, 0);
        csv_u64(w, ps->dispatches);
        /* the light grid's counters on the pass that built it (empty elsewhere) */
        bool grid = fs->grid_pass == i + 1;
        csv_f64(w, grid ? fs->grid_lights_mean : NAN, 3);
        csv_f64(w, grid ? fs->grid_lights_max : NAN, 0);
        csv_f64(w, grid ? fs->light_evals_per_pixel : NAN, 3);
        csv_f64(w, ps->scissor_pixels, 0);   /* light_volumes scissor only */
        csv_f64(w, ps->samples_shaded, 1);
        /* msaa, deferred: the frame's edge-pixel fraction on its edge pass's row */
        csv_f64(w, strcmp(ps->name, "edges") == 0 ? fs->edge_fraction : NAN, 6);
        csv_u64(w, f->pass_times_frame_only ? 0 : 1);
        csv_u64(w, f->pass_times_frame_only ? 0 : 1);
        pass_bound(w, f, ps);
        csv_end_row(w);
    }
}

bool run_files_bound_rates(run_files *f, const char *const gl[6], const char *format,
                           int samples)
{
    static device_profile prof;   /* large; a trial opens its files once */
    char path[4096], err[4400];
    memset(&prof, 0, sizeof prof);
    device_profile_set_gl(&prof, gl);
    f->has_rates = device_profile_cache_path(&prof, path, sizeof path) && fs_exists(path) &&
                   meta_read_profile(path, &prof, err, sizeof err) &&
                   bound_rates_of(&prof, format, samples, &f->rates);
    return f->has_rates;
}

void run_files_second(run_files *f, const char *run_id, uint32_t trial, const second_bin *b)
{
    csv_writer *w = f->seconds;
    if (!w)
        return;
    row_start(w, run_id, trial);
    csv_u64(w, b->second);
    csv_u64(w, b->complete ? 1 : 0);
    if (b->frames) {
        csv_u64(w, b->lights_min);
        csv_u64(w, b->lights_max);
    } else {
        csv_empty(w);
        csv_empty(w);
    }
    csv_u64(w, b->frames);
    csv_u64(w, b->frames);  /* FPS of a second is the number of frames that ended in it */
    csv_f64(w, b->frametime_mean_us, 3);
    csv_f64(w, b->frametime_sd_us, 3);
    csv_f64(w, b->frametime_p50_us, 3);
    csv_f64(w, b->frametime_p99_us, 3);
    csv_f64(w, b->draw_calls_mean, 3);
    csv_end_row(w);
}

void run_files_convergence(run_files *f, const char *run_id, uint32_t trial,
                           const convergence_point *p)
{
    csv_writer *w = f->convergence;
    if (!w)
        return;
    row_start(w, run_id, trial);
    csv_f64(w, p->elapsed_s, 6);
    csv_u64(w, p->frames);
    csv_f64(w, p->mean_us, 3);
    csv_f64(w, p->ci95_us, 3);
    csv_f64(w, p->mean_us > 0 ? p->ci95_us / p->mean_us : NAN, 6);
    csv_end_row(w);
}

bool run_files_open_errors(run_files *f, const char *run_dir, char *err, size_t errlen)
{
    f->errors = open_in(run_dir, "errors.csv", errors_columns, NCOLS(errors_columns), err,
                        errlen);
    return f->errors != NULL;
}

bool run_files_open_coverage(run_files *f, const char *run_dir, char *err, size_t errlen)
{
    f->coverage = open_in(run_dir, "coverage.csv", coverage_columns, NCOLS(coverage_columns),
                          err, errlen);
    return f->coverage != NULL;
}

void run_files_coverage(run_files *f, const char *run_id, uint32_t trial, uint32_t frame,
                        double t_scene, uint32_t light, double coverage)
{
    csv_writer *w = f->coverage;
    if (!w)
        return;
    frame_row_start(w, run_id, trial, frame, t_scene);
    csv_u64(w, light);
    csv_f64(w, coverage, 6);
    csv_end_row(w);
}

bool run_files_open_lightgrid(run_files *f, const char *run_dir, char *err, size_t errlen)
{
    f->lightgrid = open_in(run_dir, "lightgrid.csv", lightgrid_columns, NCOLS(lightgrid_columns),
                           err, errlen);
    return f->lightgrid != NULL;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

bool run_files_lightgrid(run_files *f, const char *run_id, uint32_t trial, uint32_t frame,
                         double t_scene, const uint32_t *lengths, size_t n)
{
    csv_writer *w = f->lightgrid;
    if (!w || n == 0)
        return true;
    uint32_t *v = malloc(n * sizeof *v);
    if (!v)
        return false;
    memcpy(v, lengths, n * sizeof *v);
    qsort(v, n, sizeof *v, cmp_u32);
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && v[j] == v[i])
            j++;
        frame_row_start(w, run_id, trial, frame, t_scene);
        csv_u64(w, v[i]);
        csv_u64(w, j - i);
        csv_end_row(w);
        i = j;
    }
    free(v);
    return true;
}

void run_files_error(run_files *f, const char *run_id, uint32_t trial, uint32_t frame,
                     double t_scene, const image_error *e)
{
    csv_writer *w = f->errors;
    if (!w)
        return;
    frame_row_start(w, run_id, trial, frame, t_scene);
    csv_g(w, e->rmse);
    csv_g(w, e->psnr_db);
    csv_g(w, e->max_abs);
    csv_g(w, e->frac_over_1_255);
    csv_u64(w, e->nonfinite);
    csv_g(w, e->edge_rmse);   /* empty when the reference has no edge pixel */
    csv_u64(w, e->edge_pixels);
    csv_end_row(w);
}

/* Every file a run_files may hold, in the order they commit. */
#define RUN_FILES_ALL(f)                                                                   \
    {&(f)->frames, &(f)->passes, &(f)->seconds, &(f)->convergence, &(f)->errors,           \
     &(f)->coverage, &(f)->lightgrid}

bool run_files_commit(run_files *f, char *err, size_t errlen)
{
    csv_writer **all[] = RUN_FILES_ALL(f);
    bool ok = true;
    for (size_t i = 0; i < NCOLS(all); i++) {
        if (!*all[i])
            continue;
        if (ok)
            ok = csv_commit(*all[i], err, errlen);
        else
            csv_abort(*all[i]);
        *all[i] = NULL;
    }
    return ok;
}

void run_files_abort(run_files *f)
{
    csv_writer **all[] = RUN_FILES_ALL(f);
    for (size_t i = 0; i < NCOLS(all); i++)
        csv_abort(*all[i]);
    memset(f, 0, sizeof *f);
}

bool output_write_run_summary(const char *run_dir, const experiment *e, const run_spec *s,
                              const pass_plan *pp, const trial_result *t, size_t ntrials,
                              const char *message, char *err, size_t errlen)
{
    char path[4096];
    join(path, sizeof path, run_dir, "summary.csv");
    csv_writer *w = csv_open(path, summary_columns, summary_ncolumns, err, errlen);
    if (!w)
        return false;
    const run_params *p = &s->p;
    /* The G-buffer of a design that has one: "preset[/position][/normal]" where the
     * gbuffer keys choose it, else the design's own ("light-prepass", "ids"). */
    char gbuffer[96] = "";
    renderer_options ro = {0};
    params_to_renderer_options(p, &ro);
    snprintf(gbuffer, sizeof gbuffer, "%s", renderer_gbuffer_layout(p->renderer, &ro));
    if (renderer_uses_gbuffer(p->renderer, &ro)) {
        param_kv kv[PARAM_KV_MAX];
        size_t n = run_params_kv(p, kv, PARAM_KV_MAX);
        for (size_t k = 0; k < n; k++) {
            bool preset = strcmp(kv[k].key, "gbuffer.preset") == 0;
            bool field = strcmp(kv[k].key, "gbuffer.position") == 0 ||
                         strcmp(kv[k].key, "gbuffer.normal") == 0;
            if (preset || (field && strcmp(kv[k].value, "preset") != 0)) {
                size_t len = strlen(gbuffer);
                snprintf(gbuffer + len, sizeof gbuffer - len, "%s%.30s", len ? "/" : "",
                         kv[k].value);
            }
        }
    }
    for (size_t i = 0; i < ntrials; i++) {
        const trial_result *r = &t[i];
        csv_str(w, e->name);
        csv_str(w, s->id);
        csv_str(w, p->renderer);
        csv_str(w, p->scene);
        csv_i64(w, p->width);
        csv_i64(w, p->height);
        csv_str(w, gbuffer);
        csv_str(w, light_placement_name(p->lights.placement));
        csv_str(w, rng_kind_name(p->lights.rng));
        csv_u64(w, p->lights.seed);
        /* the most lights measured; the planned most when nothing was measured */
        csv_u64(w, r->frames ? r->lights_max : light_count_max(&p->lights.count));
        /* the range the placed lights had (overlap's, or lights.sizing's mean), as the
         * trial used it; the manifest's radius where no trial placed lights */
        char radius[32];
        if (r->frames && isfinite(r->lights_radius))
            num_plain_float((float)r->lights_radius, radius, sizeof radius);
        else
            num_plain_float(p->lights.radius, radius, sizeof radius);
        csv_str(w, radius);
        csv_u64(w, r->trial);
        csv_u64(w, r->frames);
        csv_f64(w, r->measured_s, 6);
        csv_f64(w, r->fps_mean, 3);
        csv_f64(w, r->ft.mean, 3);
        csv_f64(w, r->ft.sd, 3);
        csv_f64(w, r->ft_ci95, 3);
        csv_f64(w, r->ft.p50, 3);
        csv_f64(w, r->ft.p99, 3);
        /* the "1% low": the rate of the slowest 1% of frames, 1e6 / p99 frame time */
        csv_f64(w, r->ft.p99 > 0 ? 1e6 / r->ft.p99 : NAN, 3);
        metrics_write_summary(w, &r->m, METRIC_SLOT_S1);
        csv_u64(w, pp->gbuffer_bytes);
        /* Image error: empty unless the manifest names a reference (error:). */
        csv_g(w, r->image_rmse);
        csv_g(w, r->image_psnr_db);
        csv_g(w, r->image_max_abs);
        csv_f64(w, r->nonfinite, 0);
        csv_f64(w, r->harness_us_mean, 3);
        /* as convergence.csv's elapsed_s; empty when the interval never stayed within
         * 1% of the mean, or nothing was measured */
        csv_f64(w, r->frames ? r->ci1pct_after_s : NAN, 6);
        metrics_write_summary(w, &r->m, METRIC_SLOT_S2);
        csv_g(w, r->image_edge_rmse);
        csv_f64(w, r->image_edge_pixels, 0);
        metrics_write_summary(w, &r->m, METRIC_SLOT_S3);
        if (r->order)
            csv_u64(w, r->order);
        else
            csv_empty(w);
        csv_str(w, r->metric);
        csv_f64(w, r->metric_us, 3);
        for (int b = 0; b < 3; b++)   /* bound_us, limiter, bound_pct */
            csv_empty(w);
        csv_str(w, r->status);
        csv_str(w, strcmp(r->status, "ok") == 0 ? "" : message);
        csv_end_row(w);
    }
    return csv_commit(w, err, errlen);
}

void output_sweep_meta_of(const experiment *e, unsigned shard, unsigned nshards, size_t nruns,
                          sweep_meta *m)
{
    memset(m, 0, sizeof *m);
    snprintf(m->format, sizeof m->format, "%s", OUTPUT_FORMAT);
    snprintf(m->experiment, sizeof m->experiment, "%s", e->name);
    snprintf(m->manifest_path, sizeof m->manifest_path, "%s", e->path);
    memcpy(m->manifest_hash, e->hash, sizeof m->manifest_hash);
    m->runs = nruns;
    m->scale = e->scale;
    m->smoke = e->smoke;
    if (shard)
        snprintf(m->shard, sizeof m->shard, "%u/%u", shard, nshards);
    else
        snprintf(m->shard, sizeof m->shard, "all");
}

bool output_write_sweep_meta(const char *out_dir, const sweep_meta *m, char *err, size_t errlen)
{
    char path[4096];
    join(path, sizeof path, out_dir, "sweep.yaml");
    yaml_out *y = yo_open(path, err, errlen);
    if (!y)
        return false;
    yo_map_begin(y);
    yo_key(y, "format"); yo_str(y, OUTPUT_FORMAT);   /* first: the folder is ours */
    yo_key(y, "experiment"); yo_str(y, m->experiment);
    yo_key(y, "manifest_path"); yo_str(y, m->manifest_path);
    yo_key(y, "manifest_hash"); yo_str(y, m->manifest_hash);
    yo_key(y, "runs"); yo_i64(y, (int64_t)m->runs);
    yo_key(y, "shard"); yo_str(y, m->shard);
    yo_key(y, "resolution_scale"); yo_f64(y, m->scale > 0 ? m->scale : 1.0);
    yo_key(y, "smoke"); yo_bool(y, m->smoke);
    yo_map_end(y);
    return yo_commit(y, err, errlen);
}

bool output_read_sweep_meta(const char *out_dir, sweep_meta *m, char *err, size_t errlen)
{
    char path[4096];
    join(path, sizeof path, out_dir, "sweep.yaml");
    memset(m, 0, sizeof *m);
    FILE *f = fopen(path, "rb");
    char buf[16384];
    size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
    if (f)
        fclose(f);
    if (!f || n == 0) {
        snprintf(err, errlen, "%s: not a shadesweep output folder (no readable sweep.yaml)",
                 out_dir);
        return false;
    }
    buf[n] = 0;
    diag_list d = {0};
    ydoc *doc = NULL;
    bool ok = ydoc_load(path, buf, n, &doc, &d) && doc->root->kind == YNODE_MAPPING;
    for (size_t i = 0; ok && i < doc->root->n; i++) {
        const ypair *pr = &doc->root->pairs[i];
        if (pr->key->kind != YNODE_SCALAR || pr->value->kind != YNODE_SCALAR)
            continue;
        const char *k = pr->key->text, *v = pr->value->text;
        if (strcmp(k, "format") == 0)
            snprintf(m->format, sizeof m->format, "%s", v);
        else if (strcmp(k, "experiment") == 0)
            snprintf(m->experiment, sizeof m->experiment, "%s", v);
        else if (strcmp(k, "manifest_path") == 0)
            snprintf(m->manifest_path, sizeof m->manifest_path, "%s", v);
        else if (strcmp(k, "manifest_hash") == 0 && pr->value->len == 16)
            memcpy(m->manifest_hash, v, 17);
        else if (strcmp(k, "runs") == 0)
            m->runs = (size_t)strtoull(v, NULL, 10);
        else if (strcmp(k, "shard") == 0)
            snprintf(m->shard, sizeof m->shard, "%s", v);
        else if (strcmp(k, "resolution_scale") == 0)
            m->scale = strtod(v, NULL);
        else if (strcmp(k, "smoke") == 0)
            m->smoke = strcmp(v, "true") == 0;
    }
    ydoc_free(doc);
    diag_free(&d);
    if (!ok || !m->manifest_hash[0]) {
        snprintf(err, errlen, "%s: no manifest_hash", path);
        return false;
    }
    return true;
}
