/* tiles.levels: 2, the coarse level of the light grid (grid.h's "levels"). */
#include "renderers/tiled/grid.h"

#include <stdio.h>

#include "renderers/frame/bindings.h"

bool light_grid_levels_option(light_grid *g, const renderer_options *o, char *err,
                              size_t errlen)
{
    g->levels = o->tile_levels ? o->tile_levels : 1;
    g->coarse = o->coarse_size ? o->coarse_size : 64;
    if (g->levels != 1 && g->levels != 2) {
        snprintf(err, errlen, "%s: tiles.levels %d: expected 1 or 2", g->name, g->levels);
        return false;
    }
    if (g->levels == 2 && (g->coarse % g->tile != 0 || g->coarse > 512)) {
        snprintf(err, errlen, "%s: tiles.coarse_size %d: expected a multiple of tiles.size "
                 "(%d) up to 512", g->name, g->coarse, g->tile);
        return false;
    }
    return true;
}

void light_grid_coarse_size(light_grid *g)
{
    g->coarse_x = g->coarse_y = g->coarse_capacity = 0;
    if (g->levels != 2 || !g->cull)
        return;
    uint32_t r = (uint32_t)(g->coarse / g->tile);
    g->coarse_x = (g->tiles_x + r - 1) / r;
    g->coarse_y = (g->tiles_y + r - 1) / r;
    /* every light in every big tile, at most the index cap: a big tile whose list does
     * not fit leaves its tiles culling every light (tile_cull.inc), the same lists */
    uint64_t want = (uint64_t)g->coarse_x * g->coarse_y * g->max_lights;
    g->coarse_capacity = (uint32_t)(want < LIGHT_GRID_INDEX_CAP ? want : LIGHT_GRID_INDEX_CAP);
}

void light_grid_coarse_defines(light_grid *g)
{
    snprintf(g->coarse_define, sizeof g->coarse_define, "COARSE_SIZE %d", g->coarse);
    snprintf(g->coarse_x_define, sizeof g->coarse_x_define, "TILES_X %u", g->coarse_x);
    snprintf(g->coarse_lists_define, sizeof g->coarse_lists_define, "COARSE_LISTS %d",
             g->coarse / g->tile);
}

const char *light_grid_coarse_lists_define(const light_grid *g)
{
    return g->coarse_x ? g->coarse_lists_define : NULL;
}

bool light_grid_coarse_alloc(light_grid *g)
{
    if (!g->coarse_x)
        return true;
    GLuint b[3];
    size_t bytes[3] = {(size_t)g->coarse_x * g->coarse_y * 16u,
                       (size_t)g->coarse_capacity * 4u, 2 * sizeof(uint32_t)};
    gl.CreateBuffers(3, b);
    for (int i = 0; i < 3; i++)
        gl.NamedBufferStorage(b[i], (GLsizeiptr)bytes[i], NULL, GL_DYNAMIC_STORAGE_BIT);
    g->coarse_tiles = b[0];
    g->coarse_indices = b[1];
    g->coarse_stats = b[2];
    return true;
}

void light_grid_coarse_release(light_grid *g)
{
    GLuint b[3] = {g->coarse_tiles, g->coarse_indices, g->coarse_stats};
    for (int i = 0; i < 3; i++)
        if (b[i])
            gl.DeleteBuffers(1, &b[i]);
    g->coarse_tiles = g->coarse_indices = g->coarse_stats = 0;
    g->coarse_program = 0;   /* the program cache's */
}

bool light_grid_coarse_compile(light_grid *g, gl_program_cache *pc, const char *samples_define,
                               char *err, size_t errlen)
{
    g->coarse_program = 0;
    if (!g->coarse_x)
        return true;
    char why[4096] = "";
    gl_program_desc d = {.name = "tile_cull_coarse", .compute = "tile_cull.comp",
                         .defines = {g->tile_define, g->coarse_x_define, g->coarse_define,
                                     samples_define}};
    if (gl_program_get(pc, &d, &g->coarse_program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "%s: %s", g->name, why);
        return false;
    }
    return true;
}

void light_grid_coarse_dispatch(const light_grid *g, gl_state *st, uint32_t nlights)
{
    const uint32_t reset[2] = {0, g->coarse_capacity};   /* b_stats: next, capacity */
    gl.NamedBufferSubData(g->coarse_stats, 0, sizeof reset, reset);
    gl_state_program(st, g->coarse_program);
    gl.Uniform1i(LOC_RENDERER, (GLint)nlights);
    /* the coarse level writes through the fine level's bindings (tile_cull.inc) */
    gl_state_storage_buffer(st, BIND_SSBO_TILE_LISTS, g->coarse_tiles);
    gl_state_storage_buffer(st, BIND_SSBO_TILE_INDICES, g->coarse_indices);
    gl_state_storage_buffer(st, BIND_SSBO_TILE_STATS, g->coarse_stats);
    gl_state_dispatch(st, g->coarse_x, g->coarse_y, 1);
    gl_state_barrier(st, GL_SHADER_STORAGE_BARRIER_BIT);
}
