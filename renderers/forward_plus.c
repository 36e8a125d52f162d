/* forward-plus: tiled forward shading (Harada, McKee and Yang, "Forward+", EG 2012).
 *
 *   shadows  (some spot or directional light casts shadows, shadows not off) as every
 *            renderer (renderers/shadow.h)
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
 * (shading_pack_light) in one storage buffer (lights.inc) sized for the run's lights.
 *
 * Overflow: the index buffer holds, per tile on average, tiles.max_lights_per_tile
 * entries (renderer_options.max_lights_per_tile), or, with 0 (the default), every
 * light of the run in every tile (cells, plus the tiles' translucent lists when built) (capped by GL_MAX_SHADER_STORAGE_BLOCK_SIZE and at
 * 2^25 entries, 128 MiB), so that no frame can run out unless that cap bites. A tile
 * whose list does not fit is never truncated: it is left empty, and collect, seeing
 * more entries asked for than the buffer holds, puts the total, the capacity and the
 * longest tile with its count into frame_stats.overflow (the run fails as
 * failed:overflow).
 *
 * MSAA (msaa > 1; renderers/base.h): the same passes, draws and dispatch. The depth
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
 * deferred.c's compute pass (per-tile edge lists, as tiled-deferred). Counters count a pixel with geometry when some sample has it
 * (a cluster's: in the slice of its nearest sample). At msaa 1 none of this exists.
 *
 * Counters (collect, after the frame's sync point, so reading them never stalls):
 * grid_cells = tiles, the mean and largest list length over the tiles, and the light
 * evaluations per shaded pixel = sum over tiles of length x pixels with geometry /
 * pixels with geometry; renderer_light_grid gives the lengths (lightgrid.csv). */
#include "renderers/deferred.h"
#include "renderers/forward_common.h"
#include "renderers/shading.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { PLUS_INDEX_CAP = 1u << 25 };

typedef struct tile_stats {
    uint32_t next, capacity;
} tile_stats;

typedef struct forward_plus {
    forward_common c;        /* first: forward_last_pass_counts() reads self as this */
    const char *name;        /* "forward-plus" or "clustered" */
    int tile;                /* pixels per tile side */
    uint32_t slices_y;       /* clustered: Olsson's S_y (clustered.slices); forward-plus: 0 */
    uint32_t slices;         /* clustered: depth slices to the far plane (prepare) */
    uint32_t tiles_x, tiles_y, ntiles;
    uint32_t ncells;         /* tiles, or tiles x slices */
    double slice_ratio;      /* clustered: far/near of each slice, (zfar/znear)^(1/slices) */
    bool grid;               /* the scene has point or spot lights: the cull pass runs */
    uint32_t ntlists;        /* tiles: the cull builds translucent lists (grid and the
                                scene has translucent objects); 0: it does not */
    uint32_t max_lights;     /* entries of the light buffer */
    uint32_t capacity;       /* entries of the index buffer */
    GLuint depth_program, cull_program;
    GLuint program[FORWARD_VARIANTS];
    GLuint lights, tiles, indices, stats;   /* buffers */
    GLuint depth_ranges;     /* msaa > 1 with the cull pass: per tile its range (vec2) */
    gpu_light *staging;      /* max_lights */
    uint32_t *readback;      /* ntiles x 4 */
    uint32_t *counts;        /* ntiles: list lengths of the last frame collected */
    bool counted;            /* counts hold a frame */
    char tile_define[24], tiles_x_define[32], tiles_y_define[32], slices_define[24];
    char slices_y_define[24], samples_define[24], tlists_define[24];
    uint64_t frame;
    uint64_t program_frame[FORWARD_VARIANTS];
    int count;               /* lights uploaded this frame */
} forward_plus;

static void *tiled_create(const char *name, bool clustered, const renderer_options *opts,
                          char *err, size_t errlen)
{
    forward_plus *r = calloc(1, sizeof *r);
    if (!r) {
        snprintf(err, errlen, "%s: out of memory", name);
        return NULL;
    }
    r->name = name;
    if (!forward_common_init(&r->c, name, opts, err, errlen))
        goto fail;
    r->c.translucent_later = true;   /* plus_prepare: over the tile lists or not */
    r->tile = opts->tile_size ? opts->tile_size : 16;
    if (r->tile != 8 && r->tile != 16 && r->tile != 32) {
        snprintf(err, errlen, "%s: tiles.size %d: expected 8, 16 or 32", name, r->tile);
        goto fail;
    }
    if (clustered) {
        int k = opts->clustered_slices ? opts->clustered_slices : 24;
        if (k < 1 || k > 64) {
            snprintf(err, errlen, "%s: clustered.slices %d: expected 1 to 64", name, k);
            goto fail;
        }
        r->slices_y = (uint32_t)k;
    }
    return r;
fail:
    forward_common_destroy(&r->c);
    free(r);
    return NULL;
}

