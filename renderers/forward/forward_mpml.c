/* forward-mpml: multi-pass multi-light forward shading (seed 000 4.6).
 * Its passes and the draw calls per frame: the comment above struct forward_mpml
 * below. */
#include "renderers/forward/forward_common.h"
#include "renderers/frame/shading.h"

#include <assert.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The most directional lights directional_in_base folds into the base pass (its
 * u_base_lights array takes 5 uniform locations each from LOC_BASE_LIGHTS); a scene
 * with more is refused in prepare. */
#define MPML_BASE_DIRECTIONAL_MAX 8

/* A frame's passes:
 *
 *   shadows  (some spot or directional light casts shadows, shadows not off) the
 *            shadow maps of the frame's shadow-casting lights (renderers/frame/shadow.h):
 *            one depth-only draw per object of each one's shadow-casting set
 *   base     depth, ambient and emissive of every visible object in one pass
 *            (4.6.2): depth LESS with writes, no blending; forward_base.frag. With
 *            forward.directional_in_base (renderer_options.directional_in_base) and
 *            a scene with directional lights, its BASE_DIRECTIONAL variant also
 *            shades the frame's directional lights (in their SHADOWS variant when
 *            one of them casts shadows; the pool is bound for it), which then get no
 *            light pass: our own option, not seed 000's design (4.6.5 and 6.3: the
 *            canyon's forward renderer drew each mesh twice, "one for the ambient
 *            term and one for the directional light")
 *   lights   for each visible light (frontend order) an additive pass (blend ONE,
 *            ONE) with depth test EQUAL and no depth writes over the objects of its
 *            illumination set (4.6.1: visible objects whose bounds intersect the
 *            light's volume; every visible object for a directional light, 4.6.5),
 *            in `visible` order, so the state buckets hold within each light's set;
 *            forward_light.frag compiled per (light type x material variant) pair
 *            the scene has, in its SHADOWS variant (seed 000 4.6.4: the light's map
 *            looked up from the interpolated position, lighting.inc + shadow.inc)
 *            for a type some light of which casts shadows. With forward.illumination_sets false
 *            (renderer_options.no_illumination_sets) every light draws every visible
 *            object (the brute force of seed 000 5.6). Runs when the scene has lights
 *            (with directional_in_base: point or spot lights).
 *   sky      the sky into untouched depth, when the scene has one
 *   translucent  (the scene has translucent objects) renderers/frame/translucent.h: one
 *            blended draw per visible translucent object, back to front, all lights
 *   resolve  the HDR target clamped into the output framebuffer
 *
 * Draw calls per frame, with V visible opaque objects, T visible translucent ones, the
 * visible lights l, I(l) the illumination set of l and C(l) the shadow-casting set of a
 * visible light that casts shadows this frame (frontend.h; none when the shadows pass does not run):
 *
 *     draws = sum over shadowed l of |C(l)|
 *             + V + sum over l of |I(l)|  (V per light without illumination sets)
 *             + (1 if the scene has a sky) + T + 1
 *
 * (|I(l)| = V for a directional light.) With directional_in_base the sum runs over
 * the point and spot lights only: D x V fewer draws for D visible directional lights.
 * A light whose set is empty draws nothing and is not counted in lights_drawn (a
 * folded directional light counts when V > 0, as its pass would have drawn). */
typedef struct forward_mpml {
    forward_common c;   /* first: forward_common_new makes the object; read as it */
    bool lights_pass;        /* the scene has lights */
    GLuint light_program[FORWARD_LIGHT_TYPES][FORWARD_VARIANTS];
    /* The light each program's u_light holds: a serial per light drawn, never reused,
     * so u_light is uploaded once per (light, program) and never stale. */
    uint64_t serial;
    uint64_t program_serial[FORWARD_LIGHT_TYPES][FORWARD_VARIANTS];
    unsigned cur_type;
    gpu_light cur;           /* the light being drawn, packed in view space */
    /* directional_in_base: the scene's directional lights (the BASE_DIRECTIONAL size),
     * the frame's packed into base_lights, uploaded once per (frame, base program) */
    bool fold;               /* the option is on and the scene has directional lights */
    uint32_t base_max;
    char base_define[32];
    gpu_light base_lights[MPML_BASE_DIRECTIONAL_MAX];
    int base_count;
    uint64_t frame;
    uint64_t base_frame[FORWARD_VARIANTS];
} forward_mpml;
_Static_assert(offsetof(forward_mpml, c) == 0, "forward_common_new: the object begins with c");

