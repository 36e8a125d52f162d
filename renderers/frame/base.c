/* The renderer base (base.h). */
#include "renderers/frame/base.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/frame/bindings.h"
#include "scenes/scene.h"

bool renderer_base_init(renderer_base *b, const char *name, const renderer_options *opts,
                        size_t max_passes, char *err, size_t errlen)
{
    memset(b, 0, sizeof *b);
    b->name = name;
    b->opts = *opts;
    if ((unsigned)opts->hdr > (unsigned)HDR_RGBA32F) {
        snprintf(err, errlen, "%s: unknown HDR format %d (expected rgba16f or rgba32f)", name,
                 (int)opts->hdr);
        return false;
    }
    if (!(opts->fog_density >= 0.0f && isfinite(opts->fog_density))) {
        snprintf(err, errlen, "%s: fog.density %g: expected a finite number >= 0", name,
                 (double)opts->fog_density);
        return false;
    }
    for (int i = 0; i < 3; i++)
        if (!(opts->fog_color[i] >= 0.0f && isfinite(opts->fog_color[i]))) {
            snprintf(err, errlen, "%s: fog.colour[%d] %g: expected a finite number >= 0", name,
                     i, (double)opts->fog_color[i]);
            return false;
        }
    b->samples = opts->msaa > 1 ? opts->msaa : 1;
    if (b->samples > 1) {
        GLint ms = 0, mc = 0, md = 0;
        gl.GetIntegerv(GL_MAX_SAMPLES, &ms);
        gl.GetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &mc);
        gl.GetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &md);
        if (!renderer_base_msaa_check(name, opts->msaa, (int)ms, (int)mc, (int)md, err, errlen))
            return false;
    }
    b->max_passes = max_passes < RENDERER_BASE_MAX_PASSES ? max_passes
                                                           : RENDERER_BASE_MAX_PASSES;
    GLint fb = 0;
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb);
    b->output_fbo = (GLuint)fb;
    if (b->opts.max_uniform_block_size <= 0) {
        GLint v = 0;
        gl.GetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &v);
        b->opts.max_uniform_block_size = v;
    }
    b->st = gl_state_create();
    b->programs = gl_program_cache_create();
    if (!b->st || !b->programs)
        goto oom;
    if (opts->queries) {
        b->queries = gl_pass_queries_create(b->max_passes, opts->timer_query,
                                            opts->pipeline_statistics);
        if (!b->queries)
            goto oom;
    }
    return true;
oom:
    snprintf(err, errlen, "%s: out of memory", name);
    return false;
}

void renderer_base_destroy(renderer_base *b)
{
    renderer_base_release_targets(b);
    renderer_base_release_scene(b);
    if (b->coverage_buffer && gl.DeleteBuffers)
        gl.DeleteBuffers(1, &b->coverage_buffer);
    b->coverage_buffer = 0;
    gl_pass_queries_destroy(b->queries);
    gl_program_cache_destroy(b->programs);
    gl_state_destroy(b->st);
    b->queries = NULL;
    b->programs = NULL;
    b->st = NULL;
}

bool renderer_base_size(renderer_base *b, const struct scene *s, char *err, size_t errlen)
{
    b->width = b->opts.width > 0 ? b->opts.width : s->width;
    b->height = b->opts.height > 0 ? b->opts.height : s->height;
    if (b->width != s->width || b->height != s->height) {
        /* the projection's aspect and the sky's viewport are the scene's */
        snprintf(err, errlen, "%s: the scene is posed for %dx%d, the output is %dx%d",
                 b->name, s->width, s->height, b->width, b->height);
        return false;
    }
    return true;
}

/* The light features of the scene's lights as lighting.inc's common defines (every
 * program of the base's cache is compiled for them) and the pass plan's `lighting`
 * line: what is compiled in, and what is left out. Attenuation is a point and spot
 * light's only (a directional light has none). A scene with coloured meshes adds
 * VERTEX_COLOR (mesh.vert, surface.inc), one whose materials read maps from a second uv
 * set adds UV2, one with skins SKINNING (mesh.vert, shadow.vert, visibility_shade.comp:
 * skin.inc), one shaded by the metallic-roughness model SHADING_PBR (lighting.inc), one
 * lit by an environment ENVIRONMENT (environment.inc: every renderer's ambient term and
 * the sky), a design that culls lights stochastically (b->stochastic) STOCHASTIC; the
 * line names them too, and the environment among what was left out when the scene has
 * none. */
