/* What deferred and tiled-deferred share (deferred_core.h). The design:
 * docs/notes/deferred.md. */
#include "renderers/deferred/deferred_core.h"

#include "renderers/frame/edge_aa.h"
#include "renderers/frame/frontend.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/query.h"
#include "renderers/frame/scene_gpu.h"
#include "renderers/frame/shading.h"
#include "renderers/frame/shadow.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const pass_names[PASS_COUNT] = {
    "shadows", "gbuffer", "ambient", "directional", "point", "spot", "compose", "sky", "resolve",
    "tiled", "fog", "translucent", "edges", "msaa-resolve", "translucent-lists", "material",
    "cull-coarse",
};

/* The order describe lists them in (tiled-deferred's "tiled" after the G-buffer). */
static const deferred_pass describe_order[PASS_COUNT] = {
    PASS_SHADOWS, PASS_GBUFFER, PASS_EDGES, PASS_COARSE, PASS_TILED, PASS_TLISTS, PASS_AMBIENT,
    PASS_DIRECTIONAL, PASS_POINT, PASS_SPOT, PASS_MATERIAL, PASS_COMPOSE, PASS_FOG, PASS_SKY,
    PASS_TRANSLUCENT, PASS_MSAA, PASS_RESOLVE,
};

unsigned deferred_material_variant(const scene_material *m)
{
    return (m->diffuse_map >= 0 ? 1u : 0u) | (m->gloss_map >= 0 ? 2u : 0u) |
           (m->normal_map >= 0 ? 4u : 0u) | (m->emissive_map >= 0 ? 8u : 0u) |
           (m->alpha == MATERIAL_MASK ? 16u : 0u);
}

deferred_renderer *deferred_core_create(const char *name, size_t size, bool tiled, bool lpp,
                                        const renderer_options *opts, char *err, size_t errlen)
{
    deferred_renderer *r = calloc(1, size);
    if (!r) {
        snprintf(err, errlen, "%s: out of memory", name);
        return NULL;
    }
    r->tiled = tiled;
    r->lpp = lpp;
    /* Options are checked here, before any scene: a bad value never becomes a default. */
    deferred_layout probe;
    if (!deferred_layout_build(opts, (deferred_needs){.gloss = true, .emissive = true}, &probe,
                               err, errlen)) {
        free(r);
        return NULL;
    }
    if ((unsigned)opts->light_volumes > (unsigned)LIGHT_VOLUMES_SCISSOR) {
        snprintf(err, errlen, "deferred: unknown light volume mode %d", (int)opts->light_volumes);
        free(r);
        return NULL;
    }
    if (!renderer_base_init(&r->b, name, opts, DEFERRED_MAX_PASSES, err, errlen)) {
        renderer_base_destroy(&r->b);
        free(r);
        return NULL;
    }
    return r;
}

void deferred_core_release(deferred_renderer *r)
{
    translucent_release(&r->translucent);
    GL_FRAMEBUFFERS_DESTROY(&r->fb_gbuffer, &r->fb_light, &r->fb_compose, &r->fb_fog,
                            &r->fb_lbuf);
    for (int i = 0; i < DEFERRED_MAX_ATTACHMENTS; i++)
        gl_target_destroy(&r->gbuf[i]);
    renderer_base_release_targets(&r->b);
    GL_TARGETS_DESTROY(&r->specular, &r->depth_sampled, &r->lbuf_diffuse, &r->lbuf_specular);
    renderer_base_release_scene(&r->b);
    r->prepared = false;
}

void deferred_core_destroy(deferred_renderer *r)
{
    if (!r)
        return;
    deferred_core_release(r);
    renderer_base_destroy(&r->b);
    free(r);
}

