// The last pass of every renderer (scene_gpu_resolve), drawn with fullscreen.vert:
// the HDR accumulation target (texture unit 0, the same size as the output) made into
// the 8-bit output, pixel for pixel (texelFetch: no filtering, no offset); alpha is 1.
// Without EXPOSURE and TONEMAP_PBR_NEUTRAL (schema 1's defaults) it is clamped to
// [0, 1] and written as it is. With them (exposure.*, tonemap; a scene's display):
//   EXPOSURE             times u_exposure, the run's linear exposure
//   TONEMAP_PBR_NEUTRAL  the Khronos PBR Neutral tone mapper (its specification, 2024),
//                        then the sRGB transfer function (IEC 61966-2-1), as a viewer
//                        shows a glTF model
// results/image_ref.c's image_display_rgba8 is the same on the CPU (the supersampled
// reference goes through it): keep the two alike.
#include "bindings.h"
layout(binding = BIND_TEX_HDR) uniform sampler2D t_hdr;
#ifdef EXPOSURE
layout(location = 0) uniform float u_exposure;
#endif

layout(location = 0) out vec4 o_color;

#ifdef TONEMAP_PBR_NEUTRAL
// PBR Neutral: linear Rec. 709 in (non-negative), linear [0, 1] out. Below the start
// of compression (K_s = 0.8 - F90, F90 = 0.04) the colour only loses a small offset f
// that keeps black black; above, the peak channel is compressed towards 1 and the
// colour desaturated towards it at rate K_d = 0.15.
vec3 pbr_neutral(vec3 c)
{
    const float F90 = 0.04, KS = 0.8 - F90, KD = 0.15;
    float x = min(c.r, min(c.g, c.b));
    float f = x <= 2.0 * F90 ? x - x * x / (4.0 * F90) : F90;
    c -= f;
    float p = max(c.r, max(c.g, c.b));
    if (p <= KS)
        return c;
    float pn = 1.0 - (1.0 - KS) * (1.0 - KS) / (p + 1.0 - 2.0 * KS);
    float g = 1.0 / (KD * (p - pn) + 1.0);
    return c * (pn / p) * g + vec3(pn) * (1.0 - g);
}

vec3 srgb_encode(vec3 c)
{
    vec3 lo = c * 12.92;
    vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
    return mix(hi, lo, lessThanEqual(c, vec3(0.0031308)));
}
#endif

void main()
{
    vec3 c = texelFetch(t_hdr, ivec2(gl_FragCoord.xy), 0).rgb;
#ifdef EXPOSURE
    c *= u_exposure;
#endif
#ifdef TONEMAP_PBR_NEUTRAL
    // a NaN or negative channel (never expected) shows as 0, as the clamp does
    c = srgb_encode(clamp(pbr_neutral(max(c, vec3(0.0))), 0.0, 1.0));
#endif
    o_color = vec4(clamp(c, 0.0, 1.0), 1.0);
}