static bool set_lighting(renderer_base *b, const struct scene *s)
{
    static const char *const type_name[3] = {"point", "spot", "directional"};
    static const char *const att_name[4] = {"inverse-square", "linear-range", "quadratic",
                                            "windowed"};
    unsigned types = 0, atts = 0;
    for (uint32_t i = 0; s && i < s->nlights_total; i++) {
        const scene_light *l = &s->lights[i];
        if ((unsigned)l->type < 3)
            types |= 1u << l->type;
        if (l->type != LIGHT_DIRECTIONAL && (unsigned)l->attenuation < 4)
            atts |= 1u << l->attenuation;
    }
    snprintf(b->light_types_define, sizeof b->light_types_define, "LIGHT_TYPES %u", types);
    snprintf(b->attenuations_define, sizeof b->attenuations_define, "LIGHT_ATTENUATIONS %u",
             atts);
    const char *defs[2] = {b->light_types_define, b->attenuations_define};
    char in[96] = "", out[96] = "";
    size_t nin = 0, nout = 0;
    for (int k = 0; k < 7; k++) {
        bool has = k < 3 ? (types >> k) & 1u : (atts >> (k - 3)) & 1u;
        const char *what = k < 3 ? type_name[k] : att_name[k - 3];
        char *to = has ? in : out;
        size_t *n = has ? &nin : &nout;
        if (*n < sizeof in)
            *n += (size_t)snprintf(to + *n, sizeof in - *n, "%s%s", *n ? ", " : "", what);
    }
    bool coloured = s && scene_has_vertex_colors(s);
    bool uv2 = s && scene_uses_uv2(s);
    bool skins = s && scene_has_skins(s);
    bool pbr = s && s->shading == SHADING_PBR;
    bool env = s && s->environment != ENVIRONMENT_NONE;
    const char *all[8] = {defs[0], defs[1], NULL, NULL, NULL, NULL, NULL, NULL};
    size_t n = 2;
    if (coloured)
        all[n++] = "VERTEX_COLOR";
    if (uv2)
        all[n++] = "UV2";
    if (skins)
        all[n++] = "SKINNING";
    if (pbr)
        all[n++] = "SHADING_PBR";
    if (env)
        all[n++] = "ENVIRONMENT";
    if (b->stochastic)
        all[n++] = "STOCHASTIC";
    snprintf(b->lighting, sizeof b->lighting, "compiled for %s%s%s%s%s%s%s; left out: %s%s",
             nin ? in : "no light", coloured ? ", vertex colours" : "",
             uv2 ? ", a second uv set" : "", skins ? ", skins" : "",
             pbr ? ", metallic-roughness (pbr)" : "", env ? ", environment: sky" : "",
             b->stochastic ? ", stochastic culling" : "",
             nout ? out : env ? "nothing" : "", env ? "" : nout ? ", environment" : "environment");
    return gl_program_cache_set_common(b->programs, all, n);
}

void renderer_base_describe(const renderer_base *b, pass_plan *out)
{
    gl_program_cache_describe(b->programs, out);
    snprintf(out->lighting, sizeof out->lighting, "%s", b->lighting);
}

bool renderer_base_scene(renderer_base *b, const struct scene *s, bool illumination_sets,
                         char *err, size_t errlen)
{
    char why[512] = "";
    renderer_base_release_scene(b);
    if (!set_lighting(b, s)) {
        snprintf(err, errlen, "%s: bug: the lighting defines were refused", b->name);
        return false;
    }
    shadow_maps_plan(&b->shadows, s, &b->opts);
    if (!frontend_init(&b->fe, s, why, sizeof why)) {
        snprintf(err, errlen, "%s: %s", b->name, why);
        return false;
    }
    b->fe.no_shadows = !b->shadows.run;
    b->fe.no_illumination = !illumination_sets;
    b->gpu = scene_gpu_create(s, why, sizeof why);
    if (!b->gpu) {
        snprintf(err, errlen, "%s: %s", b->name, why);
        return false;
    }
    return shadow_maps_create(&b->shadows, b->programs, b->name, err, errlen);
}

void renderer_base_release_scene(renderer_base *b)
{
    shadow_maps_destroy(&b->shadows);
    scene_gpu_destroy(b->gpu);
    b->gpu = NULL;
    frontend_free(&b->fe);
    memset(&b->fe, 0, sizeof b->fe);
}

void renderer_base_begin_frame(renderer_base *b, const struct scene *s, frame_stats *out)
{
    out->npasses = 0;
    out->msaa = b->samples;
    b->npasses = 0;
    /* Every frame starts from unknown state, so every frame counts alike: the first
     * set of each part of the state in a frame is a change. */
    gl_state_invalidate(b->st);
    if (s && b->gpu) {
        frontend_build(&b->fe, s);
        scene_gpu_frame(b->gpu, s);
    }
}

