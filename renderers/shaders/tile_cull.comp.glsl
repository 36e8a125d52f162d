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
// Defines: TILE_SIZE, TILES_X. Uniforms: u_light_count (lights in b_lights).
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
        s_count = 0u;
    }
    barrier();
    if (all(lessThan(pixel, size))) {
        float d = texelFetch(t_depth, pixel, 0).r;
        if (d < 1.0) {
            atomicMin(s_min_depth, floatBitsToUint(d));
            atomicMax(s_max_depth, floatBitsToUint(d));
            atomicAdd(s_covered, 1u);
        }
    }
    barrier();
    uint covered = s_covered;
    uint nlights = covered == 0u ? 0u : uint(u_light_count);

    const float STEP = 2.0 / 16777215.0;
    float dmin = max(uintBitsToFloat(s_min_depth) - STEP, 0.0);
    float dmax = uintBitsToFloat(s_max_depth) + STEP;
    g_znear = view_z(dmin);
    g_zfar = dmax >= 1.0 ? uintBitsToFloat(0xff800000u) : view_z(dmax);   // -inf
    vec2 lo = vec2(tile * uint(TILE_SIZE)) / vec2(size) * 2.0 - 1.0;
    vec2 hi = vec2(min((tile + 1u) * uint(TILE_SIZE), uvec2(size))) / vec2(size) * 2.0 - 1.0;
    vec3 c00 = view_at(lo, -1.0), c10 = view_at(vec2(hi.x, lo.y), -1.0);
    vec3 c11 = view_at(hi, -1.0), c01 = view_at(vec2(lo.x, hi.y), -1.0);
    vec3 inside = (c00 + c10 + c11 + c01) * 0.25;
    g_planes[0] = plane_through_eye(c00, c01, inside);   // left
    g_planes[1] = plane_through_eye(c10, c11, inside);   // right
    g_planes[2] = plane_through_eye(c00, c10, inside);   // bottom
    g_planes[3] = plane_through_eye(c01, c11, inside);   // top

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
        b_tiles[tile_index] = uvec4(fits ? offset : 0u, fits ? count : 0u, covered, count);
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
