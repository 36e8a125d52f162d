// With separate diffuse and specular accumulation (seed 001): the specular target
// added into the diffuse one (blend ONE, ONE), which is then the frame's light.
// Full screen (fullscreen.vert).
#include "bindings.h"
// MSAA (GB_MSAA): the specular target is multisampled, GB_SAMPLE the sample read.
#include "msaa.inc"
layout(binding = BIND_TEX_SPECULAR) uniform GB_SAMPLER t_specular;

layout(location = 0) out vec4 o_light;

void main()
{
    o_light = vec4(texelFetch(t_specular, ivec2(gl_FragCoord.xy), GB_SAMPLE).rgb, 0.0);
}
