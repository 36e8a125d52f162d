/* Per-pass timer and pipeline-statistics queries (query.h). */
#include "renderers/gl/query.h"

#include "renderers/gl/loader.h"
#include "common/grow.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* The kinds of query, each a GL target that may be active once at a time. */
enum { KIND_TIME, KIND_FRAGMENTS, KIND_PRIMITIVES, KIND_COUNT };

static const GLenum kind_target[KIND_COUNT] = {
    [KIND_TIME] = GL_TIME_ELAPSED,
    [KIND_FRAGMENTS] = GL_FRAGMENT_SHADER_INVOCATIONS_ARB,
    [KIND_PRIMITIVES] = GL_PRIMITIVES_SUBMITTED_ARB,
};

/* A pass's GL_SAMPLES_PASSED queries: one per stretch of shading draws between
 * gl_pass_queries_pause and _resume. */
typedef struct sample_segments {
    GLuint *ids;
    bool *per_sample;             /* the stretch's draws shade per sample (MSAA edges) */
    size_t n, cap;
} sample_segments;

struct gl_pass_queries {
    size_t max_passes;
    sample_segments *samples;     /* [slot][pass] */
    bool counting;                /* a GL_SAMPLES_PASSED query is active */
    bool per_sample;              /* the stretches begun now are per-sample shading */
    bool enabled[KIND_COUNT];
    size_t frame;                 /* ring slot of the frame being recorded */
    bool active;                  /* a pass is being measured */
    size_t active_pass;
    /* [slot][pass][kind], max_passes * KIND_COUNT per slot; 0 where disabled */
    GLuint *ids;
    bool *issued;                 /* [slot][pass]: measured in that slot's frame */
};

static size_t id_index(const gl_pass_queries *q, size_t slot, size_t pass, size_t kind)
{
    return (slot * q->max_passes + pass) * KIND_COUNT + kind;
}

gl_pass_queries *gl_pass_queries_create(size_t max_passes, bool timer, bool stats)
{
    if (max_passes == 0 || max_passes > RENDERER_MAX_PASSES)
        return NULL;
    gl_pass_queries *q = calloc(1, sizeof *q);
    if (!q)
        return NULL;
    q->max_passes = max_passes;
    q->enabled[KIND_TIME] = timer;
    q->enabled[KIND_FRAGMENTS] = stats;
    q->enabled[KIND_PRIMITIVES] = stats;
    size_t slots = GL_PASS_QUERIES_FRAMES * max_passes;
    q->ids = calloc(slots * KIND_COUNT, sizeof *q->ids);
    q->issued = calloc(slots, sizeof *q->issued);
    q->samples = calloc(slots, sizeof *q->samples);
    if (!q->ids || !q->issued || !q->samples) {
        gl_pass_queries_destroy(q);
        return NULL;
    }
    for (size_t s = 0; s < GL_PASS_QUERIES_FRAMES; s++)
        for (size_t p = 0; p < max_passes; p++)
            for (size_t k = 0; k < KIND_COUNT; k++)
                if (q->enabled[k])
                    gl.GenQueries(1, &q->ids[id_index(q, s, p, k)]);
    return q;
}

void gl_pass_queries_destroy(gl_pass_queries *q)
{
    if (!q)
        return;
    if (q->ids) {
        if (q->active)
            gl_pass_queries_end(q);
        size_t n = GL_PASS_QUERIES_FRAMES * q->max_passes * KIND_COUNT;
        for (size_t i = 0; i < n; i++)
            if (q->ids[i])
                gl.DeleteQueries(1, &q->ids[i]);
    }
    if (q->samples) {
        for (size_t i = 0; i < GL_PASS_QUERIES_FRAMES * q->max_passes; i++) {
            if (q->samples[i].cap)
                gl.DeleteQueries((GLsizei)q->samples[i].cap, q->samples[i].ids);
            free(q->samples[i].ids);
            free(q->samples[i].per_sample);
        }
    }
    free(q->samples);
    free(q->ids);
    free(q->issued);
    free(q);
}

/* Begins the next GL_SAMPLES_PASSED query of the measured pass. */
static void samples_start(gl_pass_queries *q)
{
    sample_segments *sg = &q->samples[q->frame * q->max_passes + q->active_pass];
    if (sg->n == sg->cap) {
        size_t cap = sg->cap;   /* sg->cap: once both arrays and the queries are there */
        bool grown = GROW(sg->ids, cap, sg->n + 1, 4);
        bool *ps = grown ? realloc(sg->per_sample, cap * sizeof *ps) : NULL;
        if (!grown || !ps) {
            fprintf(stderr, "gl_pass_queries: out of memory for sample queries\n");
            return;
        }
        sg->per_sample = ps;
        gl.GenQueries((GLsizei)(cap - sg->cap), sg->ids + sg->cap);
        sg->cap = cap;
    }
    sg->per_sample[sg->n] = q->per_sample;
    gl.BeginQuery(GL_SAMPLES_PASSED, sg->ids[sg->n++]);
    q->counting = true;
}

