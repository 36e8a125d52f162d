// The MSAA edge rule (Lauritzen, SIGGRAPH 2010), one place for the passes that classify
// pixels: deferred's edge_mark.frag, tiled-deferred's tiled_deferred.comp and the
// visibility shading, so that all find the same pixels. A pixel is an edge when a sample
// differs from sample 0: a surface on one and none on the other, a position off sample
// 0's tangent plane by more than EDGE_DEPTH_REL of its view depth (one sloped surface's
// samples are no edge), normals more than acos(EDGE_NORMAL_COS) apart, or a material
// value more than EDGE_MATERIAL_ABS apart (two materials meeting on one plane, as
// interior's generator caps on their bodies: 83/255 off forward at msaa 4 without it).
// EDGE_SAMPLE_XY (position from the depth buffer): each sample's depth is unprojected
// at that sample's own location in the pixel (the context's GL_SAMPLE_POSITIONs), so
// the samples of one plane stay on it; the stored layouts hold the pixel centre's
// values in every sample and are read at the centre.
// Needs gbuffer.inc (GSurface) first, unless EDGE_RULE_SURFACES_ONLY: then only the
// rule on surfaces given by their values (edge_surfaces_differ, edge_materials_differ:
// the visibility renderer's, rebuilt from its ids).
#if !defined(GB_POSITION_XY) && !defined(GB_DEPTH)
#define EDGE_SAMPLE_XY
#endif

#define EDGE_DEPTH_REL 0.01   // 1 % of the view depth
#define EDGE_NORMAL_COS 0.98  // about 11.5 degrees
#define EDGE_MATERIAL_ABS (2.0 / 255.0)   // a material value apart by more than 2/255

// Whether surface (present, position p, normal n) differs from sample 0's (present0,
// p0, n0) by the rule; positions in view space, normals unit length.
bool edge_surfaces_differ(bool present0, vec3 p0, vec3 n0, bool present, vec3 p, vec3 n)
{
    if (present != present0)
        return true;
    return present && (abs(dot(p - p0, n0)) > EDGE_DEPTH_REL * abs(p0.z) ||
                       dot(n, n0) < EDGE_NORMAL_COS);
}

// A surface's material as the rule compares it: the values lighting reads.
struct EdgeMaterial {
    vec3 diffuse, emissive, f0;
    float gloss, occlusion, shininess;
};

// Whether two materials differ by more than EDGE_MATERIAL_ABS in a value (shininess:
// relative above 1): where two surfaces of different materials meet on one plane (a
// coplanar cap on a body, a texture's seam), which the geometric rule cannot see.
bool edge_materials_differ(EdgeMaterial a, EdgeMaterial b)
{
    const float tol = EDGE_MATERIAL_ABS;
    return any(greaterThan(abs(b.diffuse - a.diffuse), vec3(tol))) ||
           any(greaterThan(abs(b.emissive - a.emissive), vec3(tol))) ||
           any(greaterThan(abs(b.f0 - a.f0), vec3(tol))) ||
           abs(b.gloss - a.gloss) > tol || abs(b.occlusion - a.occlusion) > tol ||
           abs(b.shininess - a.shininess) > tol * max(1.0, a.shininess);
}

#ifndef EDGE_RULE_SURFACES_ONLY
EdgeMaterial edge_material(GSurface g)
{
    return EdgeMaterial(g.diffuse, g.emissive, g.f0, g.gloss, g.occlusion, g.shininess);
}

bool edge_samples_differ(GSurface g0, GSurface g)
{
    return edge_surfaces_differ(g0.present, g0.position, g0.normal, g.present, g.position,
                                g.normal) ||
           (g.present && edge_materials_differ(edge_material(g0), edge_material(g)));
}
#endif
