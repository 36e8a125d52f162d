/* zbin (Drobot, "Improved Culling for Tiled and Clustered Rendering", SIGGRAPH 2017):
 * the light grid (grid.h) with its lists replaced by z-binning. Each frame, on the GPU:
 * dispatches of many work groups sort the lights by view depth and fill the depth bins
 * (zbin.comp: a bitonic sort, blocks in shared memory, the larger steps a dispatch each),
 * then the tiles' dispatch (tile_cull.inc's cull_tile with ZBIN_BINS) writes a bit mask
 * over the sorted lights a tile; a pixel shades the set bits between its bin's two
 * indices (zbin.inc). Forward (the default): forward_plus.c's passes; with zbin.shading:
 * deferred, tiled_deferred.c's G-buffer and compute pass. Translucent surfaces use the
 * tiles' translucent lists (indices into the sorted lights), as clustered's do.
 *
 * The registry's entry makes the object of either design and sets its grid's bins;
 * `variant` names the design that serves it. Design and memory: docs/notes/zbin.md. */
#include "renderers/tiled/tiled.h"

#include "renderers/forward/forward_common.h"
#include "renderers/frame/bindings.h"
#include "renderers/tiled/grid.h"

#include <math.h>
#include <stdio.h>

#define ZBIN_MAX_LIGHTS 65536u   /* 16-bit indices in a bin */
#define ZBIN_GROUP 256u          /* zbin.comp's work group */

bool light_grid_zbin_option(light_grid *g, const renderer_options *o, char *err,
                            size_t errlen)
{
    int n = o->zbin_bins;
    if (n < 16 || n > 4096) {
        snprintf(err, errlen, "%s: zbin.bins %d: expected 16 to 4096", g->name, n);
        return false;
    }
    g->zbins = (uint32_t)n;
    return true;
}

bool light_grid_zbin_fit(light_grid *g, int max_block, char *err, size_t errlen)
{
    g->zbin_words = (g->max_lights + 31u) / 32u;
    snprintf(g->zbin_define, sizeof g->zbin_define, "ZBIN_BINS %u", g->zbins);
    if (!g->zbins || !g->cull)
        return true;
    if (g->max_lights > ZBIN_MAX_LIGHTS) {
        snprintf(err, errlen, "%s: %u lights: a depth bin holds 16-bit indices, at most %u "
                 "lights", g->name, g->max_lights, ZBIN_MAX_LIGHTS);
        return false;
    }
    uint64_t masks = (uint64_t)g->ntiles * g->zbin_words * 4u;
    if (masks > (uint64_t)(max_block > 0 ? max_block : 0)) {
        snprintf(err, errlen, "%s: %u tiles x %u mask words need %llu bytes, this context "
                 "allows %d (GL_MAX_SHADER_STORAGE_BLOCK_SIZE); larger tiles.size, fewer "
                 "lights or a smaller resolution fit", g->name, g->ntiles, g->zbin_words,
                 (unsigned long long)masks, max_block);
        return false;
    }
    return true;
}

const char *light_grid_zbin_define(const light_grid *g)
{
    return g->zbins && g->cull ? g->zbin_define : NULL;
}

bool light_grid_zbin_compile(light_grid *g, gl_program_cache *pc, char *err, size_t errlen)
{
    g->zbin_program = 0;
    if (!g->zbins || !g->cull)
        return true;
    char why[4096] = "";
    if (gl_program_get(pc,
                       &(gl_program_desc){.name = "zbin_sort", .compute = "zbin.comp",
                                          .defines = {g->zbin_define}},
                       &g->zbin_program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "%s: %s", g->name, why);
        return false;
    }
    return true;
}

static uint32_t zbin_pow2(uint32_t n)
{
    uint32_t p2 = 1;
    while (p2 < n)
        p2 <<= 1;
    return p2;
}

static GLuint zbin_buffer(uint64_t bytes)
{
    GLuint b = 0;
    gl.CreateBuffers(1, &b);
    gl.NamedBufferStorage(b, (GLsizeiptr)(bytes ? bytes : 4u), NULL, GL_DYNAMIC_STORAGE_BIT);
    return b;
}

bool light_grid_zbin_alloc(light_grid *g)
{
    if (!g->zbins || !g->cull)
        return true;
    uint32_t pow2 = zbin_pow2(g->max_lights);
    g->zbin_sorted = zbin_buffer((uint64_t)g->max_lights * sizeof(gpu_light));
    g->zbin_keys = zbin_buffer((uint64_t)pow2 * 8u);
    g->zbin_bins = zbin_buffer(16u + (uint64_t)g->zbins * 4u);
    g->zbin_masks = zbin_buffer((uint64_t)g->ntiles * g->zbin_words * 4u);
    return true;
}

void light_grid_zbin_release(light_grid *g)
{
    GLuint b[4] = {g->zbin_sorted, g->zbin_keys, g->zbin_bins, g->zbin_masks};
    for (int i = 0; i < 4; i++)
        if (b[i])
            gl.DeleteBuffers(1, &b[i]);
    g->zbin_sorted = g->zbin_keys = g->zbin_bins = g->zbin_masks = 0;
}

