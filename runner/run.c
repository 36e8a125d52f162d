/* MAP_ANONYMOUS: the child's report to the parent lives in an anonymous shared map. */
#define _DEFAULT_SOURCE
#include "runner/run.h"

#include <dirent.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>

#include "config.h"
#include "version.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "results/fsutil.h"
#include "results/image_io.h"
#include "results/stats.h"
#include "results/yamlout.h"
#include "runner/isolate.h"
#include "runner/output.h"
#include "runner/progress.h"
#include "scenes/scene.h"

/* A fence wait longer than this is a hung GPU: the run fails rather than waits forever. */
#define SYNC_TIMEOUT_S 60.0

typedef struct frame_log {
    frame_record *v;
    size_t n, cap;
} frame_log;

static bool frame_log_push(frame_log *l, const frame_record *r)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? l->cap * 2 : 4096;
        frame_record *v = realloc(l->v, cap * sizeof *v);
        if (!v)
            return false;
        l->v = v;
        l->cap = cap;
    }
    l->v[l->n++] = *r;
    return true;
}

/* Everything one run holds while it executes. */
typedef struct run_state {
    const experiment *e;
    const run_spec *s;
    const run_options *o;
    progress *pg;
    char dir[4096];
    gl_context *ctx;
    scene *sc;
    renderer *r;
    renderer *ref;             /* error: the reference configuration; NULL without one */
    pass_plan plan;
    run_files files;
    frame_log log;
    trial_result *trials;
    char started[32], finished[32];
    char status[96];
    char message[1024];        /* why it failed, for summary.csv */
    char err[512];
} run_state;

static void utc_now(char *buf, size_t len)
{
    time_t t = time(NULL);
    struct tm tm;
    gmtime_r(&t, &tm);
    strftime(buf, len, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

/* Waits until the GPU (or llvmpipe) has finished every command issued so far. */
static bool frame_sync(run_sync how, char *err, size_t errlen)
{
    if (how == RUN_SYNC_FINISH) {
        gl.Finish();
        return true;
    }
    GLsync f = gl.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!f) {
        snprintf(err, errlen, "glFenceSync failed");
        return false;
    }
    double t0 = progress_now();
    GLenum res;
    do {
        res = gl.ClientWaitSync(f, GL_SYNC_FLUSH_COMMANDS_BIT, 100000000u /* 0.1 s */);
    } while (res == GL_TIMEOUT_EXPIRED && progress_now() - t0 < SYNC_TIMEOUT_S);
    gl.DeleteSync(f);
    if (res == GL_TIMEOUT_EXPIRED) {
        snprintf(err, errlen, "frame not finished after %.0f s", SYNC_TIMEOUT_S);
        return false;
    }
    if (res == GL_WAIT_FAILED) {
        snprintf(err, errlen, "glClientWaitSync failed");
        return false;
    }
    return true;
}

static bool span_done(const span *sp, size_t frames, double elapsed)
{
    return sp->kind == SPAN_FRAMES ? frames >= sp->frames : elapsed >= sp->seconds;
}

static double schedule_time(const run_params *p, size_t frame, double elapsed)
{
    return p->clock == RUN_CLOCK_FIXED ? (double)frame * p->step : elapsed;
}

/* The output framebuffer as an 8-bit image (pixels malloc'ed). */
static bool read_output(run_state *st, image *img, char *err, size_t errlen)
{
    const run_params *p = &st->s->p;
    *img = (image){.width = p->width, .height = p->height, .channels = 4, .type = IMAGE_U8};
    img->pixels = malloc((size_t)p->width * (size_t)p->height * 4u);
    if (!img->pixels) {
        snprintf(err, errlen, "out of memory for a %dx%d image", p->width, p->height);
        return false;
    }
    return gl_context_read_rgba8(st->ctx, img->pixels, err, errlen);
}

static bool screenshot(run_state *st, uint32_t trial, double at, char *err, size_t errlen)
{
    image img;
    char path[4200];
    snprintf(path, sizeof path, "%s/screenshot-trial%u-t%g.png", st->dir, trial, at);
    bool ok = read_output(st, &img, err, errlen) && image_write(path, &img, err, errlen);
    image_free(&img);
    return ok;
}

/* A pass's GPU time cannot exceed the wall time of the frame that waited for it;
 * llvmpipe reports such values for the first timer queries of a context (9e9 us was
 * seen). They become NAN (the CSVs then say nothing rather than something wrong), and
 * the total is summed again. Returns how many were dropped. */
static unsigned drop_implausible_gpu(frame_stats *fs, double frametime_us)
{
    unsigned dropped = 0;
    double total = 0;
    for (size_t i = 0; i < fs->npasses; i++) {
        double g = fs->pass[i].gpu_us;
        if (isfinite(g) && (g < 0 || g > frametime_us * 1.01 + 1000)) {
            fs->pass[i].gpu_us = NAN;
            dropped++;
        }
        total += fs->pass[i].gpu_us;
    }
    if (dropped)
        fs->total.gpu_us = total;   /* NAN now, as for any pass without a result */
    return dropped;
}

/* Draws one frame at schedule time t and waits for its end. */
static bool draw_frame(run_state *st, double t, frame_stats *fs)
{
    scene_update(st->sc, t);
    renderer_draw(st->r, st->sc, fs);
    return frame_sync(st->s->p.sync, st->err, sizeof st->err);
}

static bool gl_clean(run_state *st, const char *where)
{
    unsigned n = gl_context_poll_errors(st->ctx, where);
    return n == 0 && gl_context_error_count(st->ctx) == 0;
}

static void set_status(run_state *st, const char *reason)
{
    if (strcmp(st->status, "ok") == 0)
        snprintf(st->status, sizeof st->status, "failed:%s", reason);
}


/* The per-pixel largest channel error: EXR with the exact values, PNG at x16 gain
 * (1/255 off shows as 16/255; 1/16 and more is white). */
static bool save_heat_map(const image *a, const image *b, const char *base, char *err,
                          size_t errlen)
{
    size_t n = (size_t)a->width * (size_t)a->height;
    image f = {.width = a->width, .height = a->height, .channels = 1, .type = IMAGE_F32};
    image g = {.width = a->width, .height = a->height, .channels = 1, .type = IMAGE_U8};
    f.pixels = malloc(n * sizeof(float));
    g.pixels = malloc(n);
    bool ok = f.pixels && g.pixels;
    for (size_t i = 0; ok && i < n; i++) {
        int worst = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs((int)((uint8_t *)a->pixels)[4 * i + c] - (int)((uint8_t *)b->pixels)[4 * i + c]);
            worst = d > worst ? d : worst;
        }
        ((float *)f.pixels)[i] = (float)worst / 255.0f;
        ((uint8_t *)g.pixels)[i] = (uint8_t)(worst * 16 > 255 ? 255 : worst * 16);
    }
    char path[4400];
    if (ok) {
        snprintf(path, sizeof path, "%s-error.exr", base);
        ok = image_write(path, &f, err, errlen);
    } else {
        snprintf(err, errlen, "out of memory for a heat map");
    }
    if (ok) {
        snprintf(path, sizeof path, "%s-error.png", base);
        ok = image_write(path, &g, err, errlen);
    }
    free(f.pixels);
    free(g.pixels);
    return ok;
}

