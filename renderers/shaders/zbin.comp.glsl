// zbin's first dispatch (Drobot 2017; renderers/tiled/zbin.c): ONE work group sorts the
// frame's lights by the view depth of their centres and fills the depth bins.
//   1. keys: per light (key, index), key the depth's bits made order-preserving as a
//      uint, 0 for a directional light (first: every pixel shades them); padded to a
//      power of two with 0xffffffff
//   2. a bitonic sort of the pairs in b_zkeys, its steps separated by barriers: the
//      order is total (ties by index), so the bins, the counters and the image are the
//      same every run, with no atomics; a counting sort would need a stable scatter
//   3. the lights copied in that order into b_sorted (the cull and the shading read it
//      as b_lights), each pair replaced by its light's depth and reach (zbin_extent)
//   4. per bin (ZBIN_BINS linear bins over [near, far], zbin.inc): the lowest and the
//      highest sorted index whose extent overlaps it, found from binary searches over the
//      sorted centres widened by the largest reach, then a scan inwards
// Defines: ZBIN_BINS. Uniforms: u_light_count.
#include "bindings.h"
#include "frame.inc"
#include "lighting.inc"
#include "lights.inc"
#include "tiles.inc"
layout(local_size_x = 256) in;
layout(location = LOC_RENDERER) uniform int u_light_count;

layout(std430, binding = BIND_SSBO_ZBIN_SORTED) writeonly buffer Sorted {
    Light b_sorted[];
};
layout(std430, binding = BIND_SSBO_ZBIN_KEYS) coherent buffer Keys {
    uvec2 b_zkeys[];
};
shared uint s_rmax, s_directional;
const uint NT = 256u;

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

void main()
{
    uint me = gl_LocalInvocationIndex, n = uint(u_light_count);
    uint p2 = 1u;
    while (p2 < n)
        p2 <<= 1u;
    if (me == 0u) {
        s_rmax = 0u;
        s_directional = 0u;
    }
    barrier();
    for (uint i = me; i < p2; i += NT) {   // 1.
        uint key = 0xffffffffu;
        if (i < n) {
            float depth, r;
            key = 0u;
            if (zbin_extent(b_lights[i], depth, r)) {
                key = max(order_key(depth), 1u);
                atomicMax(s_rmax, floatBitsToUint(r));
            } else {
                atomicAdd(s_directional, 1u);
            }
        }
        b_zkeys[i] = uvec2(key, i);
    }
    memoryBarrierBuffer();
    barrier();
    for (uint k = 2u; k <= p2; k <<= 1u) {   // 2.
        for (uint j = k >> 1u; j > 0u; j >>= 1u) {
            for (uint t = me; t < p2 / 2u; t += NT) {
                uint a = 2u * j * (t / j) + t % j, b = a + j;
                uvec2 x = b_zkeys[a], y = b_zkeys[b];
                bool greater = x.x > y.x || (x.x == y.x && x.y > y.y);
                if (greater == ((a & k) == 0u)) {
                    b_zkeys[a] = y;
                    b_zkeys[b] = x;
                }
            }
            memoryBarrierBuffer();
            barrier();
        }
    }
    for (uint k = me; k < n; k += NT) {   // 3.
        Light l = b_lights[b_zkeys[k].y];
        b_sorted[k] = l;
        float depth, r;
        if (!zbin_extent(l, depth, r))
            r = 0.0;
        b_zkeys[k] = uvec2(floatBitsToUint(depth), floatBitsToUint(r));
    }
    memoryBarrierBuffer();
    barrier();
    uint first = s_directional;
    if (me == 0u) {
        z_count = n;
        z_directional = first;
        z_words = (n + 31u) / 32u;
    }
    float near = f_clip.x, w = (f_clip.y - f_clip.x) / float(ZBIN_BINS);
    float rmax = uintBitsToFloat(s_rmax);
    const float INF = uintBitsToFloat(0x7f800000u);
    for (uint b = me; b < uint(ZBIN_BINS); b += NT) {   // 4.
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
}
