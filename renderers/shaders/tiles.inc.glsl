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
//                 culled against, for forward_tiled.frag's fallback
// Needs bindings.h. TILES_COHERENT (tiled_deferred.comp, which reads the lists its own
// work group wrote) makes the lists coherent.
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
#ifdef TILE_DEPTH_RANGES
layout(std430, binding = BIND_SSBO_TILE_DEPTH) buffer TileDepth {
    vec2 b_tile_depth[];
};

// msaa: whether view z lies outside the depth range tile t was culled against (a
// sample's surface shaded at another position than the one culled): then every light
// of the frame is looped, in light order.
bool outside_tile_depth(uvec2 t, float z)
{
    vec2 range = b_tile_depth[t.y * uint(TILES_X) + t.x];
    return z > range.x || z < range.y;
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
