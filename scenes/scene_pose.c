/* Posing a built scene at schedule time (>>posing: objects, camera, the test scenes'
 * faults) and the manifest's camera overrides (>>camera-overrides). See scenes/scene_make.c. */
#include "scenes/scene.h"
#include "scenes/scene_anim.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

// >>posing

/* model = translate(position) * rotate(spin_axis, spin_rate * t) * scale * transform,
 * and the world bounding sphere of the object's mesh under it (its radius times scale
 * times the transform's stretch bound, so non-uniform scales and shears stay inside). */
static void pose_object(const scene *s, scene_object *o, double t)
{
    if (o->anim_node && s->anim && o->anim_node <= s->anim->nnodes) {
        sm_mat4 flip;
        sm_mat4_identity(flip);
        flip[0][0] = o->anim_mirror ? -1.0f : 1.0f;
        sm_mat4_mul(s->anim->world[o->anim_node - 1], flip, o->transform);
    }
    sm_mat4 tr, rot, sc, tmp;
    double angle = o->spin_rate != 0.0f ? fmod((double)o->spin_rate * t, 2.0 * SM_PI) : 0.0;
    sm_vec3 scale = {o->scale, o->scale, o->scale};
    sm_mat4_translate_make(o->position, tr);
    sm_mat4_rotate_make((float)angle, o->spin_axis, rot);
    sm_mat4_scale_make(scale, sc);
    sm_mat4 trs;
    sm_mat4_mul(tr, rot, tmp);
    sm_mat4_mul(tmp, sc, trs);
    sm_mat4_mul(trs, o->transform, o->model);
    const mesh *m = &s->meshes[o->mesh];
    sm_vec3 c = {m->sphere[0], m->sphere[1], m->sphere[2]};
    sm_vec3 wc;
    sm_mat4_mulv3(o->model, c, 1.0f, wc);
    o->bsphere[0] = wc[0];
    o->bsphere[1] = wc[1];
    o->bsphere[2] = wc[2];
    o->bsphere[3] = m->sphere[3] * o->scale * sm_mat4_stretch(o->transform);
}

/* The test scenes' faults (catalog.c): each says what it does, then does it. */
static void inject_fault(const scene *s)
{
    fprintf(stderr, "%s: failing at t = %.3f s, as this test scene does\n", s->name, s->t);
    fflush(stderr);
    switch (s->fault) {
    case 1: abort();
    case 2: raise(SIGSEGV); break;
    case 3: raise(SIGKILL); break;
    case 4:
        for (;;) {
            struct timespec ts = {1, 0};
            nanosleep(&ts, NULL);
        }
    }
}

/* Where the camera is at schedule time t, from the scene's path values alone.
 *   orbit:    angle = 2 pi x (hold, or t / orbit_period reduced to one turn in double
 *             precision, so long runs keep a precise camera); eye = orbit_target +
 *             (orbit_radius cos angle, orbit_height, orbit_radius sin angle), looking at
 *             orbit_target.
 *   scripted: the path fraction f = hold, or clamp(t / orbit_period, 0, 1); the nkeys key
 *             poses sit at f = k / (nkeys - 1), and eye and target are interpolated
 *             linearly between the two around f (f = 0 and f = 1 give the first and last
 *             key exactly).
 * Up is +Y. A t that is not a number counts as 0. */