/* zbin.comp's stages (its u_stage) and its block: the entries a group sorts in shared
 * memory (16 KiB), 4 pairs an invocation a step */
enum { ZS_FIRST, ZS_STEP, ZS_MERGE, ZS_BINS };
#define ZBIN_BLOCK 2048u

static void zbin_stage(gl_state *st, int stage, uint32_t k, uint32_t j, uint32_t groups)
{
    gl.Uniform1i(LOC_RENDERER + 1, stage);
    gl.Uniform1i(LOC_RENDERER + 2, (GLint)k);
    gl.Uniform1i(LOC_RENDERER + 3, (GLint)j);
    gl_state_dispatch(st, groups, 1, 1);
    gl_state_barrier(st, GL_SHADER_STORAGE_BARRIER_BIT);
}

void light_grid_zbin_dispatch(light_grid *g, gl_state *st, uint32_t nlights)
{
    g->zbin_count = nlights;
    /* the head's directional count and largest reach, summed by ZS_FIRST's atomics */
    const uint32_t head[4] = {0, 0, 0, 0};
    gl.NamedBufferSubData(g->zbin_bins, 0, sizeof head, head);
    gl_state_program(st, g->zbin_program);
    gl.Uniform1i(LOC_RENDERER, (GLint)nlights);
    gl_state_storage_buffer(st, BIND_SSBO_LIGHTS, g->lights.buffer);
    gl_state_storage_buffer(st, BIND_SSBO_ZBIN_SORTED, g->zbin_sorted);
    gl_state_storage_buffer(st, BIND_SSBO_ZBIN_KEYS, g->zbin_keys);
    gl_state_storage_buffer(st, BIND_SSBO_ZBIN_BINS, g->zbin_bins);
    /* the bitonic sort of pow2 pairs: blocks sorted in shared memory, then per larger
     * k its steps with j >= the block one dispatch each and the rest a block a group */
    uint32_t pow2 = zbin_pow2(nlights);
    uint32_t blocks = pow2 > ZBIN_BLOCK ? pow2 / ZBIN_BLOCK : 1;
    zbin_stage(st, ZS_FIRST, 0, 0, blocks);
    for (uint32_t k = 2 * ZBIN_BLOCK; k <= pow2; k <<= 1) {
        for (uint32_t j = k >> 1; j >= ZBIN_BLOCK; j >>= 1)   /* pow2 / 2 pairs */
            zbin_stage(st, ZS_STEP, k, j, pow2 / 2 / ZBIN_GROUP);
        zbin_stage(st, ZS_MERGE, k, 0, blocks);
    }
    zbin_stage(st, ZS_BINS, 0, 0, (g->zbins + ZBIN_GROUP - 1) / ZBIN_GROUP);
}

double light_grid_struct_bytes(const light_grid *g, uint32_t needed)
{
    double lights = (double)(g->zbins ? g->zbin_count : g->lights.count) * sizeof(gpu_light);
    double heads = (double)g->ntlists * 16.0, taken = (double)needed * 4.0;
    if (!g->zbins)
        return lights + (double)g->ncells * 16.0 + heads + taken;
    /* sorted lights, the bins (and their 16-byte head), the masks' used words; the
     * translucent lists when the scene has them */
    double words = ceil(g->zbin_count / 32.0);
    return lights + 16.0 + g->zbins * 4.0 + (double)g->ntiles * words * 4.0 + heads + taken;
}

// >>the renderer

static void *zbin_create(const renderer_options *opts, char *err, size_t errlen)
{
    if (opts->zbin_deferred)
        return tiled_deferred_zbin_create(opts, err, errlen);
    forward_common *c = forward_tiled_new("zbin", false, opts, err, errlen);
    if (c && !light_grid_zbin_option(c->grid, opts, err, errlen)) {
        renderer_forward_plus_impl.destroy(c);
        return NULL;
    }
    return c;
}

static const renderer_impl *zbin_variant(const renderer_options *opts)
{
    return opts->zbin_deferred ? &renderer_tiled_deferred_impl : &renderer_forward_plus_impl;
}

static uint32_t zbin_max_lights(const renderer_options *opts, int max_uniform_block_size)
{
    (void)opts;
    (void)max_uniform_block_size;
    return ZBIN_MAX_LIGHTS;
}

const renderer_impl renderer_zbin_impl = {
    .name = "zbin",
    .description = "z-binning (Drobot 2017): lights sorted by view depth into linear depth "
                   "bins and a bit mask over them a screen tile, all on the GPU; forward: "
                   "depth pre-pass, each pixel shades its tile's bits within its bin; "
                   "deferred: from the G-buffer",
    .reads = "gbuffer tiles.size tiles.depth_culling tiles.prune tiles.levels "
             "tiles.coarse_size zbin lights.culling "
             "lights.culling_error hdr msaa fog aa",
    .create = zbin_create,
    .variant = zbin_variant,
    .max_lights = zbin_max_lights,
};