/* error: the frame just drawn against the reference configuration drawing the same
 * scene state (same time, lights and camera): its row in errors.csv, the worst values
 * in *tr, images on request. Runs between measured frames, after the bookkeeping. */
static bool measure_error(run_state *st, uint32_t trial, uint32_t frame, double at,
                          trial_result *tr, char *err, size_t errlen)
{
    const run_params *p = &st->s->p;
    image run = {0}, ref = {0};
    image_error e = {0};
    size_t nonfinite = 0;
    bool ok = read_output(st, &run, err, errlen);
    if (ok) {
        /* the run's own float accumulation, where it has one */
        size_t n = (size_t)p->width * (size_t)p->height * 4u;
        float *hdr = malloc(n * sizeof *hdr);
        if (hdr && !renderer_read_hdr(st->r, hdr, p->width, p->height, &nonfinite))
            nonfinite = 0;
        free(hdr);
        frame_stats fs;
        renderer_draw(st->ref, st->sc, &fs);
        gl.Finish();
        renderer_collect(st->ref, &fs);
        ok = read_output(st, &ref, err, errlen) && image_compare(&run, &ref, &e, err, errlen);
    }
    if (ok) {
        e.nonfinite += nonfinite;
        run_files_error(&st->files, st->s->id, trial, frame, st->sc->t, &e);
        if (isnan(tr->image_rmse) || e.rmse > tr->image_rmse)
            tr->image_rmse = e.rmse;
        if (isnan(tr->image_psnr_db) || e.psnr_db < tr->image_psnr_db)
            tr->image_psnr_db = e.psnr_db;
        if (isnan(tr->image_max_abs) || e.max_abs > tr->image_max_abs)
            tr->image_max_abs = e.max_abs;
        tr->nonfinite = (isnan(tr->nonfinite) ? 0 : tr->nonfinite) + (double)e.nonfinite;
    }
    if (ok && p->error_save_images) {
        char base[4300];
        snprintf(base, sizeof base, "%s/error-trial%u-t%g", st->dir, trial, at);
        char path[4400];
        snprintf(path, sizeof path, "%s-run.png", base);
        ok = image_write(path, &run, err, errlen);
        snprintf(path, sizeof path, "%s-reference.png", base);
        ok = ok && image_write(path, &ref, err, errlen);
        ok = ok && save_heat_map(&run, &ref, base, err, errlen);
    }
    image_free(&run);
    image_free(&ref);
    return ok;
}

