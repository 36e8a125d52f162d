// zbin's sort and bins (Drobot 2017; renderers/tiled/zbin.c), in dispatches of many work
// groups (u_stage; light_grid_zbin_dispatch issues them; a block: 2,048 entries):
//   ZS_FIRST  a group a block: each light's (key, index), key its depth's bits made an
//             order-preserving uint, 0 for a directional light (first: every pixel shades
//             them), padded to a power of two with 0xffffffff (the largest reach and the
//             directional count by atomics into the bins' head); the bitonic steps with
//             k <= the block, in shared memory
//   ZS_STEP   one bitonic step (u_k, u_j) with j >= the block, a pair an invocation
//   ZS_MERGE  a group a block: u_k's steps with j < the block, in shared memory
//   The last of these (k = all) copies the lights in order into b_sorted (the cull and
//   the shading read it as b_lights), each pair replaced by its depth and reach.
//   ZS_BINS   per bin (ZBIN_BINS linear bins over [near, far], zbin.inc): the lowest and
//             highest sorted index whose extent overlaps it (binary searches over the
//             sorted centres widened by the largest reach, then a scan inwards)
// The order is total (ties by index): the same every run. Defines: ZBIN_BINS.
#include "bindings.h"
#include "frame.inc"
#include "lighting.inc"
#include "lights.inc"
#include "tiles.inc"
layout(local_size_x = 256) in;
layout(location = LOC_RENDERER) uniform int u_light_count;
layout(location = LOC_RENDERER + 1) uniform int u_stage;
layout(location = LOC_RENDERER + 2) uniform int u_k;
layout(location = LOC_RENDERER + 3) uniform int u_j;

layout(std430, binding = BIND_SSBO_ZBIN_SORTED) writeonly buffer Sorted {
    Light b_sorted[];
};
layout(std430, binding = BIND_SSBO_ZBIN_KEYS) coherent buffer Keys {
    uvec2 b_zkeys[];
};
const uint NT = 256u, BLOCK = 2048u;   // zbin.c's ZBIN_BLOCK
const int ZS_FIRST = 0, ZS_STEP = 1, ZS_MERGE = 2, ZS_BINS = 3;   // zbin.c's
shared uvec2 s_keys[BLOCK];
shared uint s_rmax, s_directional;   // the group's, then one atomic each into the head

// The depth (view, positive in front) and reach of light l that the bins use: its centre
// and its range (a spot's whole sphere; the cull's test is the tighter one), a little
// larger against rounding; false for a directional light (in every bin). The one place
// a light's range enters the bins.
bool zbin_extent(Light l, out float depth, out float r)
{
    depth = -l.position_range.z;
    r = light_cull_range(l);   // with STOCHASTIC the frame's cut range (lighting.inc)
#if HAS_DIRECTIONAL
    if (int(l.color_type.w) == LIGHT_DIRECTIONAL)
        return false;
#endif
    r += 1e-4 * (r + length(l.position_range.xyz));
    return true;
}

uint order_key(float f)
{
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}

float depth_at(uint k)
{
    return uintBitsToFloat(b_zkeys[k].x);
}

float reach_at(uint k)
{
    return uintBitsToFloat(b_zkeys[k].y);
}

// The first sorted index in [first, end) whose depth is >= v (end when none).
uint lower_bound(uint first, uint end, float v)
{
    while (first < end) {
        uint mid = (first + end) / 2u;
        if (depth_at(mid) < v)
            first = mid + 1u;
        else
            end = mid;
    }
    return first;
}

bool overlaps(uint k, float b0, float b1)
{
    float d = depth_at(k), r = reach_at(k);
    return d - r <= b1 && d + r >= b0;
}

uint pow2_of(uint n)
{
    uint p2 = 1u;
    while (p2 < n)
        p2 <<= 1u;
    return p2;
}

// One compare-and-swap of a bitonic step (k, j) on pair t: (a, a + j) ordered ascending
// when bit k of a's global index is clear. x, y: the pair's two entries; true to swap.
uint pair_first(uint t, uint j)
{
    return 2u * j * (t / j) + t % j;
}

bool out_of_order(uvec2 x, uvec2 y, uint a, uint k)
{
    bool greater = x.x > y.x || (x.x == y.x && x.y > y.y);
    return greater == ((a & k) == 0u);
}

