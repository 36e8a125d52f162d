// tiled-deferred's one light pass (Andersson 2009, Lauritzen 2010): a work group per
// TILE_SIZE x TILE_SIZE tile of the G-buffer, an invocation per pixel. The tile's
// depth range and frustum and its light list are made as tile_cull.comp makes them
// (tile_cull.inc: counted, placed with one atomicAdd, written in light order); then
// every pixel loads its surface (gbuffer.inc, the layout's defines as the deferred
// renderer's passes get them) and adds ambient x diffuse + emissive and the lights of
// the tile's list (directional lights pass every tile) with forward-spml's range
// rejection, and stores the sum into the HDR target (image unit BIND_IMAGE_HDR,
// rgba16f, or rgba32f with HDR_RGBA32F: the image's format qualifier must be the
// target's, renderers/frame/base.h): ambient, directional and local lights in one pass, one
// write per pixel.
// The variants (NO_GRID, SLICES, TLISTS, MSAA_SAMPLES, LIGHT_PREPASS) and the defines:
// the comment above main().
#define TILES_COHERENT
#include "bindings.h"
#include "frame.inc"
#include "environment.inc"
#include "lighting.inc"
#include "lights.inc"
#include "tiles.inc"

vec2 g_frag_xy;   // the pixel's centre (or a sample's position), for gbuffer.inc
#define GB_FRAG_XY g_frag_xy
#ifdef MSAA_SAMPLES
int gb_sample = 0;
#define GB_SAMPLE gb_sample
#define HDR_IMAGE image2DMS
// the context's GL_SAMPLE_POSITIONs (after u_light_count)
layout(location = LOC_RENDERER + 1) uniform vec2 u_sample_pos[8];
#else
#define HDR_IMAGE image2D
#endif
#include "gbuffer.inc"
#ifdef MSAA_SAMPLES
#include "edge_rule.inc"
layout(std430, binding = BIND_SSBO_EDGES) buffer EdgeCount {
    uint edges;   // edge pixels of the frame
} b_edges;
shared uint s_nedges;
shared uint s_edges[TILE_SIZE * TILE_SIZE];   // the tile's edge pixels (local index)
#endif

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;
#if defined(LIGHT_PREPASS) && defined(LIGHT_BUFFER_RGBA8)
layout(binding = BIND_IMAGE_HDR, rgba8) writeonly uniform HDR_IMAGE i_hdr;
layout(binding = BIND_IMAGE_LIGHT_SPECULAR, rgba8) writeonly uniform HDR_IMAGE i_specular;
#elif defined(LIGHT_PREPASS)
layout(binding = BIND_IMAGE_HDR, rgba16f) writeonly uniform HDR_IMAGE i_hdr;
layout(binding = BIND_IMAGE_LIGHT_SPECULAR, rgba16f) writeonly uniform HDR_IMAGE i_specular;
#elif defined(HDR_RGBA32F)
layout(binding = BIND_IMAGE_HDR, rgba32f) writeonly uniform HDR_IMAGE i_hdr;
#else
layout(binding = BIND_IMAGE_HDR, rgba16f) writeonly uniform HDR_IMAGE i_hdr;
#endif

// What a pixel (or sample) stores: the shaded colour, or (LIGHT_PREPASS) the diffuse
// light in c and the specular light in s.
struct Shaded {
    vec3 c, s;
};

#include "tile_cull.inc"

