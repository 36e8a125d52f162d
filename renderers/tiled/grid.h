#pragma once
/* The light grid of the tiled and clustered renderers (forward-plus, clustered,
 * tiled-deferred; Harada et al. 2012, Olsson et al. 2012), written once.
 *
 * The renderer owns the dispatch itself (which program, what else it binds); this
 * module sizes, allocates, resets, binds and reads back what every one of them shares:
 * sizing, cull, buffers, the index cap and the counters, each in the comment above
 * LIGHT_GRID_INDEX_CAP below. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/frame/frontend.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/state.h"
#include "renderers/frame/light_buffer.h"
#include "renderers/renderer.h"
#include "renderers/frame/translucent.h"
#include "scenes/scene.h"

/* The grid, part by part:
 *
 *   sizing     the screen cut into tiles of `tile` pixels (tiles.size: 8, 16 or 32),
 *              tiles_x x tiles_y of them; clustered cuts each tile's view depth into
 *              `slices` exponential slices (shading_cluster_slices from clustered.slices,
 *              Olsson's S_y; at most 1024), cells = tiles x slices (tiles alone else)
 *   cull       the grid is culled only when the scene has a point or spot light; the
 *              renderer's one compute dispatch (tiles_x x tiles_y work groups, tiles.inc
 *              and tile_cull.inc) writes per cell a list of the lights that reach it,
 *              and, when the scene has translucent objects, per tile a translucent list
 *              after the cells (TLISTS, heads b_tiles[cells + tile])
 *   buffers    the frame's visible lights (light_buffer.h, a storage buffer sized for
 *              the run's lights), the list heads (16 bytes a head), one index buffer
 *              shared by every list and the stats word pair {next, capacity}
 *   index cap  the index buffer holds, per head, renderer_options.max_lights_per_tile
 *              entries, or with 0 (the default) every light of the run, capped by
 *              GL_MAX_SHADER_STORAGE_BLOCK_SIZE and at LIGHT_GRID_INDEX_CAP entries
 *              (2^25, 128 MiB): no frame runs out unless a cap bites. A list that does
 *              not fit is left empty, never truncated, and collect reports the overflow
 *   counters   after the frame's sync point: grid_cells, the mean and largest list length,
 *              light evaluations per shaded pixel (sum of length x pixels with geometry /
 *              pixels with geometry), the translucent lists' mean and largest, and the
 *              overflow message naming the longest list; the lengths stay for
 *              renderer_impl.light_grid (lightgrid.csv)
 *
 * The renderer owns the dispatch itself (which program, what else it binds); this
 * module sizes, allocates, resets, binds and reads back what every one of them shares. */
#define LIGHT_GRID_INDEX_CAP (1u << 25)   /* entries of the index buffer at most */

typedef struct light_grid {
    const char *name;                /* the renderer: first word of its messages */
    int tile;                        /* pixels per tile side */
    bool depth_mask;                 /* tiles.depth_culling: mask (DEPTH_MASK, tile_cull.inc) */
    bool prune_samples;              /* tiles.prune: samples (PRUNE_SAMPLES, tile_cull.inc) */
    float culling_error;             /* lights.culling: stochastic's error; 0: exact
                                        (light_grid_culling_option) */
    uint32_t slices_y;               /* clustered: Olsson's S_y (clustered.slices); else 0 */
    /* >>light_grid_size, at prepare */
    uint32_t slices;                 /* clustered: depth slices to the far plane; else 0 */
    double slice_ratio;              /* clustered: far/near of each slice */
    uint32_t tiles_x, tiles_y, ntiles;
    uint32_t ncells;                 /* tiles, or tiles x slices */
    bool cull;                       /* the scene has point or spot lights: lists are culled */
    uint32_t ntlists;                /* tiles: translucent lists built too (cull and the scene
                                        has translucent objects); 0: none */
    uint32_t max_lights;             /* entries of the light buffer (the run's lights, >= 1) */
    uint32_t capacity;               /* entries of the index buffer (light_grid_capacity) */
    /* >>light_grid_alloc */
    light_buffer lights;             /* the frame's visible lights */
    GLuint tiles, indices, stats;    /* list heads, index buffer, {next, capacity} */
    uint32_t *readback;              /* (ncells + ntlists) x 4 */
    uint32_t *counts;                /* ncells: list lengths of the last frame collected */
    bool counted;                    /* counts hold a frame */
    char tile_define[24], tiles_x_define[32], tiles_y_define[32], slices_define[24];
    char slices_y_define[24], tlists_define[24];
    /* tiles.levels: 2 (coarse.c): big tiles of `coarse` pixels culled first */
    int levels, coarse;              /* tiles.levels, tiles.coarse_size */
    uint32_t coarse_x, coarse_y, coarse_capacity;   /* at light_grid_size */
    GLuint coarse_tiles, coarse_indices, coarse_stats, coarse_program;
    char coarse_define[24], coarse_x_define[32], coarse_lists_define[24];
    /* zbin (zbin.c): lights sorted by view depth, depth bins, a bit mask a tile */
    uint32_t zbins;                  /* zbin.bins; 0: not zbin (lists in the index buffer) */
    uint32_t zbin_words;             /* mask words a tile: ceil(max_lights / 32) */
    GLuint zbin_sorted, zbin_keys, zbin_bins, zbin_masks, zbin_program;
    uint32_t zbin_count;             /* lights sorted this frame */
    char zbin_define[24];
} light_grid;

