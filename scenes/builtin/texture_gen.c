/* Procedural textures and the seeded gradient noise: see scenes/builtin/texture_gen.h.
 *
 * Sections: >>noise >>desc >>patterns >>maps */
#include "scenes/builtin/texture_gen.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/rng.h"
#include "scenes/scene_fail.h"

/* >>noise ------------------------------------------------------------------------------ */

#define LATTICE_BITS 22
#define LATTICE_WRAP ((float)(1u << LATTICE_BITS))

void texture_noise_keys(uint32_t seed, uint32_t *keys, unsigned n)
{
    rng g;
    rng_seed(&g, RNG_PCG32, seed);
    for (unsigned i = 0; i < n; i++)
        keys[i] = rng_next(&g);
}

/* Chris Wellons' lowbias32 integer hash. */
static uint32_t mix32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

static float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

/* dot(gradient of lattice point (ix, iy), (dx, dy)); 8 unit gradients, picked by
 * mix32(ix ^ row) with row = mix32(iy ^ mix32(key)). */
static float grad(uint32_t row, uint32_t ix, float dx, float dy)
{
    static const float g[8][2] = {
        {1.0f, 0.0f}, {-1.0f, 0.0f}, {0.0f, 1.0f}, {0.0f, -1.0f},
        {0.70710678f, 0.70710678f}, {-0.70710678f, 0.70710678f},
        {0.70710678f, -0.70710678f}, {-0.70710678f, -0.70710678f},
    };
    const float *v = g[mix32(ix ^ row) >> 29];
    return v[0] * dx + v[1] * dy;
}

/* Splits x into a lattice cell (wrapped to the period, or to the 2^22 lattice) and the
 * fraction in [0, 1). */
static void cell_of(float x, uint32_t period, uint32_t *i0, uint32_t *i1, float *frac)
{
    if (!isfinite(x))
        x = 0.0f;
    if (fabsf(x) >= LATTICE_WRAP)
        x = fmodf(x, LATTICE_WRAP);        /* exact; keeps the cell index in range */
    float fl = floorf(x);
    *frac = x - fl;
    if (!(*frac < 1.0f))                   /* x just below an integer, rounded up */
        *frac = 0.0f;
    int64_t i = (int64_t)fl;
    if (!period || !(period & (period - 1))) {  /* none or a power of two: a mask */
        uint32_t mask = period ? period - 1 : (1u << LATTICE_BITS) - 1;
        *i0 = (uint32_t)i & mask;
        *i1 = (*i0 + 1) & mask;
        return;
    }
    int64_t w = i % (int64_t)period;
    if (w < 0)
        w += period;
    *i0 = (uint32_t)w;
    *i1 = *i0 + 1 == period ? 0 : *i0 + 1;
}

float texture_noise2(float x, float y, uint32_t key, uint32_t period_x, uint32_t period_y)
{
    uint32_t x0, x1, y0, y1;
    float fx, fy;
    cell_of(x, period_x, &x0, &x1, &fx);
    cell_of(y, period_y, &y0, &y1, &fy);
    uint32_t k = mix32(key), r0 = mix32(y0 ^ k), r1 = mix32(y1 ^ k);
    float n00 = grad(r0, x0, fx, fy);
    float n10 = grad(r0, x1, fx - 1.0f, fy);
    float n01 = grad(r1, x0, fx, fy - 1.0f);
    float n11 = grad(r1, x1, fx - 1.0f, fy - 1.0f);
    float u = fade(fx), v = fade(fy);
    float a = n00 + u * (n10 - n00), b = n01 + u * (n11 - n01);
    /* 2D gradient noise with unit gradients stays within sqrt(1/2) */
    float n = (a + v * (b - a)) * 1.41421356f;
    return n > 1.0f ? 1.0f : (n < -1.0f ? -1.0f : n);
}

