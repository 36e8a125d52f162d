/* The light grid (grid.h). */
#include "renderers/tiled/grid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/frame/bindings.h"
#include "renderers/forward/forward_common.h"
#include "renderers/frame/shading.h"
#include "renderers/frame/stochastic.h"

bool light_grid_tile_option(light_grid *g, const char *name, const renderer_options *o,
                            char *err, size_t errlen)
{
    g->name = name;
    g->tile = o->tile_size;
    g->depth_mask = o->depth_mask;
    g->prune_samples = o->prune_samples;
    if (g->tile != 8 && g->tile != 16 && g->tile != 32) {
        snprintf(err, errlen, "%s: tiles.size %d: expected 8, 16 or 32", name, g->tile);
        return false;
    }
    return light_grid_levels_option(g, o, err, errlen);
}

bool light_grid_slices_option(light_grid *g, const char *name, const renderer_options *o,
                              char *err, size_t errlen)
{
    g->name = name;
    int k = o->clustered_slices;
    if (k < 1 || k > 64) {
        snprintf(err, errlen, "%s: clustered.slices %d: expected 1 to 64", name, k);
        return false;
    }
    g->slices_y = (uint32_t)k;
    return true;
}

void light_grid_culling_option(light_grid *g, renderer_base *b, const renderer_options *o)
{
    g->culling_error = o->culling_error > 0.0f ? o->culling_error : 0.0f;
    b->stochastic = g->culling_error > 0.0f;
}

bool light_grid_size(light_grid *g, const scene *s, int width, int height, bool cull,
                     bool translucency, char *err, size_t errlen)
{
    g->tiles_x = (uint32_t)((width + g->tile - 1) / g->tile);
    g->tiles_y = (uint32_t)((height + g->tile - 1) / g->tile);
    g->ntiles = g->tiles_x * g->tiles_y;
    g->slices = 0;
    if (g->slices_y && !shading_cluster_slices_ok(g->name, s->proj[1][1], s->cam.znear,
                                                  s->cam.zfar, (int)g->slices_y, &g->slices,
                                                  &g->slice_ratio, err, errlen))
        return false;
    g->ncells = g->ntiles * (g->slices ? g->slices : 1u);
    g->cull = cull;
    g->ntlists = cull && translucency ? g->ntiles : 0u;
    g->max_lights = s->nlights_total ? s->nlights_total : 1u;
    light_grid_coarse_size(g);
    return true;
}

int light_grid_max_block(void)
{
    GLint max_block = 0;
    gl.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    return max_block;
}

bool light_grid_heads_fit(const light_grid *g, const char *what, int max_block, char *err,
                          size_t errlen)
{
    uint32_t heads = g->ncells + g->ntlists;   /* opaque cells, then translucent lists */
    if ((uint64_t)heads * 16u <= (uint64_t)(max_block > 0 ? max_block : 0))
        return true;
    snprintf(err, errlen, "%s: %u %s need %llu bytes of list heads, this context allows %d "
             "(GL_MAX_SHADER_STORAGE_BLOCK_SIZE); larger tiles.size%s or a smaller "
             "resolution fit", g->name, heads, what, (unsigned long long)heads * 16u, max_block,
             g->slices > 0 ? ", fewer clustered.slices" : "");
    return false;
}

bool light_grid_lights_fit(const light_grid *g, uint32_t nlights, int max_block, char *err,
                           size_t errlen)
{
    if ((uint64_t)g->max_lights * sizeof(gpu_light) <= (uint64_t)(max_block > 0 ? max_block : 0))
        return true;
    snprintf(err, errlen,
             "%s: %u lights need %llu bytes of storage buffer, this context "
             "allows %d (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)",
             g->name, nlights, (unsigned long long)g->max_lights * sizeof(gpu_light), max_block);
    return false;
}

void light_grid_capacity(light_grid *g, uint32_t max_lights_per_tile, int max_block)
{
    /* zbin's tiles keep bit masks, not lists: only the translucent lists take indices */
    uint64_t heads = (g->zbins && g->cull ? 0u : g->ncells) + g->ntlists;
    uint64_t want = max_lights_per_tile ? heads * max_lights_per_tile : heads * g->max_lights;
    uint64_t block_entries = max_block > 0 ? (uint64_t)max_block / 4u : 0u;
    if (want > block_entries)
        want = block_entries;
    if (want > LIGHT_GRID_INDEX_CAP)
        want = LIGHT_GRID_INDEX_CAP;
    g->capacity = (uint32_t)(want ? want : 1u);
}

