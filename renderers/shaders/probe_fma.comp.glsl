// `shadesweep probe`: the compute stage's arithmetic rate (probe_fma.inc), one result
// an invocation into the buffer at binding 1.
#include "probe_fma.inc"
layout(local_size_x = 64) in;
layout(location = 0) uniform int u_iterations;
layout(std430, binding = 1) writeonly buffer Dst { vec4 dst[]; };

void main()
{
    uint i = gl_GlobalInvocationID.x;
    dst[i] = probe_fma(vec4(float(i & 255u) * 1e-3, 0.5, 0.25, 1.0), u_iterations);
}