float texture_fbm2(float x, float y, const uint32_t *keys, unsigned octaves,
                   uint32_t period_x, uint32_t period_y)
{
    if (octaves < 1)
        octaves = 1;
    if (octaves > TEXTURE_MAX_OCTAVES)
        octaves = TEXTURE_MAX_OCTAVES;
    float sum = 0.0f, norm = 0.0f, amp = 1.0f, f = 1.0f;
    for (unsigned o = 0; o < octaves; o++) {
        uint32_t px = period_x ? period_x << o : 0, py = period_y ? period_y << o : 0;
        sum += amp * texture_noise2(x * f, y * f, keys[o], px, py);
        norm += amp;
        amp *= 0.5f;
        f *= 2.0f;
    }
    float n = sum / norm;
    return n > 1.0f ? 1.0f : (n < -1.0f ? -1.0f : n);
}

/* >>desc ------------------------------------------------------------------------------- */

static const char *const pattern_names[TEXTURE_PATTERN_COUNT] = {"checker", "bricks", "noise"};

const char *texture_pattern_name(texture_pattern p)
{
    return (unsigned)p < TEXTURE_PATTERN_COUNT ? pattern_names[p] : NULL;
}

static bool pow2(uint32_t x) { return x && !(x & (x - 1)); }

static bool all_zero(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (v[i] != 0.0f)
            return false;
    return true;
}

static bool unit_range(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!(v[i] >= 0.0f && v[i] <= 1.0f))
            return false;
    return true;
}

bool texture_desc_resolve(const texture_desc *in, texture_desc *out, char *err, size_t errlen)
{
    texture_desc d = *in;
    if (!d.width)
        d.width = 256;
    if (!d.height)
        d.height = 256;
    if (!d.cells)
        d.cells = 8;
    if (all_zero(d.color_a, 3) && all_zero(d.color_b, 3)) {
        d.color_a[0] = d.color_a[1] = d.color_a[2] = 0.75f;
        d.color_b[0] = d.color_b[1] = d.color_b[2] = 0.35f;
    }
    if (d.gloss_a == 0.0f && d.gloss_b == 0.0f) {
        d.gloss_a = 0.8f;
        d.gloss_b = 0.3f;
    }
    if (d.bump == 0.0f)
        d.bump = 4.0f;
    if (d.emissive_fraction == 0.0f)
        d.emissive_fraction = 0.25f;
    if (all_zero(d.emissive_color, 3))
        d.emissive_color[0] = d.emissive_color[1] = d.emissive_color[2] = 1.0f;

    if (!pow2(d.width) || !pow2(d.height) || d.width > TEXTURE_MAX_SIZE ||
        d.height > TEXTURE_MAX_SIZE)
        return scene_fail(err, errlen, "texture: size %ux%u must be powers of two up to %u",
                          d.width, d.height, TEXTURE_MAX_SIZE);
    if ((unsigned)d.pattern >= TEXTURE_PATTERN_COUNT)
        return scene_fail(err, errlen, "texture: unknown pattern %d", (int)d.pattern);
    uint32_t side = d.width < d.height ? d.width : d.height;
    if (d.cells > side || (d.pattern == TEXTURE_BRICKS && (d.cells % 2)))
        return scene_fail(err, errlen, "texture: %s needs cells in 1..%u%s (got %u)",
                          pattern_names[d.pattern], side,
                          d.pattern == TEXTURE_BRICKS ? ", even" : "", d.cells);
    float g[2] = {d.gloss_a, d.gloss_b}, f[2] = {d.noise, d.emissive_fraction};
    if (!unit_range(d.color_a, 3) || !unit_range(d.color_b, 3) || !unit_range(g, 2) ||
        !unit_range(f, 2) || !unit_range(d.emissive_color, 3))
        return scene_fail(err, errlen,
                          "texture: colours, gloss, noise and emissive_fraction must be "
                          "in 0..1");
    if (!(isfinite(d.bump) && d.bump > 0.0f && d.bump <= 1e4f))
        return scene_fail(err, errlen, "texture: bump must be in (0, 10000] texels (got %g)",
                          (double)d.bump);
    *out = d;
    return true;
}

/* >>patterns --------------------------------------------------------------------------- */

/* What a pattern says about a point: colour mix t (0: colour a, 1: colour b) and tint,
 * gloss mix, height 0..1, and whether it is lit (0..1). */
typedef struct sample {
    float t, tint, h, lit;
} sample;

