#pragma once
/* Arithmetic on the error reference's image, no GL and no OIIO (image_ref.c):
 * the supersampled reference's box filter and display conversion, and the
 * edge-weighted error. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "common/image_io.h"

/* A pixel is an edge of the reference when its luminance (Rec. 709 weights on the 8-bit
 * values / 255: 0.2126 R + 0.7152 G + 0.0722 B) differs from that of one of its four
 * neighbours inside the image by more than this. */
#define IMAGE_EDGE_THRESHOLD 0.1

/* src: (k width) x (k height) RGBA floats; dst: width x height RGBA floats, each the mean
 * of its k x k block of src (summed in double; rows in the same order as src). Linear
 * values, as the renderer's HDR target holds them: no clamp, no transfer function.
 * false for k < 1 or a size < 1. */
bool image_box_filter(const float *src, int width, int height, int k, float *dst);

/* What the resolve pass (renderers/shaders/resolve.frag.glsl) and the RGBA8 output make
 * of linear values: each colour channel times `exposure` (1: as it is), with pbr_neutral
 * the Khronos PBR Neutral tone mapper and the sRGB transfer function (image_pbr_neutral,
 * image_srgb_encode), clamped to [0, 1] (NaN as 0) and rounded to the nearest of 0..255,
 * alpha 255. flip: src has GL's row order (row 0 at the bottom) and dst gets image_io's
 * (row 0 at the top). */
void image_display_rgba8(const float *src, int width, int height, bool flip, float exposure,
                         bool pbr_neutral, uint8_t *dst);
/* The Khronos PBR Neutral tone mapper (its specification, 2024) on one linear Rec. 709
 * colour, in place (negative channels taken as 0); the sRGB transfer function
 * (IEC 61966-2-1) of one linear value in [0, 1]. resolve.frag's twins. */
void image_pbr_neutral(float rgb[3]);
float image_srgb_encode(float v);

/* mask[i] = 1 where pixel i of ref (IMAGE_U8, 3 or 4 channels) is an edge, else 0;
 * returns the number of edge pixels. */
size_t image_edge_mask(const image *ref, uint8_t *mask);

/* The RMSE of a against ref over ref's edge pixels only, defined as image_compare's
 * rmse (every channel, v / 255), into *rmse (NAN when ref has no edge) and their count
 * into *edges. a and ref: IMAGE_U8 of equal size and channels (3 or 4). */
bool image_edge_rmse(const image *a, const image *ref, double *rmse, size_t *edges, char *err,
                     size_t errlen);
