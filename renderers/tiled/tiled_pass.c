/* The tiled (or clustered) light pass over a G-buffer (tiled_pass.h): tiled-deferred's
 * shading pass and deferred-lighting's tiled light accumulation, one compute dispatch. */
#include "renderers/tiled/tiled_pass.h"

#include "renderers/frame/bindings.h"
#include "renderers/gl/program.h"
#include "renderers/frame/shadow.h"

#include <stdio.h>
#include <string.h>

bool tiled_pass_plan(tiled_pass *t, deferred_renderer *d, const scene *s, char *err,
                     size_t errlen)
{
    light_grid *g = &t->g;
    t->nlights = s->nlights_total;
    if (!light_grid_size(g, s, d->b.width, d->b.height,
                         d->count[LIGHT_POINT] + d->count[LIGHT_SPOT] > 0, d->translucency, err,
                         errlen))
        return false;
    const char *kind = g->slices ? "clustered" : "tiled";
    if (g->ntlists)
        deferred_plan(d, PASS_TLISTS, true, "in the %s dispatch: per tile, near plane to its "
                      "max depth", kind);
    else
        deferred_plan(d, PASS_TLISTS, false, "%s", !d->translucency
                                                       ? "skipped: no translucent materials"
                                                       : "skipped: no culling, every light");
    /* tiled-deferred shades the surface; deferred-lighting accumulates the light alone */
    const char *what = d->lpp ? "into the light buffer"
                              : "ambient and lights shaded";
    const char *cull = g->slices ? "lights culled per cluster" : "lights culled per tile";
    if (!g->cull)
        cull = "no point or spot light: no culling";
    if (g->coarse_x)
        deferred_plan(d, PASS_COARSE, true, "%sone dispatch: %ux%u big tiles of %d px, "
                      "lights culled per big tile; each tile culls its big tile's list",
                      g->zbins ? "zbin's sort and bins (dispatches of many groups), then "
                               : "", g->coarse_x, g->coarse_y, g->coarse);
    else if (g->levels == 2)
        deferred_plan(d, PASS_COARSE, false, "skipped, the scene has no point or spot light");
    if (g->zbins && g->cull)
        deferred_plan(d, PASS_TILED, true, "the lights sorted by view depth into %u depth "
                      "bins (dispatches of many groups%s), then per tile of %ux%u (%d px) a "
                      "bit mask over them, each pixel its bits within its bin, %s", g->zbins,
                      g->coarse_x ? ", in the coarse pass" : "",
                      g->tiles_x, g->tiles_y, g->tile, what);
    else if (g->slices)
        deferred_plan(d, PASS_TILED, true, "one dispatch: %ux%ux%u clusters (%d px), %s, %s",
                      g->tiles_x, g->tiles_y, g->slices, g->tile, cull, what);
    else
        deferred_plan(d, PASS_TILED, true, "one dispatch: %ux%u tiles of %d px, %s, %s",
                      g->tiles_x, g->tiles_y, g->tile, cull, what);
    const char *in = g->slices ? "in the clustered pass" : "in the tiled pass";
    if (!d->lpp)   /* deferred-lighting's ambient is its material pass's (its own entry) */
        deferred_plan(d, PASS_AMBIENT, false, "%s", in);
    deferred_plan(d, PASS_DIRECTIONAL, false, "%s", in);
    deferred_plan(d, PASS_POINT, false, "%s", in);
    deferred_plan(d, PASS_SPOT, false, "%s", in);
    deferred_plan(d, PASS_EDGES, false, "msaa %d: in the %s pass: pixels whose samples differ "
                  "(the same rule) listed per tile; per sample there, per pixel elsewhere",
                  d->b.samples, g->slices_y ? "clustered" : "tiled");
    return true;
}

bool tiled_pass_buffers(tiled_pass *t, deferred_renderer *d, char *err, size_t errlen)
{
    light_grid *g = &t->g;
    int max_block = light_grid_max_block();
    if (!light_grid_lights_fit(g, t->nlights, max_block, err, errlen) ||
        !light_grid_zbin_fit(g, max_block, err, errlen))
        return false;
    light_grid_capacity(g, d->b.opts.max_lights_per_tile, max_block);
    light_grid_defines(g);
    if (!light_grid_heads_fit(g, "cells", max_block, err, errlen))
        return false;
    if (!light_grid_alloc(g)) {
        snprintf(err, errlen, "%s: out of memory for %u lights and %u tiles", d->b.name,
                 t->nlights, g->ntiles);
        return false;
    }
    if (d->b.samples > 1) {
        gl.CreateBuffers(1, &t->edges);
        gl.NamedBufferStorage(t->edges, sizeof(uint32_t), NULL, GL_DYNAMIC_STORAGE_BIT);
    }
    return true;
}