static const char *const light_type_define[FORWARD_LIGHT_TYPES] = {
    [LIGHT_POINT] = "LIGHT_TYPE LIGHT_POINT",
    [LIGHT_SPOT] = "LIGHT_TYPE LIGHT_SPOT",
    [LIGHT_DIRECTIONAL] = "LIGHT_TYPE LIGHT_DIRECTIONAL",
};

static const char *const light_program_name[FORWARD_LIGHT_TYPES] = {
    [LIGHT_POINT] = "forward_point",
    [LIGHT_SPOT] = "forward_spot",
    [LIGHT_DIRECTIONAL] = "forward_directional",
};
/* The SHADOWS variants (point lights have none) */
static const char *const shadowed_program_name[FORWARD_LIGHT_TYPES] = {
    [LIGHT_POINT] = "forward_point",
    [LIGHT_SPOT] = "forward_spot_shadowed",
    [LIGHT_DIRECTIONAL] = "forward_directional_shadowed",
};

/* The base pass with the directional lights folded in: forward_base.frag's
 * BASE_DIRECTIONAL variant for every material variant present (and SHADOWS when a
 * directional light casts shadows), into c.base_program. */
static bool compile_folded_base(forward_mpml *r, const scene *s, char *err, size_t errlen)
{
    forward_common *c = &r->c;
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->nlights_total; i++)
        n += s->lights[i].type == LIGHT_DIRECTIONAL;
    if (n > MPML_BASE_DIRECTIONAL_MAX) {
        snprintf(err, errlen,
                 "forward-mpml: forward.directional_in_base shades at most %d directional "
                 "lights in the base pass; the scene has %u",
                 MPML_BASE_DIRECTIONAL_MAX, n);
        return false;
    }
    r->base_max = n;
    snprintf(r->base_define, sizeof r->base_define, "BASE_DIRECTIONAL %u", n);
    const char *extra[4] = {r->base_define, NULL, NULL, NULL};
    const char *name = forward_shadow_defines(c, LIGHT_DIRECTIONAL, extra + 1)
                           ? "forward_base_directional_shadowed"
                           : "forward_base_directional";
    for (unsigned v = 0; v < FORWARD_VARIANTS; v++)
        if ((c->variants & (1u << v)) &&
            !forward_program(c, name, "forward_base.frag", v, extra, &c->base_program[v], err,
                             errlen))
            return false;
    return true;
}

static void *mpml_create(const renderer_options *opts, char *err, size_t errlen)
{
    forward_mpml *r = forward_common_new(sizeof *r, "forward-mpml", opts, err, errlen);
    if (r)
        r->c.illumination_sets = true;   /* the one renderer that draws them */
    return r;
}

static bool mpml_prepare(void *self, const struct scene *s, char *err, size_t errlen)
{
    forward_mpml *r = self;
    memset(r->light_program, 0, sizeof r->light_program);
    memset(r->program_serial, 0, sizeof r->program_serial);
    memset(r->base_frame, 0, sizeof r->base_frame);
    r->frame = 0;
    r->base_max = 0;
    r->fold = false;
    if (!forward_common_prepare(&r->c, s, err, errlen))
        return false;
    r->fold = r->c.b.opts.directional_in_base &&
              (r->c.light_types & (1u << LIGHT_DIRECTIONAL));
    /* the light types that get passes of their own */
    unsigned passes = r->c.light_types & ~(r->fold ? 1u << LIGHT_DIRECTIONAL : 0u);
    r->lights_pass = passes != 0;
    if (r->fold ? !compile_folded_base(r, s, err, errlen)
                : !forward_compile_base(&r->c, err, errlen))
        goto fail;
    for (unsigned t = 0; t < FORWARD_LIGHT_TYPES; t++) {
        if (!(passes & (1u << t)))
            continue;
        const char *extra[4] = {light_type_define[t], NULL, NULL, NULL};
        const char *name = forward_shadow_defines(&r->c, (int)t, extra + 1)
                               ? shadowed_program_name[t]
                               : light_program_name[t];
        for (unsigned v = 0; v < FORWARD_VARIANTS; v++)
            if ((r->c.variants & (1u << v)) &&
                !forward_program(&r->c, name, "forward_light.frag", v, extra,
                                 &r->light_program[t][v], err, errlen))
                goto fail;
    }
    return true;
fail:
    r->c.prepared = false;
    return false;
}