bool deferred_build_program(deferred_renderer *r, const char *display, const char *vertex,
                            const char *fragment, const deferred_layout_defs *ld,
                            const char *const *extra, GLuint *program, char *err,
                            size_t errlen)
{
    gl_program_desc d = {.name = display, .vertex = vertex, .fragment = fragment};
    unsigned n = 0;
    for (unsigned i = 0; extra && extra[i]; i++)
        d.defines[n++] = extra[i];
    for (int i = 0; ld && i < ld->n; i++) {
        if (n >= GLP_MAX_DEFINES) {
            snprintf(err, errlen, "bug: deferred: too many defines for %s", display);
            return false;
        }
        d.defines[n++] = ld->text[i];
    }
    char why[4096] = "";
    if (gl_program_get(r->b.programs, &d, program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "deferred: %s", why);
        return false;
    }
    return true;
}

void deferred_set_sample_positions(deferred_renderer *r, GLuint fbo, GLuint program, GLint loc)
{
    GLfloat pos[8][2] = {{0.5f, 0.5f}};
    GLint prev = 0;
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &prev);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    for (int i = 0; i < r->b.samples && i < 8; i++)
        gl.GetMultisamplefv(GL_SAMPLE_POSITION, (GLuint)i, pos[i]);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)prev);
    gl.ProgramUniform2fv(program, loc, 8, &pos[0][0]);
}

bool deferred_build_msaa(deferred_renderer *r, const char *display, const char *vertex,
                         const char *fragment, const deferred_layout_defs *ld,
                         const char *const *extra, GLuint *pixel, GLuint *sample, char *err,
                         size_t errlen)
{
    if (r->b.samples <= 1)
        return deferred_build_program(r, display, vertex, fragment, ld, extra, pixel, err, errlen);
    const char *more[12];
    unsigned n = 0;
    for (unsigned i = 0; extra && extra[i] && n < 9; i++)
        more[n++] = extra[i];
    more[n++] = "GB_MSAA";
    more[n] = NULL;
    if (!deferred_build_program(r, display, vertex, fragment, ld, more, pixel, err, errlen))
        return false;
    if (!sample)
        return true;
    more[n++] = "GB_SAMPLE gl_SampleID";
    more[n] = NULL;
    return deferred_build_program(r, display, vertex, fragment, ld, more, sample, err, errlen);
}

void deferred_plan(deferred_renderer *r, deferred_pass p, bool run, const char *fmt, ...)
{
    r->run[p] = run;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->reason[p], sizeof r->reason[p], fmt, ap);
    va_end(ap);
}

/* deferred-lighting's light buffer: diffuse and specular light in the format
 * deferred_lighting.light_buffer names, and their framebuffer with the shared depth (the
 * light volumes test against the scene's depth, as deferred's do). */
static bool make_light_buffer(deferred_renderer *r, char *why, size_t len)
{
    gl_format f = r->b.opts.lpp_light_buffer == LPP_LIGHT_BUFFER_RGBA8 ? GLT_FORMAT_RGBA8
                                                                      : GLT_FORMAT_RGBA16F;
    gl_target_desc d = {.name = "lightbuffer.diffuse", .format = f, .width = r->b.width,
                        .height = r->b.height, .samples = r->b.samples};
    if (!gl_target_create(&r->lbuf_diffuse, &d, why, len))
        return false;
    d.name = "lightbuffer.specular";
    return gl_target_create(&r->lbuf_specular, &d, why, len) &&
           gl_framebuffer_create(&r->fb_lbuf,
                                 &(gl_framebuffer_desc){.name = "lightbuffer",
                                                        .color = {&r->lbuf_diffuse,
                                                                  &r->lbuf_specular},
                                                        .depth_stencil = &r->b.depth},
                                 why, len);
}

