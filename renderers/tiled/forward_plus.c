/* forward-plus: tiled forward shading (Harada, McKee and Yang, "Forward+", EG 2012).
 *
 * Passes: [shadows], depth pre-pass, ONE cull dispatch (tile_cull.comp) that writes
 * every tile's light list into one dynamically sized index buffer, shade (depth EQUAL,
 * forward_tiled.frag loops its tile's list), sky, [translucent], resolve. The lights are
 * packed as forward-spml packs them, in one storage buffer sized by the light grid
 * (renderers/tiled/grid.h). clustered's forward shading is this file too.
 *
 * Each pass in detail, the draw counts, overflow, MSAA and the counters: the comment
 * above forward_tiled_draw. */
#include "renderers/forward/forward_common.h"
#include "renderers/frame/shading.h"
#include "renderers/tiled/grid.h"
#include "renderers/tiled/tiled.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct forward_plus {
    forward_common c;   /* first: forward_common_new makes the object; read as it */
    const char *name;        /* "forward-plus" or "clustered" */
    light_grid g;            /* tiles, or clusters (g.slices_y) */
    GLuint depth_program, cull_program;
    GLuint program[FORWARD_VARIANTS];
    GLuint depth_ranges;     /* msaa > 1 with the cull pass: per tile its range (vec2) */
    char samples_define[24];
    uint64_t frame;
    uint64_t program_frame[FORWARD_VARIANTS];
    int count;               /* lights uploaded this frame */
} forward_plus;
_Static_assert(offsetof(forward_plus, c) == 0, "forward_common_new: the object begins with c");

void *forward_tiled_new(const char *name, bool clustered, const renderer_options *opts,
                           char *err, size_t errlen)
{
    forward_plus *r = forward_common_new(sizeof *r, name, opts, err, errlen);
    if (!r)
        return NULL;
    r->name = name;
    r->c.grid = &r->g;
    r->c.translucent_later = true;   /* forward_tiled_prepare: over the tile lists or not */
    if (!light_grid_tile_option(&r->g, name, opts, err, errlen))
        goto fail;
    if (clustered && !light_grid_slices_option(&r->g, name, opts, err, errlen))
        goto fail;
    light_grid_culling_option(&r->g, &r->c.b, opts);
    return r;
fail:
    forward_common_free(&r->c);
    return NULL;
}

static void *forward_tiled_create(const renderer_options *opts, char *err, size_t errlen)
{
    return forward_tiled_new("forward-plus", false, opts, err, errlen);
}

static void release_buffers(forward_plus *r)
{
    light_grid_release(&r->g);
    if (r->depth_ranges)
        gl.DeleteBuffers(1, &r->depth_ranges);
    r->depth_ranges = 0;
}