/* forward_draw_objects' hook: the current light into the program's u_light, once
 * per (light, program). */
static void mpml_on_program(void *user, unsigned variant, GLuint program)
{
    forward_mpml *r = user;
    (void)program;
    uint64_t *held = &r->program_serial[r->cur_type][variant];
    if (*held != r->serial) {
        gl.Uniform4fv(FORWARD_UNIFORM_LIGHT, 5, &r->cur.v[0][0]);
        *held = r->serial;
    }
}

/* forward_draw_objects' hook in the folded base pass: the frame's directional lights
 * into u_base_lights and u_base_count, once per (frame, program). */
static void base_on_program(void *user, unsigned variant, GLuint program)
{
    forward_mpml *r = user;
    (void)program;
    if (r->base_frame[variant] == r->frame)
        return;
    if (r->base_count > 0)
        gl.Uniform4fv(LOC_BASE_LIGHTS, 5 * r->base_count, &r->base_lights[0].v[0][0]);
    gl.Uniform1i(FORWARD_UNIFORM_LIGHT, r->base_count);
    r->base_frame[variant] = r->frame;
}

/* A frame; priming (mpml_prime): the lights pass draws the first light of each kind
 * (type, with or without a shadow map) over every visible object, which is every state
 * the frame's light draws use, not 65,536 lights' 655,360 draws. */
static void mpml_frame(forward_mpml *r, const struct scene *s, frame_stats *out, bool priming)
{
    forward_common *c = &r->c;
    forward_begin_frame(c, s, out);
    const frontend *fe = &c->b.fe;
    const bool sets = !c->b.opts.no_illumination_sets;

    uint32_t lights_drawn = 0;
    if (r->fold) {
        /* the frame's directional lights, in frontend order, for the base pass */
        r->frame++;
        r->base_count = 0;
        for (uint32_t k = 0; k < fe->nlights; k++) {
            const scene_light *l = &s->lights[fe->lights[k]];
            if (l->type != LIGHT_DIRECTIONAL || r->base_count >= (int)r->base_max)
                continue;
            gpu_light *g = &r->base_lights[r->base_count++];
            shading_pack_light(l, s->view, g);
            shading_set_shadow_layer(g, fe->shadow_layer[k]);
        }
        if (fe->nvisible > 0)
            lights_drawn += (uint32_t)r->base_count;
    }

    forward_pass_begin(c, out, "base");
    forward_bind_target(c);
    gl_state_blend(c->b.st, NULL);
    gl_state_stencil(c->b.st, NULL);
    forward_clear_target(c);
    gl_state_depth(c->b.st, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});
    if (r->fold)
        shadow_maps_bind(&c->b.shadows, c->b.st);
    forward_draw_objects(c, s, fe->visible, fe->nvisible, c->base_program,
                         r->fold ? base_on_program : NULL, r);
    forward_pass_end(c, out);

    uint64_t light_draws = 0;
    unsigned primed = 0;   /* the kinds of light drawn, when priming */
    if (r->lights_pass) {
        forward_pass_begin(c, out, "lights");
        forward_bind_target(c);
        gl_state_blend(c->b.st, &(gls_blend){.enabled = true, .src = GLS_BLEND_ONE,
                                           .dst = GLS_BLEND_ONE, .op = GLS_BLEND_OP_ADD});
        gl_state_depth(c->b.st, &(gls_depth){.compare = GLS_COMPARE_EQUAL, .write = false});
        shadow_maps_bind(&c->b.shadows, c->b.st);
        for (uint32_t k = 0; k < fe->nlights; k++) {
            const uint32_t *objects = fe->visible;
            uint32_t n = fe->nvisible;
            if (sets) {
                objects = fe->illum + fe->illum_start[k];
                n = fe->illum_start[k + 1] - fe->illum_start[k];
            }
            const scene_light *l = &s->lights[fe->lights[k]];
            if (r->fold && l->type == LIGHT_DIRECTIONAL)
                continue;
            if (priming) {   /* the kind's first light, over every visible object */
                unsigned kind = 1u << (2u * (unsigned)l->type +
                                       (fe->shadow_layer[k] != FRONTEND_NO_SHADOW));
                if (primed & kind)
                    continue;
                primed |= kind;
                objects = fe->visible;
                n = fe->nvisible;
            }
            if (n == 0)
                continue;
            r->serial++;
            r->cur_type = (unsigned)l->type;
            shading_pack_light(l, s->view, &r->cur);
            shading_set_shadow_layer(&r->cur, fe->shadow_layer[k]);
            forward_draw_objects(c, s, objects, n, r->light_program[r->cur_type],
                                 mpml_on_program, r);
            light_draws += n;
            lights_drawn++;
        }
        forward_pass_end(c, out);
    }
    out->lights_drawn = lights_drawn;
    forward_end_frame(c, out, light_draws);
}

