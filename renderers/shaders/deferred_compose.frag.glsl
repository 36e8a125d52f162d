// With separate diffuse and specular accumulation (seed 001): the specular target
// added into the diffuse one (blend ONE, ONE), which is then the frame's light.
// Full screen (fullscreen.vert).
#include "bindings.h"
layout(binding = BIND_TEX_SPECULAR) uniform sampler2D t_specular;

layout(location = 0) out vec4 o_light;

void main()
{
    o_light = vec4(texelFetch(t_specular, ivec2(gl_FragCoord.xy), 0).rgb, 0.0);
}
