/* MAP_ANONYMOUS: the child's report to the parent lives in an anonymous shared map. */
#define _DEFAULT_SOURCE
#include "runner/run.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "config.h"
#include "version.h"
#include "renderers/deferred.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "results/contention.h"
#include "results/fsutil.h"
#include "results/image_io.h"
#include "results/image_ref.h"
#include "results/stats.h"
#include "results/stream_stats.h"
#include "results/yamlout.h"
#include "runner/hash.h"
#include "runner/folder.h"
#include "runner/isolate.h"
#include "runner/memory.h"
#include "runner/output.h"
#include "runner/params.h"
#include "runner/provenance.h"
#include "runner/plan_check.h"
#include "runner/progress.h"
#include "scenes/scene.h"

/* A fence wait longer than this is a hung GPU: the run fails rather than waits forever. */
#define SYNC_TIMEOUT_S 60.0

/* Everything one run holds while it executes. */
typedef struct run_state {
    const experiment *e;
    const run_spec *s;
    const run_options *o;
    progress *pg;
    uint32_t trial;            /* the trial this process runs, 1.. */
    uint32_t order;            /* its place in its round (runner/schedule.c) */
    char metric[8];            /* measure.metric resolved for this context ("": none yet) */
    char dir[4300];            /* OUT/runs/<id>/trial-<k> */
    gl_context *ctx;
    scene *sc;
    renderer *r;
    renderer *ref;             /* error: the reference configuration; NULL without one */
    gl_offscreen ref_fb;       /* error.reference.supersample K > 1: its K W x K H output */
    float *ref_hdr;            /* ... and its HDR image read back, K W x K H RGBA */
    pass_plan plan;
    run_files files;
    trial_stream *stream;      /* the per-trial statistics, fed frame by frame */
    double prime_s;            /* prime_variants: wall time of the frames it drew */
    size_t prime_frames;
    double paused_s;           /* measured clock paused (comparisons, screenshots) */
    trial_result result;       /* this trial's row (result.trial 0: it never ran) */
    char started[32], finished[32];
    provenance_start prov;     /* the machine's load and memory at the trial's start */
    char status[96];
    char message[1024];        /* why it failed, for summary.csv */
    char err[512];
    scene_file_info scene_info; /* a file scene: what scene_file_check found */
    unsigned gbuffer_bpp;      /* the G-buffer's bytes per pixel, seed 002's model; 0: none */
    uint32_t made_opaque;      /* translucency: opaque: the materials it made opaque */
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

/* *unwritten: the image was read but could not be written (the file is not there). */
static bool screenshot(run_state *st, uint32_t trial, double at, bool *unwritten, char *err,
                       size_t errlen)
{
    image img;
    char path[4500];
    snprintf(path, sizeof path, "%s/screenshot-trial%u-t%g.png", st->dir, trial, at);
    bool ok = read_output(st, &img, err, errlen);
    if (ok && !(ok = image_write(path, &img, err, errlen)))
        *unwritten = true;
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

/* debug.busy_us (testing regression gates): a fixed amount of work, not of time: spins
 * until this thread has run us microseconds on its own CPU clock, so that every metric
 * (wall, the process's CPU time) sees the same slowdown whatever else the machine does. */
static double thread_cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void busy_wait_us(uint32_t us)
{
    double until = thread_cpu_s() + us * 1e-6;
    while (thread_cpu_s() < until)
        ;
}

/* Draws one frame at schedule time t and waits for its end; a measured frame of a
 * run with debug.busy_us (of its renderer) then busy-waits inside the frame. */
static bool draw_frame(run_state *st, double t, frame_stats *fs, bool measured)
{
    const run_params *p = &st->s->p;
    scene_update(st->sc, t);
    renderer_draw(st->r, st->sc, fs);
    bool ok = frame_sync(p->sync, st->err, sizeof st->err);
    if (ok && measured && p->debug_busy_us &&
        (!p->debug_busy_renderer[0] || strcmp(p->debug_busy_renderer, p->renderer) == 0))
        busy_wait_us(p->debug_busy_us);
    return ok;
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

/* A file of the trial could not be written: whatever else the trial's status said, it
 * is now RUN_STATUS_WRITE (the run is not complete: --resume runs it again), and the
 * message names the file (the first such). */
static void set_unwritten(char *status, size_t len, char *msg, size_t msglen, const char *why)
{
    if (strcmp(status, RUN_STATUS_WRITE) == 0)
        return;
    snprintf(status, len, "%s", RUN_STATUS_WRITE);
    snprintf(msg, msglen, "%s", why);
}


/* The per-pixel largest channel error: EXR with the exact values, PNG at x16 gain
 * (1/255 off shows as 16/255; 1/16 and more is white). *unwritten: an image could not be
 * written. */
static bool save_heat_map(const image *a, const image *b, const char *base, bool *unwritten,
                          char *err, size_t errlen)
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
    char path[4500];
    if (ok) {
        snprintf(path, sizeof path, "%s-error.exr", base);
        *unwritten = !(ok = image_write(path, &f, err, errlen));
    } else {
        snprintf(err, errlen, "out of memory for a heat map");
    }
    if (ok) {
        snprintf(path, sizeof path, "%s-error.png", base);
        *unwritten = !(ok = image_write(path, &g, err, errlen));
    }
    free(f.pixels);
    free(g.pixels);
    return ok;
}

/* error.reference.supersample K > 1: the reference drew at K W x K H into st->ref_fb;
 * its linear HDR image is box-filtered K x K down to W x H and made what the resolve
 * pass would display of it (clamped, 8 bits: image_display_rgba8), so that the 8-bit
 * images compared are alike: the run's displayed output and the filtered reference's. */
static bool read_reference_supersampled(run_state *st, image *img, char *err, size_t errlen)
{
    const run_params *p = &st->s->p;
    const int k = (int)p->error_supersample, w = p->width, h = p->height;
    const size_t small = (size_t)w * (size_t)h * 4u;
    float *box = malloc(small * sizeof *box);
    *img = (image){.width = w, .height = h, .channels = 4, .type = IMAGE_U8};
    img->pixels = malloc(small);
    bool ok = box && img->pixels;
    if (!ok)
        snprintf(err, errlen, "out of memory for the %dx%d supersampled reference", w, h);
    else if (!(ok = renderer_read_hdr(st->ref, st->ref_hdr, k * w, k * h, NULL)))
        snprintf(err, errlen, "reference %.31s: no HDR image to read", p->error_renderer);
    if (ok) {
        image_box_filter(st->ref_hdr, w, h, k, box);
        image_display_rgba8(box, w, h, true, img->pixels);   /* GL's rows: bottom first */
    }
    free(box);
    return ok;
}

/* error: the frame just drawn against the reference configuration drawing the same
 * scene state (same time, lights and camera): its row in errors.csv, the worst values
 * in *tr, images on request. Runs between measured frames, after the bookkeeping.
 * Compared are the displayed 8-bit images (the output framebuffers, RGBA8); with
 * error.reference.supersample K > 1 the reference's is its box-filtered HDR image as
 * the resolve would display it (read_reference_supersampled). */
static bool measure_error(run_state *st, uint32_t trial, uint32_t frame, double at,
                          trial_result *tr, bool *unwritten, char *err, size_t errlen)
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
        /* at its own size: see run_setup */
        st->sc->width = (int)p->error_supersample * p->width;
        st->sc->height = (int)p->error_supersample * p->height;
        renderer_draw(st->ref, st->sc, &fs);
        st->sc->width = p->width;
        st->sc->height = p->height;
        gl.Finish();
        renderer_collect(st->ref, &fs);
        ok = (p->error_supersample > 1 ? read_reference_supersampled(st, &ref, err, errlen)
                                       : read_output(st, &ref, err, errlen)) &&
             image_compare(&run, &ref, &e, err, errlen) &&
             image_edge_rmse(&run, &ref, &e.edge_rmse, &e.edge_pixels, err, errlen);
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
        /* the largest edge RMSE, and over how many edge pixels it was */
        if (!isnan(e.edge_rmse) &&
            (isnan(tr->image_edge_rmse) || e.edge_rmse > tr->image_edge_rmse)) {
            tr->image_edge_rmse = e.edge_rmse;
            tr->image_edge_pixels = (double)e.edge_pixels;
        }
    }
    if (ok && p->error_save_images) {
        char base[4400];
        snprintf(base, sizeof base, "%s/error-trial%u-t%g", st->dir, trial, at);
        char path[4500];
        snprintf(path, sizeof path, "%s-run.png", base);
        *unwritten = !(ok = image_write(path, &run, err, errlen));
        snprintf(path, sizeof path, "%s-reference.png", base);
        if (ok)
            *unwritten = !(ok = image_write(path, &ref, err, errlen));
        ok = ok && save_heat_map(&run, &ref, base, unwritten, err, errlen);
    }
    image_free(&run);
    image_free(&ref);
    return ok;
}

