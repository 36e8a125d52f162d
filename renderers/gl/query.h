#pragma once
/* Per-pass GPU measurements for renderers: GL_TIME_ELAPSED (timer queries) and
 * GL_FRAGMENT_SHADER_INVOCATIONS_ARB / GL_PRIMITIVES_SUBMITTED_ARB
 * (GL_ARB_pipeline_statistics_query).
 *
 * Use per frame, what collect() sets, the query ring and misuse: the comment above the
 * enum below. Needs a current context with the GL table loaded (loader.h), the one the
 * object was created in. */
#include <stdbool.h>
#include <stddef.h>

#include "renderers/gl/stats.h"

/* Use, per frame:
 *
 *     gl_pass_queries_begin(q, 0);  ... submit pass 0 ...  gl_pass_queries_end(q);
 *     gl_pass_queries_begin(q, 1);  ... submit pass 1 ...  gl_pass_queries_end(q);
 *     ... the frame's sync point (glFinish or a fence wait) ...
 *     gl_pass_queries_collect(q, &frame_stats);
 *
 * - A pass is an index < max_passes, the same index as in frame_stats.pass[].
 *   Each pass is measured at most once per frame; one pass is measured at a time
 *   (begin/end do not nest). Passes need not all run every frame.
 * - collect() ends the frame: for i < min(fs->npasses, max_passes) it sets
 *   fs->pass[i].gpu_us, .fragments, .primitives and .samples (GL_SAMPLES_PASSED,
 *   core GL: every driver, of the pass's draws outside gl_pass_queries_pause) from the
 *   queries of the frame just ended, NAN where that kind of query was not asked for (timer / stats
 *   false at creation), the pass was not measured this frame, or its result is
 *   not available yet. It never blocks: it checks GL_QUERY_RESULT_AVAILABLE and
 *   reports NAN rather than wait. Other fields of fs are left alone.
 * - The query objects form a ring GL_PASS_QUERIES_FRAMES frames deep; every
 *   collect() moves on to the next frame's objects, so an object whose result was
 *   not yet available is not begun again until that many frames later.
 * - Misuse (a pass index out of range, begin while a pass is being measured, end
 *   without begin, a pass begun twice in a frame) prints "bug: ..." on stderr and
 *   is otherwise ignored; it raises no GL error.
 *
 * Needs a current context with the GL table loaded (loader.h), the one the
 * object was created in. */
enum { GL_PASS_QUERIES_FRAMES = 3 };

typedef struct gl_pass_queries gl_pass_queries;

/* timer: measure GL_TIME_ELAPSED (the context has GL 3.3 or ARB_timer_query);
 * stats: measure fragment shader invocations and primitives submitted (the
 * context has GL_ARB_pipeline_statistics_query). Both false is allowed: collect
 * then gives NAN everywhere. NULL if max_passes is 0 or above
 * RENDERER_MAX_PASSES, or memory runs out. */
gl_pass_queries *gl_pass_queries_create(size_t max_passes, bool timer, bool stats);
void gl_pass_queries_destroy(gl_pass_queries *q);   /* NULL is fine */

void gl_pass_queries_begin(gl_pass_queries *q, size_t pass);
void gl_pass_queries_end(gl_pass_queries *q);
void gl_pass_queries_collect(gl_pass_queries *q, frame_stats *fs);
/* Around draws of the measured pass that shade nothing (stencil marks, shadow maps, a
 * depth pre-pass): pass_stats.samples counts the GL_SAMPLES_PASSED of every other draw
 * of the pass. Nothing outside a pass, or when already paused / counting; NULL is
 * fine. */
void gl_pass_queries_pause(gl_pass_queries *q);
void gl_pass_queries_resume(gl_pass_queries *q);
/* MSAA edges (renderers/deferred/deferred.c): the stretches of shading draws begun while on are
 * per-sample shading; collect sums their samples apart as well
 * (pass_stats.per_sample_samples). Off again at every pass's begin; NULL is fine. */
void gl_pass_queries_per_sample(gl_pass_queries *q, bool on);
