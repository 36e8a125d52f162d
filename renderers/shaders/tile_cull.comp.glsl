// forward-plus's light culling (Harada et al. 2012): one work group per screen tile of
// TILE_SIZE x TILE_SIZE pixels, one invocation per pixel.
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
//      light order (a prefix sum over each batch's pass flags). A list that does not
//      fit the buffer is not written: the tile records an empty list (and its true
//      length in w); b_stats.next then exceeds the capacity and the frame fails
//      (forward_plus.c), whatever order the tiles took their places in.
// Clustered (Olsson, Billeter and Assarsson 2012), with SLICES defined: each tile is cut
// into SLICES exponential depth slices, slice k holding view depths from
// near x r^k to near x r^(k+1), r = (far/near)^(1/SLICES), i.e. k = floor(log(-z/near)
// / log(r)) (Olsson's k with 1 + 2 tan(fov/2) / S_y = r); cluster (tile, k) gets the
// lights of steps 3-4 tested against the tile's planes and the slice's depth range
// (intersected with the tile's; each slice widened by 1e-3 of its depth so that a
// fragment's own computation of k, in forward_tiled.frag, never lands in a cluster
// that misses a light reaching it). Only the slices the tile's depth range meets, one
// more on either side, get lists; the others are written empty. Cells are numbered
// k x TILES_X x TILES_Y + tile.
// Defines: TILE_SIZE, TILES_X (and SLICES, TILES_Y). Uniforms: u_light_count.
#include "bindings.h"
#include "frame.inc"
#include "lighting.inc"
#include "lights.inc"
#include "tiles.inc"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

layout(binding = BIND_TEX_DEPTH) uniform sampler2D t_depth;
layout(location = LOC_RENDERER) uniform int u_light_count;

const uint N = uint(TILE_SIZE * TILE_SIZE);

shared uint s_min_depth, s_max_depth, s_covered, s_count, s_offset;
#ifdef SLICES
shared uint s_slice_covered[SLICES];
#endif
shared uint s_scan[TILE_SIZE * TILE_SIZE];

vec3 view_at(vec2 ndc_xy, float ndc_z)
{
    vec4 v = f_inv_proj * vec4(ndc_xy, ndc_z, 1.0);
    return v.xyz / v.w;
}

float view_z(float depth)
{
    return view_at(vec2(0.0), depth * 2.0 - 1.0).z;
}

vec4 plane_through_eye(vec3 a, vec3 b, vec3 inside)
{
    vec3 n = normalize(cross(a, b));
    if (dot(n, inside) < 0.0)
        n = -n;
    return vec4(n, 0.0);
}

vec4 g_planes[4];
float g_znear, g_zfar;   // view z of the range: g_znear >= z >= g_zfar (both negative)

bool sphere_passes(vec3 c, float r)
{
    if (c.z - r > g_znear || c.z + r < g_zfar)
        return false;
    for (int i = 0; i < 4; i++)
        if (dot(g_planes[i].xyz, c) < -r)
            return false;
    return true;
}

bool light_passes(uint i)
{
    Light l = b_lights[i];
    int type = int(l.color_type.w);
    if (type == LIGHT_DIRECTIONAL)
        return true;
    vec3 p = l.position_range.xyz;
    float range = l.position_range.w;
    // conservative against rounding: a little larger than the range
    float slack = 1e-4 * (range + length(p));
    if (type == LIGHT_SPOT) {
        float cosa = l.direction_cos.w;
        if (cosa >= 0.5) {
            float t = range / (2.0 * cosa);
            return sphere_passes(p + l.direction_cos.xyz * t, t + slack);
        }
    }
    return sphere_passes(p, range + slack);
}

// Inclusive prefix sum of s_scan over the work group (Hillis-Steele).
void scan()
{
    uint me = gl_LocalInvocationIndex;
    for (uint step = 1u; step < N; step *= 2u) {
        uint add = me >= step ? s_scan[me - step] : 0u;
        barrier();
        s_scan[me] += add;
        barrier();
    }
}

#ifdef SLICES
float slice_scale()
{
    return float(SLICES) / log(f_clip.y / f_clip.x);
}

// The slice of view depth z (negative), as forward_tiled.frag computes it.
int slice_of(float z)
{
    return clamp(int(floor(log(-z / f_clip.x) * slice_scale())), 0, SLICES - 1);
}

// View depth (positive) where slice k begins.
float slice_start(int k)
{
    return f_clip.x * exp(float(k) / slice_scale());
}
#endif

