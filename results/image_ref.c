/* The error reference's image arithmetic (image_ref.h). */
#include "results/image_ref.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

bool image_box_filter(const float *src, int width, int height, int k, float *dst)
{
    if (!src || !dst || k < 1 || width < 1 || height < 1)
        return false;
    const size_t sw = (size_t)width * (size_t)k;
    const double n = (double)k * (double)k;
    for (size_t y = 0; y < (size_t)height; y++)
        for (size_t x = 0; x < (size_t)width; x++)
            for (size_t c = 0; c < 4; c++) {
                double sum = 0.0;
                for (size_t j = 0; j < (size_t)k; j++) {
                    const float *row = src + ((y * (size_t)k + j) * sw + x * (size_t)k) * 4;
                    for (size_t i = 0; i < (size_t)k; i++)
                        sum += (double)row[i * 4 + c];
                }
                dst[(y * (size_t)width + x) * 4 + c] = (float)(sum / n);
            }
    return true;
}

void image_pbr_neutral(float rgb[3])
{
    const float f90 = 0.04f, ks = 0.8f - f90, kd = 0.15f;
    for (int c = 0; c < 3; c++)
        rgb[c] = rgb[c] > 0.0f ? rgb[c] : 0.0f;
    float x = fminf(rgb[0], fminf(rgb[1], rgb[2]));
    float f = x <= 2.0f * f90 ? x - x * x / (4.0f * f90) : f90;
    for (int c = 0; c < 3; c++)
        rgb[c] -= f;
    float p = fmaxf(rgb[0], fmaxf(rgb[1], rgb[2]));
    if (!(p > ks))
        return;
    float pn = 1.0f - (1.0f - ks) * (1.0f - ks) / (p + 1.0f - 2.0f * ks);
    float g = 1.0f / (kd * (p - pn) + 1.0f);
    for (int c = 0; c < 3; c++)
        rgb[c] = rgb[c] * (pn / p) * g + pn * (1.0f - g);
}

float image_srgb_encode(float v)
{
    return v <= 0.0031308f ? v * 12.92f : 1.055f * powf(v, 1.0f / 2.4f) - 0.055f;
}

void image_display_rgba8(const float *src, int width, int height, bool flip, float exposure,
                         bool pbr_neutral, uint8_t *dst)
{
    const size_t w = (size_t)width, h = (size_t)height;
    for (size_t y = 0; y < h; y++) {
        const float *in = src + (flip ? h - 1 - y : y) * w * 4;
        uint8_t *out = dst + y * w * 4;
        for (size_t x = 0; x < w; x++) {
            float rgb[3];
            for (size_t c = 0; c < 3; c++)
                rgb[c] = in[x * 4 + c] * exposure;
            if (pbr_neutral) {
                image_pbr_neutral(rgb);
                for (size_t c = 0; c < 3; c++) {
                    float v = rgb[c] > 0.0f ? (rgb[c] < 1.0f ? rgb[c] : 1.0f) : 0.0f;
                    rgb[c] = image_srgb_encode(v);
                }
            }
            for (size_t c = 0; c < 3; c++) {
                float v = rgb[c];
                v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;   /* NaN fails v > 0: 0 */
                out[x * 4 + c] = (uint8_t)lrintf(v * 255.0f);
            }
            out[x * 4 + 3] = 255;
        }
    }
}

static double luminance(const uint8_t *p)
{
    return (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0;
}

static bool differs(const uint8_t *px, size_t ch, size_t i, size_t j)
{
    return fabs(luminance(px + i * ch) - luminance(px + j * ch)) > IMAGE_EDGE_THRESHOLD;
}

size_t image_edge_mask(const image *ref, uint8_t *mask)
{
    const size_t w = (size_t)ref->width, h = (size_t)ref->height, ch = (size_t)ref->channels;
    const uint8_t *px = ref->pixels;
    size_t edges = 0;
    for (size_t y = 0; y < h; y++)
        for (size_t x = 0; x < w; x++) {
            size_t i = y * w + x;
            bool edge = (x > 0 && differs(px, ch, i, i - 1)) ||
                        (x + 1 < w && differs(px, ch, i, i + 1)) ||
                        (y > 0 && differs(px, ch, i, i - w)) ||
                        (y + 1 < h && differs(px, ch, i, i + w));
            mask[i] = edge;
            edges += edge;
        }
    return edges;
}

bool image_edge_rmse(const image *a, const image *ref, double *rmse, size_t *edges, char *err,
                     size_t errlen)
{
    *rmse = NAN;
    *edges = 0;
    if (!a || !ref || !a->pixels || !ref->pixels || a->type != IMAGE_U8 ||
        ref->type != IMAGE_U8 || a->width != ref->width || a->height != ref->height ||
        a->channels != ref->channels || (ref->channels != 3 && ref->channels != 4) ||
        ref->width < 1 || ref->height < 1) {
        snprintf(err, errlen, "edge error: expected two 8-bit RGB(A) images of one size");
        return false;
    }
    const size_t n = (size_t)ref->width * (size_t)ref->height, ch = (size_t)ref->channels;
    uint8_t *mask = malloc(n);
    if (!mask) {
        snprintf(err, errlen, "edge error: out of memory for a %dx%d mask", ref->width,
                 ref->height);
        return false;
    }
    *edges = image_edge_mask(ref, mask);
    const uint8_t *pa = a->pixels, *pr = ref->pixels;
    double sum_sq = 0.0;
    for (size_t i = 0; i < n; i++)
        for (size_t c = 0; mask[i] && c < ch; c++) {
            double d = ((double)pa[i * ch + c] - (double)pr[i * ch + c]) / 255.0;
            sum_sq += d * d;
        }
    free(mask);
    if (*edges)
        *rmse = sqrt(sum_sq / (double)(*edges * ch));
    return true;
}
