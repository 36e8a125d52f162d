/* common/grow.h: GROW doubles from `first` until the need fits, keeps the elements,
 * and leaves everything as it was when the size would overflow. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>

#include "common/grow.h"

static void test_grow_doubles_and_keeps(void **state)
{
    (void)state;
    int *v = NULL;
    size_t cap = 0;
    assert_true(GROW(v, cap, 0, 8));      /* nothing needed: nothing allocated */
    assert_null(v);
    assert_int_equal(cap, 0);
    assert_true(GROW(v, cap, 1, 8));
    assert_int_equal(cap, 8);
    for (int i = 0; i < 8; i++)
        v[i] = i * i;
    assert_true(GROW(v, cap, 8, 8));      /* fits: unchanged */
    assert_int_equal(cap, 8);
    assert_true(GROW(v, cap, 33, 8));     /* 8 -> 16 -> 32 -> 64 */
    assert_int_equal(cap, 64);
    for (int i = 0; i < 8; i++)
        assert_int_equal(v[i], i * i);
    free(v);
}

static void test_grow_overflow_changes_nothing(void **state)
{
    (void)state;
    double *v = NULL;
    size_t cap = 0;
    assert_true(GROW(v, cap, 3, 0));      /* first 0: from 1 */
    assert_int_equal(cap, 4);
    v[2] = 2.5;
    double *before = v;
    assert_false(GROW(v, cap, SIZE_MAX / 4, 1));   /* SIZE_MAX / 4 * 8 bytes overflows */
    assert_ptr_equal(v, before);
    assert_int_equal(cap, 4);
    assert_false(GROW(v, cap, SIZE_MAX, 1));       /* the count itself overflows */
    assert_int_equal(cap, 4);
    assert_true(v[2] == 2.5);
    free(v);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grow_doubles_and_keeps),
        cmocka_unit_test(test_grow_overflow_changes_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
