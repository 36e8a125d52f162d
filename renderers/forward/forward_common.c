/* What the forward renderers share (forward_common.h). */
#include "renderers/forward/forward_common.h"

#include <assert.h>

#include "renderers/frame/edge_aa.h"
#include "renderers/frame/shading.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(sizeof(gpu_light) == 80, "gpu_light is 5 vec4s, as lighting.inc's Light");

/* Every scene mesh is closed or a shell seen from inside (mesh.h): back faces never
 * show, so they are culled. */
#define FORWARD_CULL GLS_CULL_BACK

unsigned forward_material_variant(const scene_material *m)
{
    return (m->diffuse_map >= 0 ? FORWARD_VARIANT_DIFFUSE : 0u) |
           (m->gloss_map >= 0 ? FORWARD_VARIANT_GLOSS : 0u) |
           (m->normal_map >= 0 ? FORWARD_VARIANT_NORMAL : 0u) |
           (m->emissive_map >= 0 ? FORWARD_VARIANT_EMISSIVE : 0u) |
           (m->alpha == MATERIAL_MASK ? FORWARD_VARIANT_ALPHA_TEST : 0u);
}

// >>creation and preparation

void *forward_common_new(size_t size, const char *name, const renderer_options *opts,
                         char *err, size_t errlen)
{
    forward_common *fc = size >= sizeof *fc ? calloc(1, size) : NULL;
    if (!fc) {
        snprintf(err, errlen, "%s: out of memory", name);
        return NULL;
    }
    if (!renderer_base_init(&fc->b, name, opts, FORWARD_MAX_PASSES, err, errlen)) {
        forward_common_free(fc);
        return NULL;
    }
    return fc;
}

static void release_prepared(forward_common *fc)
{
    translucent_release(&fc->translucent);
    gl_framebuffer_destroy(&fc->fb);
    renderer_base_release_targets(&fc->b);
    renderer_base_release_scene(&fc->b);
    fc->prepared = false;
}

void forward_common_free(forward_common *fc)
{
    if (!fc)
        return;
    release_prepared(fc);
    renderer_base_destroy(&fc->b);
    free(fc);
}

bool forward_common_prepare(forward_common *fc, const scene *s, char *err, size_t errlen)
{
    char why[512] = "";
    release_prepared(fc);
    if (!s) {
        snprintf(err, errlen, "%s: no scene to prepare for", fc->b.name);
        return false;
    }
    if (!renderer_base_size(&fc->b, s, err, errlen))
        return false;
    fc->sky = s->sky;

    fc->variants = 0;
    for (unsigned v = 0; v < FORWARD_VARIANTS; v++) {
        fc->nobjects_variant[v] = 0;
        fc->base_program[v] = 0;
    }
    for (uint32_t i = 0; i < s->nobjects; i++) {
        uint32_t m = s->objects[i].material;
        if (m >= s->nmaterials) {
            snprintf(err, errlen, "%s: object %u has material %u, the scene has %u", fc->b.name,
                     i, m, s->nmaterials);
            return false;
        }
        if (scene_material_translucent(&s->materials[m]))
            continue;   /* the translucent pass's (translucent.h) */
        unsigned v = forward_material_variant(&s->materials[m]);
        fc->variants |= 1u << v;
        fc->nobjects_variant[v]++;
    }
    fc->light_types = 0;
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        unsigned t = (unsigned)s->lights[i].type;
        if (t >= FORWARD_LIGHT_TYPES) {
            snprintf(err, errlen, "%s: light %u has an unknown type %u", fc->b.name, i, t);
            return false;
        }
        fc->light_types |= 1u << t;
    }

    if (!renderer_base_scene(&fc->b, s, fc->illumination_sets, err, errlen))
        goto fail;
    if (!renderer_base_targets(&fc->b, "hdr", why, sizeof why) ||
        !gl_framebuffer_create(&fc->fb, &(gl_framebuffer_desc){.name = "forward",
                                                               .color = {&fc->b.hdr},
                                                               .depth_stencil = &fc->b.depth},
                               why, sizeof why)) {
        snprintf(err, errlen, "%s: %s", fc->b.name, why);
        goto fail;
    }
    if (!edge_aa_prepare(&fc->b, NULL, 0, err, errlen))   /* normals from depth */
        goto fail;
    if (!translucent_prepare(&fc->translucent, &fc->b, s, &fc->b.shadows,
                             fc->translucent_later, err, errlen))
        goto fail;
    fc->prepared = true;
    return true;
fail:
    release_prepared(fc);
    return false;
}

