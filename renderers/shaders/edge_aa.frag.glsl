// Edge-detect anti-aliasing (renderers/frame/edge_aa.h; seed 001 section 19.5.2), drawn with
// fullscreen.vert into its own target: the HDR image (t_hdr) with each pixel blended
// with its 8 neighbours by how much of an edge it is. The edge test compares, per
// opposite pair of neighbours, the two depth steps from the centre with each other
// (an edge when the larger is >= 25 x the smaller) and the two cosines between the
// centre's normal and theirs (an edge when they differ by >= 0.4); the weight is the
// share of the 4 pairs that are edges. Depth is the depth buffer's window depth;
// normals come from the G-buffer (EDGE_NORMALS_GBUFFER, with the layout's defines) or
// are rebuilt from depth. Every read is a texelFetch clamped to the image.
#include "bindings.h"
#include "frame.inc"

#ifdef EDGE_NORMALS_GBUFFER
// gbuffer.inc reads the pixel whose centre GB_FRAG_XY names: any pixel, set per load
vec2 g_edge_xy;
#define GB_FRAG_XY g_edge_xy
#include "gbuffer.inc"
#else
layout(binding = BIND_TEX_DEPTH) uniform sampler2D t_depth;
#endif
layout(binding = BIND_TEX_HDR) uniform sampler2D t_hdr;

layout(location = 0) out vec4 o_color;

// 19.5.2's constants: how much larger one depth step must be than the other, and how
// much the cosines may differ, before a pair is an edge
const float DEPTH_RATIO = 25.0;
const float NORMAL_COS_DELTA = 0.4;
// the smaller step's floor (19.5.2 floors it so that it is never 0): 4 steps of the
// 24-bit depth buffer, so its rounding never passes for an edge
const float DEPTH_FLOOR = 4.0 / 16777215.0;

// The neighbours in 19.5.2's order: 1..4 and 5..8 are opposite pairs (i, i + 4).
const ivec2 OFFSETS[9] = ivec2[9](ivec2(0, 0), ivec2(-1, -1), ivec2(0, -1), ivec2(1, -1),
                                  ivec2(1, 0), ivec2(1, 1), ivec2(0, 1), ivec2(-1, 1),
                                  ivec2(-1, 0));

ivec2 clamp_px(ivec2 p)
{
    return clamp(p, ivec2(0), ivec2(f_viewport.xy) - 1);
}

float depth_at(ivec2 p)
{
    return texelFetch(t_depth, clamp_px(p), 0).r;
}

#ifdef EDGE_NORMALS_GBUFFER
vec3 normal_at(ivec2 p)
{
    g_edge_xy = vec2(clamp_px(p)) + 0.5;
    return gbuffer_load().normal;
}
#else
// The view-space position at pixel p (clamped), unprojected as gbuffer.inc does.
vec3 position_at(ivec2 p)
{
    ivec2 q = clamp_px(p);
    float d = texelFetch(t_depth, q, 0).r;
    vec2 ndc = (vec2(q) + 0.5) * f_viewport.zw * 2.0 - 1.0;
    vec4 v = f_inv_proj * vec4(ndc, d * 2.0 - 1.0, 1.0);
    return v.xyz / v.w;
}

// The face's normal at p from depth: along x and along y, the one-sided step whose
// depth changes less (the one that does not cross an edge), crossed.
vec3 normal_at(ivec2 p)
{
    vec3 c = position_at(p);
    vec3 r = position_at(p + ivec2(1, 0)) - c, l = c - position_at(p - ivec2(1, 0));
    vec3 u = position_at(p + ivec2(0, 1)) - c, d = c - position_at(p - ivec2(0, 1));
    vec3 dx = abs(r.z) < abs(l.z) ? r : l;
    vec3 dy = abs(u.z) < abs(d.z) ? u : d;
    vec3 n = cross(dx, dy);
    float len2 = dot(n, n);
    return len2 > 1e-30 ? n * inversesqrt(len2) : vec3(0.0, 0.0, 1.0);
}
#endif

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    float depth[9];
    vec3 normal[9];
    for (int i = 0; i < 9; i++) {
        depth[i] = depth_at(px + OFFSETS[i]);
        normal[i] = normal_at(px + OFFSETS[i]);
    }
    vec4 d1 = abs(vec4(depth[1], depth[2], depth[3], depth[4]) - depth[0]);
    vec4 d2 = abs(depth[0] - vec4(depth[5], depth[6], depth[7], depth[8]));
    vec4 dmax = max(d1, d2);
    vec4 dmin = max(min(d1, d2), DEPTH_FLOOR);
    vec4 depth_edge = step(dmin * DEPTH_RATIO, dmax);

    vec4 c1 = vec4(dot(normal[1], normal[0]), dot(normal[2], normal[0]),
                   dot(normal[3], normal[0]), dot(normal[4], normal[0]));
    vec4 c2 = vec4(dot(normal[5], normal[0]), dot(normal[6], normal[0]),
                   dot(normal[7], normal[0]), dot(normal[8], normal[0]));
    vec4 normal_edge = step(NORMAL_COS_DELTA, abs(c1 - c2));
    vec4 edge = max(depth_edge, normal_edge);
    float weight = dot(edge, vec4(0.25));

    // The mean of four bilinear samples at the centre + (+-f, +-f) pixels, f = weight / 2
    // (19.5.2: at the centre for weight 0, at the pixel's corners for 1), as its weights
    // on the 3 x 3 texels: centre (1 - f)^2, sides f (1 - f) / 2, corners f^2 / 4.
    vec4 centre = texelFetch(t_hdr, px, 0);
    vec3 sides = vec3(0.0), corners = vec3(0.0);
    for (int i = 1; i < 9; i++) {
        vec3 c = texelFetch(t_hdr, clamp_px(px + OFFSETS[i]), 0).rgb;
        if ((i & 1) == 0)
            sides += c;     // 2, 4, 6, 8: top, right, bottom, left
        else
            corners += c;   // 1, 3, 5, 7: the diagonals
    }
    float f = 0.5 * weight;
    vec3 rgb = (1.0 - f) * (1.0 - f) * centre.rgb + 0.5 * f * (1.0 - f) * sides +
               0.25 * f * f * corners;
    o_color = vec4(rgb, centre.a);
}