void light_grid_defines(light_grid *g)
{
    snprintf(g->tile_define, sizeof g->tile_define, "TILE_SIZE %d", g->tile);
    snprintf(g->tiles_x_define, sizeof g->tiles_x_define, "TILES_X %u", g->tiles_x);
    snprintf(g->tiles_y_define, sizeof g->tiles_y_define, "TILES_Y %u", g->tiles_y);
    snprintf(g->slices_define, sizeof g->slices_define, "SLICES %u", g->slices);
    snprintf(g->slices_y_define, sizeof g->slices_y_define, "SLICES_Y %u", g->slices_y);
    snprintf(g->tlists_define, sizeof g->tlists_define, "TLISTS %u", g->ncells);
    light_grid_coarse_defines(g);
}

const char *light_grid_mask_define(const light_grid *g)
{
    return g->depth_mask && g->cull ? "DEPTH_MASK" : NULL;
}

const char *light_grid_prune_define(const light_grid *g)
{
    return g->prune_samples && g->cull ? "PRUNE_SAMPLES" : NULL;
}

static GLuint make_buffer(size_t bytes)
{
    GLuint b = 0;
    gl.CreateBuffers(1, &b);
    gl.NamedBufferStorage(b, (GLsizeiptr)bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
    return b;
}

bool light_grid_alloc(light_grid *g)
{
    size_t heads = (size_t)g->ncells + g->ntlists;
    if (!light_buffer_create(&g->lights, g->max_lights))
        return false;
    g->readback = calloc(heads * 4u, sizeof *g->readback);
    g->counts = calloc(g->ncells, sizeof *g->counts);
    if (!g->readback || !g->counts)
        return false;
    g->tiles = make_buffer(heads * 16u);
    g->indices = make_buffer((size_t)g->capacity * 4u);
    g->stats = make_buffer(2 * sizeof(uint32_t));
    return light_grid_coarse_alloc(g) && light_grid_zbin_alloc(g);
}

void light_grid_release(light_grid *g)
{
    light_buffer_release(&g->lights);
    GLuint b[3] = {g->tiles, g->indices, g->stats};
    for (int i = 0; i < 3; i++)
        if (b[i])
            gl.DeleteBuffers(1, &b[i]);
    g->tiles = g->indices = g->stats = 0;
    light_grid_coarse_release(g);
    light_grid_zbin_release(g);
    free(g->readback);
    free(g->counts);
    g->readback = g->counts = NULL;
    g->counted = false;
}

translucent_grid light_grid_translucent(const light_grid *g)
{
    return (translucent_grid){{g->tile_define, g->tiles_x_define, g->tlists_define},
                              g->zbin_sorted ? g->zbin_sorted : g->lights.buffer, g->tiles,
                              g->indices};
}

// >>per frame

uint32_t light_grid_upload_lights(light_grid *g, const scene *s, const frontend *fe)
{
    uint32_t n = light_buffer_pack(&g->lights, s, fe);
    if (g->culling_error > 0.0f)
        stochastic_ranges(g->lights.staging, fe->lights, n, s, g->culling_error);
    light_buffer_upload(&g->lights);
    return n;
}

void light_grid_reset(const light_grid *g)
{
    const uint32_t reset[2] = {0, g->capacity};   /* b_stats: next, capacity */
    gl.NamedBufferSubData(g->stats, 0, sizeof reset, reset);
}

void light_grid_bind_lights(const light_grid *g, gl_state *st)
{
    /* zbin: the lights in depth order, as its dispatch sorted them (zbin.c) */
    gl_state_storage_buffer(st, BIND_SSBO_LIGHTS,
                            g->zbin_sorted ? g->zbin_sorted : g->lights.buffer);
}

void light_grid_bind_lists(const light_grid *g, gl_state *st)
{
    gl_state_storage_buffer(st, BIND_SSBO_TILE_LISTS, g->tiles);
    gl_state_storage_buffer(st, BIND_SSBO_TILE_INDICES, g->indices);
    gl_state_storage_buffer(st, BIND_SSBO_TILE_STATS, g->stats);
    if (g->coarse_x) {   /* tiles.levels: 2: what the fine tiles cull from */
        gl_state_storage_buffer(st, BIND_SSBO_COARSE_LISTS, g->coarse_tiles);
        gl_state_storage_buffer(st, BIND_SSBO_COARSE_INDICES, g->coarse_indices);
    }
    if (g->zbin_masks) {   /* zbin: the bins and the tiles' masks */
        gl_state_storage_buffer(st, BIND_SSBO_ZBIN_BINS, g->zbin_bins);
        gl_state_storage_buffer(st, BIND_SSBO_ZBIN_MASKS, g->zbin_masks);
    }
}

void light_grid_dispatch(const light_grid *g, gl_state *st)
{
    gl_state_dispatch(st, g->tiles_x, g->tiles_y, 1);
}

void light_grid_collect(light_grid *g, frame_stats *out)
{
    uint32_t needed = 0, ntr = g->ntlists;
    gl.GetNamedBufferSubData(g->stats, 0, sizeof needed, &needed);
    gl.GetNamedBufferSubData(g->tiles, 0, (GLsizeiptr)(((size_t)g->ncells + ntr) * 16u),
                             g->readback);
    double sum = 0, weighted = 0, covered = 0;
    uint32_t max = 0, longest = 0;
    for (uint32_t t = 0; t < g->ncells; t++) {
        uint32_t len = g->readback[4 * t + 3], px = g->readback[4 * t + 2];
        g->counts[t] = len;
        sum += len;
        /* zbin: x holds the tile's evaluations summed over its pixels (zbin.inc) */
        weighted += g->zbins ? (double)g->readback[4 * t] : (double)len * px;
        covered += px;
        if (len > max) {
            max = len;
            longest = t;
        }
    }
    out->grid_cells = g->ncells;
    out->grid_lights_mean = g->ncells ? sum / g->ncells : NAN;
    out->grid_lights_max = max;
    out->light_evals_per_pixel = covered > 0 ? weighted / covered : 0.0;
    out->grid_covered = (uint64_t)covered;
    out->light_struct_bytes = light_grid_struct_bytes(g, needed);
    double tsum = 0;
    uint32_t tmax = 0, tlongest = 0;
    for (uint32_t t = 0; t < ntr; t++) {
        uint32_t len = g->readback[4 * ((size_t)g->ncells + t) + 3];
        tsum += len;
        if (len > tmax) {
            tmax = len;
            tlongest = t;
        }
    }
    if (ntr) {
        out->translucent_lists = ntr;
        out->translucent_lights_mean = tsum / ntr;
        out->translucent_lights_max = tmax;
    }
    /* the lengths are the lists' true lengths, written or not; which lists were left
     * empty depends on the order the cells ran in, so the message names the longest */
    uint32_t tl = longest % g->ntiles;
    if (needed > g->capacity && tmax > max)
        snprintf(out->overflow, sizeof out->overflow,
                 "%s: the light lists need %u indices, the index buffer holds %u; tile %u "
                 "(%u, %u)'s translucent list alone needs %u",
                 g->name, needed, g->capacity, tlongest, tlongest % g->tiles_x,
                 tlongest / g->tiles_x, tmax);
    else if (needed > g->capacity && g->slices)
        snprintf(out->overflow, sizeof out->overflow,
                 "%s: the clusters' light lists need %u indices, the index buffer holds %u; "
                 "cluster %u (tile %u, %u, slice %u) alone needs %u",
                 g->name, needed, g->capacity, longest, tl % g->tiles_x, tl / g->tiles_x,
                 longest / g->ntiles, max);
    else if (needed > g->capacity)
        snprintf(out->overflow, sizeof out->overflow,
                 "%s: the tiles' light lists need %u indices, the index buffer holds %u; "
                 "tile %u (%u, %u) alone needs %u",
                 g->name, needed, g->capacity, longest, tl % g->tiles_x, tl / g->tiles_x, max);
    g->counted = true;
}

const uint32_t *light_grid_counts(const light_grid *g, size_t *n)
{
    *n = g->counted ? g->ncells : 0;
    return g->counted ? g->counts : NULL;
}

void forward_grid_collect(void *self, frame_stats *out)
{
    forward_common *c = self;
    renderer_base_collect(&c->b, out);
    if (c->prepared && c->grid->cull)
        light_grid_collect(c->grid, out);
}

const uint32_t *forward_grid_counts(const void *self, size_t *n)
{
    const forward_common *c = self;
    return light_grid_counts(c->grid, n);
}

void forward_grid_describe_translucent(const forward_common *c, pass_plan *out)
{
    if (c->grid->ntlists)
        forward_describe_pass(out, "translucent-lists", true,
                              "in the cull dispatch: per tile, near plane to its max depth");
    else if (!c->prepared)
        forward_describe_pass(out, "translucent-lists", true,
                              "per tile in the cull dispatch, when the scene has translucency");
    else
        forward_describe_pass(out, "translucent-lists", false, "%s",
                              !c->translucent.run ? "skipped: no translucent materials"
                                                  : "skipped: no cull pass, every light");
}

bool forward_grid_prepare_end(forward_common *c, GLuint *depth_ranges, char *err, size_t errlen)
{
    const light_grid *g = c->grid;
    if (c->b.samples > 1 && g->cull) {
        gl.CreateBuffers(1, depth_ranges);
        size_t words = g->depth_mask ? 4u : 2u;   /* DEPTH_MASK: and the tile's cells */
        gl.NamedBufferStorage(*depth_ranges, (GLsizeiptr)((size_t)g->ntiles * words * 4u),
                              NULL, GL_DYNAMIC_STORAGE_BIT);
    }
    const translucent_grid tg = light_grid_translucent(g);
    return translucent_compile(&c->translucent, &c->b, &c->b.shadows, g->ntlists ? &tg : NULL,
                               err, errlen);
}