/* One trial: warm-up (not recorded), then the measured frames. */
static void run_trial(run_state *st, uint32_t trial, trial_result *tr)
{
    const run_params *p = &st->s->p;
    frame_stats fs;
    memset(tr, 0, sizeof *tr);
    tr->trial = trial;
    tr->image_rmse = tr->image_psnr_db = tr->image_max_abs = tr->nonfinite = NAN;
    snprintf(tr->status, sizeof tr->status, "ok");
    st->log.n = 0;

    double w0 = progress_now();
    for (size_t k = 0; !span_done(&p->warmup, k, progress_now() - w0); k++) {
        if (!draw_frame(st, schedule_time(p, k, progress_now() - w0), &fs)) {
            snprintf(tr->status, sizeof tr->status, "failed:sync");
            return;
        }
        renderer_collect(st->r, &fs);
        if (fs.overflow[0]) {
            snprintf(tr->status, sizeof tr->status, "failed:overflow");
            snprintf(st->err, sizeof st->err, "warm-up frame %zu: %s", k, fs.overflow);
            return;
        }
    }
    if (!gl_clean(st, "warm-up")) {
        snprintf(tr->status, sizeof tr->status, "failed:gl-error");
        return;
    }

    bool shot_done[MAX_SCREENSHOTS] = {false}, error_done[MAX_SCREENSHOTS] = {false};
    double harness_s = 0, t_end = 0;
    double t0 = progress_now();
    for (size_t k = 0;; k++) {
        double start = progress_now();
        double t = schedule_time(p, k, start - t0);
        bool ok = draw_frame(st, t, &fs);
        double end = progress_now();
        if (!ok) {
            snprintf(tr->status, sizeof tr->status, "failed:sync");
            fprintf(stderr, "run %s: %s\n", st->s->id, st->err);
            break;
        }
        renderer_collect(st->r, &fs);
        if (fs.overflow[0]) {   /* a light list did not fit: nothing is truncated silently */
            snprintf(tr->status, sizeof tr->status, "failed:overflow");
            snprintf(st->err, sizeof st->err, "frame %zu: %s", k, fs.overflow);
            fprintf(stderr, "run %s: %s\n", st->s->id, st->err);
            break;
        }
        unsigned dropped = drop_implausible_gpu(&fs, (end - start) * 1e6);
        if (dropped && !tr->gpu_dropped)
            fprintf(stderr, "run %s: frame %zu: %u GPU timer result%s longer than the frame "
                    "itself, recorded as unknown\n", st->s->id, k, dropped, dropped == 1 ? "" : "s");
        tr->gpu_dropped += dropped;
        frame_record rec = {
            .frame = (uint32_t)k,
            .t_wall_s = end - t0,
            .t_scene_s = t,
            .lights = st->sc->nlights_active,
            .frametime_us = (end - start) * 1e6,
            .gpu_us = fs.total.gpu_us,
            .draw_calls = fs.total.draw_calls,
            .state_changes = fs.total.state_changes,
            .fragments = fs.total.fragments,
            .dispatches = fs.total.dispatches,
            .cell_lights_mean = fs.grid_lights_mean,
            .cell_lights_max = fs.grid_lights_max,
            .light_evals_per_pixel = fs.light_evals_per_pixel,
        };
        t_end = rec.t_wall_s;
        if (!frame_log_push(&st->log, &rec)) {
            snprintf(tr->status, sizeof tr->status, "failed:oom");
            break;
        }
        run_files_frame(&st->files, st->s->id, trial, &rec, &fs);
        for (uint32_t i = 0; i < st->sc->ncoverage_lights && i < st->sc->nlights_active; i++)
            run_files_coverage(&st->files, st->s->id, trial, rec.frame, t, i,
                               scene_light_coverage(st->sc, i));
        bool clean = gl_clean(st, "frame");
        harness_s += progress_now() - end;
        if (!clean) {
            snprintf(tr->status, sizeof tr->status, "failed:gl-error");
            break;
        }
        for (size_t i = 0; i < p->nscreenshots; i++) {
            if (shot_done[i] || t < p->screenshots[i])
                continue;
            shot_done[i] = true;
            char err[512];
            if (!screenshot(st, trial, p->screenshots[i], err, sizeof err)) {
                fprintf(stderr, "run %s: screenshot: %s\n", st->s->id, err);
                snprintf(tr->status, sizeof tr->status, "failed:screenshot");
            }
            size_t ncells = 0;
            const uint32_t *grid = renderer_light_grid(st->r, &ncells);
            if (!run_files_lightgrid(&st->files, st->s->id, trial, rec.frame, t, grid, ncells))
                snprintf(tr->status, sizeof tr->status, "failed:oom");
        }
        for (size_t i = 0; i < p->nerror_at; i++) {
            if (error_done[i] || t < p->error_at[i])
                continue;
            error_done[i] = true;
            char err[512];
            if (!measure_error(st, trial, rec.frame, p->error_at[i], tr, err, sizeof err)) {
                fprintf(stderr, "run %s: error against the reference: %s\n", st->s->id, err);
                snprintf(tr->status, sizeof tr->status, "failed:error");
            }
        }
        progress_tick(st->pg, trial, rec.lights, (double)(k + 1) / (end - t0));
        if (span_done(&p->duration, k + 1, end - t0))
            break;
    }

    /* A comparison that exceeded the manifest's limit, or non-finite light, fails it. */
    if (strcmp(tr->status, "ok") == 0 && p->error_max_rmse > 0 && tr->image_rmse > p->error_max_rmse) {
        snprintf(tr->status, sizeof tr->status, "failed:error");
        snprintf(st->err, sizeof st->err, "image RMSE %g against %s exceeds error.max_rmse %g",
                 tr->image_rmse, p->error_renderer, p->error_max_rmse);
    }
    if (strcmp(tr->status, "ok") == 0 && tr->nonfinite > 0) {
        snprintf(tr->status, sizeof tr->status, "failed:nonfinite");
        snprintf(st->err, sizeof st->err, "%.0f non-finite values in the light accumulation",
                 tr->nonfinite);
    }

    /* Post-trial arithmetic counts as bookkeeping too, spread over the frames. */
    double post0 = progress_now();
    size_t n = st->log.n;
    double *ft = malloc((n ? n : 1) * sizeof *ft);
    second_bin *bins = NULL;
    size_t nbins = 0;
    if (!ft || !stats_bin_seconds(st->log.v, n, t_end, &bins, &nbins)) {
        snprintf(tr->status, sizeof tr->status, "failed:oom");
        free(ft);
        return;
    }
    double gpu = 0, dc = 0, sc = 0, frag = 0, disp = 0, cmean = 0, cmax = NAN, evals = 0;
    size_t ngpu = 0;           /* frames with a GPU time (some may have none) */
    size_t ngrid = 0;          /* frames with a light grid */
    unsigned lmax = 0;
    for (size_t i = 0; i < n; i++) {
        const frame_record *f = &st->log.v[i];
        ft[i] = f->frametime_us;
        if (isfinite(f->gpu_us)) {
            gpu += f->gpu_us;
            ngpu++;
        }
        dc += (double)f->draw_calls;
        sc += (double)f->state_changes;
        frag += f->fragments;
        disp += (double)f->dispatches;
        if (isfinite(f->cell_lights_mean)) {
            ngrid++;
            cmean += f->cell_lights_mean;
            evals += f->light_evals_per_pixel;
            if (ngrid == 1 || f->cell_lights_max > cmax)
                cmax = f->cell_lights_max;
        }
        if (f->lights > lmax)
            lmax = f->lights;
    }
    stats_summarize(ft, n, &tr->ft);
    tr->ft_ci95 = stats_ci95_batch_means(ft, n);
    tr->frames = n;
    tr->measured_s = t_end;
    tr->fps_mean = t_end > 0 ? (double)n / t_end : NAN;
    tr->gpu_mean_us = ngpu ? gpu / (double)ngpu : NAN;   /* over the frames that have one */
    tr->draw_calls_mean = n ? dc / (double)n : NAN;
    tr->state_changes_mean = n ? sc / (double)n : NAN;
    tr->fragments_mean = n ? frag / (double)n : NAN;
    tr->dispatches_mean = n ? disp / (double)n : NAN;
    tr->cell_lights_mean = ngrid ? cmean / (double)ngrid : NAN;
    tr->cell_lights_max = ngrid ? cmax : NAN;
    tr->light_evals_per_pixel_mean = ngrid ? evals / (double)ngrid : NAN;
    tr->lights_max = lmax;
    run_files_seconds(&st->files, st->s->id, trial, bins, nbins);
    free(bins);
    convergence_point *conv = NULL;
    size_t nconv = 0;
    if (!stats_convergence(st->log.v, n, t_end, &conv, &nconv)) {
        snprintf(tr->status, sizeof tr->status, "failed:oom");
        free(ft);
        return;
    }
    tr->ci1pct_after_s = stats_converged_after(conv, nconv, 0.01);
    run_files_convergence(&st->files, st->s->id, trial, conv, nconv);
    free(conv);
    free(ft);
    harness_s += progress_now() - post0;
    tr->harness_us_mean = n ? harness_s * 1e6 / (double)n : NAN;
}