void renderer_base_shadow_pass(renderer_base *b, const struct scene *s, frame_stats *out)
{
    if (!b->shadows.run)
        return;
    renderer_base_pass_begin(b, out, "shadows");
    renderer_base_shading(b, false);   /* depth only: no samples shaded */
    shadow_maps_draw(&b->shadows, b->st, b->gpu, &b->fe, s);
    renderer_base_pass_end(b, out);
}

void renderer_base_pass_begin(renderer_base *b, frame_stats *out, const char *name)
{
    gl_state_begin_pass(b->st, name);
    if (out->npasses < RENDERER_MAX_PASSES)
        out->pass[out->npasses].single_sampled = out->pass[out->npasses].shaded_counted = false;
    if (b->queries)
        gl_pass_queries_begin(b->queries, out->npasses);
}

void renderer_base_pass_end(renderer_base *b, frame_stats *out)
{
    size_t i = out->npasses;
    if (b->queries)
        gl_pass_queries_end(b->queries);
    pass_stats *p = &out->pass[i];
    gl_state_end_pass(b->st, p);
    p->gpu_us = p->fragments = p->primitives = p->samples = NAN;   /* collect fills them */
    p->per_sample_samples = 0.0;
    p->scissor_pixels = NAN;                          /* a scissoring renderer sets it */
    if (i < RENDERER_BASE_MAX_PASSES)
        b->pass_counts[i] = *gl_state_pass_counts(b->st);
    out->npasses = i + 1;
    b->npasses = i + 1;
}

void renderer_base_shading(renderer_base *b, bool on)
{
    if (on)
        gl_pass_queries_resume(b->queries);
    else
        gl_pass_queries_pause(b->queries);
}

void renderer_base_single_sampled(frame_stats *out)
{
    if (out->npasses < RENDERER_MAX_PASSES)
        out->pass[out->npasses].single_sampled = true;
}

void renderer_base_per_sample(renderer_base *b, bool on)
{
    gl_pass_queries_per_sample(b->queries, on);
}

void renderer_base_collect(renderer_base *b, frame_stats *out)
{
    if (b->queries) {
        gl_pass_queries_collect(b->queries, out);
        return;
    }
    for (size_t i = 0; i < out->npasses; i++)
        out->pass[i].gpu_us = out->pass[i].fragments = out->pass[i].primitives =
            out->pass[i].samples = out->pass[i].per_sample_samples = NAN;
}

const gls_counts *renderer_base_pass_counts(const renderer_base *b, size_t pass)
{
    if (!b || pass >= b->npasses || pass >= RENDERER_BASE_MAX_PASSES)
        return NULL;
    return &b->pass_counts[pass];
}

// >>targets and fog

bool renderer_base_msaa_check(const char *name, int msaa, int max_samples, int max_color,
                              int max_depth, char *err, size_t errlen)
{
    if (msaa == 0 || msaa == 1)
        return true;
    if (msaa != 2 && msaa != 4 && msaa != 8) {
        snprintf(err, errlen, "%s: msaa %d: expected 1, 2, 4 or 8 samples", name, msaa);
        return false;
    }
    int limit = max_samples;
    if (max_color < limit)
        limit = max_color;
    if (max_depth < limit)
        limit = max_depth;
    if (msaa > limit) {
        snprintf(err, errlen,
                 "%s: msaa %d: this context allows at most %d samples (GL_MAX_SAMPLES %d, "
                 "GL_MAX_COLOR_TEXTURE_SAMPLES %d, GL_MAX_DEPTH_TEXTURE_SAMPLES %d)",
                 name, msaa, limit, max_samples, max_color, max_depth);
        return false;
    }
    return true;
}

gl_format renderer_base_hdr_format(const renderer_base *b)
{
    return b->opts.hdr == HDR_RGBA32F ? GLT_FORMAT_RGBA32F : GLT_FORMAT_RGBA16F;
}

GLenum renderer_base_hdr_image_format(const renderer_base *b)
{
    return gl_format_get(renderer_base_hdr_format(b))->internal_format;
}

const char *renderer_base_hdr_define(const renderer_base *b)
{
    return b->opts.hdr == HDR_RGBA32F ? "HDR_RGBA32F" : NULL;
}

