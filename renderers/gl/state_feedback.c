/* The state cache's feedback-loop check (state.h): a draw or dispatch whose program
 * samples a texture attached to the bound draw framebuffer. */
#include "renderers/gl/state_internal.h"

#include <stdio.h>
#include <string.h>

// >>the feedback-loop check (state.h)

void gl_state_set_feedback_check(gl_state *s, bool on)
{
    s->feedback_check = on;
}

bool gl_state_feedback_check(const gl_state *s)
{
    return s->feedback_check;
}

uint64_t gl_state_feedback_loops(const gl_state *s)
{
    return s->feedback_loops;
}

const char *gl_state_feedback_message(const gl_state *s)
{
    return s->feedback_message;
}

/* The texture binding a sampler type reads, or 0 for a type that is no sampler (or
 * a buffer texture, which cannot be attached to a framebuffer). */
static GLenum sampler_binding(GLenum type)
{
    switch (type) {
    case GL_SAMPLER_1D: case GL_SAMPLER_1D_SHADOW: case GL_INT_SAMPLER_1D:
    case GL_UNSIGNED_INT_SAMPLER_1D:
        return GL_TEXTURE_BINDING_1D;
    case GL_SAMPLER_2D: case GL_SAMPLER_2D_SHADOW: case GL_INT_SAMPLER_2D:
    case GL_UNSIGNED_INT_SAMPLER_2D:
        return GL_TEXTURE_BINDING_2D;
    case GL_SAMPLER_3D: case GL_INT_SAMPLER_3D: case GL_UNSIGNED_INT_SAMPLER_3D:
        return GL_TEXTURE_BINDING_3D;
    case GL_SAMPLER_CUBE: case GL_SAMPLER_CUBE_SHADOW: case GL_INT_SAMPLER_CUBE:
    case GL_UNSIGNED_INT_SAMPLER_CUBE:
        return GL_TEXTURE_BINDING_CUBE_MAP;
    case GL_SAMPLER_1D_ARRAY: case GL_SAMPLER_1D_ARRAY_SHADOW: case GL_INT_SAMPLER_1D_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_1D_ARRAY:
        return GL_TEXTURE_BINDING_1D_ARRAY;
    case GL_SAMPLER_2D_ARRAY: case GL_SAMPLER_2D_ARRAY_SHADOW: case GL_INT_SAMPLER_2D_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY:
        return GL_TEXTURE_BINDING_2D_ARRAY;
    case GL_SAMPLER_CUBE_MAP_ARRAY: case GL_SAMPLER_CUBE_MAP_ARRAY_SHADOW:
    case GL_INT_SAMPLER_CUBE_MAP_ARRAY: case GL_UNSIGNED_INT_SAMPLER_CUBE_MAP_ARRAY:
        return GL_TEXTURE_BINDING_CUBE_MAP_ARRAY;
    case GL_SAMPLER_2D_RECT: case GL_SAMPLER_2D_RECT_SHADOW: case GL_INT_SAMPLER_2D_RECT:
    case GL_UNSIGNED_INT_SAMPLER_2D_RECT:
        return GL_TEXTURE_BINDING_RECTANGLE;
    case GL_SAMPLER_2D_MULTISAMPLE: case GL_INT_SAMPLER_2D_MULTISAMPLE:
    case GL_UNSIGNED_INT_SAMPLER_2D_MULTISAMPLE:
        return GL_TEXTURE_BINDING_2D_MULTISAMPLE;
    case GL_SAMPLER_2D_MULTISAMPLE_ARRAY: case GL_INT_SAMPLER_2D_MULTISAMPLE_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_2D_MULTISAMPLE_ARRAY:
        return GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY;
    default:
        return 0;
    }
}

/* The active sampler uniforms of prog and the units they read, asked of GL once per
 * program between invalidations. */
static const sampled_program *program_samplers(gl_state *s, GLuint prog)
{
    for (unsigned i = 0; i < s->nsampled; i++)
        if (s->sampled[i].program == prog)
            return &s->sampled[i];
    unsigned slot = s->nsampled < GLS_SAMPLED_PROGRAMS ? s->nsampled++
                                                        : prog % GLS_SAMPLED_PROGRAMS;
    sampled_program *p = &s->sampled[slot];
    memset(p, 0, sizeof *p);
    p->program = prog;
    GLint n = 0;
    gl.GetProgramInterfaceiv(prog, GL_UNIFORM, GL_ACTIVE_RESOURCES, &n);
    for (GLint i = 0; i < n && p->n < GLS_SAMPLERS; i++) {
        static const GLenum props[3] = {GL_TYPE, GL_ARRAY_SIZE, GL_LOCATION};
        GLint v[3] = {0, 0, -1};
        gl.GetProgramResourceiv(prog, GL_UNIFORM, (GLuint)i, 3, props, 3, NULL, v);
        GLenum binding = sampler_binding((GLenum)v[0]);
        if (!binding || v[2] < 0)
            continue;
        char name[32] = "";
        gl.GetProgramResourceName(prog, GL_UNIFORM, (GLuint)i, (GLsizei)sizeof name, NULL, name);
        for (GLint k = 0; k < v[1] && p->n < GLS_SAMPLERS; k++) {
            GLint unit = -1;
            gl.GetUniformiv(prog, v[2] + k, &unit);
            if (unit < 0)
                continue;
            p->sampler[p->n].unit = (GLuint)unit;
            p->sampler[p->n].binding = binding;
            snprintf(p->sampler[p->n].name, sizeof p->sampler[p->n].name, "%s", name);
            p->n++;
        }
    }
    return p;
}