static float smoothstep(float e0, float e1, float x)
{
    float t = (x - e0) / (e1 - e0);
    t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
    return t * t * (3.0f - 2.0f * t);
}

static float wrap01(float x)
{
    if (!isfinite(x))
        return 0.0f;
    x -= floorf(x);
    return x < 1.0f ? x : 0.0f;
}

/* uniform in [0, 1) from a cell */
static float cell_hash(uint32_t seed, uint32_t salt, uint32_t a, uint32_t b)
{
    return (float)(mix32(a ^ mix32(b ^ mix32(seed ^ mix32(salt)))) >> 8) * (1.0f / 16777216.0f);
}

static unsigned noise_octaves(const texture_desc *d)
{
    uint32_t side = d->width < d->height ? d->width : d->height;
    unsigned o = 0;
    while (o < 8 && (d->cells << o) < side)
        o++;
    return o ? o : 1;
}

#define BEVEL 0.08f
#define MORTAR 0.06f

static sample pattern_at(const texture_desc *d, const uint32_t *keys, float u, float v)
{
    sample s = {0.0f, 1.0f, 1.0f, 0.0f};
    u = wrap01(u);
    v = wrap01(v);
    uint32_t n = d->cells;
    switch (d->pattern) {
    case TEXTURE_CHECKER: {
        float U = u * (float)n, V = v * (float)n;
        uint32_t cu = (uint32_t)U % n, cv = (uint32_t)V % n;
        float fu = U - floorf(U), fv = V - floorf(V);
        float e = fminf(fminf(fu, 1.0f - fu), fminf(fv, 1.0f - fv));
        s.t = (float)((cu + cv) & 1u);
        s.h = smoothstep(0.0f, BEVEL, e);
        if (cell_hash(d->seed, 1, cu, cv) < d->emissive_fraction)
            s.lit = smoothstep(1.5f * BEVEL, 2.0f * BEVEL, e);
        break;
    }
    case TEXTURE_BRICKS: {
        uint32_t m = n / 2;                     /* bricks per row: 2:1 bricks */
        float V = v * (float)n;
        uint32_t row = (uint32_t)V % n;
        float U = u * (float)m + ((row & 1u) ? 0.5f : 0.0f);
        uint32_t col = (uint32_t)U % m;
        float fu = U - floorf(U), fv = V - floorf(V);
        /* distance to the brick's edge in brick heights (a brick is 2 wide) */
        float e = fminf(2.0f * fminf(fu, 1.0f - fu), fminf(fv, 1.0f - fv));
        float brick = smoothstep(MORTAR, MORTAR + BEVEL, e);
        s.t = 1.0f - brick;                     /* mortar: colour b */
        s.tint = 0.85f + 0.3f * cell_hash(d->seed, 2, col, row);
        s.h = brick;
        if (cell_hash(d->seed, 3, col, row) < d->emissive_fraction)
            s.lit = smoothstep(MORTAR + BEVEL, MORTAR + 2.0f * BEVEL, e);
        break;
    }
    case TEXTURE_NOISE:
    default: {
        float f = texture_fbm2(u * (float)n, v * (float)n, keys, noise_octaves(d), n, n);
        s.t = 0.5f + 0.5f * f;
        s.h = s.t;
        s.lit = s.t;                            /* thresholded by texture_emissive */
        break;
    }
    }
    return s;
}

/* Fine noise that varies colour and gloss: 16 periods a side (fewer for tiny images). */
static float detail_at(const texture_desc *d, const uint32_t *keys, float u, float v)
{
    uint32_t side = d->width < d->height ? d->width : d->height;
    uint32_t p = side < 16 ? side : 16;
    unsigned o = 0;
    while (o < 4 && (p << o) < side)
        o++;
    return texture_fbm2(wrap01(u) * (float)p, wrap01(v) * (float)p, keys + 8, o ? o : 1, p, p);
}

#define NKEYS 12