static void camera_at(const scene *s, double t, scene_camera *c)
{
    if (isnan(t))
        t = 0.0;
    if (s->path == CAMERA_SCRIPTED && s->nkeys > 0) {
        double f = !isnan(s->hold) ? (double)s->hold
                                      : (s->orbit_period > 0 ? t / s->orbit_period : 1.0);
        f = f > 0.0 ? (f < 1.0 ? f : 1.0) : 0.0;
        double pos = f * (double)(s->nkeys - 1);
        uint32_t k = (uint32_t)pos;
        if (k + 1 >= s->nkeys) {
            sm_vec3_copy(s->key_eye[s->nkeys - 1], c->eye);
            sm_vec3_copy(s->key_target[s->nkeys - 1], c->target);
        } else {
            double u = pos - (double)k;
            for (int i = 0; i < 3; i++) {
                c->eye[i] = (float)((1.0 - u) * s->key_eye[k][i] + u * s->key_eye[k + 1][i]);
                c->target[i] =
                    (float)((1.0 - u) * s->key_target[k][i] + u * s->key_target[k + 1][i]);
            }
        }
    } else {
        double turns = !isnan(s->hold)
                           ? (double)s->hold
                           : (s->orbit_period > 0 ? fmod(t / s->orbit_period, 1.0) : 0.0);
        float a = (float)(turns * 2.0 * SM_PI);
        c->eye[0] = s->orbit_target[0] + s->orbit_radius * cosf(a);
        c->eye[1] = s->orbit_target[1] + s->orbit_height;
        c->eye[2] = s->orbit_target[2] + s->orbit_radius * sinf(a);
        sm_vec3_copy(s->orbit_target, c->target);
    }
    sm_vec3_make(0.0f, 1.0f, 0.0f, c->up);
    c->fovy = s->fovy;
    c->znear = s->znear;
    c->zfar = s->zfar;
}