/* The options, at create: tiles.size (0: 16) into g->tile (and tiles.depth_culling into
 * g->depth_mask, tiles.prune into g->prune_samples), and clustered.slices (0: 24) into g->slices_y; false with "NAME: tiles.size ..." / "NAME: clustered.slices ...". */
bool light_grid_tile_option(light_grid *g, const char *name, const renderer_options *o,
                            char *err, size_t errlen);
bool light_grid_slices_option(light_grid *g, const char *name, const renderer_options *o,
                              char *err, size_t errlen);
/* lights.culling (renderers/frame/stochastic.h), at create by a design that reads it:
 * o->culling_error into g, and b's programs made with STOCHASTIC when it is > 0. */
struct renderer_base;
void light_grid_culling_option(light_grid *g, struct renderer_base *b,
                               const renderer_options *o);

/* At prepare, for s at width x height: the tiles, the slices (refused beyond 1024 with a
 * message), the cells, whether the lists are culled (cull) and whether translucent lists
 * are built (cull and translucency), and max_lights. */
bool light_grid_size(light_grid *g, const scene *s, int width, int height, bool cull,
                     bool translucency, char *err, size_t errlen);
/* GL_MAX_SHADER_STORAGE_BLOCK_SIZE of the context. */
int light_grid_max_block(void);
/* Whether the heads (cells + translucent lists, 16 bytes each) fit a storage block of
 * max_block bytes; false with "NAME: HEADS WHAT need ... bytes of list heads ...". */
bool light_grid_heads_fit(const light_grid *g, const char *what, int max_block, char *err,
                          size_t errlen);
/* Whether max_lights lights fit a storage block; false with "NAME: N lights need ...". */
bool light_grid_lights_fit(const light_grid *g, uint32_t nlights, int max_block, char *err,
                           size_t errlen);
/* The index buffer's entries (the header's cap) for max_lights_per_tile (0: every light). */
void light_grid_capacity(light_grid *g, uint32_t max_lights_per_tile, int max_block);
/* TILE_SIZE, TILES_X, TILES_Y, SLICES, SLICES_Y and TLISTS (the cells) into the defines. */
/* "DEPTH_MASK" for the cull and shading programs when the lists are masked, else NULL. */
const char *light_grid_mask_define(const light_grid *g);
/* "PRUNE_SAMPLES" for the cull programs when the lists are pruned by samples, else NULL. */
const char *light_grid_prune_define(const light_grid *g);
void light_grid_defines(light_grid *g);
/* tiles.levels: 2 (coarse.c): big tiles of g->coarse pixels, coarse_x x coarse_y of them
 * (none at levels 1 or without the cull), culled first by their own dispatch
 * (tile_cull.comp with COARSE_SIZE) into their own heads and indices (every light in
 * every big tile, capped); each fine tile then culls its big tile's list (COARSE_LISTS,
 * bound at BIND_SSBO_COARSE_*): the same lists as levels 1. levels_option: at create
 * (from light_grid_tile_option); size, defines, alloc, release: from the grid's own. */
bool light_grid_levels_option(light_grid *g, const renderer_options *o, char *err,
                              size_t errlen);
void light_grid_coarse_size(light_grid *g);
void light_grid_coarse_defines(light_grid *g);
/* "COARSE_LISTS R" (R fine tiles a big tile's side) for the fine cull, else NULL. */
const char *light_grid_coarse_lists_define(const light_grid *g);
bool light_grid_coarse_alloc(light_grid *g);
void light_grid_coarse_release(light_grid *g);
/* The coarse program into g->coarse_program (none without big tiles); samples_define:
 * "MSAA_SAMPLES n" at msaa > 1, else NULL. False with a message. */