bool renderer_base_hdr_target(const renderer_base *b, gl_target *t, const char *name, char *err,
                              size_t errlen)
{
    return gl_target_create(t, &(gl_target_desc){.name = name,
                                                 .format = renderer_base_hdr_format(b),
                                                 .width = b->width, .height = b->height,
                                                 .samples = b->samples},
                            err, errlen);
}

bool renderer_base_targets(renderer_base *b, const char *hdr_name, char *err, size_t errlen)
{
    renderer_base_release_targets(b);
    if (!renderer_base_hdr_target(b, &b->hdr, hdr_name, err, errlen) ||
        !gl_target_create(&b->depth, &(gl_target_desc){.name = "depth",
                                                      .format = GLT_FORMAT_DEPTH24_STENCIL8,
                                                      .width = b->width, .height = b->height,
                                                      .samples = b->samples},
                          err, errlen))
        return false;
    if (b->samples <= 1)
        return true;
    b->samples = b->hdr.samples;   /* what the driver gave: at least opts.msaa */
    return gl_target_create(&b->hdr_resolved,
                            &(gl_target_desc){.name = "hdr.resolved",
                                              .format = renderer_base_hdr_format(b),
                                              .width = b->width, .height = b->height},
                            err, errlen) &&
           gl_framebuffer_create(&b->msaa_read, &(gl_framebuffer_desc){.name = "msaa.read",
                                                                      .color = {&b->hdr}},
                                 err, errlen) &&
           gl_framebuffer_create(&b->msaa_draw,
                                 &(gl_framebuffer_desc){.name = "msaa.resolved",
                                                        .color = {&b->hdr_resolved}},
                                 err, errlen);
}

void renderer_base_release_aa(edge_aa *e)
{
    GL_FRAMEBUFFERS_DESTROY(&e->fb, &e->depth_read, &e->depth_draw);
    GL_TARGETS_DESTROY(&e->out, &e->depth1);
    e->program = 0;   /* the base's cache owns it */
    e->run = false;
}

void renderer_base_release_targets(renderer_base *b)
{
    GL_FRAMEBUFFERS_DESTROY(&b->msaa_read, &b->msaa_draw);
    renderer_base_release_aa(&b->aa);
    GL_TARGETS_DESTROY(&b->hdr_resolved, &b->hdr, &b->depth);
}

const gl_target *renderer_base_display(const renderer_base *b)
{
    if (b->aa.run)
        return &b->aa.out;
    return b->samples > 1 ? &b->hdr_resolved : &b->hdr;
}

bool renderer_base_read_hdr(const renderer_base *b, float *rgba, int width, int height)
{
    const gl_target *t = renderer_base_display(b);
    if (!t->texture || width != t->width || height != t->height)
        return false;
    gl_texture_read_float(t->texture, width, height, rgba);
    return true;
}

/* The compute program `name` (NAME.comp; "NAME_msaa" with MSAA_SAMPLES at samples > 1)
 * that reads the depth target between frames; 0 with a message that names `what`. */
static GLuint depth_program(renderer_base *b, const char *name, const char *msaa_name,
                            const char *compute, const char *what, char *err, size_t errlen)
{
    if (!b->depth.texture) {
        snprintf(err, errlen, "%s: %s: no depth target (not prepared)", b->name, what);
        return 0;
    }
    char samples[32], why[512];
    snprintf(samples, sizeof samples, "MSAA_SAMPLES %d", b->samples);
    GLuint program = 0;
    if (gl_program_get(b->programs,
                       &(gl_program_desc){.name = b->samples > 1 ? msaa_name : name,
                                          .compute = compute,
                                          .defines = {b->samples > 1 ? samples : NULL}},
                       &program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "%s: %s: %s", b->name, what, why);
        return 0;
    }
    return program;
}

bool renderer_base_coverage(renderer_base *b, uint64_t *covered, char *err, size_t errlen)
{
    *covered = 0;
    GLuint program = depth_program(b, "coverage", "coverage_msaa", "coverage.comp", "coverage",
                                   err, errlen);
    if (!program)
        return false;
    if (!b->coverage_buffer) {
        gl.CreateBuffers(1, &b->coverage_buffer);
        gl.NamedBufferStorage(b->coverage_buffer, sizeof(GLuint), NULL, GL_DYNAMIC_STORAGE_BIT);
    }
    const GLuint zero = 0;
    gl.NamedBufferSubData(b->coverage_buffer, 0, sizeof zero, &zero);
    gl.UseProgram(program);
    gl.BindTextureUnit(BIND_TEX_DEPTH, b->depth.texture);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_SSBO_COVERAGE, b->coverage_buffer);
    gl.DispatchCompute(((GLuint)b->width + 7u) / 8u, ((GLuint)b->height + 7u) / 8u, 1);
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint n = 0;
    gl.GetNamedBufferSubData(b->coverage_buffer, 0, sizeof n, &n);
    gl.BindTextureUnit(BIND_TEX_DEPTH, 0);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_SSBO_COVERAGE, 0);
    gl.UseProgram(0);
    gl_state_invalidate(b->st);
    *covered = n;
    return true;
}