static bool forward_tiled_prepare(void *self, const struct scene *s, char *err, size_t errlen)
{
    forward_plus *r = self;
    release_buffers(r);
    memset(r->program, 0, sizeof r->program);
    memset(r->program_frame, 0, sizeof r->program_frame);
    r->depth_program = r->cull_program = 0;
    if (!forward_common_prepare(&r->c, s, err, errlen))
        return false;
    forward_common *c = &r->c;
    light_grid *g = &r->g;
    if (!light_grid_size(g, s, c->b.width, c->b.height,
                         (c->light_types & ((1u << LIGHT_POINT) | (1u << LIGHT_SPOT))) != 0,
                         c->translucent.run, err, errlen))
        goto fail;
    int max_block = light_grid_max_block();
    if (!light_grid_heads_fit(g, g->slices ? "clusters" : "tiles", max_block, err, errlen) ||
        !light_grid_lights_fit(g, s->nlights_total, max_block, err, errlen) ||
        !light_grid_zbin_fit(g, max_block, err, errlen))
        goto fail;
    light_grid_capacity(g, c->b.opts.max_lights_per_tile, max_block);

    /* programs */
    light_grid_defines(g);
    /* msaa > 1: the cull reads every sample, and shading gets the tiles' ranges */
    bool ms = c->b.samples > 1;
    snprintf(r->samples_define, sizeof r->samples_define, "MSAA_SAMPLES %d", c->b.samples);
    const char *grid_defs[8] = {g->tile_define, g->tiles_x_define,
                                g->slices ? g->tiles_y_define : NULL,
                                g->slices ? g->slices_define : NULL,
                                g->slices ? g->slices_y_define : NULL,
                                ms ? "TILE_DEPTH_RANGES" : NULL, light_grid_mask_define(g),
                                light_grid_zbin_define(g)};
    /* the cull's defines: grid_defs without the NULLs, then the samples, then TLISTS
     * when it builds translucent lists (a NULL ends the list) */
    const char *cull_defs[12] = {NULL};
    unsigned ncull = 0;
    for (unsigned i = 0; i < 8; i++)
        if (grid_defs[i])
            cull_defs[ncull++] = grid_defs[i];
    if (ms)
        cull_defs[ncull++] = r->samples_define;
    if (g->ntlists)
        cull_defs[ncull++] = g->tlists_define;
    if (light_grid_prune_define(g))
        cull_defs[ncull++] = light_grid_prune_define(g);
    if (light_grid_coarse_lists_define(g))
        cull_defs[ncull++] = light_grid_coarse_lists_define(g);
    char why[4096] = "";
    if (gl_program_get(c->b.programs,
                       &(gl_program_desc){.name = "depth_only", .vertex = "mesh.vert",
                                          .fragment = "depth_only.frag"},
                       &r->depth_program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "%s: %s", r->name, why);
        goto fail;
    }
    if (g->cull &&
        gl_program_get(c->b.programs,
                       &(gl_program_desc){
                           .name = g->slices ? (g->ntlists ? "cluster_cull_translucent"
                                                           : "cluster_cull")
                                             : (g->ntlists ? "tile_cull_translucent"
                                                           : "tile_cull"),
                           .compute = "tile_cull.comp",
                           .defines = {cull_defs[0], cull_defs[1], cull_defs[2],
                                       cull_defs[3], cull_defs[4], cull_defs[5],
                                       cull_defs[6], cull_defs[7], cull_defs[8],
                                       cull_defs[9], cull_defs[10]}},
                       &r->cull_program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "%s: %s", r->name, why);
        goto fail;
    }
    if (!light_grid_coarse_compile(g, c->b.programs, ms ? r->samples_define : NULL, err,
                                   errlen) ||
        !light_grid_zbin_compile(g, c->b.programs, err, errlen))
        goto fail;
    const char *extra[12] = {NULL};
    unsigned k = 0;
    if (g->cull) {
        for (unsigned i = 0; i < 8; i++)
            if (grid_defs[i])
                extra[k++] = grid_defs[i];
    } else {
        extra[k++] = "NO_GRID";
    }
    bool shadowed = forward_shadow_defines(c, -1, extra + k) != 0;
    const char *name = shadowed ? "forward_tiled_shadowed" : "forward_tiled";
    for (unsigned v = 0; v < FORWARD_VARIANTS; v++)
        if ((c->variants & (1u << v)) &&
            !forward_program(c, name, "forward_tiled.frag", v, extra, &r->program[v], err,
                             errlen))
            goto fail;

    /* buffers */
    if (!light_grid_alloc(g)) {
        snprintf(err, errlen, "%s: out of memory for %u lights and %u cells", r->name,
                 s->nlights_total, g->ncells);
        goto fail;
    }
    if (!forward_grid_prepare_end(c, &r->depth_ranges, err, errlen))
        goto fail;
    return true;
fail:
    release_buffers(r);
    c->prepared = false;
    return false;
}

static void plus_on_program(void *user, unsigned variant, GLuint program)
{
    forward_plus *r = user;
    forward_light_count_once(&r->program_frame[variant], r->frame, r->count);
}

static void bind_buffers(forward_plus *r)
{
    light_grid_bind_lights(&r->g, r->c.b.st);
    if (r->g.cull) {
        light_grid_bind_lists(&r->g, r->c.b.st);
        if (r->depth_ranges)
            gl_state_storage_buffer(r->c.b.st, BIND_SSBO_TILE_DEPTH, r->depth_ranges);
    }
}

