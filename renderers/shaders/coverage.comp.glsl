// The pixels a frame's scene covers (renderer_base_coverage): those where any sample of
// the depth target is nearer than the far plane (depth < 1), counted into one word.
// Runs between frames, on the harness's time, never inside a measured frame.
#include "bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;

#ifdef MSAA_SAMPLES
layout(binding = BIND_TEX_DEPTH) uniform sampler2DMS t_depth;
#else
layout(binding = BIND_TEX_DEPTH) uniform sampler2D t_depth;
#endif
layout(std430, binding = BIND_SSBO_COVERAGE) buffer Coverage {
    uint b_covered;
};

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
#ifdef MSAA_SAMPLES
    if (any(greaterThanEqual(pixel, textureSize(t_depth))))
        return;
    bool covered = false;
    for (int i = 0; i < MSAA_SAMPLES; i++)
        covered = covered || texelFetch(t_depth, pixel, i).r < 1.0;
#else
    if (any(greaterThanEqual(pixel, textureSize(t_depth, 0))))
        return;
    bool covered = texelFetch(t_depth, pixel, 0).r < 1.0;
#endif
    if (covered)
        atomicAdd(b_covered, 1u);
}
