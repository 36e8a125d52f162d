/* The null renderer: the harness's own baseline. Each frame is one pass,
 * "clear", that clears colour, depth and stencil of the output framebuffer to a
 * fixed colour; nothing is drawn, no program, no target of its own. */
#include "renderers/renderer.h"

#include "renderers/gl/loader.h"
#include "renderers/gl/query.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* The clear colour, exactly representable in RGBA8: (51, 102, 153, 255). */
#define NULL_CLEAR_R (51.0f / 255.0f)
#define NULL_CLEAR_G (102.0f / 255.0f)
#define NULL_CLEAR_B (153.0f / 255.0f)
#define NULL_CLEAR_A 1.0f

typedef struct null_renderer {
    GLuint framebuffer;          /* the draw framebuffer bound at creation: the output */
    gl_pass_queries *queries;    /* NULL without opts->queries */
} null_renderer;

static double now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec / 1e3;
}

static void *null_create(const renderer_options *opts, char *err, size_t errlen)
{
    null_renderer *r = calloc(1, sizeof *r);
    if (!r) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    GLint fb = 0;
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb);
    r->framebuffer = (GLuint)fb;
    if (opts->queries) {
        r->queries = gl_pass_queries_create(1, opts->timer_query, opts->pipeline_statistics);
        if (!r->queries) {
            snprintf(err, errlen, "null renderer: cannot set up its queries (out of memory)");
            free(r);
            return NULL;
        }
    }
    return r;
}

static bool null_prepare(void *self, const struct scene *s, char *err, size_t errlen)
{
    (void)self;
    (void)s;   /* any scene, NULL included: the null renderer draws none of it */
    (void)err;
    (void)errlen;
    return true;
}

static void null_draw(void *self, const struct scene *s, frame_stats *out)
{
    null_renderer *r = self;
    (void)s;
    double t0 = now_us();
    if (r->queries)
        gl_pass_queries_begin(r->queries, 0);
    /* The framebuffer of creation, bound again in case a caller moved it: the
     * same object every frame, nothing new. The clear values are set per frame
     * so that nothing else that shares the context can change what we clear to. */
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, r->framebuffer);
    gl.ClearColor(NULL_CLEAR_R, NULL_CLEAR_G, NULL_CLEAR_B, NULL_CLEAR_A);
    gl.ClearDepth(1.0);
    gl.ClearStencil(0);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    if (r->queries)
        gl_pass_queries_end(r->queries);
    double t1 = now_us();

    out->npasses = 1;
    out->pass[0] = (pass_stats){
        .name = "clear",
        .gpu_us = NAN,           /* collect() fills these in after the sync point */
        .cpu_us = t1 - t0,
        .draw_calls = 0,         /* a clear is neither a draw call ... */
        .state_changes = 0,      /* ... nor a state change */
        .fragments = NAN,
        .samples = NAN,
        .primitives = NAN,
        .scissor_pixels = NAN,
    };
    out->lights_drawn = 0;
}

static void null_collect(void *self, frame_stats *out)
{
    null_renderer *r = self;
    if (r->queries) {
        gl_pass_queries_collect(r->queries, out);
        return;
    }
    for (size_t i = 0; i < out->npasses; i++)
        out->pass[i].gpu_us = out->pass[i].fragments = out->pass[i].primitives =
            out->pass[i].samples = NAN;
}

static void null_describe(const void *self, pass_plan *out)
{
    (void)self;
    out->npasses = 1;
    snprintf(out->pass[0].name, sizeof out->pass[0].name, "clear");
    out->pass[0].run = true;
    snprintf(out->pass[0].reason, sizeof out->pass[0].reason, "clears the output framebuffer");
    out->nprograms = 0;
    out->ntargets = 0;
    out->gbuffer_bytes = 0;
    out->target_bytes = 0;
}

static void null_destroy(void *self)
{
    null_renderer *r = self;
    if (!r)
        return;
    gl_pass_queries_destroy(r->queries);
    free(r);
}

const renderer_impl renderer_null_impl = RENDERER_IMPL(
    null, "null", "",
    "clears the output once per frame and draws nothing: the harness's "
    "own overhead",
    .collect = null_collect, .no_base = true, .read_hdr = NULL);   /* no float target: renderer_read_hdr says false */
