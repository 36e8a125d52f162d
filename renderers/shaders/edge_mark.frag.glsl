// MSAA edge marking (deferred with msaa > 1; Lauritzen, SIGGRAPH 2010): full screen, per
// pixel, over the multisampled G-buffer (GB_MSAA). A pixel is an edge when any of its
// samples differs from sample 0: a surface on one and none on the other, view depths
// that differ by more than EDGE_DEPTH_REL of sample 0's, or normals more than
// acos(EDGE_NORMAL_COS) apart. Edge pixels pass (the pass's stencil op sets the edge
// bit in every sample); the others are discarded. No colour is written.
#include "frame.inc"
int gb_sample = 0;
#define GB_SAMPLE gb_sample
#include "gbuffer.inc"

#define EDGE_DEPTH_REL 0.01   // 1 % of the view depth
#define EDGE_NORMAL_COS 0.98  // about 11.5 degrees

void main()
{
    int n = textureSamples(t_gb0);
    gb_sample = 0;
    GSurface g0 = gbuffer_load();
    bool edge = false;
    for (int i = 1; i < n; i++) {
        gb_sample = i;
        GSurface g = gbuffer_load();
        if (g.present != g0.present)
            edge = true;
        else if (g.present &&
                 (abs(g.position.z - g0.position.z) > EDGE_DEPTH_REL * abs(g0.position.z) ||
                  dot(g.normal, g0.normal) < EDGE_NORMAL_COS))
            edge = true;
    }
    if (!edge)
        discard;
}