bool forward_program(forward_common *fc, const char *display, const char *fragment,
                     unsigned variant, const char *const *extra, GLuint *program, char *err,
                     size_t errlen)
{
    gl_program_desc d = {.name = display, .vertex = "mesh.vert", .fragment = fragment};
    unsigned n = 0;
    /* The map defines of shading_material_defines (those of the deferred G-buffer
     * pass too, so both see the same surface), from a material with just the maps
     * of the variant. */
    scene_material mat = {.diffuse_map = -1, .gloss_map = -1, .normal_map = -1,
                          .emissive_map = -1};
    if (variant & FORWARD_VARIANT_DIFFUSE)
        mat.diffuse_map = 0;
    if (variant & FORWARD_VARIANT_GLOSS)
        mat.gloss_map = 0;
    if (variant & FORWARD_VARIANT_NORMAL)
        mat.normal_map = 0;
    if (variant & FORWARD_VARIANT_EMISSIVE)
        mat.emissive_map = 0;
    if (variant & FORWARD_VARIANT_ALPHA_TEST)
        mat.alpha = MATERIAL_MASK;
    const char *defs[SHADING_MATERIAL_DEFINES] = {NULL};
    unsigned k = shading_material_defines(&mat, defs);
    for (unsigned i = 0; i < k && i < SHADING_MATERIAL_DEFINES; i++)
        d.defines[n++] = defs[i];
    for (unsigned i = 0; extra && extra[i]; i++) {
        if (n + 2 >= GLP_MAX_DEFINES) {
            snprintf(err, errlen, "bug: %s: too many defines for %s", fc->b.name, display);
            return false;
        }
        d.defines[n++] = extra[i];
    }
    /* fog at the end of the shading (fog.inc): only the programs of a foggy run */
    if (renderer_base_fog(&fc->b))
        d.defines[n++] = "FOG";
    char why[4096] = "";
    if (gl_program_get(fc->b.programs, &d, program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "%s: %s", fc->b.name, why);
        return false;
    }
    renderer_base_fog_uniform(&fc->b, *program);
    return true;
}

bool forward_compile_base(forward_common *fc, char *err, size_t errlen)
{
    for (unsigned v = 0; v < FORWARD_VARIANTS; v++)
        if ((fc->variants & (1u << v)) &&
            !forward_program(fc, "forward_base", "forward_base.frag", v, NULL,
                             &fc->base_program[v], err, errlen))
            return false;
    return true;
}

// >>per frame

void forward_light_count_once(uint64_t *seen, uint64_t frame, int count)
{
    if (*seen != frame) {
        gl.Uniform1i(FORWARD_UNIFORM_LIGHT, count);
        *seen = frame;
    }
}

void forward_begin_frame(forward_common *fc, const scene *s, frame_stats *out)
{
    renderer_base_begin_frame(&fc->b, s, out);
    fc->frame_scene = s;
    renderer_base_shadow_pass(&fc->b, s, out);
}

unsigned forward_shadow_defines(const forward_common *fc, int type, const char *defs[2])
{
    if (type >= 0 && !shadow_maps_for_type(&fc->b.shadows, type))
        return 0;
    return shadow_maps_defines(&fc->b.shadows, defs);
}

void forward_pass_begin(forward_common *fc, frame_stats *out, const char *name)
{
    renderer_base_pass_begin(&fc->b, out, name);
}

void forward_pass_end(forward_common *fc, frame_stats *out)
{
    renderer_base_pass_end(&fc->b, out);
}

void forward_bind_target(forward_common *fc)
{
    gl_state_framebuffer(fc->b.st, fc->fb.fbo);
    gl_state_viewport(fc->b.st, 0, 0, fc->b.width, fc->b.height);
}

void forward_clear_target(forward_common *fc)
{
    static const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    gl_state_clear(fc->b.st, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT,
                   black, 1.0, 0);
}

void forward_draw_objects(forward_common *fc, const scene *s, const uint32_t *objects,
                          uint32_t n, const GLuint programs[FORWARD_VARIANTS],
                          forward_program_fn on_program, void *user)
{
    gl_state_cull(fc->b.st, FORWARD_CULL);
    for (uint32_t k = 0; k < n; k++) {
        uint32_t o = objects[k];
        unsigned v = forward_material_variant(&s->materials[s->objects[o].material]);
        gl_state_program(fc->b.st, programs[v]);
        if (on_program)
            on_program(user, v, programs[v]);
        scene_gpu_draw_object(fc->b.gpu, fc->b.st, s, o);
    }
}

void forward_sky_pass(forward_common *fc, frame_stats *out)
{
    forward_pass_begin(fc, out, "sky");
    forward_bind_target(fc);
    scene_gpu_draw_sky(fc->b.gpu, fc->b.st);   /* depth LEQUAL, no writes: where depth is 1 */
    forward_pass_end(fc, out);
}

void forward_resolve_pass(forward_common *fc, frame_stats *out)
{
    forward_pass_begin(fc, out, "resolve");
    renderer_base_single_sampled(out);   /* the output */
    scene_gpu_resolve(fc->b.gpu, fc->b.st, renderer_base_display(&fc->b)->texture,
                      fc->b.output_fbo, fc->b.width, fc->b.height);
    forward_pass_end(fc, out);
}

// >>describe