static void mpml_draw(void *self, const struct scene *s, frame_stats *out)
{
    mpml_frame(self, s, out, false);
}

static void mpml_prime(void *self, const struct scene *s, frame_stats *out)
{
    mpml_frame(self, s, out, true);
}

static void mpml_describe(const void *self, pass_plan *out)
{
    const forward_mpml *r = self;
    const forward_common *c = &r->c;
    forward_describe_begin(c, out);
    if (r->fold)
        forward_describe_pass(out, "base", true,
                              "depth, ambient, emissive and %u directional light%s "
                              "(forward.directional_in_base)",
                              r->base_max, r->base_max == 1 ? "" : "s");
    else
        forward_describe_pass(out, "base", true, "%s",
                              c->b.opts.directional_in_base && c->prepared
                                  ? "depth, ambient and emissive (seed 000 4.6.2); no directional "
                                    "light to fold in"
                                  : "depth, ambient and emissive of the visible objects (seed "
                                    "000 4.6.2)");
    if (c->prepared && r->fold && !r->lights_pass)
        forward_describe_pass(out, "lights", false,
                              "skipped: the scene's only lights are directional, shaded in the "
                              "base pass");
    else if (!c->prepared || r->lights_pass)
        forward_describe_pass(out, "lights", true, "%s",
                              r->fold ? (c->b.opts.no_illumination_sets
                                             ? "per point and spot light, every visible object, "
                                               "depth EQUAL, additive (sets off)"
                                             : "per point and spot light, its illumination set, "
                                               "depth EQUAL, additive (4.6.3)")
                              : c->b.opts.no_illumination_sets
                                  ? "per visible light, every visible object, depth EQUAL, "
                                    "additive (illumination sets off)"
                                  : "per visible light, its illumination set, depth EQUAL, "
                                    "additive (seed 000 4.6.3)");
    else
        forward_describe_pass(out, "lights", false, "skipped, the scene has no lights");
    forward_describe_tail(c, out);
}

static void mpml_destroy(void *self)
{
    forward_common_free(self);
}

/* The meshes each light reaches, counted as half of the scene's. */
static uint64_t mpml_draws_per_light(const renderer_estimate *e)
{
    return (e->nmeshes + 1) / 2;
}

const renderer_impl renderer_forward_mpml_impl = RENDERER_IMPL(
    mpml, "forward-mpml", "forward.illumination_sets forward.directional_in_base hdr msaa fog aa",
    "multi-pass multi-light forward (seed 000 4.6): a depth, ambient and "
    "emissive pass, then an additive depth-EQUAL pass per visible light "
    "over its illumination set",
    .read_hdr = forward_read_hdr, .draws_per_light = mpml_draws_per_light,
    .prime = mpml_prime);
