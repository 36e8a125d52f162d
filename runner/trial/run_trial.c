/* One trial's frame loop (runner/trial/run_internal.h). */
#define _DEFAULT_SOURCE
#include "runner/trial/run_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "renderers/gl/context.h"
#include "renderers/renderer.h"
#include "results/contention.h"
#include "results/image_ref.h"
#include "runner/folder/folder.h"
#include "runner/plan/workload.h"

void run_utc_now(char *buf, size_t len)
{
    time_t t = time(NULL);
    struct tm tm;
    gmtime_r(&t, &tm);
    strftime(buf, len, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

/* Waits until the GPU (or llvmpipe) has finished every command issued so far. */
static bool frame_sync(run_sync how, char *err, size_t errlen)
{
    return gl_context_sync(how != RUN_SYNC_FINISH, SYNC_TIMEOUT_S, err, errlen);
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
 * run with debug.busy_us (of its renderer) then busy-waits inside the frame, and trial
 * debug.stall_trial hangs in it (until its time limit kills it, or a stop signal). */
static bool draw_frame(run_state *st, double t, frame_stats *fs, bool measured)
{
    const run_params *p = &st->s->p;
    scene_update(st->sc, t);
    (st->priming ? renderer_prime : renderer_draw)(st->r, st->sc, fs);
    bool ok = frame_sync(p->sync, st->err, sizeof st->err);
    bool debug = !p->debug_busy_renderer[0] || strcmp(p->debug_busy_renderer, p->renderer) == 0;
    if (ok && measured && debug && p->debug_busy_us)
        busy_wait_us(p->debug_busy_us);
    for (int s = 0; ok && measured && debug && p->debug_stall_trial == st->trial && s < 3600 &&
                    !run_stop_signal(); s++)
        sleep(1);
    return ok;
}

bool run_gl_clean(run_state *st, const char *where)
{
    unsigned n = gl_context_poll_errors(st->ctx, where);
    return n == 0 && gl_context_error_count(st->ctx) == 0;
}

void run_set_status(run_state *st, const char *reason)
{
    if (strcmp(st->status, "ok") == 0)
        snprintf(st->status, sizeof st->status, "failed:%s", reason);
}

/* A file of the trial could not be written: whatever else the trial's status said, it
 * is now RUN_STATUS_WRITE (the run is not complete: --resume runs it again), and the
 * message names the file (the first such). */
void run_set_unwritten(char *status, size_t len, char *msg, size_t msglen, const char *why)
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
        const scene_display *dp = &st->sc->display;
        image_display_rgba8(box, w, h, true, dp->exposed ? dp->exposure : 1.0f,
                            dp->tonemap == TONEMAP_PBR_NEUTRAL, img->pixels);   /* GL's rows */
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
        gl_context_sync(false, 0, NULL, 0);
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
 * are built before anything is measured (renderer_prime: each draw state, not each
 * draw, where a renderer says how). None is recorded;
 * meta.yaml states how many there were and how long they took (timing.prime_*). */
bool run_prime_variants(run_state *st)
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
    size_t i = 0;
    st->priming = true;
    for (; i < n && !(i && p->draw_limit_s > 0 && progress_now() - t0 >= p->draw_limit_s); i++) {
        if (!draw_frame(st, times[i], &fs, false)) {
            st->priming = false;
            char why[sizeof st->err];
            memcpy(why, st->err, sizeof why);
            snprintf(st->err, sizeof st->err, "priming: %.490s", why);
            run_set_status(st, "sync");
            return false;
        }
        renderer_collect(st->r, &fs);
    }
    st->priming = false;
    st->prime_s = progress_now() - t0;
    st->prime_frames = i;
    if (!run_gl_clean(st, "prime")) {
        snprintf(st->err, sizeof st->err, "GL error while priming the renderer");
        run_set_status(st, "gl-error");
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
    run_files_second(&k->st->files, k->st->s->id, k->trial, b);
}

static void sink_point(void *ctx, const convergence_point *p)
{
    trial_sink *k = ctx;
    run_files_convergence(&k->st->files, k->st->s->id, k->trial, p);
}

/* A capture (what) that failed with err, said on stderr: the trial's status becomes
 * RUN_STATUS_WRITE when a file could not be written (unwritten), else failed:<status>,
 * unless it is RUN_STATUS_WRITE already. */
static void capture_failed(run_state *st, trial_result *tr, const char *what,
                           const char *status, bool unwritten, const char *err)
{
    fprintf(stderr, "run %s: %s: %s\n", st->s->id, what, err);
    if (unwritten)
        run_set_unwritten(tr->status, sizeof tr->status, st->err, sizeof st->err, err);
    else if (strcmp(tr->status, RUN_STATUS_WRITE) != 0)
        snprintf(tr->status, sizeof tr->status, "failed:%s", status);
}

/* The first of times[from..n) that is due at schedule time t (t >= it) and not done;
 * n when none is. */
static size_t next_due(const double *times, size_t n, const bool *done, double t, size_t from)
{
    while (from < n && (done[from] || !(t >= times[from])))
        from++;
    return from;
}

/* The screenshots and comparisons due at schedule time t (each once per trial); the
 * caller has paused the measured clock. */
static void capture_due(run_state *st, uint32_t trial, uint32_t frame, double t, bool *shot_done,
                        bool *error_done, trial_result *tr)
{
    const run_params *p = &st->s->p;
    size_t ns = p->nscreenshots, ne = p->nerror_at;
    for (size_t i = 0; (i = next_due(p->screenshots, ns, shot_done, t, i)) < ns; i++) {
        shot_done[i] = true;
        char err[512];
        bool unwritten = false;
        if (!screenshot(st, trial, p->screenshots[i], &unwritten, err, sizeof err))
            capture_failed(st, tr, "screenshot", "screenshot", unwritten, err);
        /* the light lists of the screenshot's frame, as a histogram (lightgrid.csv) */
        size_t ncells = 0;
        const uint32_t *grid = renderer_light_grid(st->r, &ncells);
        if (!run_files_lightgrid(&st->files, st->s->id, trial, frame, t, grid, ncells))
            snprintf(tr->status, sizeof tr->status, "failed:oom");
    }
    for (size_t i = 0; (i = next_due(p->error_at, ne, error_done, t, i)) < ne; i++) {
        error_done[i] = true;
        char err[512];
        bool unwritten = false;
        if (!measure_error(st, trial, frame, p->error_at[i], tr, &unwritten, err, sizeof err))
            capture_failed(st, tr, "error against the reference", "error", unwritten, err);
    }
}

static bool capture_is_due(const run_params *p, double t, const bool *shot_done,
                           const bool *error_done)
{
    return next_due(p->screenshots, p->nscreenshots, shot_done, t, 0) < p->nscreenshots ||
           next_due(p->error_at, p->nerror_at, error_done, t, 0) < p->nerror_at;
}

/* The earliest screenshot or error time not yet taken; INFINITY: none. */
static double next_capture(const run_params *p, const bool *shot_done, const bool *error_done)
{
    double t = INFINITY;
    for (size_t i = 0; i < p->nscreenshots; i++)
        t = shot_done[i] ? t : fmin(t, p->screenshots[i]);
    for (size_t i = 0; i < p->nerror_at; i++)
        t = error_done[i] ? t : fmin(t, p->error_at[i]);
    return t;
}

/* A measured frame's quantities of results/metrics.def, each from its `from`. */
static void frame_metrics_of(frame_record *r, const frame_stats *fs, const gbuffer_traffic *gt,
                             const frame_cpu *cpu)
{
#define FRAME_METRIC(field, type, frames, fprec, from, ...) r->field = (from);
#include "results/metrics.def"
}

/* What the trial's first measured frame shows: results/metrics.def's `shown`. */
typedef struct frame_shown {
    double coverage;   /* covered pixels / pixels; NAN: not counted */
    workload_reach reach;   /* the lights reaching its covered pixels (NAN: not counted) */
} frame_shown;

/* The lights that reach each covered pixel of the first measured frame (the workload's
 * own figure: the renderer's depth of the frame, the scene's lights as posed for it),
 * and trial 1's heat map of them, lights-heat-trial1.png. False when the trial ends
 * here (the count failed, or the map could not be written). */
static bool count_reaching(run_state *st, uint32_t trial, frame_shown *shown, trial_result *tr)
{
    const run_params *p = &st->s->p;
    size_t n = (size_t)p->width * (size_t)p->height;
    uint32_t *counts = malloc(n * sizeof *counts);
    if (!counts) {
        snprintf(tr->status, sizeof tr->status, "failed:oom");
        snprintf(st->err, sizeof st->err, "out of memory for the lights reaching %zu pixels", n);
        return false;
    }
    uint32_t lights = st->sc->nlights_active;
    bool ok = renderer_lights_reaching(st->r, st->sc, counts, st->err, sizeof st->err);
    if (!ok)
        snprintf(tr->status, sizeof tr->status, "failed:coverage");
    else if (!(ok = workload_reach_stats(counts, n, lights, &shown->reach))) {
        snprintf(tr->status, sizeof tr->status, "failed:oom");
        snprintf(st->err, sizeof st->err, "out of memory for a histogram of %u lights", lights);
    }
    char msg[256];
    if (ok && workload_brute_force(shown->reach.mean, lights, msg, sizeof msg))
        fprintf(stderr, "run %s: warning: %s\n", st->s->id, msg);
    if (ok && trial == 1) {   /* an unwritten map leaves the run incomplete, not ended */
        char path[4500], err[512];
        snprintf(path, sizeof path, "%s/lights-heat-trial%u.png", st->dir, trial);
        if (!workload_heat_map(path, counts, p->width, p->height, lights, err, sizeof err))
            capture_failed(st, tr, "lights heat map", "output", true, err);
    }
    free(counts);
    return ok;
}

/* The trial's first measured frame, between frames (the caller has paused the measured
 * clock): the fraction of the screen its scene covers, and its brightest channel as
 * displayed. A frame of a scene with objects that shows nothing (no pixel covered, or
 * black) fails the trial as failed:empty unless allow_empty: its frame time would rank a
 * view of nothing. False when the trial ends here. */
static bool check_shown(run_state *st, uint32_t trial, double t, frame_shown *shown,
                        trial_result *tr)
{
    const run_params *p = &st->s->p;
    shown->coverage = NAN;
    if (!renderer_has_coverage(st->r))
        return true;   /* null: draws nothing by design */
    uint64_t covered = 0;
    if (!renderer_coverage(st->r, &covered, st->err, sizeof st->err)) {
        snprintf(tr->status, sizeof tr->status, "failed:coverage");
        return false;
    }
    shown->coverage = (double)covered / ((double)p->width * (double)p->height);
    if (!count_reaching(st, trial, shown, tr))
        return false;
    if (p->allow_empty || st->sc->nobjects == 0)
        return true;
    if (covered == 0) {
        snprintf(st->err, sizeof st->err,
                 "the scene covers no pixel of the first measured frame (schedule time %g s): "
                 "the camera sees none of its %u object%s; allow_empty: true measures it "
                 "anyway",
                 t, st->sc->nobjects, st->sc->nobjects == 1 ? "" : "s");
    } else {
        /* only a frame that must show something is read back to see that it does */
        image img = {0};
        if (!read_output(st, &img, st->err, sizeof st->err)) {
            image_free(&img);
            snprintf(tr->status, sizeof tr->status, "failed:coverage");
            return false;
        }
        unsigned brightest = 0;
        const uint8_t *px = img.pixels;
        for (size_t i = 0; i < (size_t)p->width * (size_t)p->height * 4u; i += 4)
            for (size_t c = 0; c < 3; c++)
                brightest = px[i + c] > brightest ? px[i + c] : brightest;
        image_free(&img);
        if (brightest > 1)
            return true;
        snprintf(st->err, sizeof st->err,
                 "the first measured frame (schedule time %g s) is black: no channel of any "
                 "pixel above 1 of 255, with %.3g%% of the screen covered; allow_empty: true "
                 "measures it anyway",
                 t, 100.0 * shown->coverage);
    }
    snprintf(tr->status, sizeof tr->status, "failed:empty");
    fprintf(stderr, "run %s: %s\n", st->s->id, st->err);
    return false;
}

/* A trial's TRIAL_METRICs of results/metrics.def, each from its `from`. */
static void trial_metrics_of(metric_totals *m, const contention_trial *ctn,
                             const frame_shown *shown, double sm_mhz)
{
#define TRIAL_METRIC(trial, sprec, from, ...) m->trial = (from);
#include "results/metrics.def"
}

/* One trial: warm-up (not recorded), then the measured frames. On the measured clock,
 * the time from one frame's end to the next one's start is the harness's (CSV rows,
 * GL error checks, statistics, progress), so measured_s = frames x (frametime_mean_us +
 * harness_us_mean) by construction; the statistics (results/stream_stats.h) take each
 * frame as it ends. */
void run_one_trial(run_state *st, uint32_t trial, trial_result *tr)
{
    const run_params *p = &st->s->p;
    frame_stats fs;
    memset(tr, 0, sizeof *tr);
    tr->trial = trial;
    tr->lights_radius = st->lights_radius;
    tr->image_rmse = tr->image_psnr_db = tr->image_max_abs = tr->nonfinite = NAN;
    tr->image_edge_rmse = tr->image_edge_pixels = NAN;
    metric_totals_none(&tr->m);
    snprintf(tr->status, sizeof tr->status, "ok");
    /* how much of the machine the trial got (results/contention.h) */
    double loadavg = contention_loadavg_1m();
    unsigned ncpus = contention_usable_cpus();
    run_clocks_open(st);   /* NVML, when there is an NVIDIA device: before the warm-up */

    /* draw_limit: the seconds of frames the trial may draw, priming included */
    const double limit = p->draw_limit_s > 0 ? p->draw_limit_s - st->prime_s : INFINITY;
    double w0 = progress_now();
    for (size_t k = 0; !span_done(&p->warmup, k, progress_now() - w0) &&
                       progress_now() - w0 < limit; k++) {
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
    if (!run_gl_clean(st, "warm-up")) {
        snprintf(tr->status, sizeof tr->status, "failed:gl-error");
        return;
    }
    const double measure_limit = limit - (progress_now() - w0);
    /* The lights as the measured frames will have them: after every step of setup that
     * can change them, right before the first measured frame (once a run: trial 1's). */
    if (trial == 1) {
        char path[4400], err[512];
        snprintf(path, sizeof path, "%s/lights.csv", st->dir);
        if (!workload_lights_csv(path, st->sc, err, sizeof err)) {
            fprintf(stderr, "run %s: lights.csv: %s\n", st->s->id, err);
            run_set_unwritten(tr->status, sizeof tr->status, st->err, sizeof st->err, err);
        }
    }

    trial_sink sink = {.st = st, .trial = trial};
    trial_stream_begin(st->stream, 0.01, sink_second, sink_point, &sink);
    bool shot_done[MAX_SCREENSHOTS] = {false}, error_done[MAX_SCREENSHOTS] = {false};
    frame_shown shown = {.coverage = NAN, .reach = {NAN, NAN, NAN, NAN, 0}};
    double harness_s = 0, t_end = 0, start = 0, t_last = 0;
    size_t n = 0;
    measured_clock mc;
    contention_sample c0, c1;
    contention_sample_now(&c0);
    /* the process CPU clock, read next to each frame's two ends (outside them) */
    double cpu0 = contention_process_cpu_s();
    run_clocks_start(st);
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
        gbuffer_traffic gt = renderer_traffic(st->r, &fs);
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
        if (!run_gl_clean(st, "frame")) {
            snprintf(tr->status, sizeof tr->status, "failed:gl-error");
            break;
        }
        if (k == 0) {   /* what the trial measures must show something */
            mclock_pause(&mc);
            bool shows = check_shown(st, trial, t, &shown, tr);
            mclock_resume(&mc);
            if (!shows)
                break;
        }
        if (capture_is_due(p, t, shot_done, error_done)) {
            mclock_pause(&mc);
            capture_due(st, trial, rec.frame, t, shot_done, error_done, tr);
            mclock_resume(&mc);
        }
        if (run_clocks_due(st)) {   /* NVML between frames, off the measured clock */
            mclock_pause(&mc);
            run_clocks_tick(st);
            mclock_resume(&mc);
        }
        progress_tick(st->pg, trial, rec.lights, (double)(k + 1) / end);
        if (span_done(&p->duration, k + 1, end))
            break;
        if (end >= measure_limit) {   /* draw_limit spent: the captures left, and no more */
            double next = next_capture(p, shot_done, error_done);
            if (next == INFINITY)
                break;
            /* clock: fixed goes straight to the frame that takes the next one */
            if (p->clock == RUN_CLOCK_FIXED && p->step > 0 && ceil(next / p->step - 1e-9) > k + 1)
                k = (size_t)ceil(next / p->step - 1e-9) - 1;
        }
        cpu0 = contention_process_cpu_s();
        start = mclock_now(&mc);
        harness_s += start - end;
    }
    contention_sample_now(&c1);
    run_clocks_end(st);
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
    trial_metrics_of(&tr->m, &ctn, &shown, run_clocks_median_sm(st));
    tr->lights_max = tt.lights_max;
    tr->ci1pct_after_s = tt.ci_converged_after_s;
    tr->harness_us_mean = n ? harness_s * 1e6 / (double)n : NAN;
}