bool deferred_make_targets(deferred_renderer *r, char *err, size_t errlen)
{
    char why[512] = "";
    const int w = r->b.width, h = r->b.height;
    gl_framebuffer_desc gdesc = {.name = "gbuffer", .depth_stencil = &r->b.depth};
    bool sep = r->b.opts.separate_specular;
    /* the light accumulation in the run's HDR format, and depth (renderers/frame/base.h) */
    if (!renderer_base_targets(&r->b, sep ? "light.diffuse" : "light", why, sizeof why))
        goto fail;
    for (int i = 0; i < r->layout.nattachments; i++) {
        if (!gl_target_create(&r->gbuf[i], &(gl_target_desc){.name = r->layout.att[i].name,
                                                             .format = r->layout.att[i].format,
                                                             .width = w, .height = h,
                                                             .samples = r->b.samples},
                              why, sizeof why))
            goto fail;
        gdesc.color[i] = &r->gbuf[i];
    }
    if (!r->tiled && r->layout.position == DEFERRED_POSITION_DEPTH_BUFFER &&
        !gl_target_create(&r->depth_sampled,
                          &(gl_target_desc){.name = "depth.sampled",
                                            .format = r->b.depth.format,
                                            .width = w, .height = h,
                                            .samples = r->b.samples},
                          why, sizeof why))
        goto fail;
    if (sep && !renderer_base_hdr_target(&r->b, &r->specular, "light.specular", why, sizeof why))
        goto fail;
    if (!gl_framebuffer_create(&r->fb_gbuffer, &gdesc, why, sizeof why))
        goto fail;
    if (!gl_framebuffer_create(&r->fb_light,
                               &(gl_framebuffer_desc){.name = "light",
                                                      .color = {&r->b.hdr,
                                                                sep ? &r->specular : NULL},
                                                      .depth_stencil = &r->b.depth},
                               why, sizeof why))
        goto fail;
    if (sep && !gl_framebuffer_create(&r->fb_compose,
                                      &(gl_framebuffer_desc){.name = "compose",
                                                             .color = {&r->b.hdr},
                                                             .depth_stencil = &r->b.depth},
                                      why, sizeof why))
        goto fail;
    if (r->lpp && !make_light_buffer(r, why, sizeof why))
        goto fail;
    if (r->run[PASS_FOG] &&
        !gl_framebuffer_create(&r->fb_fog, &(gl_framebuffer_desc){.name = "fog",
                                                                  .color = {&r->b.hdr}},
                               why, sizeof why))
        goto fail;
    return true;
fail:
    snprintf(err, errlen, "deferred: %s", why);
    return false;
}

bool deferred_compile_gbuffer(deferred_renderer *r, char *err, size_t errlen)
{
    deferred_layout_defs ld;
    deferred_layout_defines(&r->layout, &ld);

    for (unsigned v = 0; v < DEFERRED_VARIANTS; v++) {
        if (!(r->variants & (1u << v)))
            continue;
        scene_material m = {.diffuse_map = (v & 1u) ? 0 : -1, .gloss_map = (v & 2u) ? 0 : -1,
                            .normal_map = (v & 4u) ? 0 : -1, .emissive_map = (v & 8u) ? 0 : -1,
                            .alpha = (v & 16u) ? MATERIAL_MASK : MATERIAL_OPAQUE};
        const char *defs[SHADING_MATERIAL_DEFINES + 1] = {NULL};
        shading_material_defines(&m, defs);
        if (!deferred_build_program(r, "deferred_gbuffer", "mesh.vert", "gbuffer.frag", &ld, defs,
                           &r->gbuffer_program[v], err, errlen))
            return false;
    }
    return true;
}

/* The fog pass's program (only when it runs): fullscreen.vert + deferred_fog.frag. */
bool deferred_compile_fog(deferred_renderer *r, char *err, size_t errlen)
{
    if (!r->run[PASS_FOG])
        return true;
    /* msaa > 1: per sample everywhere (its one input, depth, differs per sample) */
    const char *extra[5] = {"FOG", NULL, NULL, NULL, NULL};
    int n = 1;
    if (r->unclipped)
        extra[n++] = "FULLSCREEN_UNCLIPPED";
    if (r->b.samples > 1) {
        extra[n++] = "GB_MSAA";
        extra[n++] = "GB_SAMPLE gl_SampleID";
    }
    if (!deferred_build_program(r, "deferred_fog", "fullscreen.vert", "deferred_fog.frag", NULL, extra,
                       &r->fog_program, err, errlen))
        return false;
    renderer_base_fog_uniform(&r->b, r->fog_program);
    return true;
}