// The steps of k with j from j0 down to 1 on this group's block in s_keys (size: the
// block's entries), global index base + local.
void local_steps(uint base, uint size, uint k, uint j0)
{
    uint me = gl_LocalInvocationIndex;
    for (uint j = j0; j > 0u; j >>= 1u) {
        for (uint t = me; t < size / 2u; t += NT) {
            uint a = pair_first(t, j), b = a + j;
            uvec2 x = s_keys[a], y = s_keys[b];
            if (out_of_order(x, y, base + a, k)) {
                s_keys[a] = y;
                s_keys[b] = x;
            }
        }
        barrier();
    }
}

// The block back to b_zkeys; when the sort is done (last), the lights in that order
// into b_sorted and each entry replaced by its light's depth and reach.
void store_block(uint base, uint size, uint n, bool last)
{
    for (uint i = gl_LocalInvocationIndex; i < size; i += NT) {
        uint g = base + i;
        if (!last) {
            b_zkeys[g] = s_keys[i];
        } else if (g < n) {
            Light l = b_lights[s_keys[i].y];
            b_sorted[g] = l;
            float depth, r;
            if (!zbin_extent(l, depth, r))
                r = 0.0;
            b_zkeys[g] = uvec2(floatBitsToUint(depth), floatBitsToUint(r));
        }
    }
}

void sort_first(uint n, uint p2)
{
    uint me = gl_LocalInvocationIndex, size = min(p2, BLOCK), base = gl_WorkGroupID.x * BLOCK;
    if (me == 0u) {
        s_rmax = 0u;
        s_directional = 0u;
    }
    barrier();
    for (uint i = me; i < size; i += NT) {
        uint g = base + i, key = 0xffffffffu;
        if (g < n) {
            float depth, r;
            key = 0u;
            if (zbin_extent(b_lights[g], depth, r)) {
                key = max(order_key(depth), 1u);
                atomicMax(s_rmax, floatBitsToUint(r));   // r >= 0: its bits order as it
            } else {
                atomicAdd(s_directional, 1u);
            }
        }
        s_keys[i] = uvec2(key, g);
    }
    barrier();
    if (me == 0u) {
        atomicMax(z_rmax, s_rmax);
        atomicAdd(z_directional, s_directional);
    }
    for (uint k = 2u; k <= size; k <<= 1u)
        local_steps(base, size, k, k >> 1u);
    store_block(base, size, n, size == p2);
}

void sort_merge(uint n, uint p2)
{
    uint base = gl_WorkGroupID.x * BLOCK;
    for (uint i = gl_LocalInvocationIndex; i < BLOCK; i += NT)
        s_keys[i] = b_zkeys[base + i];
    barrier();
    local_steps(base, BLOCK, uint(u_k), BLOCK / 2u);
    store_block(base, BLOCK, n, uint(u_k) == p2);
}

void sort_step()
{
    uint j = uint(u_j), a = pair_first(gl_GlobalInvocationID.x, j), b = a + j;
    uvec2 x = b_zkeys[a], y = b_zkeys[b];
    if (out_of_order(x, y, a, uint(u_k))) {
        b_zkeys[a] = y;
        b_zkeys[b] = x;
    }
}

void fill_bins(uint n)
{
    uint first = z_directional;
    if (gl_GlobalInvocationID.x == 0u) {
        z_count = n;
        z_words = (n + 31u) / 32u;
    }
    float near = f_clip.x, w = (f_clip.y - f_clip.x) / float(ZBIN_BINS);
    float rmax = uintBitsToFloat(z_rmax);
    const float INF = uintBitsToFloat(0x7f800000u);
    uint b = gl_GlobalInvocationID.x;
    if (b >= uint(ZBIN_BINS))
        return;
    float b0 = near + float(b) * w, b1 = b0 + w;
    float e = 1e-3 * w + 1e-5 * abs(b1);   // against rounding of the pixel's bin
    b0 = b == 0u ? -INF : b0 - e;
    b1 = b == uint(ZBIN_BINS) - 1u ? INF : b1 + e;
    uint lo = lower_bound(first, n, b0 - rmax);
    uint end = lower_bound(lo, n, b1 + rmax);
    while (lo < end && !overlaps(lo, b0, b1))
        lo++;
    uint hi = end;
    while (hi > lo && !overlaps(hi - 1u, b0, b1))
        hi--;
    b_zbins[b] = lo < hi ? lo | (hi - 1u) << 16 : 0xffffu;
}

void main()
{
    uint n = uint(u_light_count), p2 = pow2_of(n);
    if (u_stage == ZS_FIRST)
        sort_first(n, p2);
    else if (u_stage == ZS_STEP)
        sort_step();
    else if (u_stage == ZS_MERGE)
        sort_merge(n, p2);
    else
        fill_bins(n);
}
