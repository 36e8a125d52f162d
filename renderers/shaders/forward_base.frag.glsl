// forward-mpml's first pass (seed 000 4.6.2): depth, ambient and emissive in one pass,
// A = ambient light x diffuse material (appendix D), plus the emissive term. The
// lights are added by forward_light.frag in depth-EQUAL additive passes.
// Defines: the material's maps (surface.inc).
#include "frame.inc"
#include "surface.inc"

layout(location = 0) out vec4 o_color;

void main()
{
    Surface s = surface_get();
    o_color = vec4(f_ambient.rgb * s.diffuse + s.emissive, 1.0);
}
