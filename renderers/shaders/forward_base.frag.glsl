// forward-mpml's first pass (seed 000 4.6.2): depth, ambient and emissive in one pass,
// A = ambient light x diffuse material (appendix D), plus the emissive term. The
// lights are added by forward_light.frag in depth-EQUAL additive passes.
// Defines: the material's maps (surface.inc); FOG (fog.inc): the sum fogged, so that
// with the light passes' fog_factor the total is the fogged image.
#include "frame.inc"
#include "surface.inc"
#include "fog.inc"

layout(location = 0) out vec4 o_color;

void main()
{
    Surface s = surface_get();
    vec3 c = f_ambient.rgb * s.diffuse + s.emissive;
#ifdef FOG
    c = fog_apply(c, s.position.z);
#endif
    o_color = vec4(c, 1.0);
}
