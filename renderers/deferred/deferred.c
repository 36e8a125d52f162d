/* The deferred renderer (seed 000 section 4.5; seeds 001-004 for the G-buffer layouts
 * and the light volumes). Passes, as passes.csv names them: shadows, gbuffer (one draw
 * per visible object into the layout's attachments and the shared depth-stencil),
 * ambient, directional (full screen per light), point and spot (per light, by
 * light_volumes: fullscreen, volume, stencil, with or without a scissor; the MODES
 * table of deferred_lights.c), then what deferred_core.c shares with tiled-deferred
 * (fog, sky, translucent, msaa-resolve, edge-aa, resolve). With position from depth,
 * the depth-stencil target is copied into "depth.sampled" for the light passes.
 * gbuffer_bytes counts the G-buffer's colour attachments. Every pass, mode, target and
 * draw count in full: docs/notes/deferred.md. */
#include "renderers/deferred/deferred.h"
#include "renderers/deferred/deferred_lights.h"

#include "renderers/frame/frontend.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/state.h"
#include "renderers/frame/scene_gpu.h"
#include "renderers/frame/shading.h"
#include "renderers/frame/shadow.h"
#include "scenes/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// >>create and prepare

static void *deferred_create(const renderer_options *opts, char *err, size_t errlen)
{
    return deferred_core_create("deferred", sizeof(deferred), false, false, opts, err, errlen);
}

static bool deferred_prepare(void *self, const scene *s, char *err, size_t errlen)
{
    deferred *r = self;
    deferred_renderer *d = &r->d;
    if (!deferred_lights_prepare_begin(r, s, err, errlen))
        return false;
    deferred_plan(d, PASS_AMBIENT, true, "%s%s",
                  d->needs.emissive ? "ambient x diffuse + emissive, full screen"
                                    : "ambient x diffuse, full screen (no material is emissive)",
                  d->b.opts.sky_stencil ? "; the full-screen passes skip the sky by the stencil"
                                        : "");
    deferred_plan_lights(r);
    deferred_plan(d, PASS_TILED, false, "deferred shades with light volumes, not tiles");
    deferred_plan(d, PASS_EDGES, d->b.samples > 1,
                  "msaa %d: pixels whose samples differ (off the plane > 1%% of depth, normal > "
                  "11.5 deg) get stencil bit 0x40; per sample there, per pixel elsewhere",
                  d->b.samples);
    return deferred_lights_prepare_end(r, s, NULL, NULL, err, errlen);
}

// >>per frame

static void deferred_draw(void *self, const scene *s, frame_stats *out)
{
    deferred *r = self;
    deferred_renderer *d = &r->d;
    gl_state *st = d->b.st;
    if (!deferred_lights_frame_begin(r, s, out))
        return;

    /* >>ambient + emissive */
    deferred_pass_begin(d, out, PASS_AMBIENT);
    gl_state_framebuffer(st, d->fb_light.fbo);
    if (d->b.opts.sky_stencil && !d->run[PASS_SKY]) {
        /* the sky's pixels: what the ambient pass writes there, as nothing else will */
        static const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
        gl_state_clear(st, GL_COLOR_BUFFER_BIT, black, 1.0, 0);
    }
    gl_state_blend(st, NULL);
    gl_state_depth(st, NULL);
    gl_state_cull(st, GLS_CULL_NONE);
    deferred_bind_gbuffer_textures(d);
    deferred_fullscreen_classes(r, r->ambient_program, r->ambient_sample_program);
    deferred_pass_end(d, out);

    deferred_light_passes(r, s, out);

    GLuint hdr_fbo = d->fb_light.fbo;   /* where the sky goes */
    if (d->run[PASS_COMPOSE]) {
        deferred_pass_begin(d, out, PASS_COMPOSE);
        gl_state_framebuffer(st, d->fb_compose.fbo);
        gl_state_blend(st, &DEFERRED_BLEND_ADD);
        gl_state_depth(st, NULL);
        gl_state_cull(st, GLS_CULL_NONE);
        gl_state_texture(st, DEFERRED_SPECULAR_UNIT, d->specular.texture);
        deferred_fullscreen_classes(r, r->compose_program, r->compose_sample_program);
        deferred_pass_end(d, out);
        hdr_fbo = d->fb_compose.fbo;
    }
    deferred_frame_end(d, s, out, hdr_fbo);
}

static void deferred_destroy(void *self)
{
    deferred_core_destroy(self);
}

// >>for tests

uint64_t deferred_last_mark_draws(const void *self, int type)
{
    const deferred *r = self;
    return r && type >= 0 && type < DEFERRED_LIGHT_TYPES ? r->mark_draws[type] : 0;
}

uint64_t deferred_last_shade_draws(const void *self, int type)
{
    const deferred *r = self;
    return r && type >= 0 && type < DEFERRED_LIGHT_TYPES ? r->shade_draws[type] : 0;
}

/* The G-buffer's, and depth.sampled (when the position comes from depth). */
static uint64_t deferred_own_bytes(const renderer_estimate *e)
{
    return deferred_gbuffer_own_bytes(e) + 4u * e->samples * e->pixels;
}

const renderer_impl renderer_deferred_impl = RENDERER_IMPL(
    deferred, "deferred", "gbuffer deferred hdr msaa fog aa",
    "G-buffer pass, then ambient, directional and light-volume passes "
    "(fullscreen | volume | stencil | stencil-two-pass), sky last",
    .collect = deferred_collect, .read_hdr = deferred_read_hdr, .traffic = deferred_traffic,
    .own_bytes = deferred_own_bytes, .draws_per_light = deferred_draws_per_light);