// ambient x diffuse + emissive and the lights of g's list (its tile's, or its cluster's
// by its view depth), after the lists are made; LIGHT_PREPASS: the list's diffuse and
// specular light alone
Shaded shade_surface(GSurface g, uint tile_index)
{
#if defined(ZBIN_BINS)
    uint first = 0u, n = 0u;   // zbin: the mask and the bin instead (below)
#elif !defined(NO_GRID)
#ifndef SLICES
    uint cell = tile_index;
#else
    uint cell = uint(slice_of(g.position.z)) * uint(TILES_X * TILES_Y) + tile_index;
#endif
    uvec4 list = b_tiles[cell];
    uint first = list.x, n = list.y;
#else
    uint first = 0u, n = uint(u_light_count);
#endif
#ifdef LIGHT_PREPASS
    Shaded o = Shaded(vec3(0.0), vec3(0.0));
#else
    vec3 a = ambient_light(g.position, g.normal, g.diffuse, g.gloss, g.shininess, g.occlusion);
#ifdef ENVIRONMENT
    a = g.present ? a : vec3(0.0);   // the environment's specular needs no diffuse colour
#endif
    Shaded o = Shaded(a + g.emissive, vec3(0.0));
#endif
    if (g.present) {
#ifdef ZBIN_BINS
        // zbin (zbin.inc): the tile mask's bits within the bin of the position
        ZbinIter it = zbin_begin(tile_index, g.position.z, false);
        uint i;
        while (zbin_next(it, i)) {
#else
        for (uint k = 0u; k < n; k++) {
            uint i = tile_light(first, k);
#endif
            if (!light_reaches(i, g.position))
                continue;
#ifdef LIGHT_PREPASS
            vec3 d, sp;
            light_prepass(b_lights[i], g.position, g.normal, g.shininess, g.f0, d, sp);
            o.c += d;
            o.s += sp;
#else
            o.c += shade_light(b_lights[i], g.position, g.normal, g.diffuse, g.gloss,
                               g.shininess);
#endif
        }
    }
    return o;
}

// One store of what a pixel's sample i (single-sampled: the pixel) takes; the light
// buffer's alpha is 0, as the volumes' blending leaves it.
#ifdef LIGHT_PREPASS
#define STORED_ALPHA 0.0
#else
#define STORED_ALPHA 1.0
#endif
void store(ivec2 p, int i, Shaded o)
{
#ifdef MSAA_SAMPLES
    imageStore(i_hdr, p, i, vec4(o.c, STORED_ALPHA));
#ifdef LIGHT_PREPASS
    imageStore(i_specular, p, i, vec4(o.s, 0.0));
#endif
#else
    imageStore(i_hdr, p, vec4(o.c, STORED_ALPHA));
#ifdef LIGHT_PREPASS
    imageStore(i_specular, p, vec4(o.s, 0.0));
#endif
#endif
}

// NO_GRID (no point or spot light in the scene): no culling, every light looped.
// SLICES (clustered with clustered.shading: deferred): the tile's clusters are culled as
// tile_cull.comp culls them, and each pixel takes its cluster's list by the view depth
// of its G-buffer position.
// TLISTS (the scene has translucent objects): each tile's translucent list too, as
// tile_cull.comp makes it (cull_translucent), for the translucent pass after the sky.
// MSAA_SAMPLES (msaa > 1; Lauritzen 2010's compute path): the G-buffer, depth and HDR
// target are multisampled (GB_MSAA, image2DMS). The tile's depth range covers every
// sample (as tile_cull.comp's MSAA_SAMPLES path); each pixel is classified by
// edge_rule.inc (the rule of deferred's edge_mark.frag) and sample 0 is shaded for every
// pixel and stored into every sample of a non-edge pixel; edge pixels are appended to a
// per-tile list in shared memory and, after a barrier, the work group shades their other
// samples (read at their GL_SAMPLE_POSITIONs, u_sample_pos), N - 1 per listed pixel,
// spread over its invocations. b_edges counts the frame's edge pixels. With SLICES a
// cluster is counted covered when any sample of a pixel lies in it, so that each sample
// finds its cluster's list.
// LIGHT_PREPASS (deferred-lighting with deferred_lighting.lights: tiled): the lights
// alone, without ambient, emissive or the material, summed as deferred_light.frag's
// LIGHT_PREPASS sums them (diffuse light with a white diffuse and no gloss, specular with
// a black diffuse and a gloss of 1) and stored into the light buffer's two images,
// diffuse at BIND_IMAGE_HDR and specular at BIND_IMAGE_LIGHT_SPECULAR (rgba16f, or rgba8
// with LIGHT_BUFFER_RGBA8, where the store clamps to 1 as the volumes' blending does).
// DEPTH_MASK (tiles.depth_culling: mask): the tile's list masked by the cells its
// samples occupy, as tile_cull.comp's. ZBIN_BINS (zbin with zbin.shading: deferred): the
// tile keeps a bit mask over the depth-sorted lights (zbin_cull_tile), and each pixel
// or sample shades its bits within the bin of its position (zbin.inc).
// Defines: TILE_SIZE, TILES_X (TILES_Y, SLICES, TLISTS, MSAA_SAMPLES, LIGHT_PREPASS,
// LIGHT_BUFFER_RGBA8, DEPTH_MASK), the G-buffer layout's, SHADOWS.
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
                          vec3(0.0), 1.0, vec3(0.04));
    if (inside)
        g = gbuffer_load();
