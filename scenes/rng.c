/* Seeded generators: see rng.h for what each reproduces. */
#include "scenes/rng.h"

#include <string.h>

static uint32_t pcg32_next(rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ULL + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31u));
}

/* Mersenne twister MT19937, as std::mt19937: init_genrand and the standard tempering. */
static void mt_seed(rng *r, uint32_t seed)
{
    r->mt[0] = seed;
    for (unsigned i = 1; i < 624; i++)
        r->mt[i] = 1812433253u * (r->mt[i - 1] ^ (r->mt[i - 1] >> 30)) + i;
    r->mti = 624;
}

static uint32_t mt_next(rng *r)
{
    if (r->mti >= 624) {
        for (unsigned i = 0; i < 624; i++) {
            uint32_t y = (r->mt[i] & 0x80000000u) | (r->mt[(i + 1) % 624] & 0x7fffffffu);
            uint32_t v = r->mt[(i + 397) % 624] ^ (y >> 1);
            if (y & 1u)
                v ^= 0x9908b0dfu;
            r->mt[i] = v;
        }
        r->mti = 0;
    }
    uint32_t y = r->mt[r->mti++];
    y ^= y >> 11;
    y ^= (y << 7) & 0x9d2c5680u;
    y ^= (y << 15) & 0xefc60000u;
    y ^= y >> 18;
    return y;
}

void rng_seed(rng *r, rng_kind kind, uint32_t seed)
{
    memset(r, 0, sizeof *r);
    r->kind = kind;
    switch (kind) {
    case RNG_MSVC:
        r->state = seed;
        break;
    case RNG_PCG32:
        /* pcg32_srandom_r(rng, initstate = seed, initseq = 54) */
        r->state = 0;
        r->inc = (54u << 1u) | 1u;
        pcg32_next(r);
        r->state += seed;
        pcg32_next(r);
        break;
    case RNG_MT19937:
        mt_seed(r, seed);
        break;
    }
}

uint32_t rng_next(rng *r)
{
    switch (r->kind) {
    case RNG_MSVC:
        /* 32-bit state arithmetic, as the MSVC runtime's holdrand. */
        r->state = (uint32_t)((uint32_t)r->state * 214013u + 2531011u);
        return (uint32_t)(r->state >> 16) & 0x7fffu;
    case RNG_PCG32:
        return pcg32_next(r);
    case RNG_MT19937:
        return mt_next(r);
    }
    return 0;
}

uint32_t rng_max(const rng *r) { return r->kind == RNG_MSVC ? 0x7fffu : 0xffffffffu; }

float rng_unit(rng *r)
{
    uint32_t max = rng_max(r);
    return (float)((double)rng_next(r) / (double)max);
}

const char *rng_kind_name(rng_kind k)
{
    switch (k) {
    case RNG_MSVC: return "msvc";
    case RNG_PCG32: return "pcg32";
    case RNG_MT19937: return "mt19937";
    }
    return "?";
}