/* aa: edge (edge_aa.h), its normals from this G-buffer (the layout's defines). */
bool deferred_prepare_edge_aa(deferred_renderer *r, char *err, size_t errlen)
{
    deferred_layout_defs ld;
    deferred_layout_defines(&r->layout, &ld);
    const char *defs[DEFERRED_MAX_LAYOUT_DEFS];
    for (int i = 0; i < ld.n; i++)
        defs[i] = ld.text[i];
    return edge_aa_prepare(&r->b, defs, ld.n, err, errlen);
}

bool deferred_prepare_scene(deferred_renderer *r, const scene *s, char *err, size_t errlen)
{
    if (!s) {
        snprintf(err, errlen, "deferred: no scene to prepare for");
        return false;
    }
    /* Programs of an earlier scene are not this scene's: start a fresh cache. */
    gl_program_cache_destroy(r->b.programs);
    r->b.programs = gl_program_cache_create();
    if (!r->b.programs) {
        snprintf(err, errlen, "deferred: out of memory");
        return false;
    }
    memset(r->gbuffer_program, 0, sizeof r->gbuffer_program);
    r->fog_program = 0;

    if (!renderer_base_size(&r->b, s, err, errlen))
        return false;
    r->unclipped = gl_state_fullscreen_unclipped_fits(r->b.st, r->b.width, r->b.height);

    r->variants = 0;
    r->nobjects = s->nobjects;
    r->translucency = false;   /* translucent_prepare plans the same pass, later */
    for (uint32_t i = 0; i < s->nobjects; i++) {
        uint32_t m = s->objects[i].material;
        if (m >= s->nmaterials) {
            snprintf(err, errlen, "deferred: object %u has material %u, the scene has %u", i, m,
                     s->nmaterials);
            return false;
        }
        if (!scene_material_translucent(&s->materials[m]))   /* translucent.h's */
            r->variants |= 1u << deferred_material_variant(&s->materials[m]);
        else
            r->translucency = true;
    }
    r->light_types = 0;
    memset(r->count, 0, sizeof r->count);
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        unsigned t = (unsigned)s->lights[i].type;
        if (t >= DEFERRED_LIGHT_TYPES) {
            snprintf(err, errlen, "deferred: light %u has an unknown type %u", i, t);
            return false;
        }
        r->light_types |= 1u << t;
        r->count[t]++;
    }
    r->needs = deferred_needs_of(s);
    if (r->lpp)
        deferred_layout_light_prepass(r->needs, &r->layout);
    else if (!deferred_layout_build(&r->b.opts, r->needs, &r->layout, err, errlen))
        return false;

    /* >>the scene on the GPU, the frontend (light volumes, not object sets) and the shadow
     * maps, whose plan the pass plan reads */
    if (!renderer_base_scene(&r->b, s, false, err, errlen))
        return false;

    /* >>the pass plan's common entries (the renderer adds its lighting's) */
    deferred_plan(r, PASS_SHADOWS, r->b.shadows.run, "%s", r->b.shadows.reason);
    deferred_plan(r, PASS_GBUFFER, true,
                  "%u objects into %d attachments (%s, %u bytes/pixel)", s->nobjects,
                  r->layout.nattachments,
                  r->lpp ? (r->needs.pbr ? "light pre-pass: normal, rough, f0"
                                         : "light pre-pass: normal, shininess")
                         : deferred_preset_name(r->b.opts.gbuffer),
                  deferred_layout_bytes_per_pixel(&r->layout));
    deferred_plan(r, PASS_COMPOSE, r->b.opts.separate_specular, "%s",
                  r->b.opts.separate_specular ? "specular light added into the diffuse light"
                                              : "diffuse and specular light share one target");
    if (renderer_base_fog(&r->b))
        deferred_plan(r, PASS_FOG, true, "full screen after the lights: depth to view z, "
                      "exp(-%g z) of the light kept (seed 000 4.5.12)",
                      (double)r->b.opts.fog_density);
    else
        deferred_plan(r, PASS_FOG, false, "fog off (fog.density 0)");
    deferred_plan(r, PASS_SKY, s->sky, "%s",
                  s->sky ? "into untouched depth, last" : "the scene has no sky");
    deferred_plan(r, PASS_RESOLVE, true, "light clamped into the output framebuffer");
    deferred_plan(r, PASS_MSAA, r->b.samples > 1, "the %d samples of the light averaged (a "
                  "blit, linear HDR)", r->b.samples);
    return true;
}

