// The per-tile light lists of the tiled renderers (forward_plus.c), std430:
//   b_tiles[t]    x: the list's first entry in b_indices, y: its length (lights),
//                 z: pixels of the tile with geometry (depth < 1), w: 0
//   b_indices[]   light indices into b_lights, each tile's list contiguous and in
//                 light order
//   b_stats       next: entries handed out so far; capacity: entries the index
//                 buffer holds; overflow_tile: the first tile that did not fit + 1
//                 (0: none), overflow_count: its length
// Needs bindings.h.
layout(std430, binding = BIND_SSBO_TILE_LISTS) buffer TileLists {
    uvec4 b_tiles[];
};
layout(std430, binding = BIND_SSBO_TILE_INDICES) buffer TileIndices {
    uint b_indices[];
};
layout(std430, binding = BIND_SSBO_TILE_STATS) buffer TileStats {
    uint next;
    uint capacity;
    uint overflow_tile;
    uint overflow_count;
} b_stats;
