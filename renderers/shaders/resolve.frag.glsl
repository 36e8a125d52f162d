// The last pass of every renderer (scene_gpu_resolve), drawn with fullscreen.vert:
// the HDR accumulation target (texture unit 0, the same size as the output) clamped
// to [0, 1], pixel for pixel (texelFetch: no filtering, no offset); alpha is 1.
#include "bindings.h"
layout(binding = BIND_TEX_HDR) uniform sampler2D t_hdr;

layout(location = 0) out vec4 o_color;

void main()
{
    vec3 c = texelFetch(t_hdr, ivec2(gl_FragCoord.xy), 0).rgb;
    o_color = vec4(clamp(c, 0.0, 1.0), 1.0);
}