/* The program's display name: its grid, its output and whether it builds translucent
 * lists ("tiled_deferred", "clustered_light_prepass_translucent", ...). */
static const char *program_name(const tiled_pass *t, const deferred_renderer *d)
{
    static const char *const names[2][2][2] = {
        {{"tiled_deferred", "tiled_deferred_translucent"},
         {"tiled_light_prepass", "tiled_light_prepass_translucent"}},
        {{"clustered_deferred", "clustered_deferred_translucent"},
         {"clustered_light_prepass", "clustered_light_prepass_translucent"}}};
    return names[t->g.slices != 0][d->lpp][t->g.ntlists != 0];
}

bool tiled_pass_compile(tiled_pass *t, deferred_renderer *d, char *err, size_t errlen)
{
    const light_grid *g = &t->g;
    deferred_layout_defs ld;
    deferred_layout_defines(&d->layout, &ld);
    const char *extra[16] = {g->tile_define, g->tiles_x_define};
    int n = 2;
    if (d->b.samples > 1) {   /* the multisampled G-buffer, per tile edge list */
        /* the count the driver gave (known once the targets exist) */
        snprintf(t->msaa_define, sizeof t->msaa_define, "MSAA_SAMPLES %d", d->b.samples);
        extra[n++] = "GB_MSAA";
        extra[n++] = t->msaa_define;
    }
    if (d->lpp) {   /* the light buffer's two images, in its format */
        extra[n++] = "LIGHT_PREPASS";
        if (d->b.opts.lpp_light_buffer == LPP_LIGHT_BUFFER_RGBA8)
            extra[n++] = "LIGHT_BUFFER_RGBA8";
    } else if (renderer_base_hdr_define(&d->b)) {   /* the image store's format qualifier */
        extra[n++] = renderer_base_hdr_define(&d->b);
    }
    if (g->slices) {
        extra[n++] = g->tiles_y_define;
        extra[n++] = g->slices_define;
        extra[n++] = g->slices_y_define;
    }
    if (!g->cull)
        extra[n++] = "NO_GRID";
    if (g->ntlists)
        extra[n++] = g->tlists_define;
    if (light_grid_mask_define(g))
        extra[n++] = light_grid_mask_define(g);
    if (light_grid_prune_define(g))
        extra[n++] = light_grid_prune_define(g);
    if (light_grid_coarse_lists_define(g))
        extra[n++] = light_grid_coarse_lists_define(g);
    if (light_grid_zbin_define(g))
        extra[n++] = light_grid_zbin_define(g);
    n += (int)shadow_maps_defines(&d->b.shadows, extra + n);   /* any type: one program */
    gl_program_desc desc = {.name = program_name(t, d), .compute = "tiled_deferred.comp"};
    unsigned k = 0;
    for (int i = 0; i < n; i++)
        desc.defines[k++] = extra[i];
    for (int i = 0; i < ld.n && k < GLP_MAX_DEFINES; i++)
        desc.defines[k++] = ld.text[i];
    if (k < (unsigned)n + (unsigned)ld.n) {
        snprintf(err, errlen, "bug: %s: too many defines for tiled_deferred", d->b.name);
        return false;
    }
    char why[4096] = "";
    if (gl_program_get(d->b.programs, &desc, &t->program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "%s: %s", d->b.name, why);
        return false;
    }
    if (d->b.samples > 1)   /* u_sample_pos, after u_light_count */
        deferred_set_sample_positions(d, d->fb_gbuffer.fbo, t->program,
                                      DEFERRED_UNIFORM_LIGHT + 1);
    return light_grid_coarse_compile(&t->g, d->b.programs,
                                     d->b.samples > 1 ? t->msaa_define : NULL, err, errlen) &&
           light_grid_zbin_compile(&t->g, d->b.programs, err, errlen);
}

void tiled_pass_release(tiled_pass *t)
{
    light_grid_release(&t->g);
    if (t->edges)
        gl.DeleteBuffers(1, &t->edges);
    t->edges = 0;
    t->program = 0;
}

/* The dispatch's outputs: the HDR target (tiled-deferred), or deferred-lighting's light
 * buffer (diffuse light where tiled-deferred writes its HDR image, specular beside it). */