void gl_pass_queries_pause(gl_pass_queries *q)
{
    if (!q || !q->active || !q->counting)
        return;
    gl.EndQuery(GL_SAMPLES_PASSED);
    q->counting = false;
}

void gl_pass_queries_resume(gl_pass_queries *q)
{
    if (!q || !q->active || q->counting)
        return;
    samples_start(q);
}

void gl_pass_queries_per_sample(gl_pass_queries *q, bool on)
{
    if (!q || q->per_sample == on)
        return;
    bool counting = q->counting;
    gl_pass_queries_pause(q);
    q->per_sample = on;
    if (counting)
        gl_pass_queries_resume(q);
}

void gl_pass_queries_begin(gl_pass_queries *q, size_t pass)
{
    if (pass >= q->max_passes) {
        fprintf(stderr, "bug: gl_pass_queries_begin: pass %zu of %zu\n", pass, q->max_passes);
        return;
    }
    if (q->active) {
        fprintf(stderr, "bug: gl_pass_queries_begin: pass %zu begun while pass %zu is measured\n",
                pass, q->active_pass);
        return;
    }
    bool *issued = &q->issued[q->frame * q->max_passes + pass];
    if (*issued) {
        fprintf(stderr, "bug: gl_pass_queries_begin: pass %zu begun twice in one frame\n", pass);
        return;
    }
    for (size_t k = 0; k < KIND_COUNT; k++)
        if (q->enabled[k])
            gl.BeginQuery(kind_target[k], q->ids[id_index(q, q->frame, pass, k)]);
    *issued = true;
    q->active = true;
    q->active_pass = pass;
    q->per_sample = false;
    q->samples[q->frame * q->max_passes + pass].n = 0;
    samples_start(q);
}

void gl_pass_queries_end(gl_pass_queries *q)
{
    if (!q->active) {
        fprintf(stderr, "bug: gl_pass_queries_end without gl_pass_queries_begin\n");
        return;
    }
    for (size_t k = 0; k < KIND_COUNT; k++)
        if (q->enabled[k])
            gl.EndQuery(kind_target[k]);
    gl_pass_queries_pause(q);
    q->active = false;
}

/* The result of one query, or NAN if it is not available yet. */
static double result(GLuint id)
{
    GLuint available = GL_FALSE;
    gl.GetQueryObjectuiv(id, GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available)
        return NAN;
    GLuint64 v = 0;
    gl.GetQueryObjectui64v(id, GL_QUERY_RESULT, &v);
    return (double)v;
}

void gl_pass_queries_collect(gl_pass_queries *q, frame_stats *fs)
{
    if (q->active) {
        fprintf(stderr, "bug: gl_pass_queries_collect while pass %zu is measured\n",
                q->active_pass);
        gl_pass_queries_end(q);
    }
    size_t n = fs->npasses < q->max_passes ? fs->npasses : q->max_passes;
    for (size_t p = 0; p < n; p++) {
        double v[KIND_COUNT];
        bool issued = q->issued[q->frame * q->max_passes + p];
        for (size_t k = 0; k < KIND_COUNT; k++)
            v[k] = issued && q->enabled[k] ? result(q->ids[id_index(q, q->frame, p, k)]) : NAN;
        fs->pass[p].gpu_us = v[KIND_TIME] / 1000.0;   /* ns -> us; NAN stays NAN */
        fs->pass[p].fragments = v[KIND_FRAGMENTS];
        fs->pass[p].primitives = v[KIND_PRIMITIVES];
        /* the pass's shading draws: every stretch between pauses (0 if none) */
        const sample_segments *sg = &q->samples[q->frame * q->max_passes + p];
        double samples = issued ? 0.0 : NAN, per_sample = issued ? 0.0 : NAN;
        for (size_t i = 0; issued && i < sg->n; i++) {
            double v1 = result(sg->ids[i]);
            samples += v1;
            if (sg->per_sample[i])
                per_sample += v1;
        }
        fs->pass[p].samples = samples;
        fs->pass[p].per_sample_samples = per_sample;
    }
    for (size_t p = 0; p < q->max_passes; p++)
        q->issued[q->frame * q->max_passes + p] = false;
    q->frame = (q->frame + 1) % GL_PASS_QUERIES_FRAMES;
}
