// forward-plus's light culling (Harada et al. 2012): one work group per screen tile of
// TILE_SIZE x TILE_SIZE pixels, one invocation per pixel.
// The steps, clustered (SLICES), MSAA_SAMPLES, TLISTS and the defines: above main().
// Defines: TILE_SIZE, TILES_X (and SLICES, SLICES_Y, TILES_Y; MSAA_SAMPLES,
// TILE_DEPTH_RANGES; TLISTS; DEPTH_MASK, PRUNE_SAMPLES; COARSE_SIZE or COARSE_LISTS).
// Uniforms: u_light_count.
#define TILES_COHERENT   // clusters read their tile's list, written in this dispatch
#include "bindings.h"
#include "frame.inc"
#include "lighting.inc"
#include "lights.inc"
#include "tiles.inc"
layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

#ifdef MSAA_SAMPLES
layout(binding = BIND_TEX_DEPTH) uniform sampler2DMS t_depth;
#else
layout(binding = BIND_TEX_DEPTH) uniform sampler2D t_depth;
#endif

#include "tile_cull.inc"

//   1. The tile's depth range: the smallest and largest pre-pass depth of its pixels
//      with geometry (depth < 1), widened by two steps of the 24-bit depth buffer so
//      that no surface's reconstructed depth falls outside; a tile without geometry
//      gets an empty list.
//   2. Its frustum: four planes through the eye and the edges of the tile on the near
//      plane (from the inverse projection), and the depth range.
//   3. Every light of the frame is tested, TILE_SIZE^2 at a time, one per invocation:
//      point lights as their sphere (radius = range); spots as the smaller of that
//      sphere and the cone's bounding sphere; directional lights always pass. The
//      test is conservative (a light that reaches no pixel of the tile may pass; one
//      that reaches one always does), so the shading loop, which rejects by range
//      again, adds exactly what forward-spml adds.
//   4. The list is counted first, then its place in the shared index buffer taken
//      with one atomicAdd (dynamically sized: no per-tile budget), then written in
//      light order (a bit mask per chunk of lights, popped by runs of words at places
//      given by an exclusive prefix of the runs' counts; cull_cell in
//      tile_cull.inc). A list that does not fit the buffer is not written: the tile
//      records an empty list (and its true length in w); b_stats.next then exceeds the capacity and the frame fails
//      (forward_plus.c), whatever order the tiles took their places in.
// Clustered (Olsson, Billeter and Assarsson 2012), with SLICES defined: each tile is cut
// into exponential depth slices, k = floor(log(-z/near) / log(1 + 2 tan(fov/2) / S_y))
// with S_y = SLICES_Y (clustered.slices), so that clusters are about as deep as they are
// wide; SLICES of them reach the far plane (shading_cluster_slices). The tile's list is
// made first, then each slice the tile's depth range meets (one more on either side) is
// culled from that list against the slice's depth range (cull_clusters, tile_cull.inc);
// the other clusters are written empty.
// MSAA_SAMPLES (msaa > 1): the depth is multisampled and step 1 reads EVERY sample of
// each pixel (texelFetch with each sample index, not a resolved copy: a resolve would
// average or pick depths, and a light reaching only a sample off the pixel centre, at
// the tile's nearest or farthest depth, would be culled); a pixel counts as covered
// when some sample has geometry, in the slice of its nearest such sample. With
// TILE_DEPTH_RANGES the tile's range is also written to b_tile_depth (tiles.inc) for
// the shading pass.
// DEPTH_MASK (tiles.depth_culling: mask): after step 1, the cells of the range each
// sample occupies (tile_mask_cover), and the tile's list keeps only the lights whose
// depth extent covers one of them (Harada's 2.5D culling; tile_cull.inc).
// TLISTS (the scene has translucent objects): then, in the same work group, the tile's
// translucent list (near plane to the tile's max depth, cull_translucent in
// tile_cull.inc) for the translucent pass.
// COARSE_SIZE (tiles.levels: 2, coarse.c): the dispatch of the big tiles, COARSE_SIZE
// pixels a side (TILES_X: theirs), each invocation covering every TILE_SIZE-th pixel of
// its big tile; their lists, culled as a tile's (with more slack, light_sphere), are
// what each tile of the fine dispatch culls then (COARSE_LISTS, cull_tile).
void cover_pixel(ivec2 pixel)
{
    if (all(lessThan(pixel, ivec2(f_viewport.xy)))) {
#ifdef MSAA_SAMPLES
        float d, d_far;
        pixel_depth_range(pixel, d, d_far);
#else
        float d = texelFetch(t_depth, pixel, 0).r, d_far = d;
#endif
        if (d < 1.0) {
            tile_cover(d, d_far);
#ifdef SLICES
            atomicAdd(s_slice_covered[slice_of(view_z(d))], 1u);
#endif
        }
    }
}

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    tile_reset(gl_LocalInvocationIndex);
    barrier();
#ifdef COARSE_SIZE
    const int R = COARSE_SIZE / TILE_SIZE;
    ivec2 base = ivec2(gl_WorkGroupID.xy) * COARSE_SIZE + ivec2(gl_LocalInvocationID.xy);
    for (int y = 0; y < R; y++)
        for (int x = 0; x < R; x++)
            cover_pixel(base + ivec2(x, y) * TILE_SIZE);
#else
    cover_pixel(pixel);
#endif
    barrier();
    cull_tile(pixel);   // DEPTH_MASK: the depth mask first (tile_cull.inc)
}