bool light_grid_coarse_compile(light_grid *g, gl_program_cache *pc, const char *samples_define,
                               char *err, size_t errlen);
/* The coarse dispatch (the caller's "cull-coarse" pass, the depth target bound at
 * BIND_TEX_DEPTH): it leaves the coarse buffers at the lists' bindings, so the caller
 * binds the grid's (light_grid_bind_lists) before the fine cull. */
void light_grid_coarse_dispatch(const light_grid *g, gl_state *st, uint32_t nlights);
/* The buffers and the readback arrays; false when out of memory (the caller says so). */
bool light_grid_alloc(light_grid *g);
/* What alloc made; a zeroed grid is fine (the options and sizes stay). */
void light_grid_release(light_grid *g);
/* The translucent pass's view of the grid (translucent_compile). */
translucent_grid light_grid_translucent(const light_grid *g);

/* zbin (zbin.c): zbin.bins into g->zbins (16 to 4096), at create; after
 * light_grid_size: whether the masks and the sort fit (at most 65536 lights: 16-bit
 * indices) with a message; the define (ZBIN_BINS n, NULL when not zbin or not culled);
 * the program, the buffers, their release. */
bool light_grid_zbin_option(light_grid *g, const renderer_options *o, char *err,
                            size_t errlen);
bool light_grid_zbin_fit(light_grid *g, int max_block, char *err, size_t errlen);
const char *light_grid_zbin_define(const light_grid *g);
bool light_grid_zbin_compile(light_grid *g, gl_program_cache *pc, char *err, size_t errlen);
bool light_grid_zbin_alloc(light_grid *g);
void light_grid_zbin_release(light_grid *g);
/* The sort-and-bin dispatches (zbin.comp, many work groups each; docs/notes/zbin.md counts
 * them) over the frame's nlights lights (uploaded, at BIND_SSBO_LIGHTS); then
 * light_grid_bind_lights binds the sorted ones. */
void light_grid_zbin_dispatch(light_grid *g, gl_state *st, uint32_t nlights);
/* Bytes of the light structures the last frame used: zbin's sorted lights, bins and
 * masks; else the lights, the list heads and the indices taken (needed). */
double light_grid_struct_bytes(const light_grid *g, uint32_t needed);

// >>per frame

/* The frame's visible lights into the light buffer (with stochastic culling their ranges
 * cut for the frame, stochastic_ranges); returns how many. */
uint32_t light_grid_upload_lights(light_grid *g, const scene *s, const frontend *fe);
/* Before the dispatch: stats = {0, capacity}. */
void light_grid_reset(const light_grid *g);
/* The light buffer at BIND_SSBO_LIGHTS; the lists' buffers at their bindings. */
void light_grid_bind_lights(const light_grid *g, gl_state *st);
void light_grid_bind_lists(const light_grid *g, gl_state *st);
/* The dispatch: one work group per tile. */
void light_grid_dispatch(const light_grid *g, gl_state *st);
/* After the frame's sync point (only when the lists were culled): the counters into out,
 * the lengths into counts. */
void light_grid_collect(light_grid *g, frame_stats *out);
/* renderer_impl.light_grid: the lengths of the last frame collected. */
const uint32_t *light_grid_counts(const light_grid *g, size_t *n);
struct forward_common;
/* renderer_impl.collect and .light_grid of a forward renderer whose forward_common.grid
 * is set (forward-plus, clustered, visibility): the base's counters, then the grid's
 * when the cull pass ran. */
void forward_grid_collect(void *self, frame_stats *out);
const uint32_t *forward_grid_counts(const void *self, size_t *n);
/* The plan's "translucent-lists" entry of such a renderer (forward_describe_pass): built
 * in the cull dispatch when the scene has translucency and the cull runs. */
void forward_grid_describe_translucent(const struct forward_common *c, pass_plan *out);
/* The end of such a renderer's prepare: at msaa > 1 with the cull pass, *depth_ranges,
 * the tiles' culled depth ranges (TILE_DEPTH_RANGES: a vec2 a tile; a uvec4 with
 * DEPTH_MASK, the tile's cells too); then the translucent
 * pass over the grid's translucent lists (every light without them). False with a
 * message. */
bool forward_grid_prepare_end(struct forward_common *c, GLuint *depth_ranges, char *err,
                              size_t errlen);