void deferred_prepare_end(deferred_renderer *r)
{
    char why[512] = "";
    translucent_reason(&r->translucent, true, why, sizeof why);
    deferred_plan(r, PASS_TRANSLUCENT, r->translucent.run, "%s", why);
    r->prepared = true;
}

// >>per frame

void deferred_pass_begin(deferred_renderer *r, frame_stats *out, deferred_pass p)
{
    renderer_base_pass_begin(&r->b, out, pass_names[p]);
}

void deferred_pass_end(deferred_renderer *r, frame_stats *out)
{
    renderer_base_pass_end(&r->b, out);
}

/* The sky mask (docs/notes/deferred.md): bit 7 marks a surface. */
static const gls_stencil SURFACE_MARK = {
    .enabled = true, .front = {.compare = GLS_COMPARE_ALWAYS, .pass = GLS_STENCIL_OP_REPLACE},
    .ref = 0x80, .write_mask = 0x80};

void deferred_bind_gbuffer_textures(deferred_renderer *r)
{
    for (int i = 0; i < r->layout.nattachments; i++)
        gl_state_texture(r->b.st, DEFERRED_FIRST_GBUFFER_UNIT + (unsigned)i, r->gbuf[i].texture);
    if (r->layout.position == DEFERRED_POSITION_DEPTH_BUFFER)
        gl_state_texture(r->b.st, DEFERRED_DEPTH_UNIT, r->depth_sampled.texture
                                                           ? r->depth_sampled.texture
                                                           : r->b.depth.texture);
}

void deferred_fullscreen(deferred_renderer *r)
{
    gl_state_draw_fullscreen(r->b.st, r->b.width, r->b.height, r->unclipped);
}

bool deferred_frame_begin(deferred_renderer *r, const scene *s, frame_stats *out)
{
    gl_state *st = r->b.st;
    out->npasses = 0;
    out->lights_drawn = 0;
    if (!r->prepared || !s)
        return false;
    renderer_base_begin_frame(&r->b, s, out);   /* every frame counted alike */
    renderer_base_shadow_pass(&r->b, s, out);      /* first: the light passes sample them */

    /* >>gbuffer */
    deferred_pass_begin(r, out, PASS_GBUFFER);
    gl_state_framebuffer(st, r->fb_gbuffer.fbo);
    gl_state_viewport(st, 0, 0, r->b.width, r->b.height);
    gl_state_clear(st, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, NULL,
                   1.0, r->b.opts.light_volumes == LIGHT_VOLUMES_STENCIL_TWO_PASS ? 1 : 0);
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    gl_state_blend(st, NULL);
    gl_state_stencil(st, r->b.opts.sky_stencil ? &SURFACE_MARK : NULL);   /* the sky mask */
    gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});
    gl_state_cull(st, GLS_CULL_BACK);
    for (uint32_t k = 0; k < r->b.fe.nvisible; k++) {
        uint32_t o = r->b.fe.visible[k];
        unsigned v = deferred_material_variant(&s->materials[s->objects[o].material]);
        gl_state_program(st, r->gbuffer_program[v]);
        scene_gpu_draw_object(r->b.gpu, st, s, o);
    }
    if (r->depth_sampled.texture) {   /* position from depth: what the light passes sample */
        GLenum target = r->b.samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
        gl.CopyImageSubData(r->b.depth.texture, target, 0, 0, 0, 0, r->depth_sampled.texture,
                            target, 0, 0, 0, 0, r->b.width, r->b.height, 1);
    }
    deferred_pass_end(r, out);
    return true;
}

/* Fog after the lights (deferred_fog.frag): into the light target alone, blended so
 * that light' = colour (1 - f) + light f, alpha kept; the sky comes after it. */