// Culls every light against the planes and [g_zfar, g_znear] into cell `cell`'s list.
// Called by the whole work group with the same arguments.
void cull_cell(uint cell, uint covered, uint nlights)
{
    uint me = gl_LocalInvocationIndex;
    if (me == 0u)
        s_count = 0u;
    barrier();

    // count
    for (uint base = 0u; base < nlights; base += N) {
        uint i = base + me;
        if (i < nlights && light_passes(i))
            atomicAdd(s_count, 1u);
    }
    barrier();
    uint count = s_count;
    if (me == 0u) {
        uint offset = count == 0u ? 0u : atomicAdd(b_stats.next, count);
        bool fits = offset <= b_stats.capacity && count <= b_stats.capacity - offset;
        s_offset = fits ? offset : 0xffffffffu;
        b_tiles[cell] = uvec4(fits ? offset : 0u, fits ? count : 0u, covered, count);
    }
    barrier();
    uint offset = s_offset;
    if (offset == 0xffffffffu || count == 0u)
        return;   // uniform across the work group
    // write, in light order
    uint written = 0u;
    for (uint base = 0u; base < nlights; base += N) {
        uint i = base + me;
        bool pass = i < nlights && light_passes(i);
        s_scan[me] = pass ? 1u : 0u;
        barrier();
        scan();
        if (pass)
            b_indices[offset + written + s_scan[me] - 1u] = i;
        uint batch = s_scan[N - 1u];
        barrier();
        written += batch;
    }
}

void main()
{
    uint me = gl_LocalInvocationIndex;
    uvec2 tile = gl_WorkGroupID.xy;
    uint tile_index = tile.y * uint(TILES_X) + tile.x;
    ivec2 size = ivec2(f_viewport.xy);
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
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
    if (all(lessThan(pixel, size))) {
        float d = texelFetch(t_depth, pixel, 0).r;
        if (d < 1.0) {
            atomicMin(s_min_depth, floatBitsToUint(d));
            atomicMax(s_max_depth, floatBitsToUint(d));
            atomicAdd(s_covered, 1u);
#ifdef SLICES
            atomicAdd(s_slice_covered[slice_of(view_z(d))], 1u);
#endif
        }
    }
    barrier();
    uint covered = s_covered;
    uint nlights = covered == 0u ? 0u : uint(u_light_count);

    const float STEP = 2.0 / 16777215.0;
    float dmin = max(uintBitsToFloat(s_min_depth) - STEP, 0.0);
    float dmax = uintBitsToFloat(s_max_depth) + STEP;
    float tile_znear = view_z(dmin);
    float tile_zfar = dmax >= 1.0 ? uintBitsToFloat(0xff800000u) : view_z(dmax);   // -inf
    vec2 lo = vec2(tile * uint(TILE_SIZE)) / vec2(size) * 2.0 - 1.0;
    vec2 hi = vec2(min((tile + 1u) * uint(TILE_SIZE), uvec2(size))) / vec2(size) * 2.0 - 1.0;
    vec3 c00 = view_at(lo, -1.0), c10 = view_at(vec2(hi.x, lo.y), -1.0);
    vec3 c11 = view_at(hi, -1.0), c01 = view_at(vec2(lo.x, hi.y), -1.0);
    vec3 inside = (c00 + c10 + c11 + c01) * 0.25;
    g_planes[0] = plane_through_eye(c00, c01, inside);   // left
    g_planes[1] = plane_through_eye(c10, c11, inside);   // right
    g_planes[2] = plane_through_eye(c00, c10, inside);   // bottom
    g_planes[3] = plane_through_eye(c01, c11, inside);   // top

#ifndef SLICES
    g_znear = tile_znear;
    g_zfar = tile_zfar;
    cull_cell(tile_index, covered, nlights);
#else
    uint ntiles = uint(TILES_X * TILES_Y);
    int kmin = 0, kmax = -1;   // no geometry: every cluster empty
    if (covered > 0u) {
        kmin = max(slice_of(tile_znear) - 1, 0);
        kmax = isinf(tile_zfar) ? SLICES - 1 : min(slice_of(tile_zfar) + 1, SLICES - 1);
    }
    for (int k = 0; k < SLICES; k++) {
        uint cell = uint(k) * ntiles + tile_index;
        if (k < kmin || k > kmax) {
            if (me == 0u)
                b_tiles[cell] = uvec4(0u);
            continue;
        }
        const float EPS = 1e-3;
        g_znear = min(tile_znear, -slice_start(k) * (1.0 - EPS));
        g_zfar = max(tile_zfar, -slice_start(k + 1) * (1.0 + EPS));
        cull_cell(cell, s_slice_covered[k], nlights);
        barrier();
    }
#endif
}