static void pose_camera(scene *s, double t)
{
    camera_at(s, t, &s->cam);
    const scene_camera *c = &s->cam;
    sm_lookat(c->eye, c->target, c->up, s->view);
    sm_perspective(c->fovy, (float)s->width / (float)s->height, c->znear, c->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
}

void scene_update(scene *s, double t)
{
    s->t = t;
    if (s->fault && t >= 0.2)
        inject_fault(s);
    uint32_t n = s->nlights_total ? light_count_at(&s->count, t) : 0;
    s->nlights_active = n < s->nlights_total ? n : s->nlights_total;
    scene_anim_pose(s->anim, s->meshes, t);
    for (uint32_t i = 0; i < s->nobjects; i++)
        pose_object(s, &s->objects[i], t);
    pose_camera(s, t);
}

// >>camera-overrides

void camera_params_init(camera_params *cp)
{
    cp->radius = cp->height = cp->period = NAN;
    cp->target[0] = cp->target[1] = cp->target[2] = NAN;
    cp->znear = cp->zfar = NAN;
    cp->hold = NAN;
}

static bool finite_positive(float x) { return isfinite(x) && x > 0.0f; }

/* Whether a camera pose can make a view: finite, and the eye apart from the target by
 * more than float rounding at their magnitude. */
static bool pose_ok(const scene_camera *c)
{
    float big = 0.0f, d2 = 0.0f;
    for (int i = 0; i < 3; i++) {
        if (!isfinite(c->eye[i]) || !isfinite(c->target[i]))
            return false;
        big = fmaxf(big, fmaxf(fabsf(c->eye[i]), fabsf(c->target[i])));
        d2 += (c->eye[i] - c->target[i]) * (c->eye[i] - c->target[i]);
    }
    return sqrtf(d2) > 1e-5f * fmaxf(big, 1.0f);
}

bool scene_set_camera(scene *s, const camera_params *cp, char *err, size_t errlen)
{
    bool scripted = s->path == CAMERA_SCRIPTED;
    bool has_target = !isnan(cp->target[0]);
    /* an orbit's values on a scripted path would be silently ignored: refuse them */
    if (scripted && (!isnan(cp->radius) || !isnan(cp->height) || has_target)) {
        const char *key = !isnan(cp->radius) ? "radius" : !isnan(cp->height) ? "height" : "target";
        snprintf(err, errlen, "camera.%s: scene '%s' follows a scripted path, which has no "
                 "orbit %s (period, hold, near and far apply)", key, s->name, key);
        return false;
    }
    if (!isnan(cp->radius) && !finite_positive(cp->radius)) {
        snprintf(err, errlen, "camera.radius: expected a finite number > 0, found %g",
                 (double)cp->radius);
        return false;
    }
    if (!isnan(cp->height) && !isfinite(cp->height)) {
        snprintf(err, errlen, "camera.height: expected a finite number, found %g",
                 (double)cp->height);
        return false;
    }
    if (!isnan(cp->period) && !finite_positive(cp->period)) {
        snprintf(err, errlen, "camera.period: expected a finite number of seconds > 0, found %g",
                 (double)cp->period);
        return false;
    }
    if (has_target && !(isfinite(cp->target[0]) && isfinite(cp->target[1]) &&
                        isfinite(cp->target[2]))) {
        snprintf(err, errlen, "camera.target: expected three finite numbers, found [%g, %g, %g]",
                 (double)cp->target[0], (double)cp->target[1], (double)cp->target[2]);
        return false;
    }
    if (!isnan(cp->znear) && !finite_positive(cp->znear)) {
        snprintf(err, errlen, "camera.near: expected a finite number > 0, found %g",
                 (double)cp->znear);
        return false;
    }
    float znear = isnan(cp->znear) ? s->znear : cp->znear;
    if (!isnan(cp->zfar) && !(isfinite(cp->zfar) && cp->zfar > znear)) {
        snprintf(err, errlen, "camera.far: expected a finite number > near (%g), found %g",
                 (double)znear, (double)cp->zfar);
        return false;
    }
    float zfar = isnan(cp->zfar) ? s->zfar : cp->zfar;
    if (!(zfar > znear)) {
        snprintf(err, errlen, "camera.near: %g is not below the scene's far plane (%g)",
                 (double)znear, (double)zfar);
        return false;
    }
    if (!isnan(cp->hold) && !(cp->hold >= 0.0f && cp->hold <= 1.0f)) {
        snprintf(err, errlen, "camera.hold: expected a path fraction in [0, 1], found %g",
                 (double)cp->hold);
        return false;
    }

    scene trial = *s;   /* camera values only: the copy's pointers are not used */
    if (!isnan(cp->radius))
        trial.orbit_radius = cp->radius;
    if (!isnan(cp->height))
        trial.orbit_height = cp->height;
    if (!isnan(cp->period))
        trial.orbit_period = cp->period;
    if (has_target)
        sm_vec3_copy(cp->target, trial.orbit_target);
    trial.znear = znear;
    trial.zfar = zfar;
    if (!isnan(cp->hold))
        trial.hold = cp->hold;
    /* every pose the path can take: an orbit's eye at the quarter turns (and where it
     * holds), a scripted path's keys (the poses between lie on the segments) */
    scene_camera c;
    bool ok = true;
    if (scripted) {
        for (uint32_t k = 0; k < trial.nkeys && ok; k++) {
            trial.hold = trial.nkeys > 1 ? (float)k / (float)(trial.nkeys - 1) : 0.0f;
            camera_at(&trial, 0.0, &c);
            ok = pose_ok(&c);
        }
    } else {
        for (int q = 0; q < 4 && ok; q++) {
            trial.hold = (float)q * 0.25f;
            camera_at(&trial, 0.0, &c);
            ok = pose_ok(&c);
        }
    }
    trial.hold = isnan(cp->hold) ? s->hold : cp->hold;
    if (ok) {
        camera_at(&trial, s->t, &c);
        ok = pose_ok(&c);
    }
    if (!ok) {
        snprintf(err, errlen, "camera: the eye (%g, %g, %g) meets the target (%g, %g, %g) or "
                 "is not finite: no view direction (radius %g, height %g)",
                 (double)c.eye[0], (double)c.eye[1], (double)c.eye[2], (double)c.target[0],
                 (double)c.target[1], (double)c.target[2], (double)trial.orbit_radius,
                 (double)trial.orbit_height);
        return false;
    }
    s->orbit_radius = trial.orbit_radius;
    s->orbit_height = trial.orbit_height;
    s->orbit_period = trial.orbit_period;
    sm_vec3_copy(trial.orbit_target, s->orbit_target);
    s->znear = trial.znear;
    s->zfar = trial.zfar;
    s->hold = trial.hold;
    pose_camera(s, s->t);
    return true;
}