void forward_describe_pass(pass_plan *out, const char *name, bool run, const char *fmt, ...)
{
    if (out->npasses >= RENDERER_MAX_PASSES)
        return;
    pass_plan_entry *e = &out->pass[out->npasses++];
    snprintf(e->name, sizeof e->name, "%s", name);
    e->run = run;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->reason, sizeof e->reason, fmt, ap);
    va_end(ap);
}

void forward_describe_resources(const forward_common *fc, pass_plan *out)
{
    renderer_base_describe(&fc->b, out);
    scene_gpu_describe(fc->b.gpu, out);   /* sky and resolve */
    out->ntargets = 0;
    out->target_bytes = 0;
    const gl_target *targets[] = {&fc->b.hdr, &fc->b.depth, &fc->b.hdr_resolved};
    for (size_t i = 0; i < sizeof targets / sizeof targets[0]; i++) {
        if (!targets[i]->texture)
            continue;
        gl_target_describe(targets[i], &out->target[out->ntargets++]);
        out->target_bytes += targets[i]->bytes;
    }
    edge_aa_describe_target(&fc->b, out);
    shadow_maps_describe(&fc->b.shadows, out);
    out->gbuffer_bytes = 0;
}

void forward_describe_begin(const forward_common *fc, pass_plan *out)
{
    const shadow_maps *sm = &fc->b.shadows;
    out->npasses = 0;
    if (!fc->prepared ||
        sm->asking[LIGHT_POINT] + sm->asking[LIGHT_SPOT] + sm->asking[LIGHT_DIRECTIONAL] == 0)
        return;
    forward_describe_pass(out, "shadows", sm->run, "%s", sm->reason);
}

// >>forward-spml's light limit

uint32_t forward_spml_max_lights(int max_uniform_block_size)
{
    if (max_uniform_block_size <= 0)
        return 0;
    return (uint32_t)((size_t)max_uniform_block_size / sizeof(gpu_light));
}

// >>for tests

const gls_counts *forward_last_pass_counts(const void *self, size_t pass)
{
    const forward_common *fc = self;
    return fc ? renderer_base_pass_counts(&fc->b, pass) : NULL;
}

const gl_target *forward_hdr_target(const void *self)
{
    const forward_common *fc = self;
    return fc ? &fc->b.hdr : NULL;
}

const gl_target *forward_depth_target(const void *self)
{
    const forward_common *fc = self;
    return fc ? &fc->b.depth : NULL;
}


bool forward_read_hdr(void *self, float *rgba, int width, int height)
{
    const forward_common *fc = self;
    return fc && fc->prepared && renderer_base_read_hdr(&fc->b, rgba, width, height);
}

void forward_end_frame(forward_common *fc, frame_stats *out, uint64_t light_draws)
{
    if (fc->sky)
        forward_sky_pass(fc, out);
    uint64_t translucent_draws = translucent_draw(&fc->translucent, &fc->b, fc->b.gpu, &fc->b.fe,
                                                  fc->frame_scene, &fc->b.shadows, fc->fb.fbo, out);
    renderer_base_msaa_resolve_pass(&fc->b, out);   /* msaa > 1 only */
    edge_aa_pass(&fc->b, out, NULL, 0);   /* aa: edge */
    forward_resolve_pass(fc, out);
    uint64_t shadow_draws = fc->b.shadows.run ? fc->b.fe.shadow_start[fc->b.fe.nlights] : 0u;
    uint64_t expected = shadow_draws + (uint64_t)fc->b.fe.nvisible + light_draws +
                        (fc->sky ? 1u : 0u) + translucent_draws + (fc->b.aa.run ? 1u : 0u) + 1u;
    assert(translucent_draws == (fc->translucent.run ? fc->b.fe.ntranslucent : 0u));
    uint64_t draws = 0;
    for (size_t i = 0; i < out->npasses; i++)
        draws += out->pass[i].draw_calls;
    assert(draws == expected);
    (void)draws;
    (void)expected;
}

void forward_describe_tail(const forward_common *fc, pass_plan *out)
{
    if (renderer_base_fog(&fc->b))
        forward_describe_pass(out, "fog", true,
                              "no pass of its own: in the shading passes' FOG variants, "
                              "exp(-%g z) of the light kept", (double)fc->b.opts.fog_density);
    else
        forward_describe_pass(out, "fog", false, "skipped, fog off (fog.density 0)");
    if (!fc->prepared || fc->sky)
        forward_describe_pass(out, "sky", true, "the sky, last, into untouched depth");
    else
        forward_describe_pass(out, "sky", false, "skipped, the scene has no sky");
    char why[256];
    translucent_reason(&fc->translucent, fc->prepared, why, sizeof why);
    forward_describe_pass(out, "translucent", !fc->prepared || fc->translucent.run, "%s", why);
    if (fc->b.samples > 1)
        forward_describe_pass(out, "msaa-resolve", true,
                              "the %d samples of the HDR target averaged (a blit, linear HDR)",
                              fc->b.samples);
    edge_aa_describe_pass(&fc->b, out);
    forward_describe_pass(out, "resolve", true,
                          "the HDR target clamped into the output framebuffer");
    forward_describe_resources(fc, out);
}
