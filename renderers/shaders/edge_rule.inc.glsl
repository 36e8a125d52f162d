// The MSAA edge rule (Lauritzen, SIGGRAPH 2010), one place for the two passes that
// classify pixels: deferred's edge_mark.frag (stencil) and tiled-deferred's
// tiled_deferred.comp (a per-tile edge list), so that both find the same pixels. A
// pixel is an edge when a sample differs from sample 0: a surface on one and none on
// the other, a position off sample 0's tangent plane by more than EDGE_DEPTH_REL of
// its view depth (the samples of one sloped surface, whose depths differ when the
// position comes from the depth buffer, are no edge), or normals more than
// acos(EDGE_NORMAL_COS) apart.
// EDGE_SAMPLE_XY (position from the depth buffer): each sample's depth is unprojected
// at that sample's own location in the pixel (the context's GL_SAMPLE_POSITIONs), so
// the samples of one plane stay on it; the stored layouts hold the pixel centre's
// values in every sample and are read at the centre.
// Needs gbuffer.inc (GSurface) first.
#if !defined(GB_POSITION_XY) && !defined(GB_DEPTH)
#define EDGE_SAMPLE_XY
#endif

#define EDGE_DEPTH_REL 0.01   // 1 % of the view depth
#define EDGE_NORMAL_COS 0.98  // about 11.5 degrees

bool edge_samples_differ(GSurface g0, GSurface g)
{
    if (g.present != g0.present)
        return true;
    return g.present && (abs(dot(g.position - g0.position, g0.normal)) >
                             EDGE_DEPTH_REL * abs(g0.position.z) ||
                         dot(g.normal, g0.normal) < EDGE_NORMAL_COS);
}