static float height_at(const texture_desc *d, const uint32_t *keys, float u, float v)
{
    sample s = pattern_at(d, keys, u, v);
    float h = s.h;
    if (d->noise > 0.0f)
        h = h * (1.0f - 0.1f * d->noise) + 0.1f * d->noise * (0.5f + 0.5f * detail_at(d, keys, u, v));
    return h < 0.0f ? 0.0f : (h > 1.0f ? 1.0f : h);
}

float texture_height(const texture_desc *d, float u, float v)
{
    uint32_t keys[NKEYS];
    texture_noise_keys(d->seed, keys, NKEYS);
    return height_at(d, keys, u, v);
}

/* >>maps ------------------------------------------------------------------------------- */

static uint8_t to8(float x)
{
    x = x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
    return (uint8_t)(x * 255.0f + 0.5f);
}

/* Resolves *in into *d, allocates out (channels a texel) and makes the noise keys. */
static bool image_alloc(const texture_desc *in, texture_desc *d, uint32_t *keys,
                        uint32_t channels, texture_image *out, const char *who, char *err,
                        size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!in)
        return scene_fail(err, errlen, "%s: no desc", who);
    if (!texture_desc_resolve(in, d, err, errlen))
        return false;
    out->data = malloc((size_t)d->width * d->height * channels);
    if (!out->data)
        return scene_fail(err, errlen, "%s: out of memory for %ux%u", who, d->width, d->height);
    out->width = d->width;
    out->height = d->height;
    out->channels = channels;
    texture_noise_keys(d->seed, keys, NKEYS);
    return true;
}

/* the centre of texel i of n, in 0..1 */
static float texel_centre(uint32_t i, uint32_t n) { return ((float)i + 0.5f) / (float)n; }

/* Writes the texel at (u, v) (its centre) to p, out->channels bytes. */
typedef void texel_paint(const texture_desc *d, const uint32_t *keys, float u, float v,
                         uint8_t *p);

/* A map whose every texel depends on its centre alone. */
static bool paint_map(const texture_desc *in, texture_image *out, uint32_t channels,
                      texel_paint *paint, const char *who, char *err, size_t errlen)
{
    texture_desc d;
    uint32_t keys[NKEYS];
    if (!image_alloc(in, &d, keys, channels, out, who, err, errlen))
        return false;
    for (uint32_t y = 0; y < d.height; y++)
        for (uint32_t x = 0; x < d.width; x++)
            paint(&d, keys, texel_centre(x, d.width), texel_centre(y, d.height),
                  &out->data[((size_t)y * d.width + x) * channels]);
    return true;
}

/* A value at (u, v), as height_at. */
typedef float texel_value(const texture_desc *d, const uint32_t *keys, float u, float v);

/* The value at every texel centre, row by row, in an array the caller frees; NULL after
 * freeing out when out of memory. */
static float *texel_field(const texture_desc *d, const uint32_t *keys, texel_value *value,
                          texture_image *out, const char *who, char *err, size_t errlen)
{
    float *f = malloc((size_t)d->width * d->height * sizeof *f);
    if (!f) {
        texture_free(out);
        scene_fail(err, errlen, "%s: out of memory", who);
        return NULL;
    }
    for (uint32_t y = 0; y < d->height; y++)
        for (uint32_t x = 0; x < d->width; x++)
            f[(size_t)y * d->width + x] =
                value(d, keys, texel_centre(x, d->width), texel_centre(y, d->height));
    return f;
}

static void diffuse_texel(const texture_desc *d, const uint32_t *keys, float u, float v,
                          uint8_t *p)
{
    sample s = pattern_at(d, keys, u, v);
    float k = s.tint * (1.0f + 0.5f * d->noise * detail_at(d, keys, u, v));
    for (int c = 0; c < 3; c++)
        p[c] = to8(k * (d->color_a[c] + s.t * (d->color_b[c] - d->color_a[c])));
    p[3] = 255;
}

bool texture_diffuse(const texture_desc *in, texture_image *out, char *err, size_t errlen)
{
    return paint_map(in, out, 4, diffuse_texel, "texture_diffuse", err, errlen);
}

