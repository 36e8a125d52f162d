/* MAP_ANONYMOUS: the child's report to the parent lives in an anonymous shared map. */
#define _DEFAULT_SOURCE
#include "runner/trial/run_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "common/fsutil.h"
#include "common/image_io.h"
#include "runner/folder/folder.h"
#include "runner/trial/isolate.h"
#include "runner/manifest/params.h"
#include "runner/plan/memory.h"

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
        tr->lights_radius = NAN;
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
 * they match (folder_check_trial, what resume looks for; runner/folder/trials.c merges the
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
    run_utc_now(st->finished, sizeof st->finished);
    char err[512];
    /* runs/<id>/trial-<k>: none of the three may be a link (docs/reliability.md) */
    if (!fs_mkdirs_tail(st->dir, 3, err, sizeof err) || !run_write_meta(st, err, sizeof err) ||
        !output_write_run_summary(st->dir, st->e, st->s, &st->plan, tr, 1, st->message, err,
                                  sizeof err) ||
        !folder_write_run_files(st->dir, err, sizeof err)) {
        /* files.txt is not there: the trial is not complete (the parent writes its row
         * again, runner/cli/schedule.c, or --resume runs it) */
        fprintf(stderr, "run %s: %s\n", st->s->id, err);
        run_set_unwritten(st->status, sizeof st->status, st->message, sizeof st->message, err);
        return false;
    }
    return true;
}

/* Runs trial st->trial of st->s in this process (a fresh one: context, scene,
 * programs and priming are each trial's own); its status ends in st->status. */
