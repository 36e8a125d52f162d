// The light a tile's (or cluster's) list brings to a surface, added to c: forward_tiled.frag
// and visibility_shade.comp. Needs lighting.inc, lights.inc, tiles.inc and the shader's
// u_light_count. `first`, `count`: the list (NO_GRID: 0 and every light); `tile`: the
// pixel's screen tile. With TILE_DEPTH_RANGES (msaa > 1) a position outside the depth
// range the tile was culled against (a sample's surface shaded at the pixel centre)
// loops every light of the frame instead, in light order. ZBIN_BINS (zbin, zbin.inc):
// the pixel's tile mask and bin instead of a list (`every`: the bin without the mask).
void tile_lights_add(inout vec3 c, uint first, uint count, uvec2 tile, vec3 P, vec3 N,
                     vec3 diffuse, float gloss, float shininess)
{
    bool every = false;
#if defined(TILE_DEPTH_RANGES) && !defined(NO_GRID)
    every = outside_tile_depth(tile, P.z);
    if (every)
        count = uint(u_light_count);
#endif
#if defined(ZBIN_BINS) && !defined(TRANSLUCENT)
    // zbin: the directional lights, then the tile mask's bits within the bin of P
    ZbinIter it = zbin_begin(tile.y * uint(TILES_X) + tile.x, P.z, every);
    uint i;
    while (zbin_next(it, i))
        if (light_reaches(i, P))
            c += shade_light(b_lights[i], P, N, diffuse, gloss, shininess);
#else
    for (uint k = 0u; k < count; k++) {
        uint i = every ? k : tile_light(first, k);
        if (!light_reaches(i, P))
            continue;
        c += shade_light(b_lights[i], P, N, diffuse, gloss, shininess);
    }
#endif
}