/* The measured clock: CLOCK_MONOTONIC seconds since the measurement started, less
 * the time it was paused. Comparisons with the reference and screenshots run paused:
 * they take neither frame time, nor harness time, nor per-second bin time, and with
 * clock: wall the schedule time does not jump over them either. */
typedef struct measured_clock {
    double t0, paused, pause_start;
} measured_clock;

static void mclock_start(measured_clock *c)
{
    *c = (measured_clock){.t0 = progress_now()};
}

static double mclock_now(const measured_clock *c) { return progress_now() - c->t0 - c->paused; }

static void mclock_pause(measured_clock *c) { c->pause_start = progress_now(); }

static void mclock_resume(measured_clock *c) { c->paused += progress_now() - c->pause_start; }

/* The schedule times a run visits (warm-up and measurement both start at 0) end at
 * most at this; where the span does not say (clock: wall with {frames: n}, clock:
 * fixed with {seconds: s}), one turn of the camera path and the light count's growth
 * to its maximum are what can change with time. */
static double schedule_horizon(const run_state *st)
{
    const run_params *p = &st->s->p;
    double h = 0;
    bool known = true;
    const span *spans[2] = {&p->warmup, &p->duration};
    for (int i = 0; i < 2; i++) {
        const span *sp = spans[i];
        if (p->clock == RUN_CLOCK_FIXED && sp->kind == SPAN_FRAMES)
            h = fmax(h, sp->frames ? (double)(sp->frames - 1) * p->step : 0);
        else if (p->clock == RUN_CLOCK_WALL && sp->kind == SPAN_SECONDS)
            h = fmax(h, sp->seconds);
        else if (!(sp->kind == SPAN_FRAMES && sp->frames == 0) &&
                 !(sp->kind == SPAN_SECONDS && sp->seconds == 0))
            known = false;
    }
    if (!known) {
        const light_count *lc = &st->sc->count;
        h = fmax(h, st->sc->orbit_period);
        if (lc->growth && lc->step > 0 && lc->max > lc->start)
            h = fmax(h, ceil((double)(lc->max - lc->start) / lc->step) * lc->every);
    }
    return isfinite(h) && h > 0 ? h : 0;
}

#define PRIME_SAMPLES 5

