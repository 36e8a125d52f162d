// Deferred's fog pass (seed 000 4.5.12: the fog "reads the G-Buffer's per-pixel depth",
// a post-processing pass after the lights; seed 001 computes its fog in the final
// full-screen pass too): full screen (fullscreen.vert) over the light target, after
// the lights (and compose), before the sky. Each pixel's view depth comes from the
// depth buffer (t_depth, unprojected through f_inv_proj as gbuffer.inc does), and
// fog.inc's factor f is blended in: the output (colour x (1 - f), f) with blend
// RGB ONE, SRC_ALPHA (light' = colour (1 - f) + light f) and alpha ZERO, ONE (the
// light's alpha stays). Pixels no surface covers (depth 1: the sky's, or black) get
// (0, 1): unchanged, as forward renderers leave them. The framebuffer has no depth
// attachment, so sampling the depth texture here is no feedback loop.
#include "bindings.h"
#include "frame.inc"
#include "fog.inc"

#ifndef FOG
#error "deferred_fog.frag is compiled with FOG"
#endif

// MSAA (GB_MSAA): depth is multisampled; the pass runs per sample (GB_SAMPLE gl_SampleID).
#include "msaa.inc"
layout(binding = BIND_TEX_DEPTH) uniform GB_SAMPLER t_depth;

layout(location = 0) out vec4 o_fog;

void main()
{
    float d = texelFetch(t_depth, ivec2(gl_FragCoord.xy), GB_SAMPLE).r;
    float f = 1.0;
    if (d < 1.0) {
        vec2 ndc = gl_FragCoord.xy * f_viewport.zw * 2.0 - 1.0;
        vec4 p = f_inv_proj * vec4(ndc, d * 2.0 - 1.0, 1.0);
        f = fog_factor(p.z / p.w);
    }
    o_fog = vec4(u_fog.rgb * (1.0 - f), f);
}
