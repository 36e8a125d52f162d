#pragma once
/* scenes/builtin/texture_gen.h: procedural textures for the scenes' materials, and the seeded
 * gradient noise they and the terrain share. No OpenGL in here: an image is bytes the
 * renderers upload as they are.
 *
 * The four maps of a material, the image layout, determinism and the list of functions:
 * the comment above the limits below. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* A material is one texture_desc; its four maps come from the same pattern, so they
 * agree (mortar is dark, dull, sunken and never lit):
 *   texture_diffuse     RGBA8: colour (stored as given; the renderer decides whether the
 *                       texture is sRGB), alpha 255
 *   texture_gloss       R8: gloss 0..1
 *   texture_normal_map  RGBA8: tangent-space normal, RGB = n * 0.5 + 0.5 (x along +u,
 *                       y along +v, z out of the surface, z > 0), alpha = height 0..1
 *   texture_emissive    RGBA8: RGB = emissive colour * mask, alpha = mask
 *
 * Images are row-major, tightly packed, the first row is v = 0 (uploaded as GL's
 * t = 0, see scenes/mesh.h), texel (x, y) samples the pattern at its centre
 * ((x + 0.5) / width, (y + 0.5) / height). Every pattern has period 1 in u and v, so the
 * maps tile seamlessly. Deterministic: the same desc gives the same bytes (no clock, no
 * rand(); noise keys come from PCG32 with the seed, see scenes/rng.h).
 *
 * What it offers:
 *   maps     texture_desc_resolve, texture_diffuse, texture_gloss, texture_normal_map,
 *            texture_emissive, texture_height, texture_free, texture_pattern_name
 *   noise    texture_noise_keys, texture_noise2, texture_fbm2
 */
#define TEXTURE_MAX_SIZE 8192u
#define TEXTURE_MAX_OCTAVES 12u

typedef enum texture_pattern {
    TEXTURE_CHECKER = 0,       /* cells x cells squares, bevelled edges; lit: whole squares */
    TEXTURE_BRICKS,            /* cells rows of bricks (2:1), running bond; lit: bricks */
    TEXTURE_NOISE,             /* fractal noise (stone, ground); lit: the highest ridges */
    TEXTURE_PATTERN_COUNT
} texture_pattern;

typedef struct texture_image {
    uint32_t width, height;
    uint32_t channels;         /* 1 (R8) or 4 (RGBA8) */
    uint8_t *data;             /* width * height * channels bytes */
} texture_image;

/* Zero means default for every field, as noted. */
typedef struct texture_desc {
    uint32_t width, height;    /* powers of two, 1..TEXTURE_MAX_SIZE; 0: 256 */
    texture_pattern pattern;   /* 0: checker */
    uint32_t cells;            /* checker squares or brick rows per side, 1..min(width,
                                * height) (bricks: even); noise: the first octave's
                                * periods per side; 0: 8 */
    uint32_t seed;             /* noise, brick tint and which cells are lit */
    float color_a[3], color_b[3];  /* 0..1; both all zero: light and dark grey.
                                * checker: the two squares; bricks: brick, mortar;
                                * noise: low, high */
    float gloss_a, gloss_b;    /* 0..1, as the colours; both zero: 0.8, 0.3 */
    float noise;               /* 0..1: how much noise varies colour and gloss (0: none) */
    float bump;                /* normal map: relief depth in texels for a 0..1 height
                                * step; > 0; 0: 4 */
    float emissive_fraction;   /* 0..1: share of cells (bricks) lit; noise: of the area,
                                * roughly; 0: 0.25 */
    float emissive_color[3];   /* 0..1; all zero: white */
} texture_desc;

/* Applies the defaults of `in` into *out and checks it: false with a message for a size
 * that is not a power of two or too large, an unknown pattern, bad cells (0 after
 * defaults, more than the size, odd for bricks), a non-finite or out-of-range value.
 * out may alias in. */
bool texture_desc_resolve(const texture_desc *in, texture_desc *out, char *err, size_t errlen);

/* Each fills *out (freed with texture_free) from a desc (defaults applied as above);
 * false with a message and *out zeroed on a bad desc or out of memory. */
bool texture_diffuse(const texture_desc *d, texture_image *out, char *err, size_t errlen);
bool texture_gloss(const texture_desc *d, texture_image *out, char *err, size_t errlen);
bool texture_normal_map(const texture_desc *d, texture_image *out, char *err, size_t errlen);
bool texture_emissive(const texture_desc *d, texture_image *out, char *err, size_t errlen);

/* The pattern's height at (u, v), 0..1, period 1 in both; `d` must be resolved
 * (texture_desc_resolve). The normal map is its central difference one texel apart:
 * n = normalize(-bump * dh/dx, -bump * dh/dy, 1), dh/dx and dh/dy per texel. */
float texture_height(const texture_desc *d, float u, float v);

void texture_free(texture_image *img);          /* NULL or freed twice is fine */
const char *texture_pattern_name(texture_pattern p);   /* "checker", ...; NULL if unknown */

/* >>noise ------------------------------------------------------------------------------ */

/* n keys for the octaves of a seed: PCG32 (scenes/rng.h) seeded with `seed`. */
void texture_noise_keys(uint32_t seed, uint32_t *keys, unsigned n);

/* 2D gradient (Perlin) noise with a hashed lattice keyed by `key`, quintic fade, in
 * [-1, 1]; 0 at lattice points. period_x, period_y > 0 make it periodic with that many
 * lattice cells (x and y are in lattice units); 0: not periodic. Non-finite x or y count
 * as 0; |x|, |y| beyond 2^22 are wrapped (the lattice is 2^22 cells wide). */
float texture_noise2(float x, float y, uint32_t key, uint32_t period_x, uint32_t period_y);

/* Fractal sum of `octaves` octaves (1..TEXTURE_MAX_OCTAVES) of texture_noise2, octave o
 * at frequency 2^o with keys[o] and amplitude 0.5^o (periods doubling too), divided by
 * the sum of the amplitudes: in [-1, 1]. */
float texture_fbm2(float x, float y, const uint32_t *keys, unsigned octaves,
                   uint32_t period_x, uint32_t period_y);
