/* Variants of a loaded manifest: `run --smoke` and `run --scale S`. */
#include "runner/manifest/manifest_parse.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/renderer.h"
#include "runner/manifest/hash.h"
#include "runner/manifest/sweep_axis.h"
#include "scenes/scene.h"

/* >>smoke */

#define SMOKE_SECONDS 2.0   /* of frames a smoke trial draws, priming included */

static void smoke_span(span *s, double max_s, uint32_t max_frames)
{
    if (s->kind == SPAN_FRAMES)
        s->frames = s->frames < max_frames ? s->frames : max_frames;
    else
        s->seconds = s->seconds < max_s ? s->seconds : max_s;
}

/* Times past the smoke run's end (schedule seconds) move to its middle; duplicates go. */
static void smoke_times(double *t, size_t *n, double end)
{
    size_t k = 0;
    for (size_t i = 0; i < *n; i++) {
        double v = t[i] < end ? t[i] : end / 2;
        bool dup = false;
        for (size_t j = 0; j < k; j++)
            dup = dup || t[j] == v;
        if (!dup)
            t[k++] = v;
    }
    *n = k;
}

void experiment_make_smoke(experiment *e)
{
    static const char *const collapse[] = {"resolution", "trials", "warmup", "duration",
                                           "draw_limit"};
    size_t k = 0;
    for (size_t i = 0; i < e->naxes; i++) {
        /* a block's first axis moves to k: its first is then k (nblocks: blocks that
         * start at i, empty ones included, all move) */
        for (size_t b = 0; b <= e->nblocks && e->nblocks; b++)
            if (e->block_first[b] == i)
                e->block_first[b] = k;
        bool drop = false;
        for (size_t j = 0; j < sizeof collapse / sizeof collapse[0]; j++)
            drop = drop || strcmp(e->axes[i].path, collapse[j]) == 0;
        if (drop) {
            free(e->axes[i].values);
            free(e->axes[i].line);
            free(e->axes[i].col);
        } else {
            e->axes[k++] = e->axes[i];
        }
    }
    for (size_t b = 0; b <= e->nblocks && e->nblocks; b++)
        if (e->block_first[b] > k)
            e->block_first[b] = k;   /* the end, and blocks that start past the last axis */
    e->naxes = k;   /* a block left with no axis: the base point once */

    run_params *b = &e->base;
    if (b->width > 160 || b->height > 120) {
        b->width = 160;
        b->height = 120;
    }
    b->trials = 1;
    b->warmup = (span){.kind = SPAN_FRAMES, .frames = 0};
    smoke_span(&b->duration, SMOKE_SECONDS, 120);
    /* a slow frame (16384 lights) must not stretch 120 frames, or the priming, far
     * past the promise: the trial stops drawing once SMOKE_SECONDS are spent, unless
     * the manifest (or --set) gives its own draw_limit (exact frame counts in tests) */
    if (!(b->draw_limit_s > 0))
        b->draw_limit_s = SMOKE_SECONDS;
    double end = b->duration.kind == SPAN_FRAMES
                     ? b->duration.frames * (b->clock == RUN_CLOCK_FIXED ? b->step : 1.0 / 60)
                     : b->duration.seconds;
    smoke_times(b->screenshots, &b->nscreenshots, end);
    smoke_times(b->error_at, &b->nerror_at, end);

    size_t len = strlen(e->name);
    if (len > sizeof e->name - 7)
        len = sizeof e->name - 7;
    snprintf(e->name + len, sizeof e->name - len, "-smoke");
    char salted[32];
    e->smoke = true;
    snprintf(salted, sizeof salted, "%s+smoke", e->hash);
    hash_hex(fnv1a64(salted, strlen(salted)), 16, e->hash);
}

static bool scale_side(int *side, double scale)
{
    double v = floor(*side * scale + 0.5);
    *side = v < 1 ? 1 : v > MAX_SIDE ? MAX_SIDE + 1 : (int)v;
    return *side <= MAX_SIDE;
}

/* Both sides scaled (neither skipped when the other is too large). */
static bool scale_size(int *w, int *h, double scale)
{
    bool ok_w = scale_side(w, scale);
    bool ok_h = scale_side(h, scale);
    return ok_w && ok_h;
}

bool experiment_scale_resolution(experiment *e, double scale, char *err, size_t errlen)
{
    if (!(scale > 0 && scale <= 16)) {
        snprintf(err, errlen, "--scale: expected a number > 0 and <= 16, found %g", scale);
        return false;
    }
    run_params *b = &e->base;
    bool ok = scale_size(&b->width, &b->height, scale);
    for (size_t i = 0; i < e->naxes && ok; i++) {
        struct sweep_axis *ax = &e->axes[i];
        if (strcmp(ax->path, "resolution") != 0)
            continue;
        for (size_t j = 0; j < ax->nvalues && ok; j++) {
            run_params *v = &ax->values[j];
            ok = scale_size(&v->width, &v->height, scale);
            for (size_t k = 0; k < j && ok; k++)
                if (ax->values[k].width == v->width && ax->values[k].height == v->height) {
                    snprintf(err, errlen,
                             "--scale %g: swept resolutions %zu and %zu both become %dx%d",
                             scale, k + 1, j + 1, v->width, v->height);
                    return false;
                }
        }
    }
    if (!ok) {
        snprintf(err, errlen, "--scale %g: a resolution would exceed %dx%d", scale, MAX_SIDE,
                 MAX_SIDE);
        return false;
    }
    e->scale = scale;
    char salted[64];
    snprintf(salted, sizeof salted, "%s+scale=%.17g", e->hash, scale);
    hash_hex(fnv1a64(salted, strlen(salted)), 16, e->hash);
    return true;
}

