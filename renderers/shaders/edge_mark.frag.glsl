// MSAA edge marking (deferred with msaa > 1; Lauritzen, SIGGRAPH 2010): full screen, per
// pixel, over the multisampled G-buffer (GB_MSAA). A pixel is an edge when any of its
// samples differs from sample 0 by edge_rule.inc's rule (shared with tiled_deferred.comp).
// Edge pixels pass (the pass's stencil op sets the edge bit in every sample); the others
// are discarded. No colour is written.
#include "bindings.h"
#include "frame.inc"
int gb_sample = 0;
#define GB_SAMPLE gb_sample
vec2 g_frag_xy;
#define GB_FRAG_XY g_frag_xy
layout(location = LOC_RENDERER) uniform vec2 u_sample_pos[8];
#include "gbuffer.inc"
// EDGE_SAMPLE_XY (position from depth): samples read at u_sample_pos (edge_rule.inc)
#include "edge_rule.inc"

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
        if (edge_samples_differ(g0, gbuffer_load()))
            edge = true;
    }
    if (!edge)
        discard;
}
