#pragma once
/* The visibility renderer's id packing (visibility.c; Burns and Hunt, JCGT 2(2), 2013):
 * one 32-bit unsigned integer per pixel (the R32UI target "visibility"),
 *
 *     id = draw << tri_bits | triangle
 *
 * draw: the object's index in the frame's visible list; triangle: gl_PrimitiveID, the
 * triangle of the object's mesh. The split is chosen per scene at prepare: tri_bits is
 * the fewest bits that hold the triangles of the largest mesh an opaque object uses
 * (at least 1), the draw gets the other 32 - tri_bits bits, and 0xffffffff (the
 * target's clear value) means "no surface", so the largest draw index is never used:
 * at most 2^(32 - tri_bits) - 1 draws. A scene whose opaque objects (each may be
 * visible) are more than that is refused. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/renderer.h"

#define VIS_EMPTY 0xffffffffu   /* no surface at the pixel */

/* The split for a scene of `objects` opaque objects whose largest mesh has
 * `max_triangles` triangles: true with *tri_bits set, or false with "NAME: ..." naming
 * the numbers and the limit. */
bool visibility_split(const char *name, uint32_t objects, uint32_t max_triangles,
                      unsigned *tri_bits, char *err, size_t errlen);

/* The id of triangle `triangle` of visible draw `draw` (both within the split). */
static inline uint32_t visibility_pack(uint32_t draw, uint32_t triangle, unsigned tri_bits)
{
    return draw << tri_bits | triangle;
}

/* Seed 002's MRT terms (results/bandwidth.h) for the id target, a collected frame at
 * width x height with `samples` per pixel: written, 4 bytes x the samples the
 * "visibility" pass passes (overdraw included, as the G-buffer pass's); read, 4 bytes x
 * every sample of the screen x the "shade" pass's dispatches (one per run of equal maps,
 * each reading every pixel's ids). Not in it: the triangles' refetch (indices and
 * vertices, through the caches), as the model leaves the texture reads out of the
 * G-buffer's terms. NAN for a count that is NAN or a frame without those passes. */
gbuffer_traffic visibility_id_traffic(int width, int height, int samples, const frame_stats *fs);
