#pragma once
/* The state cache's object, shared by its files: state.c (the cache, counting, setters,
 * draws, passes) and state_feedback.c (the feedback-loop check). Not for renderers:
 * they see gl_state only through state.h. */
#include "renderers/gl/state.h"

#include <stdbool.h>
#include <stdint.h>
#include <time.h>


/* Parts of the state, each known or not (a bit in gl_state.known). */
enum {
    K_PROGRAM,
    K_FRAMEBUFFER,
    K_VERTEX_ARRAY,
    K_VIEWPORT,
    K_BLEND_ON,
    K_BLEND_FUNC,        /* equations and factors */
    K_COLOR_MASK,
    K_DEPTH_ON,
    K_DEPTH_FUNC,
    K_DEPTH_WRITE,
    K_STENCIL_ON,
    K_STENCIL_FUNC_FRONT,
    K_STENCIL_FUNC_BACK,
    K_STENCIL_OP_FRONT,
    K_STENCIL_OP_BACK,
    K_STENCIL_WRITE,
    K_CULL_ON,
    K_CULL_FACE,
    K_COUNT
};
_Static_assert(K_COUNT <= 32, "known bits fit in 32");

typedef struct stencil_func {
    GLenum func;
    GLint ref;
    GLuint mask;
} stencil_func;

typedef struct stencil_ops {
    GLenum sfail, dpfail, dppass;
} stencil_ops;

/* What GL holds, as far as the bits of known say. */
typedef struct gl_values {
    GLuint program, framebuffer, vertex_array;
    GLint viewport[4];
    GLuint texture[GLS_MAX_TEXTURE_UNITS];
    GLuint buffer[GLS_MAX_BUFFER_BINDINGS];
    struct image_binding {
        GLuint texture;
        GLenum access, format;
    } image[GLS_MAX_IMAGE_UNITS];
    bool blend_on;
    GLenum blend_func[6];            /* op rgb, op alpha, src rgb, dst rgb, src alpha, dst alpha */
    bool color_mask[4];
    bool depth_on;
    GLenum depth_func;
    bool depth_write;
    bool stencil_on;
    stencil_func stencil_func[2];    /* [0] front, [1] back */
    stencil_ops stencil_ops[2];
    GLuint stencil_write;
    bool cull_on;
    GLenum cull_face;
} gl_values;

enum { GLS_SAMPLED_PROGRAMS = 32, GLS_SAMPLERS = 16 };

/* The active sampler uniforms of one program (the feedback-loop check). */
typedef struct sampled_program {
    GLuint program;
    unsigned n;
    struct {
        GLuint unit;
        GLenum binding;              /* GL_TEXTURE_BINDING_2D, ... for the sampler's type */
        char name[32];
    } sampler[GLS_SAMPLERS];
} sampled_program;

struct gl_state {
    bool force;
    GLuint empty_vertex_array;
    GLint max_viewport[2];           /* GL_MAX_VIEWPORT_DIMS */
    uint32_t known;                  /* 1 << K_* */
    uint32_t texture_known;          /* 1 << unit */
    uint32_t buffer_known;           /* 1 << storage binding */
    uint32_t image_known;            /* 1 << image unit */
    gl_values gl;

    bool in_pass;
    const char *pass_name;
    struct timespec pass_start;
    gls_counts pass, total;

    /* >>the feedback-loop check (state.h) */
    bool feedback_check;
    int max_color_attachments;       /* GL_MAX_COLOR_ATTACHMENTS, at most 8 */
    uint64_t feedback_loops;
    char feedback_message[768];
    unsigned nsampled;               /* programs in sampled[], forgotten by invalidate */
    sampled_program sampled[GLS_SAMPLED_PROGRAMS];
};

/* Before a draw or dispatch (`what`): with the check on, a texture that the bound
 * program samples and the bound draw framebuffer has attached is reported (state.h). */
void gl_state_check_feedback(gl_state *s, const char *what);
