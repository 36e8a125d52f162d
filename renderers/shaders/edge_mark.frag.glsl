// MSAA edge marking (deferred with msaa > 1; Lauritzen, SIGGRAPH 2010): full screen, per
// pixel, over the multisampled G-buffer (GB_MSAA). A pixel is an edge when any of its
// samples differs from sample 0: a surface on one and none on the other, a position off
// sample 0's tangent plane by more than EDGE_DEPTH_REL of its view depth (so the samples
// of one sloped surface, whose depths differ when position comes from the depth
// buffer, are not an edge), or normals more than acos(EDGE_NORMAL_COS) apart. Edge pixels pass (the pass's stencil op sets the edge
// bit in every sample); the others are discarded. No colour is written.
#include "bindings.h"
#include "frame.inc"
int gb_sample = 0;
#define GB_SAMPLE gb_sample
// Position from the depth buffer: each sample's depth is unprojected at that sample's
// own location (u_sample_pos, the context's GL_SAMPLE_POSITIONs), so that the samples of
// one plane stay on it; the stored layouts hold the pixel centre's values in every
// sample, and are read at the centre.
#if !defined(GB_POSITION_XY) && !defined(GB_DEPTH)
#define EDGE_SAMPLE_XY
#endif
vec2 g_frag_xy;
#define GB_FRAG_XY g_frag_xy
layout(location = LOC_RENDERER) uniform vec2 u_sample_pos[8];
#include "gbuffer.inc"

#define EDGE_DEPTH_REL 0.01   // 1 % of the view depth
#define EDGE_NORMAL_COS 0.98  // about 11.5 degrees

void main()
{
    int n = textureSamples(t_gb0);
    vec2 pixel = floor(gl_FragCoord.xy);
    g_frag_xy = gl_FragCoord.xy;
#ifdef EDGE_SAMPLE_XY
    g_frag_xy = pixel + u_sample_pos[0];
#endif
    gb_sample = 0;
    GSurface g0 = gbuffer_load();
    bool edge = false;
    for (int i = 1; i < n; i++) {
        gb_sample = i;
#ifdef EDGE_SAMPLE_XY
        g_frag_xy = pixel + u_sample_pos[min(i, 7)];
#endif
        GSurface g = gbuffer_load();
        if (g.present != g0.present)
            edge = true;
        else if (g.present &&
                 (abs(dot(g.position - g0.position, g0.normal)) >
                      EDGE_DEPTH_REL * abs(g0.position.z) ||
                  dot(g.normal, g0.normal) < EDGE_NORMAL_COS))
            edge = true;
    }
    if (!edge)
        discard;
}
