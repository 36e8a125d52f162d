#pragma once
/* The GL state cache: every state change and every draw of a renderer goes
 * through it, and it is where draw calls and state changes are counted, per pass.
 * (DOOM 3 BFG's GL_State: the GL state renderers change lives in one struct, only
 * differences reach GL, and a switch forces full re-application to catch caching
 * bugs.)
 *
 * Use, what each category counts, the force switch, unknown state, what is assumed
 * and never touched, and misuse: the comment above the categories below. Needs a
 * current GL 4.5 context whose GL table is loaded. */
#include "renderers/gl/loader.h"
#include "renderers/gl/stats.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

enum { GLS_MAX_TEXTURE_UNITS = 16, GLS_MAX_BUFFER_BINDINGS = 16, GLS_MAX_IMAGE_UNITS = 8 };

/*     gl_state *s = gl_state_create();
 *     per frame, per pass:
 *         gl_state_begin_pass(s, "lights");
 *         gl_state_framebuffer(s, fb.fbo);
 *         gl_state_program(s, prog);
 *         gl_state_texture(s, 0, albedo.texture);
 *         gl_state_blend(s, &(gls_blend){.enabled = true, .src = GLS_BLEND_ONE,
 *                                        .dst = GLS_BLEND_ONE});
 *         gl_state_depth(s, NULL);                  // no depth test, no depth writes
 *         gl_state_draw_fullscreen(s, w, h, false); // or gl_state_vertex_array + draw_*
 *         gl_state_end_pass(s, &frame_stats->pass[i]);
 *     gl_state_destroy(s);
 *
 * What the cache holds, by category (gls_category). Each setter call whose value
 * differs from what the cache knows GL to hold makes the GL calls for just the
 * parts that differ and counts ONE change in its category; a call that changes
 * nothing makes no GL call and counts nothing. "state_changes" (pass_stats,
 * gls_counts) is the sum over the first seven categories:
 *
 *   program       gl_state_program: the current program
 *   texture       gl_state_texture: the texture bound to each unit (one change per
 *                 unit that changes; glBindTextureUnit; sampling parameters are the
 *                 texture's own, set when it is made: no sampler objects)
 *   framebuffer   gl_state_framebuffer: the draw framebuffer (GL_DRAW_FRAMEBUFFER)
 *   blend         gl_state_blend: GL_BLEND, equations and factors (RGB and alpha);
 *                 gl_state_color_mask: glColorMask (output merger state like blend)
 *   depth         gl_state_depth: GL_DEPTH_TEST, glDepthFunc, glDepthMask
 *   stencil       gl_state_stencil: GL_STENCIL_TEST, per face func/ref/read mask and
 *                 the three ops (two-sided), glStencilMask
 *   cull          gl_state_cull: GL_CULL_FACE, glCullFace (glFrontFace stays GL_CCW)
 *
 * Counted on their own and NOT in state_changes (the papers' state changes are the
 * seven above): viewport (gl_state_viewport), vertex_array (gl_state_vertex_array),
 * and what compute passes bind: buffer (gl_state_storage_buffer: SSBO binding
 * points), image (gl_state_image: image units) and barrier (gl_state_barrier: every
 * glMemoryBarrier, never cached). Compute dispatches (gl_state_dispatch) are counted
 * per pass like draws, in their own count (dispatches), not in draw_calls.
 *
 * State that is switched off is not compared in its details: with blending off
 * the factors do not matter, so switching it off counts one change and leaves the
 * factors in GL as they were, and switching it back on with the same factors is
 * one change (glEnable) again. The same holds for depth, stencil and cull.
 *
 * Draws: gl_state_draw_* call GL and count one draw call each (instanced draws
 * too). Clears (gl_state_clear) are not draws; the write masks they need are set
 * through the cache and count where they change something.
 *
 * Counting: gl_state_begin_pass() zeroes the pass's counts, gl_state_end_pass()
 * copies them into a pass_stats. Every change and draw is also added to the totals
 * (gl_state_total_counts), those made outside a pass only there.
 *
 * Force (gl_state_set_force): every setter call makes the GL calls for every part
 * of its value that matters (with blending off, just glDisable(GL_BLEND)) and
 * counts one change, equal or not; draws are unaffected. A renderer's image must
 * not change with force on: if it does, something changed GL state behind the
 * cache's back.
 *
 * Unknown state: the cache starts with everything unknown, and gl_state_invalidate()
 * (after code outside the cache touched GL state) makes everything unknown again.
 * It reads nothing back from GL: the next set of each part always applies and counts.
 * Code outside the cache must not change what it caches without invalidating it.
 * So a renderer's first frame counts the first set of everything, and later frames
 * count changes from where the previous frame left GL; a renderer that wants every
 * frame counted alike invalidates at the start of each frame.
 *
 * Assumed and never touched: GL_SCISSOR_TEST, GL_RASTERIZER_DISCARD and
 * GL_POLYGON_OFFSET_FILL off, glFrontFace GL_CCW (GL's defaults). (The shadows pass,
 * renderers/frame/shadow.c, switches GL_POLYGON_OFFSET_FILL on for its draws and off again
 * before it ends, as deferred does with GL_DEPTH_CLAMP.) Textures,
 * framebuffers and vertex arrays should be made without binding them (direct state
 * access, as target.h does); the empty vertex array is the cache's own.
 *
 * Misuse (a texture unit out of range, passes nested or ended without a begin)
 * prints "bug: ..." on stderr and raises no GL error. Needs a current GL 4.5
 * context whose GL table is loaded. */