#ifdef MSAA_SAMPLES
    if (me == 0u)
        s_nedges = 0u;
#endif
#ifndef NO_GRID
    tile_reset(me);
#endif
#if !defined(NO_GRID) || defined(MSAA_SAMPLES)
    barrier();
#endif
#ifdef MSAA_SAMPLES
    // every sample: the depth range, the edge rule, (SLICES) the clusters they lie in
    bool edge = false;
    float d = 1.0, d_far = 0.0;   // the nearest and farthest sample with geometry
    uvec2 slices_met = uvec2(0u);
    if (inside) {
        pixel_depth_range(pixel, d, d_far);
        gb_sample = 0;
#ifdef EDGE_SAMPLE_XY
        g_frag_xy = vec2(pixel) + u_sample_pos[0];
#endif
        GSurface g0 = gbuffer_load();
        for (int i = 1; i < MSAA_SAMPLES; i++) {
            gb_sample = i;
            g_frag_xy = vec2(pixel) + 0.5;
#ifdef EDGE_SAMPLE_XY
            g_frag_xy = vec2(pixel) + u_sample_pos[i];
#endif
            GSurface gi = gbuffer_load();
            if (edge_samples_differ(g0, gi))
                edge = true;
#ifdef SLICES
            if (gi.present) {
                int k = slice_of(gi.position.z);
                slices_met[k >> 5] |= 1u << uint(k & 31);
            }
#endif
        }
        gb_sample = 0;
        g_frag_xy = vec2(pixel) + 0.5;
        if (edge) {
            // sample 0 of an edge pixel is shaded where it lies, as a per-sample
            // fragment of deferred's edge class is (its position rebuilt there)
            g = g0;
            s_edges[atomicAdd(s_nedges, 1u)] = me;
        }
    }
#else
    float d = inside ? texelFetch(t_depth, pixel, 0).r : 1.0, d_far = d;
#endif
#ifndef NO_GRID
    if (inside) {
        if (d < 1.0) {
            tile_cover(d, d_far);
#ifdef SLICES
            if (g.present) {
                int k0 = slice_of(g.position.z);
                atomicAdd(s_slice_covered[k0], 1u);
#ifdef MSAA_SAMPLES
                slices_met[k0 >> 5] &= ~(1u << uint(k0 & 31));
#endif
            }
#ifdef MSAA_SAMPLES
            for (int k = 0; k < SLICES; k++)   // the other samples' clusters, once each
                if ((slices_met[k >> 5] & (1u << uint(k & 31))) != 0u)
                    atomicAdd(s_slice_covered[k], 1u);
#endif
#endif
        }
    }
    barrier();
    cull_tile(pixel);   // DEPTH_MASK: the depth mask first (tile_cull.inc)
    memoryBarrierBuffer();
    barrier();
#elif defined(MSAA_SAMPLES)
    barrier();   // the edge list complete
#endif
    Shaded c = shade_surface(g, tile_index);
#ifndef MSAA_SAMPLES
    if (inside)
        store(pixel, 0, c);
#else
    if (inside) {
        store(pixel, 0, c);
        if (!edge)   // one shading for the whole pixel
            for (int i = 1; i < MSAA_SAMPLES; i++)
                store(pixel, i, c);
    }
    // the edge pixels' samples 1..N-1, spread over the work group
    uint nedges = s_nedges;
    uint per = uint(MSAA_SAMPLES - 1);
    for (uint k = me; k < nedges * per; k += uint(TILE_SIZE * TILE_SIZE)) {
        uint local = s_edges[k / per];
        int i = 1 + int(k % per);
        ivec2 p = ivec2(tile) * TILE_SIZE + ivec2(int(local % uint(TILE_SIZE)),
                                                  int(local / uint(TILE_SIZE)));
        gb_sample = i;
        g_frag_xy = vec2(p) + u_sample_pos[i];   // as a per-sample fragment's gl_FragCoord
        store(p, i, shade_surface(gbuffer_load(), tile_index));
    }
    if (me == 0u && nedges > 0u)
        atomicAdd(b_edges.edges, nedges);
#endif
}