static void cpu_model(char *buf, size_t len)
{
    snprintf(buf, len, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "model name", 10) == 0) {
            char *colon = strchr(line, ':');
            if (colon) {
                colon++;
                while (*colon == ' ' || *colon == '\t')
                    colon++;
                colon[strcspn(colon, "\n")] = 0;
                snprintf(buf, len, "%s", colon);
            }
            break;
        }
    }
    fclose(f);
}

static bool write_meta(run_state *st, char *err, size_t errlen)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/meta.yaml", st->dir);
    yaml_out *y = yo_open(path, err, errlen);
    if (!y)
        return false;
    const experiment *e = st->e;
    yo_map_begin(y);
    yo_key(y, "run_id"); yo_str(y, st->s->id);
    yo_key(y, "experiment"); yo_str(y, e->name);
    yo_key(y, "status"); yo_str(y, st->status);
    yo_key(y, "manifest");
    yo_map_begin(y);
    yo_key(y, "path"); yo_str(y, e->path);
    yo_key(y, "hash"); yo_str(y, e->hash);
    yo_map_end(y);
    yo_key(y, "shadesweep");
    yo_map_begin(y);
    yo_key(y, "version"); yo_str(y, SHADESWEEP_VERSION);
    yo_key(y, "commit"); yo_str(y, SHADESWEEP_COMMIT);
    yo_map_end(y);

    yo_key(y, "parameters");
    yo_map_begin(y);
    param_kv kv[PARAM_KV_MAX];
    size_t nkv = run_params_kv(&st->s->p, kv, PARAM_KV_MAX);
    for (size_t i = 0; i < nkv; i++) {
        yo_key(y, kv[i].key);
        yo_str(y, kv[i].value);
    }
    yo_map_end(y);

    yo_key(y, "gl");
    yo_map_begin(y);
    const gl_info *gi = st->ctx ? gl_context_info(st->ctx) : NULL;
    yo_key(y, "backend"); yo_str(y, gi ? gi->backend : NULL);
    yo_key(y, "device"); yo_str(y, gi ? gi->device : NULL);
    yo_key(y, "vendor"); yo_str(y, gi ? gi->vendor : NULL);
    yo_key(y, "renderer"); yo_str(y, gi ? gi->renderer : NULL);
    yo_key(y, "version"); yo_str(y, gi ? gi->version : NULL);
    yo_key(y, "glsl"); yo_str(y, gi ? gi->glsl_version : NULL);
    yo_key(y, "debug_context"); yo_bool(y, gi && gi->debug_context);
    yo_key(y, "timer_query"); yo_bool(y, gi && gi->timer_query);
    yo_key(y, "pipeline_statistics"); yo_bool(y, gi && gi->pipeline_statistics);
    yo_map_end(y);

    char cpu[256], host[256] = "unknown";
    cpu_model(cpu, sizeof cpu);
    gethostname(host, sizeof host - 1);
    yo_key(y, "host");
    yo_map_begin(y);
    yo_key(y, "cpu"); yo_str(y, cpu);
    yo_key(y, "threads"); yo_i64(y, sysconf(_SC_NPROCESSORS_ONLN));
    yo_key(y, "hostname"); yo_str(y, host);
    yo_map_end(y);
    yo_key(y, "started"); yo_str(y, st->started);
    yo_key(y, "finished"); yo_str(y, st->finished);

    yo_key(y, "timing");
    yo_map_begin(y);
    yo_key(y, "clock_source"); yo_str(y, "CLOCK_MONOTONIC");
    yo_key(y, "frame_end"); yo_str(y, st->s->p.sync == RUN_SYNC_FINISH ? "glFinish" : "fence");
    yo_key(y, "ci95_method"); yo_str(y, "batch means, 10 batches, Student t");
    yo_map_end(y);

    yo_key(y, "pass_plan");
    yo_map_begin(y);
    yo_key(y, "passes");
    yo_seq_begin(y);
    for (size_t i = 0; i < st->plan.npasses; i++) {
        yo_map_begin(y);
        yo_key(y, "name"); yo_str(y, st->plan.pass[i].name);
        yo_key(y, "run"); yo_bool(y, st->plan.pass[i].run);
        yo_key(y, "reason"); yo_str(y, st->plan.pass[i].reason);
        yo_map_end(y);
    }
    yo_seq_end(y);
    yo_key(y, "programs");
    yo_seq_begin(y);
    for (size_t i = 0; i < st->plan.nprograms; i++)
        yo_str(y, st->plan.program[i]);
    yo_seq_end(y);
    yo_key(y, "targets");
    yo_seq_begin(y);
    for (size_t i = 0; i < st->plan.ntargets; i++) {
        const target_plan_entry *t = &st->plan.target[i];
        yo_map_begin(y);
        yo_key(y, "name"); yo_str(y, t->name);
        yo_key(y, "format"); yo_str(y, t->format);
        yo_key(y, "width"); yo_i64(y, t->width);
        yo_key(y, "height"); yo_i64(y, t->height);
        yo_key(y, "bytes"); yo_i64(y, (int64_t)t->bytes);
        yo_map_end(y);
    }
    yo_seq_end(y);
    yo_key(y, "gbuffer_bytes"); yo_i64(y, (int64_t)st->plan.gbuffer_bytes);
    yo_key(y, "target_bytes"); yo_i64(y, (int64_t)st->plan.target_bytes);
    yo_map_end(y);
    yo_map_end(y);
    return yo_commit(y, err, errlen);
}

