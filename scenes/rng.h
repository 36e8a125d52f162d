#pragma once
/* Seeded generators for light placement; each reproduces its reference exactly.
 *   msvc    Visual C++ srand()/rand(): state = state * 214013 + 2531011,
 *           output (state >> 16) & 0x7fff (RAND_MAX 32767), the generator of seed 003.
 *   pcg32   O'Neill's PCG-XSH-RR 64/32, stream 54 (the reference pcg32_srandom
 *           initialisation: initstate = seed, initseq = 54).
 *   mt19937 Matsumoto-Nishimura 32-bit Mersenne twister, seeded as std::mt19937(seed). */
#include <stdint.h>

typedef enum rng_kind { RNG_MSVC = 0, RNG_PCG32, RNG_MT19937 } rng_kind;

typedef struct rng {
    rng_kind kind;
    uint64_t state, inc;       /* msvc: state; pcg32: state and increment */
    uint32_t mt[624];
    unsigned mti;
} rng;

void rng_seed(rng *r, rng_kind kind, uint32_t seed);
uint32_t rng_next(rng *r);            /* msvc: 0..32767; others: full 32 bits */
uint32_t rng_max(const rng *r);       /* largest value rng_next can return */
/* Uniform in [0, 1]: next / max, as the papers' `rand() / (float)RAND_MAX`. */
float rng_unit(rng *r);
const char *rng_kind_name(rng_kind k);