// >>categories and counts

typedef enum gls_category {
    GLS_CAT_PROGRAM,
    GLS_CAT_TEXTURE,
    GLS_CAT_FRAMEBUFFER,
    GLS_CAT_BLEND,
    GLS_CAT_DEPTH,
    GLS_CAT_STENCIL,
    GLS_CAT_CULL,
    GLS_CAT_VIEWPORT,          /* from here on: not in state_changes */
    GLS_CAT_VERTEX_ARRAY,
    GLS_CAT_BUFFER,            /* storage buffer bindings (gl_state_storage_buffer) */
    GLS_CAT_IMAGE,             /* image unit bindings (gl_state_image) */
    GLS_CAT_BARRIER,           /* memory barriers issued (gl_state_barrier) */
    GLS_CAT_COUNT
} gls_category;

/* The categories that make up state_changes: those before this one. */
#define GLS_CAT_STATE_CHANGES_END GLS_CAT_VIEWPORT

/* "program", "texture", "framebuffer", "blend", "depth", "stencil", "cull",
 * "viewport", "vertex_array", "buffer", "image", "barrier"; "unknown" out of range. */
const char *gl_state_category_name(gls_category c);

typedef struct gls_counts {
    uint64_t draw_calls;
    uint64_t dispatches;                 /* compute dispatches (gl_state_dispatch), apart
                                            from draw_calls */
    uint64_t state_changes;              /* sum of category[0 .. GLS_CAT_STATE_CHANGES_END) */
    uint64_t category[GLS_CAT_COUNT];
} gls_counts;

// >>state values (sokol style: every zero is the default)

typedef enum gls_compare {
    GLS_COMPARE_DEFAULT = 0,             /* GLS_COMPARE_ALWAYS */
    GLS_COMPARE_NEVER,
    GLS_COMPARE_LESS,
    GLS_COMPARE_EQUAL,
    GLS_COMPARE_LEQUAL,
    GLS_COMPARE_GREATER,
    GLS_COMPARE_NOTEQUAL,
    GLS_COMPARE_GEQUAL,
    GLS_COMPARE_ALWAYS,
    GLS_COMPARE_COUNT
} gls_compare;

typedef enum gls_blend_factor {
    GLS_BLEND_DEFAULT = 0,               /* src: GLS_BLEND_ONE, dst: GLS_BLEND_ZERO;
                                            alpha: the same as the RGB factor */
    GLS_BLEND_ZERO,
    GLS_BLEND_ONE,
    GLS_BLEND_SRC_COLOR,
    GLS_BLEND_ONE_MINUS_SRC_COLOR,
    GLS_BLEND_DST_COLOR,
    GLS_BLEND_ONE_MINUS_DST_COLOR,
    GLS_BLEND_SRC_ALPHA,
    GLS_BLEND_ONE_MINUS_SRC_ALPHA,
    GLS_BLEND_DST_ALPHA,
    GLS_BLEND_ONE_MINUS_DST_ALPHA,
    GLS_BLEND_FACTOR_COUNT
} gls_blend_factor;

typedef enum gls_blend_op {
    GLS_BLEND_OP_DEFAULT = 0,            /* RGB: GLS_BLEND_OP_ADD; alpha: the same as RGB */
    GLS_BLEND_OP_ADD,
    GLS_BLEND_OP_SUBTRACT,
    GLS_BLEND_OP_REVERSE_SUBTRACT,
    GLS_BLEND_OP_MIN,
    GLS_BLEND_OP_MAX,
    GLS_BLEND_OP_COUNT
} gls_blend_op;

typedef struct gls_blend {
    bool enabled;                        /* false: blending off, the rest ignored */
    gls_blend_factor src, dst;
    gls_blend_op op;
    gls_blend_factor src_alpha, dst_alpha;
    gls_blend_op op_alpha;
} gls_blend;

/* Depth: the test is on unless compare is ALWAYS (or DEFAULT) and write is false;
 * so the zero value {0} means no depth test and no depth writes. */