static const gls_blend BLEND_FOG = {.enabled = true, .src = GLS_BLEND_ONE,
                                    .dst = GLS_BLEND_SRC_ALPHA, .op = GLS_BLEND_OP_ADD,
                                    .src_alpha = GLS_BLEND_ZERO, .dst_alpha = GLS_BLEND_ONE,
                                    .op_alpha = GLS_BLEND_OP_ADD};

static void fog_pass(deferred_renderer *r, frame_stats *out)
{
    gl_state *st = r->b.st;
    deferred_pass_begin(r, out, PASS_FOG);
    gl_state_framebuffer(st, r->fb_fog.fbo);
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    gl_state_blend(st, &BLEND_FOG);
    gl_state_depth(st, NULL);
    gl_state_stencil(st, NULL);
    gl_state_cull(st, GLS_CULL_NONE);
    gl_state_texture(st, DEFERRED_DEPTH_UNIT, r->b.depth.texture);
    gl_state_program(st, r->fog_program);
    renderer_base_per_sample(&r->b, r->b.samples > 1);   /* msaa: per sample everywhere */
    deferred_fullscreen(r);
    renderer_base_per_sample(&r->b, false);
    /* the depth target is drawn with (sky) next: not bound for sampling meanwhile */
    if (r->layout.position != DEFERRED_POSITION_DEPTH_BUFFER)
        gl_state_texture(st, DEFERRED_DEPTH_UNIT, 0);
    deferred_pass_end(r, out);
}

void deferred_frame_end(deferred_renderer *r, const scene *s, frame_stats *out, GLuint hdr_fbo)
{
    gl_state *st = r->b.st;
    if (r->run[PASS_FOG])
        fog_pass(r, out);

    /* >>sky: last, into untouched depth */
    if (r->run[PASS_SKY]) {
        deferred_pass_begin(r, out, PASS_SKY);
        gl_state_framebuffer(st, hdr_fbo);
        gl_state_viewport(st, 0, 0, r->b.width, r->b.height);
        gl_state_blend(st, NULL);
        gl_state_stencil(st, NULL);
        gl_state_cull(st, GLS_CULL_NONE);
        gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_LEQUAL, .write = false});
        scene_gpu_draw_sky(r->b.gpu, st);
        deferred_pass_end(r, out);
    }

    /* >>translucent: forward, over the opaque light and depth (seed 001 19.8.1) */
    if (r->run[PASS_TRANSLUCENT])
        translucent_draw(&r->translucent, &r->b, r->b.gpu, &r->b.fe, s, &r->b.shadows, hdr_fbo, out);

    /* >>resolve: msaa > 1, the samples averaged first (renderers/frame/base.h) */
    renderer_base_msaa_resolve_pass(&r->b, out);

    /* >>edge-aa (aa: edge), its normals from the G-buffer */
    GLuint gb[DEFERRED_MAX_ATTACHMENTS];
    for (int i = 0; i < r->layout.nattachments; i++)
        gb[i] = r->gbuf[i].texture;
    edge_aa_pass(&r->b, out, gb, r->layout.nattachments);

    /* >>resolve */
    deferred_pass_begin(r, out, PASS_RESOLVE);
    renderer_base_single_sampled(out);   /* the output */
    gl_state_blend(st, NULL);
    gl_state_stencil(st, NULL);
    gl_state_depth(st, NULL);
    gl_state_cull(st, GLS_CULL_NONE);
    scene_gpu_resolve(r->b.gpu, st, renderer_base_display(&r->b)->texture, r->b.output_fbo,
                      r->b.width, r->b.height);
    deferred_pass_end(r, out);
}

static void describe_target(const gl_target *t, pass_plan *out)
{
    if (!t->texture || out->ntargets >= sizeof out->target / sizeof out->target[0])
        return;
    gl_target_describe(t, &out->target[out->ntargets++]);
    out->target_bytes += t->bytes;
}

