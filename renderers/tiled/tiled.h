#pragma once
/* What clustered (clustered.c) and zbin (zbin.c) make its objects with: the forward tiled renderer's
 * object (forward_plus.c, forward-plus's, with clustered.slices when `clustered`) or
 * tiled-deferred's (tiled_deferred.c, its tiles cut into depth slices). After create, the
 * registry entries renderer_forward_plus_impl and renderer_tiled_deferred_impl serve them
 * (renderer_impl.variant). NULL with a message. */
#include <stdbool.h>
#include <stddef.h>

#include "renderers/renderer.h"

extern const renderer_impl renderer_forward_plus_impl;
extern const renderer_impl renderer_tiled_deferred_impl;

void *forward_tiled_new(const char *name, bool clustered, const renderer_options *opts,
                        char *err, size_t errlen);
void *tiled_deferred_clustered_create(const renderer_options *opts, char *err, size_t errlen);
/* zbin with zbin.shading: deferred: tiled-deferred's object with zbin's bins (zbin.c). */
void *tiled_deferred_zbin_create(const renderer_options *opts, char *err, size_t errlen);