typedef struct gls_depth {
    gls_compare compare;                 /* DEFAULT: ALWAYS */
    bool write;
} gls_depth;

typedef enum gls_stencil_op {
    GLS_STENCIL_OP_DEFAULT = 0,          /* GLS_STENCIL_OP_KEEP */
    GLS_STENCIL_OP_KEEP,
    GLS_STENCIL_OP_ZERO,
    GLS_STENCIL_OP_REPLACE,
    GLS_STENCIL_OP_INCR_CLAMP,
    GLS_STENCIL_OP_DECR_CLAMP,
    GLS_STENCIL_OP_INVERT,
    GLS_STENCIL_OP_INCR_WRAP,
    GLS_STENCIL_OP_DECR_WRAP,
    GLS_STENCIL_OP_COUNT
} gls_stencil_op;

typedef struct gls_stencil_face {
    gls_compare compare;                 /* DEFAULT: ALWAYS */
    gls_stencil_op fail, depth_fail, pass;   /* stencil test fails / passes but depth
                                                fails / both pass; DEFAULT: KEEP */
} gls_stencil_face;

typedef struct gls_stencil {
    bool enabled;                        /* false: stencil test off (and no stencil
                                            writes), the rest ignored */
    gls_stencil_face front;
    gls_stencil_face back;               /* used only when two_sided */
    bool two_sided;                      /* false: back faces as front faces */
    uint8_t ref;
    uint8_t read_mask;                   /* 0: 0xff (a test that reads nothing is
                                            GLS_COMPARE_ALWAYS) */
    uint8_t write_mask;                  /* 0: 0xff (to write nothing, KEEP) */
} gls_stencil;

typedef enum gls_cull {
    GLS_CULL_NONE = 0,
    GLS_CULL_BACK,
    GLS_CULL_FRONT,
    GLS_CULL_COUNT
} gls_cull;

enum {
    GLS_COLOR_MASK_NONE = 0,
    GLS_COLOR_MASK_R = 1,
    GLS_COLOR_MASK_G = 2,
    GLS_COLOR_MASK_B = 4,
    GLS_COLOR_MASK_A = 8,
    GLS_COLOR_MASK_RGBA = 15,
};

// >>the cache

typedef struct gl_state gl_state;

/* NULL when memory runs out. Makes the empty vertex array (no GL error possible). */
gl_state *gl_state_create(void);
void gl_state_destroy(gl_state *s);      /* NULL is fine */

void gl_state_set_force(gl_state *s, bool force);
bool gl_state_force(const gl_state *s);
void gl_state_invalidate(gl_state *s);

/* >>setters: each compares, applies what differs, counts one change if anything did */
void gl_state_program(gl_state *s, GLuint program);                   /* 0: none */
void gl_state_texture(gl_state *s, unsigned unit, GLuint texture);    /* 0: none; unit < 16 */
void gl_state_framebuffer(gl_state *s, GLuint framebuffer);           /* the draw framebuffer */
void gl_state_blend(gl_state *s, const gls_blend *blend);             /* NULL: {0}, off */
void gl_state_color_mask(gl_state *s, unsigned mask);                 /* GLS_COLOR_MASK_* bits */
void gl_state_depth(gl_state *s, const gls_depth *depth);             /* NULL: {0}, off */
void gl_state_stencil(gl_state *s, const gls_stencil *stencil);       /* NULL: {0}, off */
void gl_state_cull(gl_state *s, gls_cull cull);
/* The culling set last (a pass sets it before it draws; after gl_state_invalidate, until
 * then, what the cache last knew). */
gls_cull gl_state_cull_current(const gl_state *s);
void gl_state_viewport(gl_state *s, int x, int y, int width, int height);
void gl_state_vertex_array(gl_state *s, GLuint vertex_array);         /* 0: the empty one */
/* The whole of buffer at GL_SHADER_STORAGE_BUFFER binding point `binding` (< 16;
 * glBindBufferBase); 0: none. Counted in "buffer", not in state_changes. */
void gl_state_storage_buffer(gl_state *s, unsigned binding, GLuint buffer);
/* Level 0 of texture (not layered) at image unit `unit` (< 8) with access
 * (GL_READ_ONLY / GL_WRITE_ONLY / GL_READ_WRITE) and format (GL_RGBA16F, ...);
 * texture 0: none. Counted in "image", not in state_changes. */
void gl_state_image(gl_state *s, unsigned unit, GLuint texture, GLenum access, GLenum format);
/* glMemoryBarrier(bits): never cached (a barrier orders what came before it), counted
 * in "barrier" every time. */
void gl_state_barrier(gl_state *s, GLbitfield bits);