/*   shadows  (some spot or directional light casts shadows, shadows not off) as every
 *            renderer (renderers/frame/shadow.h)
 *   depth    the visible objects, depth only (mesh.vert + depth_only.frag, colour
 *            mask off), depth LESS with writes: the pre-pass the tiles are cut from
 *   cull     (only when the scene has a point or spot light) ONE compute dispatch of
 *            tiles_x x tiles_y work groups (tile_cull.comp): per tile its depth range
 *            from the pre-pass and its frustum, every light of the frame tested
 *            against them, the passing lights' indices written into one index buffer,
 *            dynamically sized: each tile takes its place with one atomicAdd after
 *            counting, so no tile has a budget of its own (see "overflow" below). The
 *            dispatch samples the depth target, so the output framebuffer (no texture
 *            attached) is bound for it: texturing from an image attached to the bound
 *            draw framebuffer is undefined, compute shaders included (GL 4.5 section 9.3;
 *            the state cache's feedback-loop check, state.h)
 *   shade    the visible objects again, depth EQUAL without writes:
 *            forward_tiled.frag adds ambient, emissive and the lights of its tile's
 *            list (directional lights pass every tile's test, so each list holds the
 *            same terms as forward-spml's loop, in the same order); without the cull
 *            pass every light of the frame (all directional) is looped
 *   sky, [translucent], resolve   as every renderer (translucent.h); when the cull
 *            pass runs, the translucent pass loops its tile's translucent list, which
 *            the cull dispatch builds after the opaque lists when (and only when) the
 *            scene has translucent objects (TLISTS, tile_cull.inc: every light against
 *            the tile's planes from the camera's near plane to the tile's max depth, or
 *            to the far side where some pixel of the tile has no geometry), per tile for
 *            clustered too: its clusters cover only the slices the tile's opaque depth
 *            range meets, so a pane's own cluster may be empty. Same index buffer, same
 *            overflow rule; heads after the opaque cells (b_tiles[cells + tile])
 *
 * Draw calls per frame, with V visible objects (dispatches counted apart):
 *
 *     draws = sum over shadowed l of |C(l)| + V (depth) + V (shade) + sky + 1
 *     dispatches = 1 when the scene has a point or spot light, else 0
 *
 * The lights: the frame's visible lights packed as forward-spml packs them
 * (shading_pack_light) in one storage buffer (lights.inc) sized for the run's lights: the light grid's
 * (renderers/tiled/grid.h: tiles, clusters, buffers, the index cap and the counters).
 *
 * Overflow: the index buffer's size is the grid's (grid.h). A tile whose list does not
 * fit is never truncated: it is left empty, and collect, seeing more entries asked for
 * than the buffer holds, puts the total, the capacity and the longest tile with its
 * count into frame_stats.overflow (the run fails as failed:overflow).
 *
 * MSAA (msaa > 1; renderers/frame/base.h): the same passes, draws and dispatch. The depth
 * pre-pass writes the multisampled depth; the cull pass (tile_cull.comp with
 * MSAA_SAMPLES) reads every sample of every pixel of its tile with texelFetch and a
 * sample index (no resolved depth copy: a copy would keep one depth per pixel and
 * cull a light that reaches only another sample), so the tile's depth range holds
 * every sample with geometry; it also writes that range per tile (b_tile_depth,
 * TILE_DEPTH_RANGES, one more small buffer). The shade pass draws into the
 * multisampled HDR target, depth EQUAL per sample, shading once per pixel at its
 * centre with the coverage of the samples it passes on, as forward-spml does; a
 * fragment whose centre's view z falls outside its tile's range (the centre of a
 * partly covered pixel is extrapolated) loops every light of the frame instead of
 * the tile's or cluster's list, so it adds what forward-spml adds. Then the base's
 * msaa-resolve and the resolve. clustered with clustered.shading: deferred shades in
 * tiled_deferred.c's compute pass (per-tile edge lists, as tiled-deferred). Counters count a pixel with geometry when some sample has it
 * (a cluster's: in the slice of its nearest sample). At msaa 1 none of this exists.
 *
 * Counters (collect, after the frame's sync point, so reading them never stalls):
 * grid_cells = tiles, the mean and largest list length over the tiles, and the light
 * evaluations per shaded pixel = sum over tiles of length x pixels with geometry /
 * pixels with geometry; renderer_light_grid gives the lengths (lightgrid.csv). */
static void forward_tiled_draw(void *self, const struct scene *s, frame_stats *out)
{
    forward_plus *r = self;
    forward_common *c = &r->c;
    forward_begin_frame(c, s, out);
    const frontend *fe = &c->b.fe;

    /* the frame's visible lights, as forward-spml packs them */
    uint32_t n = light_grid_upload_lights(&r->g, s, fe);
    r->count = (int)n;
    r->frame++;

    forward_pass_begin(c, out, "depth");
    renderer_base_shading(&c->b, false);   /* depth only: no samples shaded */
    forward_bind_target(c);
    gl_state_blend(c->b.st, NULL);
    gl_state_stencil(c->b.st, NULL);
    forward_clear_target(c);
    gl_state_color_mask(c->b.st, GLS_COLOR_MASK_NONE);
    gl_state_depth(c->b.st, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});
    gl_state_cull(c->b.st, GLS_CULL_BACK);
    gl_state_program(c->b.st, r->depth_program);
    for (uint32_t k = 0; k < fe->nvisible; k++)
        scene_gpu_draw_object_geometry(c->b.gpu, c->b.st, s, fe->visible[k]);
    forward_pass_end(c, out);

    if (r->g.coarse_x) {   /* tiles.levels: 2: the big tiles first (coarse.c) */
        forward_pass_begin(c, out, "cull-coarse");
        gl_state_framebuffer(c->b.st, c->b.output_fbo);
        gl_state_texture(c->b.st, BIND_TEX_DEPTH, c->b.depth.texture);
        if (r->g.zbin_program)   /* zbin: the big tiles' lists index the sorted lights */
            light_grid_zbin_dispatch(&r->g, c->b.st, (uint32_t)r->count);
        light_grid_bind_lights(&r->g, c->b.st);
        light_grid_coarse_dispatch(&r->g, c->b.st, (uint32_t)r->count);
        forward_pass_end(c, out);
    }
    if (r->g.cull) {
        out->grid_pass = out->npasses + 1;
        forward_pass_begin(c, out, "cull");
        if (r->g.zbin_program && !r->g.coarse_x)   /* zbin: sorted and binned first */
            light_grid_zbin_dispatch(&r->g, c->b.st, (uint32_t)r->count);
        light_grid_reset(&r->g);
        gl_state_program(c->b.st, r->cull_program);
        gl.Uniform1i(FORWARD_UNIFORM_LIGHT, r->count);
        /* no draw framebuffer that has the sampled depth attached (the header) */
        gl_state_framebuffer(c->b.st, c->b.output_fbo);
        gl_state_texture(c->b.st, BIND_TEX_DEPTH, c->b.depth.texture);   /* x samples */
        bind_buffers(r);
        light_grid_dispatch(&r->g, c->b.st);
        gl_state_barrier(c->b.st, GL_SHADER_STORAGE_BARRIER_BIT);
        /* the depth target is drawn to next: not bound for sampling meanwhile */
        gl_state_texture(c->b.st, BIND_TEX_DEPTH, 0);
        forward_pass_end(c, out);
    }

    forward_pass_begin(c, out, "shade");
    forward_bind_target(c);
    gl_state_color_mask(c->b.st, GLS_COLOR_MASK_RGBA);
    gl_state_depth(c->b.st, &(gls_depth){.compare = GLS_COMPARE_EQUAL, .write = false});
    bind_buffers(r);
    shadow_maps_bind(&c->b.shadows, c->b.st);
    forward_draw_objects(c, s, fe->visible, fe->nvisible, r->program, plus_on_program, r);
    forward_pass_end(c, out);

    out->lights_drawn = n;
    forward_end_frame(c, out, fe->nvisible);
}