static void *plus_create(const renderer_options *opts, char *err, size_t errlen)
{
    return tiled_create("forward-plus", false, opts, err, errlen);
}

static void *clustered_create(const renderer_options *opts, char *err, size_t errlen)
{
    return tiled_create("clustered", true, opts, err, errlen);
}

static void release_buffers(forward_plus *r)
{
    GLuint b[5] = {r->lights, r->tiles, r->indices, r->stats, r->depth_ranges};
    for (int i = 0; i < 5; i++)
        if (b[i])
            gl.DeleteBuffers(1, &b[i]);
    r->lights = r->tiles = r->indices = r->stats = r->depth_ranges = 0;
    free(r->staging);
    free(r->readback);
    free(r->counts);
    r->staging = NULL;
    r->readback = r->counts = NULL;
    r->counted = false;
}

static GLuint make_buffer(size_t bytes)
{
    GLuint b = 0;
    gl.CreateBuffers(1, &b);
    gl.NamedBufferStorage(b, (GLsizeiptr)bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
    return b;
}

static bool plus_prepare(void *self, const struct scene *s, char *err, size_t errlen)
{
    forward_plus *r = self;
    release_buffers(r);
    memset(r->program, 0, sizeof r->program);
    memset(r->program_frame, 0, sizeof r->program_frame);
    r->depth_program = r->cull_program = 0;
    if (!forward_common_prepare(&r->c, s, err, errlen))
        return false;
    forward_common *c = &r->c;
    r->tiles_x = (uint32_t)((c->b.width + r->tile - 1) / r->tile);
    r->tiles_y = (uint32_t)((c->b.height + r->tile - 1) / r->tile);
    r->ntiles = r->tiles_x * r->tiles_y;
    r->slices = 0;
    if (r->slices_y) {
        r->slices = shading_cluster_slices(s, (int)r->slices_y, &r->slice_ratio);
        if (r->slices > 1024) {
            snprintf(err, errlen,
                     "%s: %u depth slices from near %g to far %g (each %.4g times deeper, "
                     "clustered.slices %u): at most 1024; raise near or lower clustered.slices",
                     r->name, r->slices, (double)s->cam.znear, (double)s->cam.zfar,
                     r->slice_ratio, r->slices_y);
            goto fail;
        }
    }
    r->ncells = r->ntiles * (r->slices ? r->slices : 1u);
    r->grid = (c->light_types & ((1u << LIGHT_POINT) | (1u << LIGHT_SPOT))) != 0;
    r->ntlists = r->grid && c->translucent.run ? r->ntiles : 0u;
    uint32_t heads = r->ncells + r->ntlists;   /* opaque cells, then translucent lists */
    uint32_t n = s->nlights_total;
    r->max_lights = n ? n : 1u;

    GLint max_block = 0;
    gl.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    if (!light_grid_heads_fit(r->name, heads, r->slices ? "clusters" : "tiles", r->slices > 0,
                              max_block, err, errlen))
        goto fail;
    uint64_t block_entries = max_block > 0 ? (uint64_t)max_block / 4u : 0u;
    if ((uint64_t)r->max_lights * sizeof(gpu_light) > (uint64_t)(max_block > 0 ? max_block : 0)) {
        snprintf(err, errlen,
                 "%s: %u lights need %llu bytes of storage buffer, this context "
                 "allows %d (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)",
                 r->name, n, (unsigned long long)r->max_lights * sizeof(gpu_light), max_block);
        goto fail;
    }
    uint64_t want = c->b.opts.max_lights_per_tile
                        ? (uint64_t)heads * c->b.opts.max_lights_per_tile
                        : (uint64_t)heads * r->max_lights;
    if (want > block_entries)
        want = block_entries;
    if (want > PLUS_INDEX_CAP)
        want = PLUS_INDEX_CAP;
    r->capacity = (uint32_t)(want ? want : 1u);

    /* programs */
    snprintf(r->tile_define, sizeof r->tile_define, "TILE_SIZE %d", r->tile);
    snprintf(r->tiles_x_define, sizeof r->tiles_x_define, "TILES_X %u", r->tiles_x);
    snprintf(r->tiles_y_define, sizeof r->tiles_y_define, "TILES_Y %u", r->tiles_y);
    snprintf(r->slices_define, sizeof r->slices_define, "SLICES %u", r->slices);
    snprintf(r->slices_y_define, sizeof r->slices_y_define, "SLICES_Y %u", r->slices_y);
    /* msaa > 1: the cull reads every sample, and shading gets the tiles' ranges */
    bool ms = c->b.samples > 1;
    snprintf(r->samples_define, sizeof r->samples_define, "MSAA_SAMPLES %d", c->b.samples);
    snprintf(r->tlists_define, sizeof r->tlists_define, "TLISTS %u", r->ncells);
    const char *grid_defs[6] = {r->tile_define, r->tiles_x_define,
                                r->slices ? r->tiles_y_define : NULL,
                                r->slices ? r->slices_define : NULL,
                                r->slices ? r->slices_y_define : NULL,
                                ms ? "TILE_DEPTH_RANGES" : NULL};
    /* the cull's defines: grid_defs without the NULLs, then the samples, then TLISTS
     * when it builds translucent lists (a NULL ends the list) */
    const char *cull_defs[9] = {NULL};
    unsigned ncull = 0;
    for (unsigned i = 0; i < 6; i++)
        if (grid_defs[i])
            cull_defs[ncull++] = grid_defs[i];
    if (ms)
        cull_defs[ncull++] = r->samples_define;
    if (r->ntlists)
        cull_defs[ncull++] = r->tlists_define;
    char why[4096] = "";
    if (gl_program_get(c->b.programs,
                       &(gl_program_desc){.name = "depth_only", .vertex = "mesh.vert",
                                          .fragment = "depth_only.frag"},
                       &r->depth_program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "%s: %s", r->name, why);
        goto fail;
    }
    if (r->grid &&
        gl_program_get(c->b.programs,
                       &(gl_program_desc){
                           .name = r->slices ? (r->ntlists ? "cluster_cull_translucent"
                                                           : "cluster_cull")
                                             : (r->ntlists ? "tile_cull_translucent"
                                                           : "tile_cull"),
                           .compute = "tile_cull.comp",
                           .defines = {cull_defs[0], cull_defs[1], cull_defs[2],
                                       cull_defs[3], cull_defs[4], cull_defs[5],
                                       cull_defs[6], cull_defs[7]}},
                       &r->cull_program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "%s: %s", r->name, why);
        goto fail;
    }
    const char *extra[10] = {NULL};
    unsigned k = 0;
    if (r->grid) {
        for (unsigned i = 0; i < 6; i++)
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
    r->staging = calloc(r->max_lights, sizeof *r->staging);
    r->readback = calloc((size_t)heads * 4u, sizeof *r->readback);
    r->counts = calloc(r->ncells, sizeof *r->counts);
    if (!r->staging || !r->readback || !r->counts) {
        snprintf(err, errlen, "%s: out of memory for %u lights and %u cells", r->name, n,
                 r->ncells);
        goto fail;
    }
    r->lights = make_buffer((size_t)r->max_lights * sizeof(gpu_light));
    r->tiles = make_buffer((size_t)heads * 16u);
    r->indices = make_buffer((size_t)r->capacity * 4u);
    r->stats = make_buffer(sizeof(tile_stats));
    if (ms && r->grid)
        r->depth_ranges = make_buffer((size_t)r->ntiles * 2u * sizeof(float));
    const translucent_grid tg = {{r->tile_define, r->tiles_x_define, r->tlists_define},
                                 r->lights, r->tiles, r->indices};
    if (!translucent_compile(&c->translucent, &c->b, &c->b.shadows, r->ntlists ? &tg : NULL,
                             err, errlen))
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
    (void)program;
    if (r->program_frame[variant] != r->frame) {
        gl.Uniform1i(FORWARD_UNIFORM_LIGHT, r->count);
        r->program_frame[variant] = r->frame;
    }
}

static void bind_buffers(forward_plus *r)
{
    gl_state_storage_buffer(r->c.b.st, BIND_SSBO_LIGHTS, r->lights);
    if (r->grid) {
        gl_state_storage_buffer(r->c.b.st, BIND_SSBO_TILE_LISTS, r->tiles);
        gl_state_storage_buffer(r->c.b.st, BIND_SSBO_TILE_INDICES, r->indices);
        gl_state_storage_buffer(r->c.b.st, BIND_SSBO_TILE_STATS, r->stats);
        if (r->depth_ranges)
            gl_state_storage_buffer(r->c.b.st, BIND_SSBO_TILE_DEPTH, r->depth_ranges);
    }
}

static void plus_draw(void *self, const struct scene *s, frame_stats *out)
{
    forward_plus *r = self;
    forward_common *c = &r->c;
    if (!c->prepared) {
        fprintf(stderr, "bug: %s: draw before a successful prepare\n", r->name);
        out->npasses = 0;
        return;
    }
    forward_begin_frame(c, s, out);
    const frontend *fe = &c->b.fe;
    renderer_base_shadow_pass(&c->b, s, out);

    /* the frame's visible lights, as forward-spml packs them */
    uint32_t n = fe->nlights < r->max_lights ? fe->nlights : r->max_lights;
    for (uint32_t k = 0; k < n; k++) {
        shading_pack_light(&s->lights[fe->lights[k]], s->view, &r->staging[k]);
        shading_set_shadow_layer(&r->staging[k], fe->shadow_layer[k]);
    }
    r->count = (int)n;
    r->frame++;
    if (n)
        gl.NamedBufferSubData(r->lights, 0, (GLsizeiptr)(n * sizeof(gpu_light)), r->staging);

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

    if (r->grid) {
        out->grid_pass = out->npasses + 1;
        forward_pass_begin(c, out, "cull");
        const tile_stats reset = {0, r->capacity};
        gl.NamedBufferSubData(r->stats, 0, sizeof reset, &reset);
        gl_state_program(c->b.st, r->cull_program);
        gl.Uniform1i(FORWARD_UNIFORM_LIGHT, r->count);
        /* no draw framebuffer that has the sampled depth attached (the header) */
        gl_state_framebuffer(c->b.st, c->b.output_fbo);
        gl_state_texture(c->b.st, BIND_TEX_DEPTH, c->b.depth.texture);   /* x samples */
        bind_buffers(r);
        gl_state_dispatch(c->b.st, r->tiles_x, r->tiles_y, 1);
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

static void plus_collect(void *self, frame_stats *out)
{
    forward_plus *r = self;
    forward_collect(&r->c, out);
    if (!r->c.prepared || !r->grid)
        return;
    light_grid_collect(&(light_grid_readback){r->name, r->tiles, r->stats, r->ncells, r->ntiles,
                                              r->tiles_x, r->slices, r->capacity, r->readback,
                                              r->counts, r->ntlists},
                       out);
    r->counted = true;
}

static const uint32_t *plus_light_grid(const void *self, size_t *n)
{
    const forward_plus *r = self;
    *n = r->counted ? r->ncells : 0;
    return r->counted ? r->counts : NULL;
}

static void plus_describe(const void *self, pass_plan *out)
{
    const forward_plus *r = self;
    const forward_common *c = &r->c;
    out->npasses = 0;
    forward_describe_shadows(c, out);
    forward_describe_pass(out, "depth", true, "the visible objects, depth only");
    if ((!c->prepared || r->grid) && r->slices)
        forward_describe_pass(out, "cull", true,
                              "one dispatch: %ux%ux%u clusters (%d px, r = %.4g), lights "
                              "culled per cluster",
                              r->tiles_x, r->tiles_y, r->slices, r->tile, r->slice_ratio);
    else if (!c->prepared || r->grid)
        forward_describe_pass(out, "cull", true,
                              "one dispatch: %ux%u tiles of %d px, lights culled per tile "
                              "into %u indices",
                              r->tiles_x, r->tiles_y, r->tile, r->capacity);
    else
        forward_describe_pass(out, "cull", false,
                              "skipped, the scene has no point or spot light");
    if (r->ntlists)
        forward_describe_pass(out, "translucent-lists", true,
                              "in the cull dispatch: per tile, near plane to its max depth");
    else if (!c->prepared)
        forward_describe_pass(out, "translucent-lists", true,
                              "per tile in the cull dispatch, when the scene has translucency");
    else
        forward_describe_pass(out, "translucent-lists", false, "%s",
                              !c->translucent.run ? "skipped: no translucent materials"
                                                  : "skipped: no cull pass, every light");
    forward_describe_pass(out, "shade", true,
                          r->grid ? (r->slices ? "every visible object once, depth EQUAL, "
                                                 "its cluster's lights"
                                               : "every visible object once, depth EQUAL, "
                                                 "its tile's lights")
                                  : "every visible object once, depth EQUAL, every light");
    forward_describe_tail(c, out);
}

static void plus_destroy(void *self)
{
    forward_plus *r = self;
    if (!r)
        return;
    release_buffers(r);
    forward_common_destroy(&r->c);
    free(r);
}

const renderer_impl renderer_forward_plus_impl = {
    .name = "forward-plus",
    .description = "tiled forward (Harada et al. 2012): depth pre-pass, lights culled per "
                   "screen tile by a compute pass, each pixel shaded with its tile's lights",
    .create = plus_create,
    .prepare = plus_prepare,
    .draw = plus_draw,
    .collect = plus_collect,
    .describe = plus_describe,
    .destroy = plus_destroy,
    .read_hdr = forward_read_hdr,
    .light_grid = plus_light_grid,
};

/* clustered: the forward passes above, or with clustered.shading: deferred the
 * G-buffer and one clustered compute pass (deferred.c, deferred_clustered_create), the
 * same cluster lists; the entries hand each call to the one chosen at creation. */
typedef struct clustered {
    const renderer_impl *impl;
    void *self;
} clustered;

extern const renderer_impl renderer_tiled_deferred_impl;

static const renderer_impl clustered_forward_impl = {
    .name = "clustered",
    .create = clustered_create,
    .prepare = plus_prepare,
    .draw = plus_draw,
    .collect = plus_collect,
    .describe = plus_describe,
    .destroy = plus_destroy,
    .read_hdr = forward_read_hdr,
    .light_grid = plus_light_grid,
};

static void *cl_create(const renderer_options *opts, char *err, size_t errlen)
{
    clustered *c = calloc(1, sizeof *c);
    if (!c) {
        snprintf(err, errlen, "clustered: out of memory");
        return NULL;
    }
    c->impl = opts->clustered_deferred ? &renderer_tiled_deferred_impl : &clustered_forward_impl;
    c->self = opts->clustered_deferred ? deferred_clustered_create(opts, err, errlen)
                                       : clustered_create(opts, err, errlen);
    if (!c->self) {
        free(c);
        return NULL;
    }
    return c;
}

static bool cl_prepare(void *self, const struct scene *s, char *err, size_t errlen)
{
    clustered *c = self;
    return c->impl->prepare(c->self, s, err, errlen);
}

static void cl_draw(void *self, const struct scene *s, frame_stats *out)
{
    clustered *c = self;
    c->impl->draw(c->self, s, out);
}

static void cl_collect(void *self, frame_stats *out)
{
    clustered *c = self;
    c->impl->collect(c->self, out);
}

static void cl_describe(const void *self, pass_plan *out)
{
    const clustered *c = self;
    c->impl->describe(c->self, out);
}

static void cl_destroy(void *self)
{
    clustered *c = self;
    if (!c)
        return;
    c->impl->destroy(c->self);
    free(c);
}

static bool cl_read_hdr(void *self, float *rgba, int width, int height)
{
    clustered *c = self;
    return c->impl->read_hdr(c->self, rgba, width, height);
}

static const uint32_t *cl_light_grid(const void *self, size_t *n)
{
    const clustered *c = self;
    return c->impl->light_grid(c->self, n);
}

const renderer_impl renderer_clustered_impl = {
    .name = "clustered",
    .description = "clustered (Olsson et al. 2012): lights culled per cluster (screen tile x "
                   "exponential depth slice) by a compute pass; forward: depth pre-pass, each "
                   "pixel shaded with its cluster's lights; deferred: from the G-buffer",
    .create = cl_create,
    .prepare = cl_prepare,
    .draw = cl_draw,
    .collect = cl_collect,
    .describe = cl_describe,
    .destroy = cl_destroy,
    .read_hdr = cl_read_hdr,
    .light_grid = cl_light_grid,
};