void deferred_describe(const void *self, pass_plan *out)
{
    const deferred_renderer *r = self;
    memset(out, 0, sizeof *out);
    if (!r->prepared)
        return;
    for (int i = 0; i < PASS_COUNT && out->npasses < RENDERER_MAX_PASSES; i++) {
        deferred_pass p = describe_order[i];
        if ((p == PASS_TILED || p == PASS_TLISTS) && !r->tiled)
            continue;   /* deferred's plan is what it always was */
        if (p == PASS_COARSE && !r->reason[p][0])
            continue;   /* planned only with tiles.levels: 2 */
        if (p == PASS_MATERIAL && !r->lpp)
            continue;
        if ((p == PASS_EDGES || p == PASS_MSAA) && r->b.samples <= 1)
            continue;   /* single-sampled: the plan is what it always was */
        if (p == PASS_RESOLVE)
            edge_aa_describe_pass(&r->b, out);   /* run or skipped, before the resolve */
        if (out->npasses >= RENDERER_MAX_PASSES)
            break;
        pass_plan_entry *e = &out->pass[out->npasses++];
        snprintf(e->name, sizeof e->name, "%s", pass_names[p]);
        e->run = r->run[p];
        snprintf(e->reason, sizeof e->reason, "%s", r->reason[p]);
    }
    renderer_base_describe(&r->b, out);
    scene_gpu_describe(r->b.gpu, out);
    for (int i = 0; i < r->layout.nattachments; i++) {
        describe_target(&r->gbuf[i], out);
        out->gbuffer_bytes += r->gbuf[i].bytes;
    }
    describe_target(&r->b.hdr, out);
    describe_target(&r->specular, out);
    describe_target(&r->lbuf_diffuse, out);
    describe_target(&r->lbuf_specular, out);
    describe_target(&r->b.depth, out);
    describe_target(&r->depth_sampled, out);
    describe_target(&r->b.hdr_resolved, out);
    edge_aa_describe_target(&r->b, out);
    shadow_maps_describe(&r->b.shadows, out);
}

// >>for tests

const deferred_layout *deferred_gbuffer_layout(const void *self)
{
    const deferred_renderer *r = self;
    return r && r->prepared ? &r->layout : NULL;
}

const gl_target *deferred_hdr_target(const void *self)
{
    const deferred_renderer *r = self;
    return r && r->prepared ? &r->b.hdr : NULL;
}

const gl_target *deferred_gbuffer_target(const void *self, int k)
{
    const deferred_renderer *r = self;
    if (!r || !r->prepared || k < 0 || k >= r->layout.nattachments)
        return NULL;
    return &r->gbuf[k];
}

const gl_target *deferred_depth_target(const void *self)
{
    const deferred_renderer *r = self;
    return r && r->prepared ? &r->b.depth : NULL;
}

gl_state *deferred_state_cache(void *self)
{
    deferred_renderer *r = self;
    return r ? r->b.st : NULL;
}

/* The "light" target (with separate_specular "light.diffuse", which the compose pass
 * has added "light.specular" into: the sum of both, what resolve clamps). */
bool deferred_read_hdr(void *self, float *rgba, int width, int height)
{
    const deferred_renderer *r = self;
    return r && r->prepared && renderer_base_read_hdr(&r->b, rgba, width, height);
}

gbuffer_traffic deferred_traffic(const void *self, const frame_stats *fs)
{
    const deferred_renderer *r = self;
    return deferred_gbuffer_traffic(r->prepared ? deferred_layout_bytes_per_pixel(&r->layout) : 0,
                                    r->b.width, r->b.height, fs);
}

uint64_t deferred_draws_per_light(const renderer_estimate *e)
{
    (void)e;
    return 2;
}

uint64_t deferred_gbuffer_own_bytes(const renderer_estimate *e)
{
    unsigned bpp = deferred_gbuffer_bytes_per_pixel(
        e->opts, e->scene ? e->needs : (deferred_needs){.gloss = true, .emissive = true});
    uint64_t samples = e->samples * e->pixels;
    uint64_t b = (uint64_t)(bpp ? bpp : 64) * samples;
    if (e->opts->separate_specular)
        b += e->hdr_bytes * samples;
    return b;
}
