/* What would make every run of a plan fail or mean nothing, refused before anything
 * is written (validate, list and run call plan_check after plan_expand): times
 * beyond a run's end, an attenuation that never falls off, and every scene and
 * camera the plan builds (scenes/ has no GL: a scene that cannot be built, such as
 * placement scene on a scene without authored lights or near not below far, fails
 * here with the message scene_build or scene_set_camera gives). */
#include "runner/plan_check.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "runner/params.h"
#include "scenes/scene.h"

/* The last schedule time a run surely reaches, or -1 when only the run knows it
 * (a wall clock counting frames, a fixed clock counting seconds); `open` when the
 * end itself is not reached (a wall clock stops at its duration). */
static double schedule_end(const run_params *p, bool *open)
{
    *open = false;
    if (p->clock == RUN_CLOCK_FIXED && p->duration.kind == SPAN_FRAMES)
        return (double)(p->duration.frames - 1) * p->step;
    if (p->clock == RUN_CLOCK_WALL && p->duration.kind == SPAN_SECONDS) {
        *open = true;
        return p->duration.seconds;
    }
    return -1;
}

static void describe_duration(const run_params *p, char *out, size_t len)
{
    if (p->duration.kind == SPAN_FRAMES)
        snprintf(out, len, "{frames: %" PRIu32 "} at step %g s: the last frame is at %g s",
                 p->duration.frames, p->step, (double)(p->duration.frames - 1) * p->step);
    else
        snprintf(out, len, "{seconds: %g}: frames start before %g s", p->duration.seconds,
                 p->duration.seconds);
}

static bool check_times(const experiment *e, const run_spec *r, const char *key,
                        const double *t, size_t n, diag_list *d)
{
    bool open;
    double end = schedule_end(&r->p, &open);
    if (end < 0)
        return true;
    for (size_t i = 0; i < n; i++)
        if (open ? t[i] >= end : t[i] > end) {
            char dur[160];
            describe_duration(&r->p, dur, sizeof dur);
            diag_add(d, e->path, 0, 0, key,
                     "expected a time the run reaches (duration %s), found %g in run %s "
                     "(%s)", dur, t[i], r->id, r->p.renderer);
            return false;
        }
    return true;
}

void run_params_scene(const run_params *p, scene_file_options *fo, scene_source *src)
{
    *fo = (scene_file_options){.path = p->scene_file, .scale = p->scene_scale,
                               .up = (scene_up)p->scene_up, .camera = p->scene_camera,
                               .allow_outside = p->scene_outside};
    *src = (scene_source){.name = p->scene, .file = p->scene_file[0] ? fo : NULL};
}

/* Two runs build the same scene and camera when these agree. */
static bool same_scene(const run_params *a, const run_params *b)
{
    return strcmp(a->scene, b->scene) == 0 && strcmp(a->scene_file, b->scene_file) == 0 &&
           a->scene_scale == b->scene_scale && a->scene_up == b->scene_up &&
           strcmp(a->scene_camera, b->scene_camera) == 0 && a->width == b->width &&
           a->height == b->height &&
           memcmp(&a->lights, &b->lights, sizeof a->lights) == 0 &&
           memcmp(&a->camera, &b->camera, sizeof a->camera) == 0;
}

bool plan_check(const experiment *e, const plan *p, diag_list *d)
{
    size_t nerr = d->n;
    for (size_t k = 0; k < p->nruns && d->n - nerr < 8; k++) {
        const run_spec *r = &p->runs[k];
        const run_params *q = &r->p;
        check_times(e, r, "error.at", q->error_at, q->nerror_at, d);
        check_times(e, r, "outputs.screenshots", q->screenshots, q->nscreenshots, d);
        if (q->lights.attenuation == ATTENUATION_QUADRATIC && q->lights.quadratic[0] == 0 &&
            q->lights.quadratic[1] == 0 && q->lights.quadratic[2] == 0)
            diag_add(d, e->path, 0, 0, "lights.quadratic",
                     "expected a, b and c not all 0 (1/(a d^2 + b d + c) would be infinite), "
                     "found all 0 in run %s", r->id);
    }
    /* every distinct scene and camera of the plan, built without GL (the lights are
     * placed too, so a radius that makes grid neighbours overlap fails here) */
    for (size_t k = 0; k < p->nruns && d->n - nerr < 8; k++) {
        const run_params *q = &p->runs[k].p;
        bool seen = false;
        for (size_t j = 0; j < k && !seen; j++)
            seen = same_scene(&p->runs[j].p, q);
        if (seen)
            continue;
        char err[512] = "";
        scene_file_options fo;
        scene_source src;
        run_params_scene(q, &fo, &src);
        scene *sc = scene_build_source(&src, &q->lights, q->width, q->height, err, sizeof err);
        bool ok = sc && scene_set_camera(sc, &q->camera, err, sizeof err);
        scene_destroy(sc);
        if (!ok)
            diag_add(d, e->path, 0, 0, "scene", "expected a scene the runs can render, found: %s "
                     "(run %s)", err, p->runs[k].id);
    }
    return d->n == nerr;
}
