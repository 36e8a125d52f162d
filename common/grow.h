#pragma once
/* One way to grow an array: `GROW(p, cap, need, first)` makes room for `need` elements
 * of *p, whose capacity is `cap` (a size_t lvalue), doubling from `first` until it fits.
 * True when there is room; false when out of memory or when the size would overflow,
 * and then p and cap are as they were (the elements still valid). */
#include <stdbool.h>
#include <stddef.h>

bool grow_array(void *pp, size_t *cap, size_t need, size_t elem_size, size_t first);

#define GROW(p, cap, need, first) grow_array(&(p), &(cap), (need), sizeof *(p), (first))
