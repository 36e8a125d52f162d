// The visibility pass (Burns and Hunt, JCGT 2(2), 2013): per pixel the draw and the
// triangle that cover it, packed into one 32-bit id (renderers/visibility/visibility.h):
// id = draw << VIS_TRI_BITS | gl_PrimitiveID, the draw being the object's index in the
// frame's visible list (u_draw) and gl_PrimitiveID the triangle of its mesh. No
// material work, except ALPHA_TEST (a MASK material): surface.inc's discard, the same
// test the other renderers make, so the same pixels are covered. Defines: VIS_TRI_BITS,
// and ALPHA_TEST with DIFFUSE_MAP for the masked materials' program.
// (bindings.h first: the loader includes a file once, #ifdef or not)
#include "bindings.h"
#ifdef ALPHA_TEST
#include "surface.inc"
#endif

layout(location = LOC_RENDERER) uniform int u_draw;

layout(location = 0) out uint o_id;

void main()
{
#ifdef ALPHA_TEST
    surface_get();   // discards below the material's alpha cutoff
#endif
    o_id = (uint(u_draw) << uint(VIS_TRI_BITS)) | uint(gl_PrimitiveID);
}