static void bind_outputs(deferred_renderer *d, gl_state *st)
{
    if (!d->lpp) {
        gl_state_image(st, BIND_IMAGE_HDR, d->b.hdr.texture, GL_WRITE_ONLY,
                       renderer_base_hdr_image_format(&d->b));
        return;
    }
    GLenum f = d->b.opts.lpp_light_buffer == LPP_LIGHT_BUFFER_RGBA8 ? GL_RGBA8 : GL_RGBA16F;
    gl_state_image(st, BIND_IMAGE_HDR, d->lbuf_diffuse.texture, GL_WRITE_ONLY, f);
    gl_state_image(st, BIND_IMAGE_LIGHT_SPECULAR, d->lbuf_specular.texture, GL_WRITE_ONLY, f);
}

void tiled_pass_run(tiled_pass *t, deferred_renderer *d, const scene *s, frame_stats *out)
{
    gl_state *st = d->b.st;
    light_grid *g = &t->g;
    t->index = 0;
    uint32_t n = light_grid_upload_lights(g, s, &d->b.fe);
    if (g->coarse_x) {   /* tiles.levels: 2: the big tiles first (coarse.c) */
        deferred_pass_begin(d, out, PASS_COARSE);
        gl_state_framebuffer(st, d->b.output_fbo);
        gl_state_texture(st, DEFERRED_DEPTH_UNIT, d->b.depth.texture);
        if (g->zbin_program)   /* zbin: the big tiles' lists index the sorted lights */
            light_grid_zbin_dispatch(g, st, n);
        light_grid_bind_lights(g, st);
        light_grid_coarse_dispatch(g, st, n);
        deferred_pass_end(d, out);
    }
    out->grid_pass = g->cull ? out->npasses + 1 : 0;
    deferred_pass_begin(d, out, PASS_TILED);
    if (g->zbin_program && !g->coarse_x)   /* zbin: sorted and binned first (zbin.c) */
        light_grid_zbin_dispatch(g, st, n);
    light_grid_reset(g);
    if (t->edges) {
        const uint32_t zero = 0;
        gl.NamedBufferSubData(t->edges, 0, sizeof zero, &zero);
        gl_state_storage_buffer(st, BIND_SSBO_EDGES, t->edges);
    }
    gl_state_program(st, t->program);
    gl.Uniform1i(LOC_RENDERER, (GLint)n);
    deferred_bind_gbuffer_textures(d);
    gl_state_texture(st, DEFERRED_DEPTH_UNIT, d->b.depth.texture);
    shadow_maps_bind(&d->b.shadows, st);
    light_grid_bind_lights(g, st);
    light_grid_bind_lists(g, st);
    bind_outputs(d, st);
    /* it samples the depth target: no draw framebuffer that has it attached */
    gl_state_framebuffer(st, d->b.output_fbo);
    light_grid_dispatch(g, st);
    /* the sky draws into the target, resolve (or the material pass) samples it; the
     * translucent pass reads the translucent lists */
    gl_state_barrier(st, GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                             (g->ntlists ? GL_SHADER_STORAGE_BARRIER_BIT : 0u));
    /* the depth target is drawn with (sky) next: not bound for sampling meanwhile */
    if (d->layout.position != DEFERRED_POSITION_DEPTH_BUFFER)
        gl_state_texture(st, DEFERRED_DEPTH_UNIT, 0);
    deferred_pass_end(d, out);
    if (t->edges)
        t->index = out->npasses;   /* 1 + its index */
    out->lights_drawn = n;
}

void tiled_pass_collect(tiled_pass *t, deferred_renderer *d, frame_stats *out)
{
    if (d->prepared && t->g.cull)
        light_grid_collect(&t->g, out);
    renderer_base_collect(&d->b, out);
    if (t->index && t->index <= out->npasses) {
        /* msaa N: the dispatch shades sample 0 of every pixel and N - 1 more samples of
         * each edge pixel; as deferred counts them: N samples per pixel, the edge pixels'
         * per sample (samples_shaded = pixels + edges (N - 1), renderer_collect) */
        gl.GetNamedBufferSubData(t->edges, 0, sizeof(uint32_t), &t->edge_pixels);
        double pixels = (double)d->b.width * d->b.height, n = d->b.samples;
        pass_stats *p = &out->pass[t->index - 1];
        p->samples = pixels * n;
        p->per_sample_samples = (double)t->edge_pixels * n;
        out->edge_fraction = t->edge_pixels / pixels;
    }
}