static void object_label(GLenum kind, GLuint name, const char *what, char *out, size_t len)
{
    GLsizei n = 0;
    out[0] = '\0';
    gl.GetObjectLabel(kind, name, (GLsizei)len, &n, out);
    if (n <= 0)
        snprintf(out, len, "%s %u", what, (unsigned)name);
}

static void report_feedback(gl_state *s, const char *what, GLuint prog, GLuint fbo,
                            GLuint texture, const char *sampler, GLuint unit,
                            const char *attachment)
{
    s->feedback_loops++;
    if (s->feedback_loops > 8)
        return;   /* the run has failed already; the log need not fill up */
    char pl[128], fl[64], tl[64];
    object_label(GL_PROGRAM, prog, "program", pl, sizeof pl);
    object_label(GL_FRAMEBUFFER, fbo, "framebuffer", fl, sizeof fl);
    object_label(GL_TEXTURE, texture, "texture", tl, sizeof tl);
    snprintf(s->feedback_message, sizeof s->feedback_message,
             "feedback loop in pass %s: %s of program %s samples texture %s (sampler %s, "
             "unit %u) while it is attached to the draw framebuffer %s (%s); GL 4.5 section "
             "9.3 leaves the result undefined",
             s->in_pass && s->pass_name ? s->pass_name : "(none)", what, pl, tl, sampler,
             (unsigned)unit, fl, attachment);
    if (gl.IsEnabled(GL_DEBUG_OUTPUT))
        gl.DebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_ERROR, 9003,
                              GL_DEBUG_SEVERITY_HIGH, -1, s->feedback_message);
    else
        fprintf(stderr, "bug: %s\n", s->feedback_message);
}

/* Before a draw or dispatch: does the current program sample a texture that is
 * attached to the draw framebuffer? Asks GL, not the cache. */
void gl_state_check_feedback(gl_state *s, const char *what)
{
    if (!s->feedback_check)
        return;
    GLint prog = 0, fbo = 0;
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &prog);
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    if (prog <= 0 || fbo <= 0)
        return;   /* the default framebuffer has no texture attached */
    const sampled_program *p = program_samplers(s, (GLuint)prog);
    if (!p->n)
        return;
    GLuint attached[8 + 2];
    const char *point[8 + 2];
    static const char *const color_names[8] = {"colour 0", "colour 1", "colour 2", "colour 3",
                                               "colour 4", "colour 5", "colour 6", "colour 7"};
    unsigned na = 0;
    for (int i = 0; i < s->max_color_attachments + 2; i++) {
        GLenum a = i < s->max_color_attachments ? (GLenum)(GL_COLOR_ATTACHMENT0 + i)
                   : i == s->max_color_attachments ? GL_DEPTH_ATTACHMENT
                                                   : GL_STENCIL_ATTACHMENT;
        GLint type = GL_NONE, name = 0;
        gl.GetNamedFramebufferAttachmentParameteriv((GLuint)fbo, a,
                                                    GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
        if (type != GL_TEXTURE)
            continue;
        gl.GetNamedFramebufferAttachmentParameteriv((GLuint)fbo, a,
                                                    GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
        attached[na] = (GLuint)name;
        point[na++] = i < s->max_color_attachments ? color_names[i]
                      : i == s->max_color_attachments ? "depth" : "stencil";
    }
    if (!na)
        return;
    GLint active = GL_TEXTURE0;
    gl.GetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (unsigned j = 0; j < p->n; j++) {
        GLint bound = 0;
        gl.ActiveTexture(GL_TEXTURE0 + p->sampler[j].unit);
        gl.GetIntegerv(p->sampler[j].binding, &bound);
        for (unsigned k = 0; bound > 0 && k < na; k++)
            if ((GLuint)bound == attached[k]) {
                report_feedback(s, what, (GLuint)prog, (GLuint)fbo, (GLuint)bound,
                                p->sampler[j].name, p->sampler[j].unit, point[k]);
                j = p->n;   /* one report per draw */
                break;
            }
    }
    gl.ActiveTexture((GLenum)active);
}