/* Sets up one run; on failure st->status says why and st->err holds the message. */
static bool run_setup(run_state *st)
{
    const run_params *p = &st->s->p;
    gl_context_desc cd = {
        .backend = st->o->backend,
        .device = st->o->device,
        .debug = st->o->debug_gl,
        .width = p->width,
        .height = p->height,
    };
    if (!fs_mkdirs(st->dir, st->err, sizeof st->err)) {
        set_status(st, "output");
        return false;
    }
    if (!(st->ctx = gl_context_create(&cd, st->err, sizeof st->err))) {
        set_status(st, "context");
        return false;
    }
    if (!(st->sc = scene_build(p->scene, &p->lights, p->width, p->height, st->err,
                               sizeof st->err)) ||
        !scene_set_camera(st->sc, &p->camera, st->err, sizeof st->err)) {
        set_status(st, "scene");
        return false;
    }
    const gl_info *gi = gl_context_info(st->ctx);
    renderer_options ro = {
        .width = p->width,
        .height = p->height,
        .queries = true,
        .timer_query = gi->timer_query,
        .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size,
        .gbuffer = p->gbuffer,
        .gbuffer_position = p->gbuffer_position,
        .gbuffer_normal = p->gbuffer_normal,
        .light_volumes = p->light_volumes,
        .separate_specular = p->separate_specular,
        .no_illumination_sets = !p->illumination_sets,
        .no_shadows = p->shadows == 1,
        .light_buffer = p->light_buffer == 1 ? LIGHT_BUFFER_STORAGE : LIGHT_BUFFER_UNIFORM,
        .tile_size = 8 << p->tile_size,
        .max_lights_per_tile = p->max_lights_per_tile,
        .clustered_slices = (int)p->clustered_slices,
        .clustered_deferred = p->clustered_shading == 1,
    };
    if (!(st->r = renderer_create(p->renderer, &ro, st->err, sizeof st->err)) ||
        !renderer_prepare(st->r, st->sc, st->err, sizeof st->err)) {
        set_status(st, "renderer");
        return false;
    }
    renderer_describe(st->r, &st->plan);
    if (!gl_clean(st, "prepare")) {
        snprintf(st->err, sizeof st->err, "GL error while preparing the renderer");
        set_status(st, "gl-error");
        return false;
    }
    if (!run_files_open(&st->files, st->dir, p, st->err, sizeof st->err)) {
        set_status(st, "output");
        return false;
    }
    if (st->sc->ncoverage_lights &&
        !run_files_open_coverage(&st->files, st->dir, st->err, sizeof st->err)) {
        set_status(st, "output");
        return false;
    }
    if (p->nscreenshots && renderer_has_light_grid(st->r) &&
        !run_files_open_lightgrid(&st->files, st->dir, st->err, sizeof st->err)) {
        set_status(st, "output");
        return false;
    }
    if (p->error_renderer[0]) {
        renderer_options rr = ro;
        rr.queries = false;
        rr.gbuffer = p->error_gbuffer;
        rr.gbuffer_position = GBUFFER_POSITION_PRESET;
        rr.gbuffer_normal = GBUFFER_NORMAL_PRESET;
        rr.light_volumes = p->error_light_volumes;
        rr.separate_specular = false;
        rr.no_illumination_sets = false;
        /* a reference, not a measurement: forward-spml holds any number of lights */
        rr.light_buffer = LIGHT_BUFFER_AUTO;
        rr.max_lights_per_tile = 0;
        char why[512];
        if (!(st->ref = renderer_create(p->error_renderer, &rr, why, sizeof why)) ||
            !renderer_prepare(st->ref, st->sc, why, sizeof why)) {
            snprintf(st->err, sizeof st->err, "reference %.31s: %.400s", p->error_renderer, why);
            set_status(st, "reference");
            return false;
        }
        if (!run_files_open_errors(&st->files, st->dir, st->err, sizeof st->err)) {
            set_status(st, "output");
            return false;
        }
    }
    return true;
}

