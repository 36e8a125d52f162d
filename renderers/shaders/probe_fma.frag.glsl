// `shadesweep probe`: the fragment stage's arithmetic rate (probe_fma.inc).
#include "probe_fma.inc"
layout(location = 0) uniform int u_iterations;
layout(location = 0) in vec2 v_uv;
layout(location = 0) out vec4 o_color;

void main()
{
    o_color = probe_fma(vec4(v_uv, 0.5, 0.25), u_iterations);
}
