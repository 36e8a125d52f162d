/* Edge-detect anti-aliasing, seed 001 19.5.2 (edge_aa.h). */
#include "renderers/frame/edge_aa.h"

#include <stdio.h>
#include <string.h>

#include "renderers/frame/bindings.h"
#include "renderers/gl/program.h"
#include "renderers/gl/state.h"

bool edge_aa_prepare(renderer_base *b, const char *const *gbuffer_defines, int n, char *err,
                     size_t errlen)
{
    edge_aa *e = &b->aa;
    renderer_base_release_aa(e);
    e->gbuffer_normals = false;
    if (b->opts.aa != AA_EDGE)
        return true;
    if (n < 0 || n + 2 >= GLP_MAX_DEFINES) {
        snprintf(err, errlen, "bug: %s: %d G-buffer defines for edge_aa", b->name, n);
        return false;
    }
    gl_program_desc d = {.name = "edge_aa", .vertex = "fullscreen.vert",
                         .fragment = "edge_aa.frag"};
    int k = 0;
    if (gl_state_fullscreen_unclipped_fits(b->st, b->width, b->height))
        d.defines[k++] = "FULLSCREEN_UNCLIPPED";
    if (gbuffer_defines && b->samples <= 1) {
        d.defines[k++] = "EDGE_NORMALS_GBUFFER";
        for (int i = 0; i < n; i++)
            d.defines[k++] = gbuffer_defines[i];
        e->gbuffer_normals = true;
    }
    char why[4096] = "";
    /* one sample a pixel: it blends the resolved image (msaa-resolve comes first) */
    if (!gl_target_create(&e->out, &(gl_target_desc){.name = "hdr.aa",
                                                     .format = renderer_base_hdr_format(b),
                                                     .width = b->width, .height = b->height},
                          why, sizeof why) ||
        !gl_framebuffer_create(&e->fb, &(gl_framebuffer_desc){.name = "edge-aa",
                                                              .color = {&e->out}},
                               why, sizeof why) ||
        gl_program_get(b->programs, &d, &e->program, why, sizeof why) != GLP_OK ||
        (b->samples > 1 &&
         (!gl_target_create(&e->depth1, &(gl_target_desc){.name = "depth.aa",
                                                          .format = b->depth.format,
                                                          .width = b->width,
                                                          .height = b->height},
                            why, sizeof why) ||
          !gl_framebuffer_create(&e->depth_read,
                                 &(gl_framebuffer_desc){.name = "edge-aa.depth.read",
                                                        .depth_stencil = &b->depth},
                                 why, sizeof why) ||
          !gl_framebuffer_create(&e->depth_draw,
                                 &(gl_framebuffer_desc){.name = "edge-aa.depth.draw",
                                                        .depth_stencil = &e->depth1},
                                 why, sizeof why)))) {
        snprintf(err, errlen, "%s: aa: edge: %s", b->name, why);
        renderer_base_release_aa(e);
        return false;
    }
    e->run = true;
    return true;
}

void edge_aa_pass(renderer_base *b, frame_stats *out, const GLuint *gbuffer, int n)
{
    edge_aa *e = &b->aa;
    if (!e->run)
        return;
    gl_state *st = b->st;
    renderer_base_pass_begin(b, out, "edge-aa");
    renderer_base_single_sampled(out);   /* hdr.aa: one sample */
    /* its own target alone: nothing it samples is attached */
    gl_state_framebuffer(st, e->fb.fbo);
    gl_state_blend(st, NULL);
    gl_state_depth(st, NULL);
    gl_state_stencil(st, NULL);
    gl_state_cull(st, GLS_CULL_NONE);
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    gl_state_program(st, e->program);
    GLuint depth = b->depth.texture, hdr = b->hdr.texture;
    if (b->samples > 1) {   /* the averaged colour; one depth sample a pixel */
        gl.BlitNamedFramebuffer(e->depth_read.fbo, e->depth_draw.fbo, 0, 0, b->width,
                                b->height, 0, 0, b->width, b->height, GL_DEPTH_BUFFER_BIT,
                                GL_NEAREST);
        depth = e->depth1.texture;
        hdr = b->hdr_resolved.texture;
    }
    gl_state_texture(st, BIND_TEX_HDR, hdr);
    gl_state_texture(st, BIND_TEX_DEPTH, depth);
    for (int k = 0; e->gbuffer_normals && gbuffer && k < n && k < EDGE_AA_MAX_GBUFFER; k++)
        gl_state_texture(st, BIND_TEX_GBUFFER0 + (unsigned)k, gbuffer[k]);
    gl_state_draw_fullscreen(st, b->width, b->height,
                             gl_state_fullscreen_unclipped_fits(st, b->width, b->height));
    /* the depth target is drawn into again next frame: not left bound for sampling */
    gl_state_texture(st, BIND_TEX_DEPTH, 0);
    renderer_base_pass_end(b, out);
}

void edge_aa_describe_pass(const renderer_base *b, pass_plan *out)
{
    if (out->npasses >= RENDERER_MAX_PASSES)
        return;
    pass_plan_entry *p = &out->pass[out->npasses++];
    snprintf(p->name, sizeof p->name, "edge-aa");
    p->run = b->aa.run;
    if (!b->aa.run)
        snprintf(p->reason, sizeof p->reason, "skipped, aa: none");
    else
        snprintf(p->reason, sizeof p->reason,
                 "seed 001 19.5.2: depth-gradient ratio and %s normals, edges blended",
                 b->aa.gbuffer_normals ? "G-buffer" : "depth-rebuilt");
}

void edge_aa_describe_target(const renderer_base *b, pass_plan *out)
{
    const gl_target *const targets[] = {&b->aa.out, &b->aa.depth1};   /* depth1: msaa > 1 */
    for (size_t i = 0; i < sizeof targets / sizeof targets[0]; i++) {
        const gl_target *t = targets[i];
        if (!t->texture || out->ntargets >= sizeof out->target / sizeof out->target[0])
            return;
        gl_target_describe(t, &out->target[out->ntargets++]);
        out->target_bytes += t->bytes;
    }
}
