#pragma once
/* The environment light (issue 36, manifest key environment.light: sky): a procedural
 * daylight sky in world space (y up), lit the way the glTF Sample Viewer lights a model
 * by an environment map, with Karis's split-sum approximation ("Real Shading in Unreal
 * Engine 4", 2013):
 *   diffuse   irradiance(N) x c_diff: the sky's irradiance / pi as 9 spherical-harmonic
 *             coefficients (Ramamoorthi and Hanrahan 2001), in the Frame block
 *   specular  prefiltered(R, roughness) x (F0 A + B): a cube map whose mip k holds the sky
 *             convolved with the GGX lobe of roughness k / (ENVIRONMENT_LEVELS - 1)
 *             (N = V = R), read at lod roughness x (levels - 1); A, B from Karis's
 *             analytic fit ("Physically Based Shading on Mobile", 2014), in the shader
 * Everything is computed here on the CPU, once a process (every trial process renders
 * the same sky: the maps do not depend on the scene; the intensity multiplies them in
 * the shader and the coefficients in the Frame block), deterministically: the same
 * arithmetic in every process, with a fixed Hammersley sample set.
 * renderers/shaders/environment.inc.glsl evaluates it; renderers/frame/scene_gpu.c uploads it. */
#include <stdint.h>

enum {
    ENVIRONMENT_FACE = 64,   /* texels along a face of mip 0 */
    ENVIRONMENT_LEVELS = 6,  /* mips 64 .. 2 texels: roughness 0, 0.2, .. 1 */
    ENVIRONMENT_SAMPLES = 256,   /* GGX samples per prefiltered texel (mips 1..) */
};

/* The sky's radiance (intensity 1) in unit world direction d: a horizon of about 1,
 * a bluish zenith and a grey ground, each blended into the horizon exponentially
 * (a soft glow along the horizon, no sun). */
void environment_sky(const double d[3], double rgb[3]);

typedef struct environment_maps {
    /* mip k, face f (GL's order +X -X +Y -Y +Z -Z), row t, column s: RGB floats at
     * level[k] + ((f * size + t) * size + s) * 3, size = ENVIRONMENT_FACE >> k */
    float *level[ENVIRONMENT_LEVELS];
    /* irradiance / pi in world direction n (unit), intensity 1:
     * sh[0] + sh[1] y + sh[2] z + sh[3] x + sh[4] x y + sh[5] y z + sh[6] (3 z^2 - 1)
     *   + sh[7] x z + sh[8] (x^2 - y^2), each an RGB (the SH basis's constants and the
     * cosine lobe's A_l folded in) */
    float sh[9][3];
    double seconds;          /* what building them took (the first call's) */
} environment_maps;

/* The maps, built at the first call (NULL when out of memory); later calls return the
 * same. Not thread-safe (the renderers are set up on one thread). */
const environment_maps *environment_get(void);
/* The direction (unit) of texel centre (s, t) of face f at a face size: GL's cube map
 * face conventions (the OpenGL 4.6 specification's table 8.19). */
void environment_texel_dir(int face, int s, int t, int size, double d[3]);