/* Releases what run_setup and the trials made (not st->trials: the parent's). */
static void run_teardown(run_state *st)
{
    run_files_abort(&st->files);
    renderer_destroy(st->ref);
    renderer_destroy(st->r);
    scene_destroy(st->sc);
    gl_context_destroy(st->ctx);
    free(st->log.v);
}

/* Rows for trials that never ran, so that every run has one row per trial. */
static void fill_missing_trials(run_state *st)
{
    for (uint32_t t = 0; t < st->s->p.trials; t++) {
        trial_result *tr = &st->trials[t];
        if (tr->trial != 0)
            continue;
        tr->trial = t + 1;
        tr->ft.mean = tr->ft.sd = tr->ft.p50 = tr->ft.p99 = NAN;
        tr->ft_ci95 = tr->fps_mean = tr->measured_s = NAN;
        tr->gpu_mean_us = tr->draw_calls_mean = tr->state_changes_mean = NAN;
        tr->dispatches_mean = tr->cell_lights_mean = tr->cell_lights_max = NAN;
        tr->light_evals_per_pixel_mean = NAN;
        tr->fragments_mean = tr->harness_us_mean = tr->ci1pct_after_s = NAN;
        tr->image_rmse = tr->image_psnr_db = tr->image_max_abs = tr->nonfinite = NAN;
        snprintf(tr->status, sizeof tr->status, "%s",
                 strcmp(st->status, "ok") ? st->status : "failed:not-run");
    }
}

