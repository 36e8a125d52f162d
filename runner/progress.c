#include "runner/progress.h"

#include <string.h>
#include <time.h>
#include <unistd.h>

#define PROGRESS_BAR 20   /* characters of the bar of completed runs */

double progress_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void fmt_duration(char *buf, size_t len, double s)
{
    if (!(s >= 0)) {
        snprintf(buf, len, "?");
        return;
    }
    unsigned long t = (unsigned long)(s + 0.5);
    if (t >= 3600)
        snprintf(buf, len, "%luh%02lum%02lus", t / 3600, t / 60 % 60, t % 60);
    else if (t >= 60)
        snprintf(buf, len, "%lum%02lus", t / 60, t % 60);
    else
        snprintf(buf, len, "%lus", t);
}

/* ETA from the mean duration of completed runs; unknown before the first. */
static void eta(const progress *pg, double now, char *buf, size_t len)
{
    if (pg->done == 0) {
        snprintf(buf, len, "?");
        return;
    }
    double per_run = (pg->run_t0 - pg->t0) / (double)pg->done;
    double left = per_run * ((double)pg->total - (double)pg->done) - (now - pg->run_t0);
    fmt_duration(buf, len, left > 0 ? left : 0);
}

void progress_init(progress *pg, size_t total, FILE *out)
{
    memset(pg, 0, sizeof *pg);
    pg->out = out;
    pg->tty = isatty(fileno(out)) == 1;
    pg->total = total;
    pg->t0 = pg->run_t0 = progress_now();
}

void progress_run_begin(progress *pg, size_t k, const char *id, const char *renderer,
                        int width, int height, unsigned trial, unsigned trials)
{
    pg->run_t0 = progress_now();
    char of[32] = "";
    if (trials != 1)
        snprintf(of, sizeof of, trials ? " of %u" : " (auto)", trials);
    if (trials == 1)
        snprintf(pg->label, sizeof pg->label, "run %zu of %zu %s %s %dx%d", k, pg->total, id,
                 renderer, width, height);
    else
        snprintf(pg->label, sizeof pg->label, "%zu of %zu: run %s %s %dx%d trial %u%s", k,
                 pg->total, id, renderer, width, height, trial, of);
    pg->last_draw = 0;
    progress_tick(pg, 0, 0, 0);
}

void progress_tick(progress *pg, unsigned trial, unsigned lights, double fps)
{
    if (!pg->tty)
        return;
    double now = progress_now();
    if (now - pg->last_draw < 0.25)
        return;
    pg->last_draw = now;
    char el[32], et[32], bar[PROGRESS_BAR + 1];
    fmt_duration(el, sizeof el, now - pg->t0);
    eta(pg, now, et, sizeof et);
    size_t filled = pg->total ? pg->done * PROGRESS_BAR / pg->total : 0;
    for (size_t i = 0; i < PROGRESS_BAR; i++)
        bar[i] = i < filled ? '#' : '.';
    bar[PROGRESS_BAR] = 0;
    fprintf(pg->out, "\r\033[K[%s] %s trial %u, %u lights, %.1f fps | elapsed %s eta %s", bar,
            pg->label, trial, lights, fps, el, et);
    fflush(pg->out);
}

void progress_run_end(progress *pg, const char *status, double fps)
{
    pg->done++;
    if (strcmp(status, "ok") != 0)
        pg->failed++;
    double now = progress_now();
    pg->run_t0 = now;
    char el[32], et[32];
    fmt_duration(el, sizeof el, now - pg->t0);
    eta(pg, now, et, sizeof et);
    if (pg->tty)
        fprintf(pg->out, "\r\033[K");
    fprintf(pg->out, "%s: %s, %.1f fps | elapsed %s eta %s\n", pg->label, status, fps, el, et);
    fflush(pg->out);
}

void progress_finish(progress *pg, const char *counts)
{
    char el[32], own[96];
    fmt_duration(el, sizeof el, progress_now() - pg->t0);
    if (!counts) {
        snprintf(own, sizeof own, "%zu run%s, %zu failed", pg->runs_done,
                 pg->runs_done == 1 ? "" : "s", pg->runs_failed);
        counts = own;
    }
    if (!pg->done)
        fprintf(pg->out, "%s (no trial run now), in %s\n", counts, el);
    else if (pg->runs_done == pg->done)
        fprintf(pg->out, "%s, in %s\n", counts, el);
    else
        fprintf(pg->out, "%s (%zu trials), in %s\n", counts, pg->done, el);
}

void progress_run_complete(progress *pg, const char *status)
{
    pg->runs_done++;
    if (strcmp(status, "ok") != 0)
        pg->runs_failed++;
}
