#pragma once
/* The entries of the tiled renderers that clustered is made of (clustered.c): the
 * forward tiled renderer (forward_plus.c, forward-plus's, with clustered.slices when
 * `clustered`) and tiled-deferred (tiled_deferred.c, its tiles cut into depth slices
 * for clustered with clustered.shading: deferred). Both objects start with their
 * renderer_base (renderers/base.h), whose options say which one a clustered object is. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/renderer.h"

struct scene;

// >>forward (forward_plus.c)

void *forward_tiled_create(const char *name, bool clustered, const renderer_options *opts,
                           char *err, size_t errlen);
bool forward_tiled_prepare(void *self, const struct scene *s, char *err, size_t errlen);
void forward_tiled_draw(void *self, const struct scene *s, frame_stats *out);
void forward_tiled_collect(void *self, frame_stats *out);
void forward_tiled_describe(const void *self, pass_plan *out);
void forward_tiled_destroy(void *self);
const uint32_t *forward_tiled_light_grid(const void *self, size_t *n);

// >>deferred (tiled_deferred.c)

/* clustered with clustered.shading: deferred: tiled-deferred's pass, its tiles cut
 * into clustered.slices depth slices. NULL with a message. */
void *tiled_deferred_clustered_create(const renderer_options *opts, char *err, size_t errlen);
bool tiled_deferred_prepare(void *self, const struct scene *s, char *err, size_t errlen);
void tiled_deferred_draw(void *self, const struct scene *s, frame_stats *out);
void tiled_deferred_collect(void *self, frame_stats *out);
const uint32_t *tiled_deferred_light_grid(const void *self, size_t *n);
void tiled_deferred_destroy(void *self);
/* describe and read_hdr are deferred's (renderers/deferred_core.h). */
