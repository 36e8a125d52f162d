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
// Needs gbuffer.inc (GSurface) first, unless EDGE_RULE_SURFACES_ONLY: then only
// edge_surfaces_differ, the rule on surfaces given by their values (the visibility
// renderer's, rebuilt from its ids).
#if !defined(GB_POSITION_XY) && !defined(GB_DEPTH)
#define EDGE_SAMPLE_XY
#endif

#define EDGE_DEPTH_REL 0.01   // 1 % of the view depth
#define EDGE_NORMAL_COS 0.98  // about 11.5 degrees

// Whether surface (present, position p, normal n) differs from sample 0's (present0,
// p0, n0) by the rule; positions in view space, normals unit length.
bool edge_surfaces_differ(bool present0, vec3 p0, vec3 n0, bool present, vec3 p, vec3 n)
{
    if (present != present0)
        return true;
    return present && (abs(dot(p - p0, n0)) > EDGE_DEPTH_REL * abs(p0.z) ||
                       dot(n, n0) < EDGE_NORMAL_COS);
}

#ifndef EDGE_RULE_SURFACES_ONLY
bool edge_samples_differ(GSurface g0, GSurface g)
{
    return edge_surfaces_differ(g0.present, g0.position, g0.normal, g.present, g.position,
                                g.normal);
}
#endif
