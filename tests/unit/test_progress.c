/* runner/plan/progress.c's ETA on synthetic trial costs (powers of two: exact arithmetic):
 * unknown before any trial ends, each kind (renderer, size, scene) at its own measured
 * mean, a kind not yet measured at the slowest one's and counted as guessed, the
 * running trial's elapsed time taken off, runs that end early taken out. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>

#include "runner/plan/progress.h"
#include "assert_near.h"

static void begin(progress *pg, const char *renderer, int w)
{
    progress_run_begin(pg, 1, "000000000000", renderer, w, w, "shapes", 1, 3);
}

static void test_eta_per_kind(void **state)
{
    (void)state;
    progress pg;
    progress_init(&pg, 0, NULL);
    assert_true(progress_expect(&pg, "deferred", 64, 64, "shapes", 3));
    assert_true(progress_expect(&pg, "forward-spml", 64, 64, "shapes", 2));
    assert_true(progress_expect(&pg, "deferred", 32, 32, "shapes", 4));
    assert_true(progress_expect(&pg, "deferred", 64, 64, "shapes", 1));   /* adds up */
    size_t guessed = 99;
    assert_true(isnan(progress_eta_s(&pg, 0, &guessed)));   /* nothing measured: unknown */

    /* deferred 64x64: 2 s and 4 s, mean 3 s, 2 left; the others at that slowest 3 s */
    begin(&pg, "deferred", 64);
    progress_record(&pg, 2);
    begin(&pg, "deferred", 64);
    progress_record(&pg, 4);
    assert_near(progress_eta_s(&pg, 0, &guessed), 3.0 * (2 + 2 + 4), 0);
    assert_int_equal(guessed, 6);

    /* deferred 32x32 measured at 0.5 s: it becomes its own, the slowest stays 3 s */
    begin(&pg, "deferred", 32);
    progress_record(&pg, 0.5);
    assert_near(progress_eta_s(&pg, 0, &guessed), 3.0 * 2 + 3.0 * 2 + 0.5 * 3, 0);
    assert_int_equal(guessed, 2);

    /* forward-spml: 8 s, corrected as it ends (1 left); every kind measured now */
    begin(&pg, "forward-spml", 64);
    progress_record(&pg, 8);
    assert_near(progress_eta_s(&pg, 0, &guessed), 3.0 * 2 + 8.0 + 0.5 * 3, 0);
    assert_int_equal(guessed, 0);

    /* a forward-spml trial running for 2 s: 6 s of it left; past its mean, none */
    begin(&pg, "forward-spml", 64);
    assert_near(progress_eta_s(&pg, 2, &guessed), 3.0 * 2 + 6.0 + 0.5 * 3, 0);
    assert_near(progress_eta_s(&pg, 16, &guessed), 3.0 * 2 + 0.5 * 3, 0);
    progress_record(&pg, 8);

    /* deferred 64x64's run ends early: its 2 trials left go, and no fewer than none */
    progress_unexpect(&pg, "deferred", 64, 64, "shapes", 2);
    assert_near(progress_eta_s(&pg, 0, &guessed), 0.5 * 3, 0);
    progress_unexpect(&pg, "deferred", 32, 32, "shapes", 5);
    assert_near(progress_eta_s(&pg, 0, &guessed), 0, 0);
    progress_free(&pg);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_eta_per_kind),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
