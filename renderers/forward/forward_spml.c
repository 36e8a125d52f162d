/* forward-spml: single-pass multi-light forward shading (seed 003 4.1).
 * Its passes, the draw calls per frame and the light buffer: the comment above
 * struct forward_spml below. */
#include "renderers/forward/forward_common.h"
#include "renderers/frame/light_buffer.h"
#include "renderers/frame/shading.h"

#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A frame's passes:
 *
 *   shadows  (some spot or directional light casts shadows, shadows not off) the
 *            shadow maps of the frame's shadow-casting lights (renderers/frame/shadow.h):
 *            one depth-only draw per object of each one's shadow-casting set; all
 *            of them are in memory when the shade pass loops over the lights
 *   shade    one pass: each visible object once, forward_spml.frag adds ambient,
 *            emissive and every visible light of the frame, looped from a uniform
 *            buffer (the seed's constant buffer) with a squared-range rejection;
 *            depth LESS with writes; with shadows, every variant is the SHADOWS one
 *            and a light's layer rides in its Light (params.z), so the buffer's
 *            80 bytes per light and the light limit below do not change (the maps'
 *            matrices are in a block of their own, shadow.h)
 *   sky      the sky into untouched depth, when the scene has one
 *   translucent  (the scene has translucent objects) renderers/frame/translucent.h: one
 *            blended draw per visible translucent object, back to front, all lights
 *   resolve  the HDR target clamped into the output framebuffer
 *
 * Draw calls per frame, with V visible opaque objects and T visible translucent ones:
 *
 *     draws = sum over shadowed l of |C(l)|  (the shadows pass, see forward_mpml.c)
 *             + V + (1 if the scene has a sky) + T + 1
 *
 * The light buffer: uniform block binding 1, std140, a Light being 5 vec4s (80
 * bytes), so a context holds forward_spml_max_lights(GL_MAX_UNIFORM_BLOCK_SIZE)
 * lights: 65536 / 80 = 819 on Mesa. The shader's array size, MAX_LIGHTS, is fixed at
 * prepare from the run's largest light count (scene.nlights_total), rounded up to a
 * power of two (at least 16) and capped at that capacity, so each variant is
 * compiled once per run. A run asking for more lights than the capacity fails in
 * prepare, before anything is drawn. Each frame uploads the frontend's visible
 * lights only; their number goes to u_light_count. lights_drawn is that number. */
typedef struct forward_spml {
    forward_common c;   /* first: forward_common_new makes the object; read as it */
    uint32_t capacity;       /* lights one uniform block of the context holds */
    uint32_t max_lights;     /* MAX_LIGHTS of the programs */
    char max_lights_define[32];
    GLuint program[FORWARD_VARIANTS];
    light_buffer lights;     /* the uniform block, or the storage buffer: max_lights */
    bool storage;            /* lights from the storage buffer (forward.light_buffer) */
    /* u_light_count is set once per (frame, program): a serial per frame. */
    uint64_t frame;
    uint64_t program_frame[FORWARD_VARIANTS];
    int count;               /* lights uploaded this frame */
} forward_spml;
_Static_assert(offsetof(forward_spml, c) == 0, "forward_common_new: the object begins with c");

static void *spml_create(const renderer_options *opts, char *err, size_t errlen)
{
    forward_spml *r = forward_common_new(sizeof *r, "forward-spml", opts, err, errlen);
    if (r)
        r->capacity = forward_spml_max_lights(r->c.b.opts.max_uniform_block_size);
    return r;
}

static void release_lights(forward_spml *r)
{
    light_buffer_release(&r->lights);
}

/* The array size for n lights: a power of two >= n (at least 16), at most the capacity. */
static uint32_t array_size(uint32_t n, uint32_t capacity)
{
    uint32_t a = 16;
    while (a < n && a < capacity)
        a *= 2;
    return a < capacity ? a : capacity;
}

static bool spml_prepare(void *self, const struct scene *s, char *err, size_t errlen)
{
    forward_spml *r = self;
    release_lights(r);
    memset(r->program, 0, sizeof r->program);
    memset(r->program_frame, 0, sizeof r->program_frame);
    r->c.prepared = false;
    if (!s) {
        snprintf(err, errlen, "forward-spml: no scene to prepare for");
        return false;
    }
    uint32_t n = s->nlights_total;
    r->storage = r->c.b.opts.light_buffer == LIGHT_BUFFER_STORAGE ||
                 (r->c.b.opts.light_buffer == LIGHT_BUFFER_AUTO && n > r->capacity);
    if (!r->storage && (n > r->capacity || r->capacity == 0)) {
        snprintf(err, errlen,
                 "forward-spml: %u lights requested, this context allows at most %u "
                 "(GL_MAX_UNIFORM_BLOCK_SIZE %d / %zu bytes; forward.light_buffer: "
                 "storage has no such limit)",
                 n, r->capacity, r->c.b.opts.max_uniform_block_size, sizeof(gpu_light));
        return false;
    }
    if (!forward_common_prepare(&r->c, s, err, errlen))
        return false;
    /* storage: the buffer holds every light of the run (at least one entry) and the
     * shader's array is unsized */
    r->max_lights = r->storage ? (n ? n : 1u) : array_size(n, r->capacity);
    snprintf(r->max_lights_define, sizeof r->max_lights_define, "MAX_LIGHTS %u", r->max_lights);
    const char *extra[5] = {r->storage ? "LIGHTS_STORAGE" : r->max_lights_define, NULL, NULL,
                            NULL, NULL};
    bool shadowed = forward_shadow_defines(&r->c, -1, extra + 1) != 0;
    const char *name = r->storage ? (shadowed ? "forward_spml_storage_shadowed"
                                              : "forward_spml_storage")
                                  : (shadowed ? "forward_spml_shadowed" : "forward_spml");
    for (unsigned v = 0; v < FORWARD_VARIANTS; v++)
        if ((r->c.variants & (1u << v)) &&
            !forward_program(&r->c, name, "forward_spml.frag", v, extra,
                             &r->program[v], err, errlen))
            goto fail;

    if (!light_buffer_create(&r->lights, r->max_lights)) {
        snprintf(err, errlen, "forward-spml: out of memory for %u lights", r->max_lights);
        goto fail;
    }
    return true;
fail:
    release_lights(r);
    r->c.prepared = false;
    return false;
}

/* forward_draw_objects' hook: this frame's light count into the program, once per
 * (frame, program). */
static void spml_on_program(void *user, unsigned variant, GLuint program)
{
    forward_spml *r = user;
    forward_light_count_once(&r->program_frame[variant], r->frame, r->count);
}

static void spml_draw(void *self, const struct scene *s, frame_stats *out)
{
    forward_spml *r = self;
    forward_common *c = &r->c;
    forward_begin_frame(c, s, out);
    const frontend *fe = &c->b.fe;

    forward_pass_begin(c, out, "shade");
    /* The frame's visible lights, packed in view space. The frontend's lights are
     * at most the run's lights, which prepare made sure fit. */
    uint32_t n = light_buffer_update(&r->lights, s, fe);
    r->count = (int)n;
    r->frame++;
    if (r->storage)
        gl_state_storage_buffer(c->b.st, BIND_SSBO_LIGHTS, r->lights.buffer);
    else
        gl.BindBufferBase(GL_UNIFORM_BUFFER, FORWARD_LIGHTS_BINDING, r->lights.buffer);

    forward_bind_target(c);
    gl_state_blend(c->b.st, NULL);
    gl_state_stencil(c->b.st, NULL);
    forward_clear_target(c);
    gl_state_depth(c->b.st, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});
    shadow_maps_bind(&c->b.shadows, c->b.st);
    forward_draw_objects(c, s, fe->visible, fe->nvisible, r->program, spml_on_program, r);
    forward_pass_end(c, out);

    out->lights_drawn = n;
    forward_end_frame(c, out, 0);
}

