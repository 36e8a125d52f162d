/* The translucent pass (translucent.h). */
#include "renderers/frame/translucent.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/frame/bindings.h"

unsigned translucent_variant(const scene_material *m)
{
    return (m->diffuse_map >= 0 ? 1u : 0u) | (m->gloss_map >= 0 ? 2u : 0u) |
           (m->normal_map >= 0 ? 4u : 0u) | (m->emissive_map >= 0 ? 8u : 0u);
}

void translucent_release(translucent_pass *t)
{
    light_buffer_release(&t->lights);
    memset(t, 0, sizeof *t);   /* programs belong to the renderer's cache */
}

/* grid NULL: forward_spml.frag over the pass's light buffer; else forward_tiled.frag
 * over the grid's translucent lists. */
static bool compile(translucent_pass *t, renderer_base *b, unsigned v, const shadow_maps *sm,
                    const translucent_grid *grid, char *err, size_t errlen)
{
    scene_material mat = {.diffuse_map = (v & 1u) ? 0 : -1, .gloss_map = (v & 2u) ? 0 : -1,
                          .normal_map = (v & 4u) ? 0 : -1, .emissive_map = (v & 8u) ? 0 : -1};
    gl_program_desc d = {.vertex = "mesh.vert",
                         .fragment = grid ? "forward_tiled.frag" : "forward_spml.frag"};
    const char *defs[SHADING_MATERIAL_DEFINES] = {NULL};
    unsigned n = 0, k = shading_material_defines(&mat, defs);
    for (unsigned i = 0; i < k; i++)
        d.defines[n++] = defs[i];
    if (grid)
        for (unsigned i = 0; i < sizeof grid->defines / sizeof grid->defines[0]; i++)
            d.defines[n++] = grid->defines[i];
    else
        d.defines[n++] = "LIGHTS_STORAGE";
    d.defines[n++] = "TRANSLUCENT";
    const char *sdefs[2] = {NULL, NULL};
    unsigned ns = sm->run ? shadow_maps_defines(sm, sdefs) : 0;
    for (unsigned i = 0; i < ns; i++)
        d.defines[n++] = sdefs[i];
    if (renderer_base_fog(b))
        d.defines[n++] = "FOG";
    d.name = grid ? (ns ? "translucent_tiled_shadowed" : "translucent_tiled")
                  : (ns ? "translucent_shadowed" : "translucent");
    char why[4096] = "";
    if (gl_program_get(b->programs, &d, &t->program[v], why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "%s: %s", b->name, why);
        return false;
    }
    renderer_base_fog_uniform(b, t->program[v]);
    return true;
}

bool translucent_prepare(translucent_pass *t, renderer_base *b, const scene *s,
                         const shadow_maps *sm, bool later, char *err, size_t errlen)
{
    translucent_release(t);
    for (uint32_t i = 0; i < s->nobjects; i++) {
        uint32_t m = s->objects[i].material;
        if (m < s->nmaterials && scene_material_translucent(&s->materials[m])) {
            t->nobjects++;
            t->variants |= 1u << translucent_variant(&s->materials[m]);
        }
    }
    t->run = t->nobjects > 0;
    if (!t->run)
        return true;
    for (unsigned v = 0; !later && v < TRANSLUCENT_VARIANTS; v++)
        if ((t->variants & (1u << v)) && !compile(t, b, v, sm, NULL, err, errlen))
            goto fail;
    t->capacity = s->nlights_total ? s->nlights_total : 1u;
    if (!light_buffer_create(&t->lights, t->capacity)) {
        snprintf(err, errlen, "%s: out of memory for %u lights", b->name, t->capacity);
        goto fail;
    }
    return true;
fail:
    translucent_release(t);
    return false;
}

bool translucent_compile(translucent_pass *t, renderer_base *b, const shadow_maps *sm,
                         const translucent_grid *g, char *err, size_t errlen)
{
    if (!t->run)
        return true;
    for (unsigned v = 0; v < TRANSLUCENT_VARIANTS; v++)
        if ((t->variants & (1u << v)) && !compile(t, b, v, sm, g, err, errlen))
            return false;
    if (!g)
        return true;
    light_buffer_release(&t->lights);   /* the renderer packs the lights */
    t->gridded = true;
    t->grid = *g;
    return true;
}

/* Premultiplied "over": RGB src + (1 - a) dst; the target's alpha kept. */
static const gls_blend BLEND_OVER = {.enabled = true, .src = GLS_BLEND_ONE,
                                     .dst = GLS_BLEND_ONE_MINUS_SRC_ALPHA,
                                     .op = GLS_BLEND_OP_ADD, .src_alpha = GLS_BLEND_ZERO,
                                     .dst_alpha = GLS_BLEND_ONE, .op_alpha = GLS_BLEND_OP_ADD};

uint64_t translucent_draw(translucent_pass *t, renderer_base *b, scene_gpu *gpu,
                          const frontend *fe, const scene *s, const shadow_maps *sm, GLuint fbo,
                          frame_stats *out)
{
    t->last_draws = 0;
    if (!t->run)
        return 0;
    gl_state *st = b->st;
    uint32_t n = fe->nlights < t->capacity ? fe->nlights : t->capacity;
    if (!t->gridded)
        light_buffer_pack(&t->lights, s, fe);   /* n of them: the same capacity */
    t->count = (int)n;
    t->frame++;
    renderer_base_pass_begin(b, out, "translucent");
    if (!t->gridded)
        light_buffer_upload(&t->lights);
    gl_state_framebuffer(st, fbo);
    gl_state_viewport(st, 0, 0, b->width, b->height);
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    gl_state_blend(st, &BLEND_OVER);
    gl_state_stencil(st, NULL);
    gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = false});
    gl_state_cull(st, GLS_CULL_BACK);
    if (t->gridded) {   /* the renderer's lights (this frame's, as packed here) and lists */
        gl_state_storage_buffer(st, BIND_SSBO_LIGHTS, t->grid.lights);
        gl_state_storage_buffer(st, BIND_SSBO_TILE_LISTS, t->grid.tiles);
        gl_state_storage_buffer(st, BIND_SSBO_TILE_INDICES, t->grid.indices);
    } else {
        gl_state_storage_buffer(st, BIND_SSBO_LIGHTS, t->lights.buffer);
    }
    if (sm->run)
        shadow_maps_bind(sm, st);
    for (uint32_t k = 0; k < fe->ntranslucent; k++) {
        uint32_t o = fe->translucent[k];
        unsigned v = translucent_variant(&s->materials[s->objects[o].material]);
        gl_state_program(st, t->program[v]);
        if (t->program_frame[v] != t->frame) {   /* the light count, once per program */
            gl.Uniform1i(LOC_RENDERER, t->count);
            t->program_frame[v] = t->frame;
        }
        scene_gpu_draw_object(gpu, st, s, o);
    }
    gl_state_blend(st, NULL);
    renderer_base_pass_end(b, out);
    t->last_draws = fe->ntranslucent;
    return fe->ntranslucent;
}

void translucent_reason(const translucent_pass *t, bool prepared, char *buf, size_t len)
{
    if (prepared && !t->run)
        snprintf(buf, len, "skipped: no translucent materials");
    else
        snprintf(buf, len, "%u translucent objects, back to front after the sky, %s, "
                 "blended over", t->nobjects,
                 t->gridded ? "their tile's translucent list" : "every visible light");
}