bool renderer_base_lights_reaching(renderer_base *b, const struct scene *s, uint32_t *counts,
                                   char *err, size_t errlen)
{
    GLuint program = depth_program(b, "lights_reaching", "lights_reaching_msaa",
                                   "lights_reaching.comp", "lights reaching", err, errlen);
    if (!program)
        return false;
    /* the lights on now, in view space as the frame drew them (s is posed for it) */
    uint32_t n = s->nlights_active;
    size_t nfloats = (size_t)(n ? n : 1) * 8u;
    float *packed = calloc(nfloats, sizeof *packed);
    if (!packed) {
        snprintf(err, errlen, "%s: lights reaching: out of memory for %u lights", b->name, n);
        return false;
    }
    for (uint32_t i = 0; i < n; i++) {
        const scene_light *l = &s->lights[i];
        sm_vec3 p, d;
        sm_mat4_mulv3(s->view, l->position, 1.0f, p);
        sm_mat4_mulv3(s->view, l->direction, 0.0f, d);
        sm_vec3_normalize(d);
        float *o = packed + 8u * i;
        o[0] = p[0], o[1] = p[1], o[2] = p[2];
        o[3] = l->type == LIGHT_DIRECTIONAL ? -1.0f : l->radius;
        o[4] = d[0], o[5] = d[1], o[6] = d[2];
        o[7] = l->type == LIGHT_SPOT ? cosf(l->spot_angle) : -2.0f;
    }
    size_t pixels = (size_t)b->width * (size_t)b->height;
    GLuint buf[2] = {0, 0};
    gl.CreateBuffers(2, buf);
    gl.NamedBufferStorage(buf[0], (GLsizeiptr)(nfloats * sizeof *packed), packed, 0);
    gl.NamedBufferStorage(buf[1], (GLsizeiptr)(pixels * sizeof *counts), NULL, 0);
    free(packed);
    sm_mat4 inv;
    sm_mat4_inv(s->proj, inv);
    gl.UseProgram(program);
    gl.UniformMatrix4fv(0, 1, GL_FALSE, &inv[0][0]);
    gl.Uniform1i(1, (GLint)n);
    gl.BindTextureUnit(BIND_TEX_DEPTH, b->depth.texture);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_SSBO_REACH_LIGHTS, buf[0]);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_SSBO_REACH_COUNTS, buf[1]);
    gl.DispatchCompute(((GLuint)b->width + 7u) / 8u, ((GLuint)b->height + 7u) / 8u, 1);
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.GetNamedBufferSubData(buf[1], 0, (GLsizeiptr)(pixels * sizeof *counts), counts);
    gl.BindTextureUnit(BIND_TEX_DEPTH, 0);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_SSBO_REACH_LIGHTS, 0);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_SSBO_REACH_COUNTS, 0);
    gl.UseProgram(0);
    gl.DeleteBuffers(2, buf);
    gl_state_invalidate(b->st);
    return true;
}

void renderer_base_msaa_resolve_pass(renderer_base *b, frame_stats *out)
{
    if (b->samples <= 1 || !b->msaa_read.fbo)
        return;
    renderer_base_pass_begin(b, out, "msaa-resolve");
    renderer_base_shading(b, false);   /* a blit: no fragment is shaded */
    /* Averages the samples in linear HDR (a float blit of a multisampled source to a
     * single-sampled one of the same size). Scissor and rasterizer discard, which a
     * blit obeys, are off between passes (state.h). */
    gl.BlitNamedFramebuffer(b->msaa_read.fbo, b->msaa_draw.fbo, 0, 0, b->width, b->height, 0,
                            0, b->width, b->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    renderer_base_pass_end(b, out);
}



bool renderer_base_fog(const renderer_base *b)
{
    return b->opts.fog_density > 0.0f;
}

void renderer_base_fog_uniform(const renderer_base *b, GLuint program)
{
    if (!program || !renderer_base_fog(b))
        return;
    gl.ProgramUniform4f(program, LOC_FOG, b->opts.fog_color[0], b->opts.fog_color[1],
                        b->opts.fog_color[2], b->opts.fog_density);
}
