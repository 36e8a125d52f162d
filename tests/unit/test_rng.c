/* The generators against their references, values from outside this project:
 *  - MSVC rand() after srand(1): 41, 18467, 6334, 26500, 19169 (the well-known
 *    Visual C++ sequence).
 *  - std::mt19937 default seed 5489: first output 3499211612, 10000th 4123659995
 *    (the C++ standard, [rand.predef]).
 *  - pcg32 seeded (42, 54) as the reference pcg32-demo: 0xa15c02b7 0x7b47f409
 *    0xba1d3330 0x83d2f293 0xbfa4784b 0xcbed606e. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "scenes/rng.h"

static void test_msvc_srand1(void **state)
{
    (void)state;
    static const uint32_t want[] = {41, 18467, 6334, 26500, 19169, 15724, 11478, 29358};
    rng r;
    rng_seed(&r, RNG_MSVC, 1);
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
        assert_int_equal(rng_next(&r), want[i]);
    assert_int_equal(rng_max(&r), 32767);
}

static void test_mt19937_standard(void **state)
{
    (void)state;
    rng r;
    rng_seed(&r, RNG_MT19937, 5489);
    uint32_t first = rng_next(&r), v = first;
    for (int i = 2; i <= 10000; i++)
        v = rng_next(&r);
    assert_int_equal(first, 3499211612u);
    assert_int_equal(v, 4123659995u);
}

static void test_pcg32_reference(void **state)
{
    (void)state;
    static const uint32_t want[] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u,
                                    0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
    rng r;
    rng_seed(&r, RNG_PCG32, 42);
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
        assert_int_equal(rng_next(&r), want[i]);
}

static void test_unit_range_and_reseed(void **state)
{
    (void)state;
    for (int k = RNG_MSVC; k <= RNG_MT19937; k++) {
        rng a, b;
        rng_seed(&a, (rng_kind)k, 1337);
        rng_seed(&b, (rng_kind)k, 1337);
        for (int i = 0; i < 5000; i++) {
            float u = rng_unit(&a);
            assert_true(u >= 0.0f && u <= 1.0f);
            assert_true(u == rng_unit(&b));   /* same seed, same stream */
        }
    }
    rng r;
    rng_seed(&r, RNG_MSVC, 1337);
    uint32_t x = rng_next(&r);
    rng_seed(&r, RNG_MSVC, 1338);
    assert_int_not_equal(x, rng_next(&r));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_msvc_srand1),
        cmocka_unit_test(test_mt19937_standard),
        cmocka_unit_test(test_pcg32_reference),
        cmocka_unit_test(test_unit_range_and_reseed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