/* >>the feedback-loop check (debug contexts and tests)
 *
 * GL 4.5 section 9.3 ("Feedback Loops Between Textures and the Framebuffer") leaves
 * texturing from an image undefined while that image is attached to the bound draw
 * framebuffer; depth and colour write masks are no exception (only disjoint texels,
 * one read and write per fragment, or glTextureBarrier between draws are). llvmpipe
 * happens to give the expected texels, a GPU need not. With the check on, every draw
 * and dispatch through the cache first asks GL (not the cache) which texture each
 * active sampler uniform of the current program reads (its unit and target) and which
 * textures the draw framebuffer has attached (colour, depth, stencil); a texture that
 * is both counts one loop and, for the first 8 of a cache's life, gives the message
 *
 *     feedback loop in pass point: draw of program deferred_point+... samples texture
 *     depth (sampler t_depth, unit 10) while it is attached to the draw framebuffer
 *     light (depth); GL 4.5 section 9.3 leaves the result undefined
 *
 * as a GL_DEBUG_TYPE_ERROR message (glDebugMessageInsert: a debug context counts it
 * as a GL error, so a test fails and a run is failed:gl-error), or on stderr as
 * "bug: ..." where debug output is off. Dispatches are checked the same way (a
 * compute shader's texturing is undefined too while the image is attached: switch
 * the draw framebuffer before the dispatch). On by default exactly when
 * GL_DEBUG_OUTPUT is enabled at gl_state_create (debug contexts: --debug-gl,
 * SHADESWEEP_GL_DEBUG=1, every test), so measured runs pay nothing; the samplers of
 * each program are read once per frame (gl_state_invalidate forgets them). */
void gl_state_set_feedback_check(gl_state *s, bool on);
bool gl_state_feedback_check(const gl_state *s);
/* Draws and dispatches found sampling an attached texture since creation, and the
 * message of the last one ("" when none). */
uint64_t gl_state_feedback_loops(const gl_state *s);
const char *gl_state_feedback_message(const gl_state *s);

/* >>draws: one draw call each. offset: bytes into the element buffer of the
 * bound vertex array. */
void gl_state_draw_arrays(gl_state *s, GLenum mode, GLint first, GLsizei count);
void gl_state_draw_arrays_instanced(gl_state *s, GLenum mode, GLint first, GLsizei count,
                                    GLsizei instances);
void gl_state_draw_elements(gl_state *s, GLenum mode, GLsizei count, GLenum type, size_t offset);
void gl_state_draw_elements_instanced(gl_state *s, GLenum mode, GLsizei count, GLenum type,
                                      size_t offset, GLsizei instances);
void gl_state_draw_elements_base_vertex(gl_state *s, GLenum mode, GLsizei count, GLenum type,
                                        size_t offset, GLint base_vertex);

/* A compute dispatch of x * y * z work groups with the bound program: one dispatch
 * (gls_counts.dispatches), not a draw call. */
void gl_state_dispatch(gl_state *s, GLuint x, GLuint y, GLuint z);

/* The full-screen triangle of renderers/shaders/fullscreen.vert over a target of
 * width x height, with that program bound: sets the viewport the shader expects,
 * (0,0,width,height), or (0,0,2*width,2*height) when unclipped (the program was
 * built with FULLSCREEN_UNCLIPPED), binds the empty vertex array and draws 3
 * vertices: one draw call. Unclipped, every implementation (llvmpipe included)
 * counts exactly width*height fragment shader invocations; see fullscreen.vert.
 * False, with nothing drawn, when the unclipped viewport would exceed
 * GL_MAX_VIEWPORT_DIMS (gl_state_fullscreen_unclipped_fits says so beforehand). */
bool gl_state_draw_fullscreen(gl_state *s, int width, int height, bool unclipped);
bool gl_state_fullscreen_unclipped_fits(const gl_state *s, int width, int height);

/* Clears the bound draw framebuffer: mask is GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT
 * | GL_STENCIL_BUFFER_BIT, every colour draw buffer to rgba (NULL: 0,0,0,0), depth to
 * depth, stencil to stencil. First sets, through the cache, what the clear needs:
 * colour mask RGBA, depth writes on (glDepthMask only: the depth test stays as it
 * is), stencil write mask 0xff. Not a draw call. */
void gl_state_clear(gl_state *s, GLbitfield mask, const float rgba[4], double depth,
                    int stencil);

// >>passes

/* Starts counting a pass; name must be a static string (it goes into pass_stats). */
void gl_state_begin_pass(gl_state *s, const char *name);
/* Ends the pass; out (may be NULL) gets name, draw_calls, state_changes and cpu_us
 * (CLOCK_MONOTONIC from begin to end); its other fields are left alone. */
void gl_state_end_pass(gl_state *s, pass_stats *out);
/* The counts of the pass in progress, or of the last pass ended. */
const gls_counts *gl_state_pass_counts(const gl_state *s);
/* Everything since creation, outside passes included. */
const gls_counts *gl_state_total_counts(const gl_state *s);