static int cmp_time(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* Before the first trial, whatever the warm-up says: one frame at each distinct time
 * of PRIME_SAMPLES spread over the run's schedule and of every screenshot and error
 * time (with clock: fixed, at the frames the run will draw), so that the
 * shader variants the driver builds at first draw (llvmpipe compiles per draw state)
 * are built before anything is measured. None is recorded;
 * meta.yaml states how many there were and how long they took (timing.prime_*). */
static bool prime_variants(run_state *st)
{
    const run_params *p = &st->s->p;
    double h = schedule_horizon(st);
    double times[PRIME_SAMPLES + 2 * MAX_SCREENSHOTS];
    size_t n = 0;
    for (size_t i = 0; i < PRIME_SAMPLES; i++)
        times[n++] = h * (double)i / (PRIME_SAMPLES - 1);
    for (size_t i = 0; i < p->nscreenshots; i++)
        times[n++] = p->screenshots[i];
    for (size_t i = 0; i < p->nerror_at; i++)
        times[n++] = p->error_at[i];
    /* clock: fixed visits multiples of step only: the nearest one, or for a capture
     * the frame that takes it (the first at or after its time) */
    for (size_t i = 0; p->clock == RUN_CLOCK_FIXED && p->step > 0 && i < n; i++)
        times[i] = p->step * (i < PRIME_SAMPLES ? round(times[i] / p->step)
                                                : ceil(times[i] / p->step - 1e-9));
    /* each time once (a run of one frame has one priming frame), in schedule order */
    qsort(times, n, sizeof times[0], cmp_time);
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (m == 0 || times[i] != times[m - 1])
            times[m++] = times[i];
    n = m;
    double t0 = progress_now();
    frame_stats fs;
    for (size_t i = 0; i < n; i++) {
        if (!draw_frame(st, times[i], &fs, false)) {
            char why[sizeof st->err];
            memcpy(why, st->err, sizeof why);
            snprintf(st->err, sizeof st->err, "priming: %.490s", why);
            set_status(st, "sync");
            return false;
        }
        renderer_collect(st->r, &fs);
    }
    st->prime_s = progress_now() - t0;
    st->prime_frames = n;
    if (!gl_clean(st, "prime")) {
        snprintf(st->err, sizeof st->err, "GL error while priming the renderer");
        set_status(st, "gl-error");
        return false;
    }
    return true;
}

/* Where the trial's per-second bins and convergence points go as each second ends. */
typedef struct trial_sink {
    run_state *st;
    uint32_t trial;
} trial_sink;

static void sink_second(void *ctx, const second_bin *b)
{
    trial_sink *k = ctx;
    run_files_seconds(&k->st->files, k->st->s->id, k->trial, b, 1);
}

static void sink_point(void *ctx, const convergence_point *p)
{
    trial_sink *k = ctx;
    run_files_convergence(&k->st->files, k->st->s->id, k->trial, p, 1);
}

/* The screenshots and comparisons due at schedule time t (each once per trial); the
 * caller has paused the measured clock. */
static void capture_due(run_state *st, uint32_t trial, uint32_t frame, double t, bool *shot_done,
                        bool *error_done, trial_result *tr)
{
    const run_params *p = &st->s->p;
    for (size_t i = 0; i < p->nscreenshots; i++) {
        if (shot_done[i] || t < p->screenshots[i])
            continue;
        shot_done[i] = true;
        char err[512];
        bool unwritten = false;
        if (!screenshot(st, trial, p->screenshots[i], &unwritten, err, sizeof err)) {
            fprintf(stderr, "run %s: screenshot: %s\n", st->s->id, err);
            if (unwritten)
                set_unwritten(tr->status, sizeof tr->status, st->err, sizeof st->err, err);
            else if (strcmp(tr->status, RUN_STATUS_WRITE) != 0)
                snprintf(tr->status, sizeof tr->status, "failed:screenshot");
        }
        /* the light lists of the screenshot's frame, as a histogram (lightgrid.csv) */
        size_t ncells = 0;
        const uint32_t *grid = renderer_light_grid(st->r, &ncells);
        if (!run_files_lightgrid(&st->files, st->s->id, trial, frame, t, grid, ncells))
            snprintf(tr->status, sizeof tr->status, "failed:oom");
    }
    for (size_t i = 0; i < p->nerror_at; i++) {
        if (error_done[i] || t < p->error_at[i])
            continue;
        error_done[i] = true;
        char err[512];
        bool unwritten = false;
        if (!measure_error(st, trial, frame, p->error_at[i], tr, &unwritten, err, sizeof err)) {
            fprintf(stderr, "run %s: error against the reference: %s\n", st->s->id, err);
            if (unwritten)
                set_unwritten(tr->status, sizeof tr->status, st->err, sizeof st->err, err);
            else if (strcmp(tr->status, RUN_STATUS_WRITE) != 0)
                snprintf(tr->status, sizeof tr->status, "failed:error");
        }
    }
}

static bool capture_is_due(const run_params *p, double t, const bool *shot_done,
                           const bool *error_done)
{
    for (size_t i = 0; i < p->nscreenshots; i++)
        if (!shot_done[i] && t >= p->screenshots[i])
            return true;
    for (size_t i = 0; i < p->nerror_at; i++)
        if (!error_done[i] && t >= p->error_at[i])
            return true;
    return false;
}

/* A measured frame's quantities of results/metrics.def, each from its `from`. */
static void frame_metrics_of(frame_record *r, const frame_stats *fs, const gbuffer_traffic *gt,
                             const frame_cpu *cpu)
{
#define FRAME_METRIC(field, type, frames, fprec, from, ...) r->field = (from);
#include "results/metrics.def"
}

/* A trial's TRIAL_METRICs of results/metrics.def, each from its `from`. */
static void trial_metrics_of(metric_totals *m, const contention_trial *ctn)
{
#define TRIAL_METRIC(trial, sprec, from, ...) m->trial = (from);
#include "results/metrics.def"
}

/* One trial: warm-up (not recorded), then the measured frames. On the measured clock,
 * the time from one frame's end to the next one's start is the harness's (CSV rows,
 * GL error checks, statistics, progress), so measured_s = frames x (frametime_mean_us +
 * harness_us_mean) by construction; the statistics (results/stream_stats.h) take each
 * frame as it ends. */
static void run_trial(run_state *st, uint32_t trial, trial_result *tr)
{
    const run_params *p = &st->s->p;
    frame_stats fs;
    memset(tr, 0, sizeof *tr);
    tr->trial = trial;
    tr->image_rmse = tr->image_psnr_db = tr->image_max_abs = tr->nonfinite = NAN;
    tr->image_edge_rmse = tr->image_edge_pixels = NAN;
    metric_totals_none(&tr->m);
    snprintf(tr->status, sizeof tr->status, "ok");
    /* how much of the machine the trial got (results/contention.h) */
    double loadavg = contention_loadavg_1m();
    unsigned ncpus = contention_usable_cpus();

    double w0 = progress_now();
    for (size_t k = 0; !span_done(&p->warmup, k, progress_now() - w0); k++) {
        if (!draw_frame(st, schedule_time(p, k, progress_now() - w0), &fs, false)) {
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

    trial_sink sink = {.st = st, .trial = trial};
    trial_stream_begin(st->stream, 0.01, sink_second, sink_point, &sink);
    bool shot_done[MAX_SCREENSHOTS] = {false}, error_done[MAX_SCREENSHOTS] = {false};
    double harness_s = 0, t_end = 0, start = 0, t_last = 0;
    size_t n = 0;
    measured_clock mc;
    contention_sample c0, c1;
    contention_sample_now(&c0);
    /* the process CPU clock, read next to each frame's two ends (outside them) */
    double cpu0 = contention_process_cpu_s();
    mclock_start(&mc);
    for (size_t k = 0;; k++) {
        double t = schedule_time(p, k, start);
        t_last = t;
        bool ok = draw_frame(st, t, &fs, true);
        double end = mclock_now(&mc);
        double cpu1 = contention_process_cpu_s();
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
        gbuffer_traffic gt = deferred_gbuffer_traffic(st->gbuffer_bpp, p->width, p->height, &fs);
        frame_record rec = {
            .frame = (uint32_t)k,
            .t_wall_s = end,
            .t_scene_s = t,
            .lights = st->sc->nlights_active,
            .frametime_us = (end - start) * 1e6,
        };
        frame_cpu cpu = contention_frame_cpu(cpu0, cpu1, rec.frametime_us, ncpus);
        frame_metrics_of(&rec, &fs, &gt, &cpu);
        t_end = end;
        n++;
        trial_stream_add(st->stream, &rec);
        run_files_frame(&st->files, st->s->id, trial, &rec, &fs);
        for (uint32_t i = 0; i < st->sc->ncoverage_lights && i < st->sc->nlights_active; i++)
            run_files_coverage(&st->files, st->s->id, trial, rec.frame, t, i,
                               scene_light_coverage(st->sc, i));
        if (!gl_clean(st, "frame")) {
            snprintf(tr->status, sizeof tr->status, "failed:gl-error");
            break;
        }
        if (capture_is_due(p, t, shot_done, error_done)) {
            mclock_pause(&mc);
            capture_due(st, trial, rec.frame, t, shot_done, error_done, tr);
            mclock_resume(&mc);
        }
        progress_tick(st->pg, trial, rec.lights, (double)(k + 1) / end);
        if (span_done(&p->duration, k + 1, end))
            break;
        cpu0 = contention_process_cpu_s();
        start = mclock_now(&mc);
        harness_s += start - end;
    }
    contention_sample_now(&c1);
    st->paused_s += mc.paused;

    /* A time the trial never reached (a wall clock counting frames, a fixed clock
     * counting seconds: plan_check cannot know the end) fails it: an error gate that
     * compared nothing must not pass. */
    for (size_t i = 0; strcmp(tr->status, "ok") == 0 && i < p->nerror_at + p->nscreenshots; i++) {
        bool is_error = i < p->nerror_at;
        size_t j = is_error ? i : i - p->nerror_at;
        if (is_error ? error_done[j] : shot_done[j])
            continue;
        snprintf(tr->status, sizeof tr->status, "failed:%s", is_error ? "error" : "screenshot");
        snprintf(st->err, sizeof st->err,
                 "%s time %g s never reached: the trial's last frame was at schedule time %g s",
                 is_error ? "error.at" : "outputs.screenshots",
                 is_error ? p->error_at[j] : p->screenshots[j], t_last);
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

    trial_totals tt;
    trial_stream_end(st->stream, t_end, &tt);
    tr->ft = tt.ft;
    tr->ft_ci95 = tt.ft_ci95;
    tr->frames = n;
    tr->measured_s = t_end;
    tr->fps_mean = t_end > 0 ? (double)n / t_end : NAN;
    tr->m = tt.m;
    contention_trial ctn;
    contention_between(&c0, &c1, loadavg, &ctn);
    trial_metrics_of(&tr->m, &ctn);
    tr->lights_max = tt.lights_max;
    tr->ci1pct_after_s = tt.ci_converged_after_s;
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

/* The process's peak resident size (VmHWM in /proc/self/status), kB; -1 unknown. */
static int64_t vm_hwm_kb(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    if (!f)
        return -1;
    char line[256];
    long long kb = -1;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "VmHWM: %lld kB", &kb) == 1)
            break;
    fclose(f);
    return kb;
}

static bool write_meta(run_state *st, char *err, size_t errlen)
{
    char path[4500];
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
    yo_key(y, "description"); yo_str(y, e->description);
    yo_key(y, "text"); yo_str(y, e->text);   /* verbatim: what the hash is of, with: */
    yo_key(y, "set");   /* run --set KEY=VALUE, verbatim, in order: applied over the text */
    yo_seq_begin(y);
    for (size_t i = 0; i < e->nsets; i++)
        yo_str(y, e->sets[i]);
    yo_seq_end(y);
    yo_key(y, "renderer_filter"); yo_str(y, e->renderer_filter);   /* run --renderer; null */
    yo_map_end(y);
    yo_key(y, "shadesweep");
    yo_map_begin(y);
    yo_key(y, "version"); yo_str(y, SHADESWEEP_VERSION);
    yo_key(y, "commit"); yo_str(y, SHADESWEEP_COMMIT);
    yo_key(y, "dirty"); yo_bool(y, strstr(SHADESWEEP_COMMIT, "-dirty") != NULL);
    yo_map_end(y);
    provenance_write_invocation(y);

    yo_key(y, "parameters");
    yo_map_begin(y);
    param_kv kv[PARAM_KV_MAX];
    size_t nkv = run_params_kv(&st->s->p, kv, PARAM_KV_MAX);
    for (size_t i = 0; i < nkv; i++) {
        yo_key(y, kv[i].key);
        yo_str(y, kv[i].value);
    }
    yo_map_end(y);

    const run_params *p = &st->s->p;
    if (p->translucency == 1) {
        yo_key(y, "made_opaque");   /* translucency: opaque */
        yo_i64(y, st->made_opaque);
    }
    if (p->scene_file[0]) {
        const scene_file_info *si = &st->scene_info;
        char hash[17];
        hash_hex(si->hash, 16, hash);
        yo_key(y, "scene_file");
        yo_map_begin(y);
        yo_key(y, "path"); yo_str(y, p->scene_file);
        yo_key(y, "hash"); yo_str(y, hash);
        yo_key(y, "scale"); yo_f64(y, p->scene_scale);
        yo_key(y, "up"); yo_str(y, p->scene_up == SCENE_UP_Z ? "z" : "y");
        yo_key(y, "camera"); yo_str(y, p->scene_camera);
        yo_key(y, "files"); yo_i64(y, si->files);
        yo_key(y, "meshes"); yo_i64(y, si->meshes);
        yo_key(y, "triangles"); yo_i64(y, (int64_t)si->triangles);
        yo_key(y, "objects"); yo_i64(y, si->objects);
        yo_key(y, "materials"); yo_i64(y, si->materials);
        yo_key(y, "materials_mask"); yo_i64(y, si->materials_mask);
        yo_key(y, "materials_blend"); yo_i64(y, si->materials_blend);
        yo_key(y, "blend"); yo_str(y, !si->materials_blend ? "none"
                                      : p->translucency == 1 ? "made opaque (translucency: opaque)"
                                                             : "translucent, in the translucent pass");
        yo_key(y, "textures"); yo_i64(y, si->textures);
        yo_key(y, "lights"); yo_i64(y, si->lights);
        yo_key(y, "cameras"); yo_i64(y, si->cameras);
        yo_key(y, "bounds_min");
        yo_seq_begin(y);
        for (int i = 0; i < 3; i++)
            yo_f64(y, si->bounds_min[i]);
        yo_seq_end(y);
        yo_key(y, "bounds_max");
        yo_seq_begin(y);
        for (int i = 0; i < 3; i++)
            yo_f64(y, si->bounds_max[i]);
        yo_seq_end(y);
        yo_map_end(y);
    }

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
    provenance_write_host(y, &st->prov);
    yo_map_end(y);
    yo_key(y, "started"); yo_str(y, st->started);
    yo_key(y, "finished"); yo_str(y, st->finished);

    yo_key(y, "timing");
    yo_map_begin(y);
    yo_key(y, "clock_source"); yo_str(y, "CLOCK_MONOTONIC");
    yo_key(y, "frame_end"); yo_str(y, st->s->p.sync == RUN_SYNC_FINISH ? "glFinish" : "fence");
    yo_key(y, "ci95_method"); yo_str(y, "batch means, 10 batches, Student t");
    yo_key(y, "percentiles"); yo_str(y, "nearest rank; exact up to 1024 frames, then a log histogram within 0.5%");
    yo_key(y, "prime_frames"); yo_i64(y, (int64_t)st->prime_frames);
    yo_key(y, "prime_s"); yo_f64(y, st->prime_s);
    yo_key(y, "paused_s"); yo_f64(y, st->paused_s);
    yo_key(y, "vm_hwm_kb"); yo_i64(y, vm_hwm_kb());
    yo_map_end(y);

    /* runner/memory.h's estimate (with the built scene when there is one) next to what
     * this process held at its peak (-1: written by the parent for a child that died) */
    memory_estimate me;
    memory_estimate_run(&st->s->p, st->sc, &me);
    int64_t hwm = st->sc ? vm_hwm_kb() : -1;
    yo_key(y, "memory");
    yo_map_begin(y);
    yo_key(y, "estimate_mb"); yo_i64(y, (int64_t)((me.resident + (1u << 19)) >> 20));
    yo_key(y, "peak_rss_mb"); yo_i64(y, hwm < 0 ? -1 : (hwm + 512) / 1024);
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
    yo_key(y, "lighting"); yo_str(y, st->plan.lighting);
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

/* measure.metric for this context. auto: the process's CPU time on a software
 * rasteriser (its threads are ours, and load that takes a core moves its wall time,
 * not its work: docs/architecture.md "What decides"), the GPU timer on hardware that
 * has one, else wall time. An explicit gpu needs timer queries. */
static bool resolve_metric(run_metric m, const gl_info *gi, char *out, size_t len, char *err,
                           size_t errlen)
{
    bool software = strstr(gi->renderer, "llvmpipe") || strstr(gi->renderer, "softpipe") ||
                    strstr(gi->renderer, "swrast");
    if (m == RUN_METRIC_GPU && !gi->timer_query) {
        snprintf(err, errlen, "measure.metric: gpu, but %s has no timer queries", gi->renderer);
        return false;
    }
    snprintf(out, len, "%s", m == RUN_METRIC_WALL ? "wall"
                             : m == RUN_METRIC_CPU ? "cpu"
                             : m == RUN_METRIC_GPU ? "gpu"
                             : software ? "cpu" : gi->timer_query ? "gpu" : "wall");
    return true;
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
    /* A file scene is checked again here: the plan named it by its content hash, and
     * a file edited since then must not be measured under the old id. */
    scene_file_options fo;
    scene_source src;
    run_params_scene(p, &fo, &src);
    if (p->scene_file[0]) {
        char hash[17];
        if (!scene_file_check(&fo, &st->scene_info, st->err, sizeof st->err)) {
            set_status(st, "scene");
            return false;
        }
        hash_hex(st->scene_info.hash, 16, hash);
        if (strcmp(hash, p->scene_hash) != 0) {
            snprintf(st->err, sizeof st->err,
                     "%.300s changed since the plan was made (content hash %s, now %s)",
                     p->scene_file, p->scene_hash, hash);
            set_status(st, "scene");
            return false;
        }
    }

    if (!(st->sc = scene_build_source(&src, &p->lights, p->width, p->height, st->err,
                                      sizeof st->err)) ||
        !scene_set_camera(st->sc, &p->camera, st->err, sizeof st->err)) {
        set_status(st, "scene");
        return false;
    }
    if (p->translucency == 1)   /* opaque: the same scene without its translucent pass */
        st->made_opaque = scene_make_opaque(st->sc);
    const gl_info *gi = gl_context_info(st->ctx);
    if (!resolve_metric(p->metric, gi, st->metric, sizeof st->metric, st->err, sizeof st->err)) {
        set_status(st, "metric");
        return false;
    }
    renderer_options ro = {
        .queries = true,
        .timer_query = gi->timer_query,
        .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size,
    };
    params_to_renderer_options(p, &ro);   /* params.def's `apply` column */
    if (!(st->r = renderer_create(p->renderer, &ro, st->err, sizeof st->err)) ||
        !renderer_prepare(st->r, st->sc, st->err, sizeof st->err)) {
        set_status(st, "renderer");
        return false;
    }
    renderer_describe(st->r, &st->plan);
    /* seed 002's G-buffer traffic (results/bandwidth.h): the layout the renderer built */
    st->gbuffer_bpp = deferred_gbuffer_bytes_per_pixel_of(p->renderer, &ro, st->sc);
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
        /* params.def's `ref` column: what the reference inherits, what it resets */
        run_params rp;
        params_reference(p, &rp);
        renderer_options rr = ro;
        params_to_renderer_options(&rp, &rr);
        rr.queries = false;
        /* a reference, not a measurement: forward-spml reads its lights from the
         * uniform block where they fit and from a storage buffer beyond it */
        rr.light_buffer = LIGHT_BUFFER_AUTO;
        char why[512];
        const int k = (int)p->error_supersample;
        if (k > 1) {
            /* its own K W x K H output, bound while renderer_create takes it as the output */
            rr.width = k * p->width;
            rr.height = k * p->height;
            if (!gl_offscreen_create(st->ctx, rr.width, rr.height, &st->ref_fb, why,
                                     sizeof why)) {
                snprintf(st->err, sizeof st->err,
                         "error.reference.supersample %d: the reference at %dx%d: %.400s", k,
                         rr.width, rr.height, why);
                set_status(st, "reference");
                return false;
            }
        }
        /* The scene's size is what renderer_base_size checks, the frame's viewport
         * (shading.c) and the projection's aspect (the same at K W x K H): the reference
         * prepares and draws (measure_error) with it at its own size, the run at W x H. */
        st->sc->width = rr.width;
        st->sc->height = rr.height;
        bool made = (st->ref = renderer_create(p->error_renderer, &rr, why, sizeof why)) &&
                    renderer_prepare(st->ref, st->sc, why, sizeof why);
        st->sc->width = p->width;
        st->sc->height = p->height;
        gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(st->ctx));
        if (!made) {
            snprintf(st->err, sizeof st->err, "reference %.31s: %.400s", p->error_renderer, why);
            set_status(st, "reference");
            return false;
        }
        /* the box filter reads the reference's HDR target: one it has (null has none) */
        if (k > 1) {
            size_t n = (size_t)rr.width * (size_t)rr.height * 4u;
            if (!(st->ref_hdr = malloc(n * sizeof *st->ref_hdr))) {
                snprintf(st->err, sizeof st->err, "out of memory for the %dx%d reference",
                         rr.width, rr.height);
                set_status(st, "oom");
                return false;
            }
            if (!renderer_read_hdr(st->ref, st->ref_hdr, rr.width, rr.height, NULL)) {
                snprintf(st->err, sizeof st->err,
                         "error.reference.supersample %d: reference %.31s has no HDR image to "
                         "box-filter", k, p->error_renderer);
                set_status(st, "reference");
                return false;
            }
        }
        if (!run_files_open_errors(&st->files, st->dir, st->err, sizeof st->err)) {
            set_status(st, "output");
            return false;
        }
    }
    if (!(st->stream = trial_stream_new())) {
        snprintf(st->err, sizeof st->err, "out of memory for the trial statistics");
        set_status(st, "oom");
        return false;
    }
    return true;
}

/* Releases what run_setup and the trial made. */
static void run_teardown(run_state *st)
{
    run_files_abort(&st->files);
    renderer_destroy(st->ref);
    gl_offscreen_destroy(&st->ref_fb);
    free(st->ref_hdr);
    renderer_destroy(st->r);
    scene_destroy(st->sc);
    gl_context_destroy(st->ctx);
    trial_stream_free(st->stream);
}

/* The row of a trial that never ran (setup failed, the child died, or its run ended
 * before it), so that every run has one row per trial. */
static void fill_missing_trial(run_state *st)
{
    trial_result *tr = &st->result;
    if (tr->trial == 0) {
        tr->trial = st->trial;
        tr->ft.mean = tr->ft.sd = tr->ft.p50 = tr->ft.p99 = NAN;
        tr->ft_ci95 = tr->fps_mean = tr->measured_s = NAN;
        tr->harness_us_mean = tr->ci1pct_after_s = NAN;
        metric_totals_none(&tr->m);
        tr->image_rmse = tr->image_psnr_db = tr->image_max_abs = tr->nonfinite = NAN;
        tr->image_edge_rmse = tr->image_edge_pixels = NAN;
        snprintf(tr->status, sizeof tr->status, "%s",
                 strcmp(st->status, "ok") ? st->status : "failed:not-run");
    }
}

static volatile sig_atomic_t stop_signal;

static void on_stop_signal(int sig)
{
    if (!stop_signal)
        stop_signal = sig;
}

void run_catch_stop_signals(void)
{
    static bool caught;
    if (caught)
        return;
    caught = true;
    struct sigaction sa = {.sa_handler = on_stop_signal}, ign = {.sa_handler = SIG_IGN};
    sigemptyset(&sa.sa_mask);
    sigemptyset(&ign.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    sigaction(SIGPIPE, &ign, NULL);
}

int run_stop_signal(void) { return stop_signal; }

const char *run_stop_name(int sig)
{
    return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "SIGHUP";
}

/* The trial's value of the metric that decides; NAN when it has none. */
static double metric_value(const trial_result *tr, const char *metric)
{
    if (strcmp(tr->status, "ok") != 0 || tr->frames == 0)
        return NAN;
    if (strcmp(metric, "cpu") == 0)
        return tr->m.cpu_mean_us;
    if (strcmp(metric, "gpu") == 0)
        return tr->m.gpu_mean_us;
    return strcmp(metric, "wall") == 0 ? tr->ft.mean : NAN;
}

/* The trial's folder: meta.yaml, its summary.csv row, then files.txt: written last, it
 * lists the others with their sizes and checksums, and a trial is complete only when
 * they match (folder_check_trial, what resume looks for; runner/trials.c merges the
 * trials into the run's files when its last trial is complete). */
static bool write_run_result(run_state *st)
{
    fill_missing_trial(st);
    trial_result *tr = &st->result;
    /* a failure after the trial measured (its files could not be written) is its row's */
    if (strcmp(st->status, "ok") != 0 && strcmp(tr->status, "ok") == 0)
        snprintf(tr->status, sizeof tr->status, "%s", st->status);
    tr->order = st->order;
    snprintf(tr->metric, sizeof tr->metric, "%s", st->metric);
    tr->metric_us = metric_value(tr, st->metric);
    utc_now(st->finished, sizeof st->finished);
    char err[512];
    if (!fs_mkdirs(st->dir, err, sizeof err) || !write_meta(st, err, sizeof err) ||
        !output_write_run_summary(st->dir, st->e, st->s, &st->plan, tr, 1, st->message, err,
                                  sizeof err) ||
        !folder_write_run_files(st->dir, err, sizeof err)) {
        /* files.txt is not there: the trial is not complete (the parent writes its row
         * again, runner/schedule.c, or --resume runs it) */
        fprintf(stderr, "run %s: %s\n", st->s->id, err);
        set_unwritten(st->status, sizeof st->status, st->message, sizeof st->message, err);
        return false;
    }
    return true;
}

/* Runs trial st->trial of st->s in this process (a fresh one: context, scene,
 * programs and priming are each trial's own); its status ends in st->status. */
static void run_one(run_state *st)
{
    if (run_setup(st) && prime_variants(st)) {
        trial_result *tr = &st->result;
        run_trial(st, st->trial, tr);
        if (strcmp(tr->status, "ok") != 0)
            snprintf(st->status, sizeof st->status, "%s", tr->status);
        char err[512];
        if (!run_files_commit(&st->files, err, sizeof err)) {
            fprintf(stderr, "run %s: %s\n", st->s->id, err);
            set_unwritten(st->status, sizeof st->status, st->err, sizeof st->err, err);
        }
    } else {
        fprintf(stderr, "run %s: %s\n", st->s->id, st->err);
    }
    if (strcmp(st->status, "ok") != 0 && st->err[0])
        snprintf(st->message, sizeof st->message, "%s", st->err);
    /* a target the driver could not allocate, an allocation that failed, near this
     * process's limit: the message says memory first, with the numbers */
    char note[240];
    if (memory_explain(st->status, st->message, memory_proc_kb(0, "VmPeak"),
                       memory_proc_kb(0, "VmHWM"), note, sizeof note)) {
        char m[sizeof st->message];
        snprintf(m, sizeof m, "%s; %.260s", note, st->message);
        snprintf(st->message, sizeof st->message, "%s", m);
    }
    write_run_result(st);
}

/* What a trial's child tells the parent, through memory shared across the fork. */
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
    const trial_result *tr = &a->st->result;
    snprintf(a->report->status, sizeof a->report->status, "%s", a->st->status);
    snprintf(a->report->message, sizeof a->report->message, "%.500s", a->st->message);
    a->report->fps = tr->frames ? tr->fps_mean : 0;
    a->report->done = 1;
    run_teardown(a->st);
    return strcmp(a->st->status, "ok") == 0 ? 0 : 1;
}

bool run_trial_isolated(const experiment *e, const run_spec *s, const run_options *o,
                        progress *pg, uint32_t trial, uint32_t order, double timeout_s,
                        trial_outcome *out)
{
    memset(out, 0, sizeof *out);
    run_state st = {.e = e, .s = s, .o = o, .pg = pg, .trial = trial, .order = order};
    snprintf(st.status, sizeof st.status, "ok");
    utc_now(st.started, sizeof st.started);
    provenance_sample(&st.prov);
    char run_dir[4096], log_path[4300], err[512];
    snprintf(run_dir, sizeof run_dir, "%s/runs/%s", o->out_dir, s->id);
    snprintf(st.dir, sizeof st.dir, "%s/trial-%u", run_dir, trial);
    snprintf(log_path, sizeof log_path, "%s/log.txt", run_dir);
    run_report *report = mmap(NULL, sizeof *report, PROT_READ | PROT_WRITE,
                              MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (report == MAP_FAILED || !folder_clear_run(st.dir, err, sizeof err) ||
        !fs_mkdirs(st.dir, err, sizeof err)) {
        fprintf(stderr, "shadesweep: run %s: %s\n", s->id,
                report != MAP_FAILED ? err : "out of memory");
        if (report != MAP_FAILED)
            munmap(report, sizeof *report);
        return false;
    }
    /* A run that would not fit the memory this process may use is refused here, in
     * the parent, before any child starts (runner/memory.h). */
    if (!memory_check_run(&s->p, st.message, sizeof st.message)) {
        snprintf(st.status, sizeof st.status, "failed:memory");
        write_run_result(&st);
        snprintf(out->status, sizeof out->status, "%s", st.status);
        snprintf(out->message, sizeof out->message, "%.500s", st.message);
        munmap(report, sizeof *report);
        return true;
    }
    child_args args = {.st = &st, .report = report};
    isolate_result ir;
    isolate_run(child_main, &args, timeout_s, log_path, &stop_signal, &ir);
    out->seconds = ir.seconds;
    if (ir.outcome == ISOLATE_INTERRUPTED && report->done) {
        /* Interrupted after its files were complete (while tearing down): keep it. */
        ir.outcome = ISOLATE_EXITED;
        ir.exit_code = strcmp(report->status, "ok") == 0 ? 0 : 1;
    }
    if (ir.outcome == ISOLATE_INTERRUPTED) {
        /* Discard the trial: resume runs it again (and its run, when it has no
         * earlier trial: trials run in order, so 1..trial-1 are complete). */
        folder_clear_run(trial == 1 ? run_dir : st.dir, err, sizeof err);
        out->interrupted = true;
        snprintf(out->status, sizeof out->status, "interrupted, discarded");
    } else if (ir.outcome == ISOLATE_EXITED && report->done) {
        snprintf(out->status, sizeof out->status, "%s", report->status);
        snprintf(out->message, sizeof out->message, "%s", report->message);
        out->fps = report->fps;
    } else {
        /* The child died or hung: the parent writes the trial's row. */
        isolate_status(&ir, st.status, sizeof st.status);
        char tail[200];
        isolate_log_tail(log_path, 3, tail, sizeof tail);
        snprintf(st.message, sizeof st.message, "%.80s after %.1f s%s%.200s",
                 ir.oom_killed ? "killed by the kernel's OOM killer (the cgroup counted it)"
                               : st.status + 7,
                 ir.seconds, tail[0] ? ": " : "", tail);
        char note[240];
        if (memory_explain(st.status, tail, ir.peak_vm_kb, ir.peak_rss_kb, note, sizeof note)) {
            char m[sizeof st.message];
            snprintf(m, sizeof m, "%s; %.260s", note, st.message);
            snprintf(st.message, sizeof st.message, "%s", m);
        }
        folder_remove_temp(st.dir);
        write_run_result(&st);
        snprintf(out->status, sizeof out->status, "%s", st.status);
        snprintf(out->message, sizeof out->message, "%.500s", st.message);
    }
    munmap(report, sizeof *report);
    return true;
}

bool run_write_missing_trial(const experiment *e, const run_spec *s, const run_options *o,
                             uint32_t trial, uint32_t order, const char *status,
                             const char *message)
{
    run_state st = {.e = e, .s = s, .o = o, .trial = trial, .order = order};
    snprintf(st.status, sizeof st.status, "%s", status);
    snprintf(st.message, sizeof st.message, "%s", message);
    utc_now(st.started, sizeof st.started);
    provenance_sample(&st.prov);
    snprintf(st.dir, sizeof st.dir, "%s/runs/%s/trial-%u", o->out_dir, s->id, trial);
    char err[512];
    if (!folder_clear_run(st.dir, err, sizeof err)) {
        fprintf(stderr, "shadesweep: run %s: %s\n", s->id, err);
        return false;
    }
    return write_run_result(&st);
}

bool run_status_ends_run(const char *status)
{
    /* Image error and non-finite light are verdicts on what was measured: the other
     * trials still measure. Anything else ends the run. */
    return strcmp(status, "ok") != 0 && strcmp(status, "failed:error") != 0 &&
           strcmp(status, "failed:nonfinite") != 0;
}

static double seconds_of(const span *sp) { return sp->kind == SPAN_SECONDS ? sp->seconds : 0; }

double run_timeout_s(const run_params *p)
{
    if (p->timeout_s > 0)
        return p->timeout_s;
    double trials = p->trials ? p->trials : TRIALS_AUTO_MAX;
    return 600.0 + 3.0 * trials * (seconds_of(&p->warmup) + seconds_of(&p->duration));
}


/* EGL device N exists: asked in a child, so that the parent never loads a GL driver. */
bool run_probe_device(int device, char *err, size_t errlen)
{
    int fds[2];
    if (pipe(fds) != 0) {
        snprintf(err, errlen, "--device: %s", strerror(errno));
        return false;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        snprintf(err, errlen, "--device: fork: %s", strerror(errno));
        return false;
    }
    if (pid == 0) {
        close(fds[0]);
        char why[400] = "";
        int n = gl_egl_device_count(why, sizeof why);
        char msg[420];
        int len = snprintf(msg, sizeof msg, "%d %s", n, why);
        ssize_t w = write(fds[1], msg, (size_t)len);
        _exit(w == len ? 0 : 1);
    }
    close(fds[1]);
    char msg[420];
    size_t got = 0;
    ssize_t r;
    while (got < sizeof msg - 1 &&
           ((r = read(fds[0], msg + got, sizeof msg - 1 - got)) > 0 || (r < 0 && errno == EINTR)))
        got += r > 0 ? (size_t)r : 0;
    msg[got] = 0;
    close(fds[0]);
    int st;
    while (waitpid(pid, &st, 0) < 0 && errno == EINTR)
        ;
    char *rest;
    long n = strtol(msg, &rest, 10);
    if (got == 0 || rest == msg) {
        snprintf(err, errlen, "--device %d: could not count the EGL devices", device);
        return false;
    }
    if (n < 0) {
        snprintf(err, errlen, "--device %d: no EGL devices (%.300s)", device, rest[0] ? rest + 1 : "");
        return false;
    }
    if (device >= n) {
        snprintf(err, errlen, "--device %d: no such EGL device; %ld found (0..%ld)", device, n,
                 n - 1);
        return false;
    }
    return true;
}
