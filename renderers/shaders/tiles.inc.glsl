// The per-tile light lists of the tiled renderers (forward_plus.c), std430:
//   b_tiles[t]    x: the list's first entry in b_indices, y: its length (lights),
//                 z: pixels of the tile with geometry (depth < 1), w: the length the
//                 list needs (y = 0 when it did not fit the index buffer)
//   b_indices[]   light indices into b_lights, each tile's list contiguous and in
//                 light order
//   b_stats       next: entries asked for so far (beyond capacity: some list did not
//                 fit); capacity: entries the index buffer holds
//   b_tile_depth[t]  (TILE_DEPTH_RANGES: forward-plus and clustered at msaa > 1) the
//                 view-z range (near, far; far -inf when open) tile t's lights were
//                 culled against, for forward_tiled.frag's fallback; with DEPTH_MASK
//                 a uvec4: the range's bits, then the tile's cell mask (depth_cell)
// Then zbin.inc (ZBIN_BINS: zbin's bins and masks). Needs bindings.h and frame.inc.
// TILES_COHERENT (tiled_deferred.comp, which reads the lists its own work group wrote)
// makes the lists coherent.
#ifdef TILES_COHERENT
#define TILES_QUALIFIER coherent
#else
#define TILES_QUALIFIER
#endif
layout(std430, binding = BIND_SSBO_TILE_LISTS) TILES_QUALIFIER buffer TileLists {
    uvec4 b_tiles[];
};
layout(std430, binding = BIND_SSBO_TILE_INDICES) TILES_QUALIFIER buffer TileIndices {
    uint b_indices[];
};
layout(std430, binding = BIND_SSBO_TILE_STATS) buffer TileStats {
    uint next;
    uint capacity;
} b_stats;
#ifdef COARSE_LISTS
// tiles.levels: 2 (coarse.c): the big tiles' lists, as b_tiles and b_indices, big tile
// (x, y) of a tile (x, y) x COARSE_LISTS, COARSE_LISTS tiles a side.
layout(std430, binding = BIND_SSBO_COARSE_LISTS) readonly buffer CoarseLists {
    uvec4 b_coarse_tiles[];
};
layout(std430, binding = BIND_SSBO_COARSE_INDICES) readonly buffer CoarseIndices {
    uint b_coarse_indices[];
};
#endif
#ifdef DEPTH_MASK
// tiles.depth_culling: mask (Harada 2012's 2.5D culling, tile_cull.inc): a tile's depth
// range [zfar, znear] (view z) cut into 32 equal cells, 0 the nearest. The cell of z
// is floor((znear - z) x scale) clamped to 0..31, with scale = 32 / (znear - zfar), or
// 0 when the range is open (zfar -inf: every depth in cell 0, the mask passes every
// light the range passes). The cull and the shading's fallback use these two functions
// alone, so both find the same cell for the same depth (monotone in z).
float depth_cell_scale(float znear, float zfar)
{
    return !isinf(zfar) && znear > zfar ? 32.0 / (znear - zfar) : 0.0;
}

int depth_cell(float z, float znear, float scale)
{
    return clamp(int(floor((znear - z) * scale)), 0, 31);
}
#endif

#ifdef TILE_DEPTH_RANGES
#ifdef DEPTH_MASK
layout(std430, binding = BIND_SSBO_TILE_DEPTH) buffer TileDepth {
    uvec4 b_tile_depth[];   // near, far (float bits), the cells the tile's samples occupy
};
#else
layout(std430, binding = BIND_SSBO_TILE_DEPTH) buffer TileDepth {
    vec2 b_tile_depth[];
};
#endif

// msaa: whether view z lies outside the depth range tile t was culled against (a
// sample's surface shaded at another position than the one culled), or (DEPTH_MASK)
// in a cell no sample of the tile occupies: then every light of the frame is looped,
// in light order.
bool outside_tile_depth(uvec2 t, float z)
{
#ifdef DEPTH_MASK
    uvec4 e = b_tile_depth[t.y * uint(TILES_X) + t.x];
    vec2 range = uintBitsToFloat(e.xy);
    if (z > range.x || z < range.y)
        return true;
    int k = depth_cell(z, range.x, depth_cell_scale(range.x, range.y));
    return (e.z & (1u << uint(k))) == 0u;
#else
    vec2 range = b_tile_depth[t.y * uint(TILES_X) + t.x];
    return z > range.x || z < range.y;
#endif
}
#endif

// The k-th light of the list that starts at b_indices[first]; with NO_GRID (no cull
// pass ran: no point or spot light) every light, in order.
uint tile_light(uint first, uint k)
{
#ifdef NO_GRID
    return k;
#else
    return b_indices[first + k];
#endif
}

#include "zbin.inc"   // zbin's bins and masks (ZBIN_BINS)
