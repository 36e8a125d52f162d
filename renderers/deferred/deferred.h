#pragma once
/* The deferred renderer (deferred.c) as tests see it: what the family shares
 * (deferred_core.h, gbuffer_layout.h) and deferred.c's own counts.
 * The design: docs/notes/deferred.md. */
#include <stdint.h>

#include "renderers/deferred/deferred_core.h"

/* Draw calls of the light-volume draws of the last frame that marked the stencil
 * (stencil modes), and that shaded (every mode), per light type (LIGHT_POINT,
 * LIGHT_SPOT, LIGHT_DIRECTIONAL). self: what renderer_deferred_impl.create returned. */
uint64_t deferred_last_mark_draws(const void *self, int type);
uint64_t deferred_last_shade_draws(const void *self, int type);
