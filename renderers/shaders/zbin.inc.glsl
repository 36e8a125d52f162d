// zbin's structures (Drobot 2017; renderers/tiled/zbin.c), std430, and the loop over a
// pixel's lights. Included by tiles.inc; empty unless ZBIN_BINS (the bins) is defined.
//   b_zbin       count: the frame's lights (sorted: b_lights is zbin.comp's b_sorted);
//                directional: how many come first (every pixel shades them); words: mask
//                words a tile; then bin k (ZBIN_BINS linear bins of view depth over
//                [near, far]): lo | hi << 16, the lowest and highest sorted index of the
//                point and spot lights whose depth extent overlaps it (lo > hi: none)
//   b_zmasks[t x words + w]   tile t's bit mask over the sorted lights (zbin_cull_tile,
//                tile_cull.inc): bit i set when light i passes the tile's test
#ifdef ZBIN_BINS
layout(std430, binding = BIND_SSBO_ZBIN_BINS) buffer ZBins {
    uint z_count;
    uint z_directional;
    uint z_words;
    uint z_rmax;   // zbin.comp: the largest reach's bits, while sorting
    uint b_zbins[];
};
layout(std430, binding = BIND_SSBO_ZBIN_MASKS) TILES_QUALIFIER buffer ZMasks {
    uint b_zmasks[];
};

// The bin of view z (negative in front): linear over [near, far], clamped to the ends.
uint zbin_of(float z)
{
    float w = (f_clip.y - f_clip.x) / float(ZBIN_BINS);
    return uint(clamp(int(floor((-z - f_clip.x) / w)), 0, ZBIN_BINS - 1));
}

// Word w of a mask, m, keeping only the bits of indices lo .. hi.
uint zbin_clip(uint m, uint w, uint lo, uint hi)
{
    uint base = w * 32u;
    if (base < lo)
        m &= 0xffffffffu << (lo - base);
    if (base + 31u > hi)
        m &= 0xffffffffu >> (base + 31u - hi);
    return m;
}

// A pixel's lights: the directional ones (0 .. directional), then the set bits of its
// tile's mask between its bin's lo and hi (every index there with `every`: msaa's
// fallback, a position outside the depth range its tile was culled against).
struct ZbinIter {
    uint k, directional, lo, hi, w, last, base, bits, row;
    bool every;
};

ZbinIter zbin_begin(uint tile_index, float z, bool every)
{
    uint bin = b_zbins[zbin_of(z)];
    ZbinIter it;
    it.k = 0u;
    it.directional = z_directional;
    it.lo = bin & 0xffffu;
    it.hi = bin >> 16;
    it.w = it.lo >> 5;
    it.last = it.hi >> 5;
    if (it.lo > it.hi) {   // an empty bin: no word
        it.w = 1u;
        it.last = 0u;
    }
    it.base = 0u;
    it.bits = 0u;
    it.row = tile_index * z_words;
    it.every = every;
    return it;
}

// The next light's index into i; false when none is left.
bool zbin_next(inout ZbinIter it, out uint i)
{
    i = 0u;
    if (it.k < it.directional) {
        i = it.k++;
        return true;
    }
    while (it.bits == 0u) {
        if (it.w > it.last)
            return false;
        it.bits = zbin_clip(it.every ? 0xffffffffu : b_zmasks[it.row + it.w], it.w, it.lo,
                            it.hi);
        it.base = it.w * 32u;
        it.w++;
    }
    int j = findLSB(it.bits);
    it.bits &= it.bits - 1u;
    i = it.base + uint(j);
    return true;
}
#endif