/* meta.yaml, then the run's summary.csv: the summary is written last, so its
 * presence means the run is complete (what --resume looks for). */
static void write_run_result(run_state *st)
{
    fill_missing_trials(st);
    utc_now(st->finished, sizeof st->finished);
    char err[512];
    if (!fs_mkdirs(st->dir, err, sizeof err) || !write_meta(st, err, sizeof err) ||
        !output_write_run_summary(st->dir, st->e, st->s, &st->plan, st->trials,
                                  st->s->p.trials, st->message, err, sizeof err)) {
        fprintf(stderr, "run %s: %s\n", st->s->id, err);
        set_status(st, "output");
    }
}

/* Runs one run_spec in this process; its status ends in st->status. */
static void run_one(run_state *st)
{
    const run_params *p = &st->s->p;
    if (run_setup(st)) {
        for (uint32_t t = 1; t <= p->trials; t++) {
            trial_result *tr = &st->trials[t - 1];
            run_trial(st, t, tr);
            if (strcmp(tr->status, "ok") != 0) {
                snprintf(st->status, sizeof st->status, "%s", tr->status);
                /* Image error and non-finite light are verdicts on what was measured:
                 * the other trials still measure. Anything else ends the run. */
                if (strcmp(tr->status, "failed:error") != 0 &&
                    strcmp(tr->status, "failed:nonfinite") != 0)
                    break;
            }
        }
        if (!run_files_commit(&st->files, st->err, sizeof st->err)) {
            fprintf(stderr, "run %s: %s\n", st->s->id, st->err);
            set_status(st, "output");
        }
    } else {
        fprintf(stderr, "run %s: %s\n", st->s->id, st->err);
    }
    if (strcmp(st->status, "ok") != 0 && st->err[0])
        snprintf(st->message, sizeof st->message, "%s", st->err);
    write_run_result(st);
}

/* What a run's child tells the parent, through memory shared across the fork. */
typedef struct run_report {
    int done;                  /* set last: the fields below are complete */
    char status[96];
    char message[512];
    double fps;
} run_report;

typedef struct child_args {
    run_state *st;
    run_report *report;
} child_args;

static int child_main(void *arg)
{
    child_args *a = arg;
    run_one(a->st);
    snprintf(a->report->status, sizeof a->report->status, "%s", a->st->status);
    snprintf(a->report->message, sizeof a->report->message, "%.500s", a->st->message);
    a->report->fps = a->st->trials[0].frames ? a->st->trials[0].fps_mean : 0;
    a->report->done = 1;
    run_teardown(a->st);
    return strcmp(a->st->status, "ok") == 0 ? 0 : 1;
}

static double seconds_of(const span *sp) { return sp->kind == SPAN_SECONDS ? sp->seconds : 0; }

double run_timeout_s(const run_params *p)
{
    if (p->timeout_s > 0)
        return p->timeout_s;
    return 600.0 + 3.0 * p->trials * (seconds_of(&p->warmup) + seconds_of(&p->duration));
}

/* Removes what a child that did not finish left behind: temporary files. */
static void remove_temp_files(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct dirent *ent;
    char path[4400];
    while ((ent = readdir(d)))
        if (strstr(ent->d_name, ".tmp.")) {
            snprintf(path, sizeof path, "%s/%s", dir, ent->d_name);
            unlink(path);
        }
    closedir(d);
}

static volatile sig_atomic_t stop_signal;

static void on_stop_signal(int sig) { stop_signal = sig; }

bool run_is_complete(const char *out_dir, const char *id)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/runs/%s/summary.csv", out_dir, id);
    return fs_exists(path);
}

