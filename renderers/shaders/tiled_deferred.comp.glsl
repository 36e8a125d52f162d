// tiled-deferred's one light pass (Andersson 2009, Lauritzen 2010): a work group per
// TILE_SIZE x TILE_SIZE tile of the G-buffer, an invocation per pixel. The tile's
// depth range and frustum and its light list are made as tile_cull.comp makes them
// (tile_cull.inc: counted, placed with one atomicAdd, written in light order); then
// every pixel loads its surface (gbuffer.inc, the layout's defines as the deferred
// renderer's passes get them) and adds ambient x diffuse + emissive and the lights of
// the tile's list (directional lights pass every tile) with forward-spml's range
// rejection, and stores the sum into the HDR target (image unit BIND_IMAGE_HDR,
// rgba16f, or rgba32f with HDR_RGBA32F: the image's format qualifier must be the
// target's, renderers/base.h): ambient, directional and local lights in one pass, one
// write per pixel.
// NO_GRID (no point or spot light in the scene): no culling, every light looped.
// SLICES (clustered with clustered.shading: deferred): the tile's clusters are culled as
// tile_cull.comp culls them, and each pixel takes its cluster's list by the view depth
// of its G-buffer position.
// TLISTS (the scene has translucent objects): each tile's translucent list too, as
// tile_cull.comp makes it (cull_translucent), for the translucent pass after the sky.
// Defines: TILE_SIZE, TILES_X (TILES_Y, SLICES, TLISTS), the G-buffer layout's, SHADOWS.
#define TILES_COHERENT
#include "bindings.h"
#include "frame.inc"
#include "lighting.inc"
#include "lights.inc"
#include "tiles.inc"

vec2 g_frag_xy;   // the pixel's centre, for gbuffer.inc
#define GB_FRAG_XY g_frag_xy
#include "gbuffer.inc"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;
#ifdef HDR_RGBA32F
layout(binding = BIND_IMAGE_HDR, rgba32f) writeonly uniform image2D i_hdr;
#else
layout(binding = BIND_IMAGE_HDR, rgba16f) writeonly uniform image2D i_hdr;
#endif

#include "tile_cull.inc"

void main()
{
    uint me = gl_LocalInvocationIndex;
    uvec2 tile = gl_WorkGroupID.xy;
    uint tile_index = tile.y * uint(TILES_X) + tile.x;
    ivec2 size = ivec2(f_viewport.xy);
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(pixel, size));
    g_frag_xy = vec2(pixel) + 0.5;
    GSurface g = GSurface(false, vec3(0.0, 0.0, -1.0), vec3(0.0, 0.0, 1.0), vec3(0.0), 0.0, 1.0,
                          vec3(0.0));
    if (inside)
        g = gbuffer_load();
#ifndef NO_GRID
    if (me == 0u) {
        s_min_depth = floatBitsToUint(1.0);
        s_max_depth = 0u;
        s_covered = 0u;
    }
#ifdef SLICES
    if (me < uint(SLICES))
        s_slice_covered[me] = 0u;
#endif
    barrier();
    if (inside) {
        float d = texelFetch(t_depth, pixel, 0).r;
        if (d < 1.0) {
            atomicMin(s_min_depth, floatBitsToUint(d));
            atomicMax(s_max_depth, floatBitsToUint(d));
            atomicAdd(s_covered, 1u);
#ifdef SLICES
            if (g.present)
                atomicAdd(s_slice_covered[slice_of(g.position.z)], 1u);
#endif
        }
    }
    barrier();
    uint covered = s_covered;
    uint nlights = covered == 0u ? 0u : uint(u_light_count);
    float tile_znear, tile_zfar;
    tile_frustum(tile, size, tile_znear, tile_zfar);
    g_znear = tile_znear;
    g_zfar = tile_zfar;
#ifndef SLICES
    cull_cell(tile_index, covered, nlights, 0u, false);
    uint cell = tile_index;
#else
    cull_clusters(tile_index, covered, nlights, tile_znear, tile_zfar);
    uint cell = uint(slice_of(g.position.z)) * uint(TILES_X * TILES_Y) + tile_index;
#endif
#ifdef TLISTS
    cull_translucent(tile, tile_index, size, covered, tile_zfar);
#endif
    memoryBarrierBuffer();
    barrier();
    uvec4 list = b_tiles[cell];
    uint first = list.x, n = list.y;
#else
    uint first = 0u, n = uint(u_light_count);
#endif
    vec3 c = f_ambient.rgb * g.diffuse + g.emissive;
    if (g.present) {
        for (uint k = 0u; k < n; k++) {
#ifdef NO_GRID
            Light l = b_lights[k];
#else
            Light l = b_lights[b_indices[first + k]];
#endif
            if (int(l.color_type.w) != LIGHT_DIRECTIONAL) {
                vec3 dv = l.position_range.xyz - g.position;
                float r = l.position_range.w;
                if (dot(dv, dv) > r * r)
                    continue;
            }
            c += shade_light(l, g.position, g.normal, g.diffuse, g.gloss, g.shininess);
        }
    }
    if (inside)
        imageStore(i_hdr, pixel, vec4(c, 1.0));
}
