// The lights that reach each pixel's surface (renderer_base_lights_reaching): the
// workload's own figure, whatever the renderer culls. Runs between frames, on the
// harness's time, never inside a measured frame. Per pixel of the depth target: the
// nearest sample with geometry (depth < 1) unprojected to view space P, then every one
// of the frame's lights tested: a point or spot light reaches P within its range
// (|P - light| <= range, the loops' squared-range test), a spot only inside its cone
// (light_incoming's cut-off: cos > the cone's), a directional light everywhere. Pixels
// without geometry get 0xffffffff. The lights are read 64 at a time; each invocation
// tests one against the box around the work group's surface points and keeps it in a
// shared list when its sphere meets it, and only the list is tested per pixel (a pixel
// tests what reaches near it: 4,096 lights at 1280x720 took 265 s of brute force on a
// loaded llvmpipe).
#include "bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;

#ifdef MSAA_SAMPLES
layout(binding = BIND_TEX_DEPTH) uniform sampler2DMS t_depth;
#else
layout(binding = BIND_TEX_DEPTH) uniform sampler2D t_depth;
#endif
// two vec4s a light: view-space position and range (range < 0: directional), view-space
// direction and the cosine of the spot's cut-off (< -1: no cone)
layout(std430, binding = BIND_SSBO_REACH_LIGHTS) readonly buffer ReachLights {
    vec4 b_lights[];
};
layout(std430, binding = BIND_SSBO_REACH_COUNTS) writeonly buffer ReachCounts {
    uint b_count[];
};
layout(location = 0) uniform mat4 u_inv_proj;
layout(location = 1) uniform int u_lights;

shared vec4 s_pos[64];
shared vec4 s_dir[64];
shared vec4 s_point[64];   // each invocation's P, w 1 where covered
shared uint s_kept;

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
#ifdef MSAA_SAMPLES
    ivec2 size = textureSize(t_depth);
#else
    ivec2 size = textureSize(t_depth, 0);
#endif
    bool inside = all(lessThan(pixel, size));
    float depth = 1.0;
    if (inside) {
#ifdef MSAA_SAMPLES
        for (int i = 0; i < MSAA_SAMPLES; i++)
            depth = min(depth, texelFetch(t_depth, pixel, i).r);
#else
        depth = texelFetch(t_depth, pixel, 0).r;
#endif
    }
    bool covered = depth < 1.0;
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
    vec4 v = u_inv_proj * vec4(ndc, depth * 2.0 - 1.0, 1.0);
    vec3 P = v.xyz / v.w;
    uint n = 0u, lights = uint(u_lights), me = gl_LocalInvocationIndex;
    s_point[me] = vec4(P, covered ? 1.0 : 0.0);
    barrier();
    // the box around the group's covered points (empty: lo > hi, which no sphere meets)
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    for (uint k = 0u; k < 64u; k++) {
        if (s_point[k].w > 0.5) {
            lo = min(lo, s_point[k].xyz);
            hi = max(hi, s_point[k].xyz);
        }
    }
    bool any_covered = hi.x >= lo.x;
    // every invocation reaches every barrier: the loop bound is uniform
    for (uint base = 0u; base < lights; base += 64u) {
        if (me == 0u)
            s_kept = 0u;
        barrier();
        uint i = base + me;
        if (i < lights && any_covered) {
            vec4 pr = b_lights[2u * i];
            vec3 q = clamp(pr.xyz, lo, hi) - pr.xyz;   // nearest point of the box
            if (pr.w < 0.0 || !(dot(q, q) > pr.w * pr.w)) {
                uint slot = atomicAdd(s_kept, 1u);
                s_pos[slot] = pr;
                s_dir[slot] = b_lights[2u * i + 1u];
            }
        }
        barrier();
        uint m = s_kept;
        for (uint j = 0u; covered && j < m; j++) {
            vec4 pr = s_pos[j];
            if (pr.w < 0.0) {
                n++;
                continue;
            }
            vec3 d = pr.xyz - P;
            float d2 = dot(d, d);
            if (d2 > pr.w * pr.w)
                continue;
            vec4 dc = s_dir[j];
            if (dc.w >= -1.0 && d2 > 0.0 && !(dot(-d * inversesqrt(d2), dc.xyz) > dc.w))
                continue;
            n++;
        }
        barrier();
    }
    if (inside)
        b_count[pixel.y * size.x + pixel.x] = covered ? n : 0xffffffffu;
}