static void gloss_texel(const texture_desc *d, const uint32_t *keys, float u, float v,
                        uint8_t *p)
{
    sample s = pattern_at(d, keys, u, v);
    float g = d->gloss_a + s.t * (d->gloss_b - d->gloss_a);
    g += 0.2f * d->noise * detail_at(d, keys, u, v);
    *p = to8(g);
}

bool texture_gloss(const texture_desc *in, texture_image *out, char *err, size_t errlen)
{
    return paint_map(in, out, 1, gloss_texel, "texture_gloss", err, errlen);
}

bool texture_normal_map(const texture_desc *in, texture_image *out, char *err, size_t errlen)
{
    texture_desc d;
    uint32_t keys[NKEYS];
    if (!image_alloc(in, &d, keys, 4, out, "texture_normal_map", err, errlen))
        return false;
    /* heights at every texel centre once; the pattern is periodic, so the differences
     * wrap around the edges */
    float *h = texel_field(&d, keys, height_at, out, "texture_normal_map", err, errlen);
    if (!h)
        return false;
    for (uint32_t y = 0; y < d.height; y++) {
        uint32_t y0 = (y + d.height - 1) % d.height, y1 = (y + 1) % d.height;
        for (uint32_t x = 0; x < d.width; x++) {
            uint32_t x0 = (x + d.width - 1) % d.width, x1 = (x + 1) % d.width;
            float dx = 0.5f * (h[(size_t)y * d.width + x1] - h[(size_t)y * d.width + x0]);
            float dy = 0.5f * (h[(size_t)y1 * d.width + x] - h[(size_t)y0 * d.width + x]);
            float nx = -d.bump * dx, ny = -d.bump * dy, nz = 1.0f;
            float len = sqrtf(nx * nx + ny * ny + nz * nz);
            uint8_t *p = &out->data[((size_t)y * d.width + x) * 4];
            p[0] = to8(0.5f + 0.5f * nx / len);
            p[1] = to8(0.5f + 0.5f * ny / len);
            p[2] = to8(0.5f + 0.5f * nz / len);
            if (p[2] < 129)                     /* z > 0 after decoding, always */
                p[2] = 129;
            p[3] = to8(h[(size_t)y * d.width + x]);
        }
    }
    free(h);
    return true;
}

static float lit_at(const texture_desc *d, const uint32_t *keys, float u, float v)
{
    return pattern_at(d, keys, u, v).lit;
}

bool texture_emissive(const texture_desc *in, texture_image *out, char *err, size_t errlen)
{
    texture_desc d;
    uint32_t keys[NKEYS];
    if (!image_alloc(in, &d, keys, 4, out, "texture_emissive", err, errlen))
        return false;
    size_t n = (size_t)d.width * d.height;
    float *lit = texel_field(&d, keys, lit_at, out, "texture_emissive", err, errlen);
    if (!lit)
        return false;
    if (d.pattern == TEXTURE_NOISE) {
        /* light the highest emissive_fraction of the texels: the threshold from a
         * histogram of the heights, then a soft edge 1/256 wide below it */
        enum { BINS = 4096 };
        uint32_t *hist = calloc(BINS, sizeof *hist);
        if (!hist) {
            free(lit);
            texture_free(out);
            return scene_fail(err, errlen, "texture_emissive: out of memory");
        }
        for (size_t i = 0; i < n; i++)
            hist[(uint32_t)(lit[i] * (BINS - 1))]++;
        size_t want = (size_t)((double)d.emissive_fraction * (double)n + 0.5), have = 0;
        uint32_t b = BINS;
        while (b > 0 && have + hist[b - 1] <= want)
            have += hist[--b];
        free(hist);
        float th = (float)b / (float)(BINS - 1);
        for (size_t i = 0; i < n; i++)
            lit[i] = smoothstep(th - 1.0f / 256.0f, th, lit[i]);
    }
    for (size_t i = 0; i < n; i++) {
        uint8_t *p = &out->data[i * 4];
        for (int c = 0; c < 3; c++)
            p[c] = to8(d.emissive_color[c] * lit[i]);
        p[3] = to8(lit[i]);
    }
    free(lit);
    return true;
}

void texture_free(texture_image *img)
{
    if (!img)
        return;
    free(img->data);
    memset(img, 0, sizeof *img);
}