static void spml_describe(const void *self, pass_plan *out)
{
    const forward_spml *r = self;
    const forward_common *c = &r->c;
    forward_describe_begin(c, out);
    if (r->storage)
        forward_describe_pass(out, "shade", true,
                              "every visible object once, up to %u lights from a storage "
                              "buffer",
                              r->max_lights);
    else
        forward_describe_pass(out, "shade", true,
                              "every visible object once, up to %u lights of %u from a uniform "
                              "buffer (seed 003 4.1)",
                              r->max_lights, r->capacity);
    forward_describe_tail(c, out);
}

RENDERER_DESTROY(spml, release_lights, forward_common_free)

/* The uniform light buffer's capacity; a storage buffer (or auto's fallback to one)
 * has no limit of its own. */
static uint32_t spml_max_lights(const renderer_options *o, int max_uniform_block_size)
{
    if (o && o->light_buffer != LIGHT_BUFFER_UNIFORM)
        return UINT32_MAX;
    return forward_spml_max_lights(max_uniform_block_size);
}

const renderer_impl renderer_forward_spml_impl = RENDERER_IMPL(
    spml, "forward-spml", "forward.light_buffer hdr msaa fog aa",
    "single-pass multi-light forward (seed 003 4.1): every visible light "
    "from a uniform buffer, looped in the fragment shader",
    .read_hdr = forward_read_hdr, .max_lights = spml_max_lights);
