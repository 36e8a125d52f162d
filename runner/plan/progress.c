#include "runner/plan/progress.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
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

static size_t kind_of(const progress *pg, const char *renderer, int width, int height,
                      const char *scene)
{
    char key[128];
    snprintf(key, sizeof key, "%s %dx%d %s", renderer, width, height, scene);
    size_t i = 0;
    while (i < pg->nkinds && strcmp(pg->kinds[i].key, key) != 0)
        i++;
    return i;
}

bool progress_expect(progress *pg, const char *renderer, int width, int height,
                     const char *scene, size_t trials)
{
    size_t i = kind_of(pg, renderer, width, height, scene);
    if (i == pg->nkinds) {
        if (pg->nkinds == pg->cap) {
            size_t cap = pg->cap ? 2 * pg->cap : 16;
            progress_kind *k = realloc(pg->kinds, cap * sizeof *k);
            if (!k)
                return false;
            pg->kinds = k;
            pg->cap = cap;
        }
        progress_kind *k = &pg->kinds[pg->nkinds++];
        memset(k, 0, sizeof *k);
        snprintf(k->key, sizeof k->key, "%s %dx%d %s", renderer, width, height, scene);
    }
    pg->kinds[i].left += trials;
    return true;
}

void progress_unexpect(progress *pg, const char *renderer, int width, int height,
                       const char *scene, size_t trials)
{
    size_t i = kind_of(pg, renderer, width, height, scene);
    if (i < pg->nkinds)
        pg->kinds[i].left -= trials < pg->kinds[i].left ? trials : pg->kinds[i].left;
}

void progress_record(progress *pg, double seconds)
{
    if (pg->cur >= pg->nkinds)
        return;
    progress_kind *k = &pg->kinds[pg->cur];
    k->measured++;
    k->seconds += seconds;
    if (k->left)
        k->left--;
}

double progress_eta_s(const progress *pg, double elapsed, size_t *guessed)
{
    double slowest = NAN;
    for (size_t i = 0; i < pg->nkinds; i++)
        if (pg->kinds[i].measured) {
            double mean = pg->kinds[i].seconds / (double)pg->kinds[i].measured;
            slowest = isnan(slowest) || mean > slowest ? mean : slowest;
        }
    *guessed = 0;
    if (isnan(slowest))
        return NAN;
    double left = 0;
    for (size_t i = 0; i < pg->nkinds; i++) {
        const progress_kind *k = &pg->kinds[i];
        double mean = k->measured ? k->seconds / (double)k->measured : slowest;
        if (!k->measured)
            *guessed += k->left;
        double t = mean * (double)k->left;
        /* the trial running is one of those left: what it has spent is done */
        if (i == pg->cur && k->left)
            t -= elapsed < mean ? elapsed : mean;
        left += t;
    }
    return left;
}

/* "6m27s", "~6m27s (3 trials guessed)" or "unknown". */
static void eta(const progress *pg, double now, char *buf, size_t len)
{
    size_t guessed;
    double left = progress_eta_s(pg, now - pg->run_t0, &guessed);
    if (isnan(left)) {
        snprintf(buf, len, "unknown");
        return;
    }
    char d[32];
    fmt_duration(d, sizeof d, left);
    if (guessed)
        snprintf(buf, len, "~%s (%zu trial%s guessed)", d, guessed, guessed == 1 ? "" : "s");
    else
        snprintf(buf, len, "%s", d);
}

void progress_init(progress *pg, size_t total, FILE *out)
{
    memset(pg, 0, sizeof *pg);
    pg->out = out;
    pg->tty = out && isatty(fileno(out)) == 1;
    pg->total = total;
    pg->t0 = pg->run_t0 = progress_now();
    pg->cur = SIZE_MAX;
}

void progress_free(progress *pg)
{
    free(pg->kinds);
    pg->kinds = NULL;
    pg->nkinds = pg->cap = 0;
    pg->cur = SIZE_MAX;
}

void progress_run_begin(progress *pg, size_t k, const char *id, const char *renderer,
                        int width, int height, const char *scene, unsigned trial,
                        unsigned trials)
{
    pg->run_t0 = progress_now();
    size_t kind = kind_of(pg, renderer, width, height, scene);
    pg->cur = kind < pg->nkinds ? kind : SIZE_MAX;
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
    char el[32], et[80], bar[PROGRESS_BAR + 1];
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
    progress_record(pg, now - pg->run_t0);
    pg->cur = SIZE_MAX;
    pg->run_t0 = now;
    char el[32], et[80];
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
