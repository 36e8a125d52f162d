#pragma once
/* Internal to the runner: a sweep axis as manifest.c builds it and sweep.c
 * expands it (manifest.h keeps `struct sweep_axis` opaque to everyone else).
 *
 * Each value is a whole run_params in which only the axis's parameter is set:
 * the bytes [off, off + size) of it are what plan_expand copies onto the base, so
 * every parameter the table marks sweepable occupies one contiguous span of
 * run_params. */
#include <stddef.h>
#include "runner/manifest/manifest.h"

struct sweep_axis {
    const char *path;          /* the parameter's dotted path (static), also its run_params_kv key */
    size_t off, size;          /* the parameter's bytes in run_params */
    size_t nvalues;            /* >= 1 */
    run_params *values;
    int *line, *col;           /* where each value is in the manifest (line -k: in the
                                * k-th --set, runner/manifest/overrides.c) */
};

/* The blocks of e's sweep: a mapping is one block of every axis. */
static inline size_t sweep_nblocks(const experiment *e)
{
    return e->nblocks ? e->nblocks : 1;
}
static inline size_t sweep_block_first(const experiment *e, size_t b)
{
    return e->nblocks ? e->block_first[b] : 0;
}
static inline size_t sweep_block_end(const experiment *e, size_t b)
{
    return e->nblocks ? e->block_first[b + 1] : e->naxes;
}