int run_plan(const experiment *e, const plan *p, const run_options *o)
{
    char err[512];
    if (!output_write_plan(o->out_dir, p, err, sizeof err)) {
        fprintf(stderr, "shadesweep: %s\n", err);
        return 2;
    }
    remove_temp_files(o->out_dir);
    sweep_meta sm = {.runs = p->nruns, .scale = e->scale, .smoke = e->smoke};
    snprintf(sm.experiment, sizeof sm.experiment, "%s", e->name);
    snprintf(sm.manifest_path, sizeof sm.manifest_path, "%s", e->path);
    memcpy(sm.manifest_hash, e->hash, sizeof sm.manifest_hash);
    if (o->shard)
        snprintf(sm.shard, sizeof sm.shard, "%u/%u", o->shard, o->nshards);
    else
        snprintf(sm.shard, sizeof sm.shard, "all");
    if (!output_write_sweep_meta(o->out_dir, &sm, err, sizeof err)) {
        fprintf(stderr, "shadesweep: %s\n", err);
        return 2;
    }
    size_t selected = 0, skipped = 0;
    for (size_t i = 0; i < p->nruns; i++) {
        const run_spec *s = &p->runs[i];
        if (o->shard && s->shard != o->shard)
            continue;
        selected++;
        skipped += o->resume && run_is_complete(o->out_dir, s->id);
    }
    if (o->resume)
        fprintf(stderr, "resuming: %zu of %zu runs already complete\n", skipped, selected);

    /* Progress goes to the terminal (or log) the user sees; each child's own
     * stderr goes to its run's log.txt. */
    int fd = dup(STDERR_FILENO);
    FILE *progress_out = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!progress_out) {
        fprintf(stderr, "shadesweep: cannot duplicate stderr\n");
        return 2;
    }
    setvbuf(progress_out, NULL, _IOLBF, 0);
    struct sigaction sa = {.sa_handler = on_stop_signal}, old_int, old_term;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    stop_signal = 0;

    progress pg;
    progress_init(&pg, selected - skipped, progress_out);
    size_t k = 0, failed = 0, done = 0;
    int rc = 0;
    for (size_t i = 0; i < p->nruns && !stop_signal; i++) {
        const run_spec *s = &p->runs[i];
        if (o->shard && s->shard != o->shard)
            continue;
        if (o->resume && run_is_complete(o->out_dir, s->id)) {
            done++;
            continue;
        }
        progress_run_begin(&pg, ++k, s->id, s->p.renderer, s->p.width, s->p.height);
        run_state st = {.e = e, .s = s, .o = o, .pg = &pg};
        snprintf(st.status, sizeof st.status, "ok");
        utc_now(st.started, sizeof st.started);
        snprintf(st.dir, sizeof st.dir, "%s/runs/%s", o->out_dir, s->id);
        char log_path[4300];
        snprintf(log_path, sizeof log_path, "%s/log.txt", st.dir);
        run_report *report = mmap(NULL, sizeof *report, PROT_READ | PROT_WRITE,
                                  MAP_SHARED | MAP_ANONYMOUS, -1, 0);
        st.trials = calloc(s->p.trials, sizeof *st.trials);
        if (report == MAP_FAILED || !st.trials || !fs_remove_tree(st.dir, err, sizeof err) ||
            !fs_mkdirs(st.dir, err, sizeof err)) {
            fprintf(stderr, "shadesweep: run %s: %s\n", s->id,
                    st.trials && report != MAP_FAILED ? err : "out of memory");
            if (report != MAP_FAILED)
                munmap(report, sizeof *report);
            free(st.trials);
            rc = 2;
            break;
        }
        child_args args = {.st = &st, .report = report};
        isolate_result ir;
        isolate_run(child_main, &args, run_timeout_s(&s->p), log_path, &stop_signal, &ir);
        double fps = 0;
        if (ir.outcome == ISOLATE_INTERRUPTED && report->done) {
            /* Interrupted after its files were complete (while tearing down): keep it. */
            ir.outcome = ISOLATE_EXITED;
            ir.exit_code = strcmp(report->status, "ok") == 0 ? 0 : 1;
        }
        if (ir.outcome == ISOLATE_INTERRUPTED) {
            /* Discard the run: resume reruns it. */
            fs_remove_tree(st.dir, err, sizeof err);
            snprintf(st.status, sizeof st.status, "interrupted, discarded");
        } else if (ir.outcome == ISOLATE_EXITED && report->done) {
            snprintf(st.status, sizeof st.status, "%s", report->status);
            fps = report->fps;
            if (report->message[0])
                fprintf(stderr, "run %s: %s\n", s->id, report->message);
        } else {
            /* The child died or hung: the parent writes the run's rows. */
            isolate_status(&ir, st.status, sizeof st.status);
            char tail[200];
            isolate_log_tail(log_path, 3, tail, sizeof tail);
            snprintf(st.message, sizeof st.message, "%.80s after %.1f s%s%.200s", st.status + 7,
                     ir.seconds, tail[0] ? ": " : "", tail);
            fprintf(stderr, "run %s: %s\n", s->id, st.message);
            remove_temp_files(st.dir);
            write_run_result(&st);
        }
        munmap(report, sizeof *report);
        free(st.trials);
        progress_run_end(&pg, st.status, fps);
        if (ir.outcome != ISOLATE_INTERRUPTED) {
            failed += strcmp(st.status, "ok") != 0;
            done++;
        }
    }
    progress_finish(&pg);
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    fclose(progress_out);

    if (!output_merge_summary(o->out_dir, p, o->shard, err, sizeof err)) {
        fprintf(stderr, "shadesweep: %s\n", err);
        return 2;
    }
    if (stop_signal) {
        fprintf(stderr,
                "interrupted by %s: %zu of %zu runs complete; to finish the others:\n"
                "  shadesweep run --resume -o %s %s\n",
                stop_signal == SIGINT ? "SIGINT" : "SIGTERM", done, selected, o->out_dir,
                e->path);
        return 128 + stop_signal;
    }
    if (rc)
        return rc;
    return failed ? 1 : 0;
}
