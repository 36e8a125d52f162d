// forward-plus's and clustered's shading pass: ambient + emissive as
// forward_base.frag, then the lights
// of this pixel's tile list (built by tile_cull.comp) in light order, each with the
// squared-range rejection of forward_spml.frag, so that both loops add the same terms
// in the same order. Depth EQUAL against the pre-pass: each pixel is shaded once.
// clustered: SLICES (and TILES_Y) defined, the list is the fragment's cluster's.
// Defines: the material's maps (surface.inc); TILE_SIZE and TILES_X (the grid);
// NO_GRID, FOG, TILE_DEPTH_RANGES (msaa > 1) and TRANSLUCENT: the comment above main().
#include "bindings.h"
#include "frame.inc"
#include "surface.inc"
#include "environment.inc"
#include "lighting.inc"
#include "lights.inc"
#include "tiles.inc"
#include "fog.inc"

layout(location = LOC_RENDERER) uniform int u_light_count;   // lights in b_lights

layout(location = 0) out vec4 o_color;

#include "tile_shade.inc"

// Defines: the material's maps (surface.inc); TILE_SIZE and TILES_X (the grid);
// NO_GRID: the scene has no point or spot light, there is no cull pass and every
// light of the frame (u_light_count, all directional) is looped. FOG (fog.inc): the sum
// fogged. TILE_DEPTH_RANGES (msaa > 1): the fragment is shaded once per pixel at the
// pixel centre (as forward-spml's), which an edge's triangle need not cover (its
// position then extrapolated) and whose samples may be occluded where the fragment is
// not; when that position's view z lies outside the depth range its tile was culled
// against (b_tile_depth), every light of the frame is looped, in light order, so that
// no light the centre sees is missed (rare: pixels on the edges of steep surfaces).
// TRANSLUCENT (the translucent pass of forward-plus, clustered and
// tiled-deferred, renderers/frame/translucent.c): the list is the tile's translucent one,
// b_tiles[TLISTS + tile] (near plane to the tile's max opaque depth, tile_cull.inc),
// for clustered too (its clusters cover only the depths of the tile's opaque samples),
// and the output premultiplied, (c a, a), as forward_spml.frag's TRANSLUCENT.
void main()
{
    Surface s = surface_get();
    vec3 c = ambient_light(s.position, s.normal, s.diffuse, s.gloss, s.shininess,
                           s.occlusion) + s.emissive;
#ifdef NO_GRID
    uint first = 0u, n = uint(u_light_count);
    uvec2 t = uvec2(0u);
#else
    uvec2 t = uvec2(gl_FragCoord.xy) / uint(TILE_SIZE);
    uint cell = t.y * uint(TILES_X) + t.x;
#if defined(TRANSLUCENT)
    cell += uint(TLISTS);
#elif defined(SLICES)
    // the cluster: this tile's slice of the fragment's view depth (tile_cull.comp)
    float log_ratio = log(1.0 + 2.0 / (f_proj[1][1] * float(SLICES_Y)));
    int k = clamp(int(floor(log(-s.position.z / f_clip.x) / log_ratio)), 0, SLICES - 1);
    cell += uint(k) * uint(TILES_X * TILES_Y);
#endif
    uvec4 list = b_tiles[cell];
    uint first = list.x, n = list.y;
#endif
    tile_lights_add(c, first, n, t, s.position, s.normal, s.diffuse, s.gloss, s.shininess);
    o_color = forward_output(c, s.position.z, s.alpha);
}