static void run_one(run_state *st)
{
    if (run_setup(st) && run_prime_variants(st)) {
        trial_result *tr = &st->result;
        run_one_trial(st, st->trial, tr);
        if (strcmp(tr->status, "ok") != 0)
            snprintf(st->status, sizeof st->status, "%s", tr->status);
        char err[512];
        if (!run_files_commit(&st->files, err, sizeof err)) {
            fprintf(stderr, "run %s: %s\n", st->s->id, err);
            run_set_unwritten(st->status, sizeof st->status, st->err, sizeof st->err, err);
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

/* measure.rasterizer (params.def): llvmpipe reads LP_NUM_THREADS when this process
 * creates its context (run_setup), so the trial's own process sets it before. */
static void apply_rasterizer(const run_params *p)
{
    if (params_rasterizer_single(p))
        setenv("LP_NUM_THREADS", "0", 1);
}

static int child_main(void *arg)
{
    child_args *a = arg;
    a->st->in_child = true;
    apply_rasterizer(&a->st->s->p);
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
    run_state st = {.e = e, .s = s, .o = o, .pg = pg, .trial = trial, .order = order,
                    .meter_lum = NAN, .lights_radius = NAN};
    snprintf(st.status, sizeof st.status, "ok");
    run_utc_now(st.started, sizeof st.started);
    provenance_sample(&st.prov);
    char run_dir[4096], log_path[4300], err[512];
    snprintf(run_dir, sizeof run_dir, "%s/runs/%s", o->out_dir, s->id);
    snprintf(st.dir, sizeof st.dir, "%s/trial-%u", run_dir, trial);
    snprintf(log_path, sizeof log_path, "%s/log.txt", run_dir);
    run_report *report = mmap(NULL, sizeof *report, PROT_READ | PROT_WRITE,
                              MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (report == MAP_FAILED || !folder_clear_run(st.dir, err, sizeof err) ||
        !fs_mkdirs_tail(st.dir, 3, err, sizeof err)) {   /* runs/<id>/trial-<k>: no link */
        fprintf(stderr, "shadesweep: run %s: %s\n", s->id,
                report != MAP_FAILED ? err : "out of memory");
        if (report != MAP_FAILED)
            munmap(report, sizeof *report);
        return false;
    }
    /* A run that would not fit the memory this process may use is refused here, in
     * the parent, before any child starts (runner/plan/memory.h). */
    if (!memory_check_run(&s->p, st.message, sizeof st.message)) {
        snprintf(st.status, sizeof st.status, "failed:memory");
        write_run_result(&st);
        snprintf(out->status, sizeof out->status, "%s", st.status);
        snprintf(out->message, sizeof out->message, "%.500s", st.message);
        munmap(report, sizeof *report);
        return true;
    }
    child_args args = {.st = &st, .report = report};
    /* The image module once, here, rather than in every child (a failure to load it is
     * the child's to report, at its first image). */
    (void)image_io_load(NULL, 0);
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
        if (ir.outcome == ISOLATE_TIMEOUT && !ir.oom_killed) {
            char limit[160];
            run_timeout_text(&s->p, limit, sizeof limit);
            snprintf(st.message, sizeof st.message, "stopped after %.1f s: %s%s%.200s",
                     ir.seconds, limit, tail[0] ? ": " : "", tail);
        } else {
            snprintf(st.message, sizeof st.message, "%.80s after %.1f s%s%.200s",
                     ir.oom_killed ? "killed by the kernel's OOM killer (the cgroup counted it)"
                                   : st.status + 7,
                     ir.seconds, tail[0] ? ": " : "", tail);
        }
        char note[240];
        if (memory_explain(st.status, tail, ir.peak_vm_kb, ir.peak_rss_kb, note, sizeof note)) {
            char m[sizeof st.message];
            snprintf(m, sizeof m, "%s; %.260s", note, st.message);
            snprintf(st.message, sizeof st.message, "%s", m);
        }
        folder_remove_temp(st.dir);
        st.child_rss_kb = ir.peak_rss_kb;
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
    run_utc_now(st.started, sizeof st.started);
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

double run_trial_timeout_s(const run_params *p)
{
    if (p->timeout_s > 0)
        return p->timeout_s;
    return 600.0 + 3.0 * (seconds_of(&p->warmup) + seconds_of(&p->duration));
}

void run_timeout_text(const run_params *p, char *buf, size_t len)
{
    if (p->timeout_s > 0)
        snprintf(buf, len, "timeout: %g s a trial, warm-up included", p->timeout_s);
    else
        snprintf(buf, len, "timeout: 0, so %g s a trial (600 + 3 x (warm-up + duration)), "
                 "warm-up included", run_trial_timeout_s(p));
}

bool run_ask_child(void (*fn)(void *arg, char *answer, size_t len), void *arg,
                   double timeout_s, char *answer, size_t len, char *err, size_t errlen)
{
    int fds[2];
    if (pipe(fds) != 0) {
        snprintf(err, errlen, "%s", strerror(errno));
        return false;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        snprintf(err, errlen, "fork: %s", strerror(errno));
        return false;
    }
    if (pid == 0) {
        close(fds[0]);
        int null = open("/dev/null", O_WRONLY);   /* what a driver says, the answer says */
        if (null >= 0)
            dup2(null, STDERR_FILENO);
        char *msg = calloc(1, len);
        if (!msg)
            _exit(1);
        fn(arg, msg, len);
        size_t n = strnlen(msg, len - 1);
        ssize_t w = write(fds[1], msg, n);
        _exit(w == (ssize_t)n ? 0 : 1);
    }
    close(fds[1]);
    struct timespec t0, t;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    size_t got = 0;
    bool late = false;
    for (;;) {
        clock_gettime(CLOCK_MONOTONIC, &t);
        double left = timeout_s - (double)(t.tv_sec - t0.tv_sec) -
                      (double)(t.tv_nsec - t0.tv_nsec) / 1e9;
        if (timeout_s > 0 && left <= 0) {
            late = true;
            break;
        }
        struct pollfd pf = {.fd = fds[0], .events = POLLIN};
        int r = poll(&pf, 1, timeout_s > 0 ? (int)(left * 1000) + 1 : -1);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            continue;   /* the time is checked above */
        ssize_t n = got < len - 1 ? read(fds[0], answer + got, len - 1 - got) : 0;
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        got += (size_t)n;
    }
    answer[got] = 0;
    close(fds[0]);
    if (late)
        kill(pid, SIGKILL);
    int st;
    while (waitpid(pid, &st, 0) < 0 && errno == EINTR)
        ;
    if (late) {
        snprintf(err, errlen, "no answer within %g s", timeout_s);
        return false;
    }
    if (got == 0) {
        snprintf(err, errlen, "no answer (the child %s %d)",
                 WIFSIGNALED(st) ? "died of signal" : "exited with", WIFSIGNALED(st) ?
                 WTERMSIG(st) : WEXITSTATUS(st));
        return false;
    }
    return true;
}

static void count_devices(void *arg, char *answer, size_t len)
{
    (void)arg;
    char why[400] = "";
    int n = gl_egl_device_count(why, sizeof why);
    snprintf(answer, len, "%d %s", n, why);
}

/* EGL device N exists: asked in a child, so that the parent never loads a GL driver. */
bool run_probe_device(int device, char *err, size_t errlen)
{
    char msg[420], why[200];
    if (!run_ask_child(count_devices, NULL, 0, msg, sizeof msg, why, sizeof why)) {
        snprintf(err, errlen, "--device %d: could not count the EGL devices (%s)", device, why);
        return false;
    }
    char *rest;
    long n = strtol(msg, &rest, 10);
    if (rest == msg) {
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

typedef struct gl_probe {
    gl_context_desc desc;
    gl_info info;
} gl_probe;

/* The context's limits as "ok N N N N N N\n<renderer>" (run_probe_gl reads them back),
 * or "no <why>". */
static void probe_gl(void *arg, char *answer, size_t len)
{
    gl_probe *g = arg;
    char why[512];
    gl_context *ctx = gl_context_create(&g->desc, why, sizeof why);
    if (!ctx) {
        snprintf(answer, len, "no %s", why);
        return;
    }
    const gl_info *i = gl_context_info(ctx);
    snprintf(answer, len, "ok %d %d %d %d %d %d\n%s", i->max_uniform_block_size,
             i->max_samples, i->max_texture_size, i->max_renderbuffer_size,
             i->max_viewport_dims[0], i->max_viewport_dims[1], i->renderer);
    gl_context_destroy(ctx);
}

bool run_probe_gl(gl_backend backend, int device, double timeout_s, gl_info *out, char *err,
                  size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (device >= 0 && !run_probe_device(device, err, errlen))
        return false;
    gl_probe g = {.desc = {.backend = backend, .device = device}};
    char answer[600], why[200];
    if (!run_ask_child(probe_gl, &g, timeout_s, answer, sizeof answer, why, sizeof why)) {
        snprintf(err, errlen, "no GL context: %s", why);
        return false;
    }
    if (strncmp(answer, "no ", 3) == 0) {
        snprintf(err, errlen, "no GL context: %.500s", answer + 3);
        return false;
    }
    int used = 0;
    if (sscanf(answer, "ok %d %d %d %d %d %d\n%n", &out->max_uniform_block_size,
               &out->max_samples, &out->max_texture_size, &out->max_renderbuffer_size,
               &out->max_viewport_dims[0], &out->max_viewport_dims[1], &used) != 6 || !used) {
        snprintf(err, errlen, "no GL context: an answer that does not parse");
        return false;
    }
    snprintf(out->renderer, sizeof out->renderer, "%s", answer + used);
    return true;
}