static void forward_tiled_describe(const void *self, pass_plan *out)
{
    const forward_plus *r = self;
    const forward_common *c = &r->c;
    const light_grid *g = &r->g;
    forward_describe_begin(c, out);
    forward_describe_pass(out, "depth", true, "the visible objects, depth only");
    if (g->levels == 2 && (!c->prepared || g->coarse_x))
        forward_describe_pass(out, "cull-coarse", true,
                              "%sone dispatch: %ux%u big tiles of %d px, lights culled per big "
                              "tile; each tile culls its big tile's list",
                              g->zbins ? "zbin's sort and bins (dispatches of many groups), "
                                         "then " : "",
                              g->coarse_x, g->coarse_y, g->coarse);
    else if (g->levels == 2)
        forward_describe_pass(out, "cull-coarse", false,
                              "skipped, the scene has no point or spot light");
    if ((!c->prepared || g->cull) && g->slices)
        forward_describe_pass(out, "cull", true,
                              "one dispatch: %ux%ux%u clusters (%d px, r = %.4g), lights "
                              "culled per cluster",
                              g->tiles_x, g->tiles_y, g->slices, g->tile, g->slice_ratio);
    else if ((!c->prepared || g->cull) && g->zbins)
        forward_describe_pass(out, "cull", true,
                              "the lights sorted by view depth into %u depth bins "
                              "(dispatches of many groups%s), then a bit mask over them for "
                              "each of %ux%u tiles of %d px",
                              g->zbins, g->coarse_x ? ", in cull-coarse" : "", g->tiles_x, g->tiles_y, g->tile);
    else if (!c->prepared || g->cull)
        forward_describe_pass(out, "cull", true,
                              "one dispatch: %ux%u tiles of %d px, lights culled per tile "
                              "into %u indices",
                              g->tiles_x, g->tiles_y, g->tile, g->capacity);
    else
        forward_describe_pass(out, "cull", false,
                              "skipped, the scene has no point or spot light");
    forward_grid_describe_translucent(c, out);
    forward_describe_pass(out, "shade", true,
                          g->cull ? (g->zbins ? "every visible object once, depth EQUAL, "
                                                "its tile mask's lights within its bin"
                                     : g->slices ? "every visible object once, depth EQUAL, "
                                                 "its cluster's lights"
                                               : "every visible object once, depth EQUAL, "
                                                 "its tile's lights")
                                  : "every visible object once, depth EQUAL, every light");
    forward_describe_tail(c, out);
}

RENDERER_DESTROY(forward_tiled, release_buffers, forward_common_free)

const renderer_impl renderer_forward_plus_impl = RENDERER_IMPL(
    forward_tiled, "forward-plus",
    "tiles lights.culling lights.culling_error hdr msaa fog aa",
    "tiled forward (Harada et al. 2012): depth pre-pass, lights culled per "
    "screen tile by a compute pass, each pixel shaded with its tile's lights",
    .collect = forward_grid_collect, .read_hdr = forward_read_hdr,
    .light_grid = forward_grid_counts);
