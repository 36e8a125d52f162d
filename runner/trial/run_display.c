/* How a trial's image is displayed and its placed lights sized (exposure.*, tonemap,
 * lights.sizing): set on the built scene before any renderer is made, so that every
 * program, the error reference's included, is compiled for it (runner/trial/run_internal.h). */
#include "runner/trial/run_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/gl/context.h"
#include "renderers/renderer.h"

/* The log-average (geometric mean) of the Rec. 709 luminance of an RGBA float image,
 * over the pixels with a finite luminance above 1e-6 (the background and unlit black
 * pixels say nothing about how bright the scene is); 0 when there is none. */
static double log_average_luminance(const float *rgba, size_t n, size_t *counted)
{
    double sum = 0.0;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        const float *p = rgba + 4 * i;
        double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        if (isfinite(y) && y > 1e-6) {
            sum += log(y);
            k++;
        }
    }
    *counted = k;
    return k ? exp(sum / (double)k) : 0.0;
}

/* The metering frame's longest side: the log-average of a frame does not need every
 * pixel, and forward-spml tests every light at every pixel (at 1920x1080 with 16,384
 * lights that is minutes on llvmpipe). */
#define METER_MAX_SIDE 256

/* exposure.mode auto: forward-spml (its lights in a storage buffer beyond the uniform
 * block, as the error reference's) draws the scene at schedule time 0, single-sampled,
 * at the run's aspect with its longest side at most METER_MAX_SIDE, and its linear image
 * is metered. The same renderer at the same size for every run of a sweep point, so
 * every renderer there is shown with the same exposure. With the placed lights' range or
 * colour derived from the exposure (lights.sizing), they are off in that frame: what
 * they add cannot decide what they are. */
static bool meter(run_state *st, const renderer_options *ro, bool lights_off, double *lum)
{
    const run_params *p = &st->s->p;
    renderer_options mo = *ro;
    mo.queries = false;
    mo.light_buffer = LIGHT_BUFFER_AUTO;
    mo.msaa = 1;
    int side = p->width > p->height ? p->width : p->height;
    if (side > METER_MAX_SIDE) {
        mo.width = (int)fmax(1.0, round((double)p->width * METER_MAX_SIDE / side));
        mo.height = (int)fmax(1.0, round((double)p->height * METER_MAX_SIDE / side));
    }
    /* the scene's size is the frame's viewport and aspect (as the supersampled error
     * reference's, run_setup.c): the meter's while it prepares and draws */
    st->sc->width = mo.width;
    st->sc->height = mo.height;
    char why[512];
    renderer *m = renderer_create("forward-spml", &mo, why, sizeof why);
    bool ok = m && renderer_prepare(m, st->sc, why, sizeof why);
    size_t n = (size_t)mo.width * (size_t)mo.height;
    float *hdr = ok ? malloc(n * 4 * sizeof *hdr) : NULL;
    if (ok && !hdr) {
        snprintf(why, sizeof why, "out of memory for a %dx%d image", mo.width, mo.height);
        ok = false;
    }
    if (ok) {
        frame_stats fs;
        scene_update(st->sc, 0.0);
        uint32_t active = st->sc->nlights_active;
        if (lights_off)
            st->sc->nlights_active = 0;
        renderer_draw(m, st->sc, &fs);
        st->sc->nlights_active = active;
        gl_context_sync(false, 0, NULL, 0);
        renderer_collect(m, &fs);
        size_t counted = 0;
        if (!(ok = renderer_read_hdr(m, hdr, mo.width, mo.height, NULL)))
            snprintf(why, sizeof why, "its image could not be read");
        else
            *lum = log_average_luminance(hdr, n, &counted);
    }
    free(hdr);
    renderer_destroy(m);
    st->sc->width = p->width;
    st->sc->height = p->height;
    gl_context_bind_default(st->ctx);
    if (!ok)
        snprintf(st->err, sizeof st->err, "exposure.mode auto: the metering frame "
                 "(forward-spml): %.440s", why);
    return ok;
}

bool run_display(run_state *st, const renderer_options *ro)
{
    const run_params *p = &st->s->p;
    scene_display *d = &st->sc->display;
    const light_params *lp = &p->lights;
    bool placed = lp->placement == PLACEMENT_RANDOM || lp->placement == PLACEMENT_GRID ||
                  lp->placement == PLACEMENT_SURFACE;
    bool derived = placed && lp->sizing != LIGHT_SIZING_RADIUS;
    d->tonemap = (tonemap_kind)p->tonemap;
    d->exposed = p->exposure_mode != EXPOSURE_NONE;
    d->exposure = 1.0f;
    st->meter_lum = NAN;
    st->meter_lights_off = false;
    if (p->exposure_mode == EXPOSURE_FIXED) {
        d->exposure = (float)(1.0 / (1.2 * exp2((double)p->exposure_ev100)));
    } else if (p->exposure_mode == EXPOSURE_AUTO) {
        double lum = 0.0;
        st->meter_lights_off = derived;
        if (!meter(st, ro, derived, &lum)) {
            run_set_status(st, "exposure");
            return false;
        }
        st->meter_lum = lum;
        /* a black metering frame (no light but the placed lights, which it leaves out)
         * keeps exposure 1: meta.yaml says so (metered_luminance 0) */
        double e = lum > 0.0 ? (double)p->exposure_key / lum : 1.0;
        d->exposure = (float)fmin(fmax(e, 0x1p-40), 0x1p40);
    }
    if (!scene_size_lights(st->sc, lp, d->exposure, st->err, sizeof st->err)) {
        run_set_status(st, "scene");
        return false;
    }
    /* the placed lights' range as used (summary.csv's lights_radius): overlap's, the
     * manifest's, or the mean of the derived ones (lights.csv has each) */
    double sum = 0.0;
    size_t k = 0;
    for (uint32_t i = 0; placed && i < st->sc->nlights_total; i++)
        if (st->sc->lights[i].type != LIGHT_DIRECTIONAL) {
            sum += st->sc->lights[i].radius;
            k++;
        }
    st->lights_radius = k ? sum / (double)k : NAN;
    return true;
}
