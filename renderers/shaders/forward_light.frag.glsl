// forward-mpml's light passes (seed 000 4.6.3): one light, u_light, over the objects
// of its illumination set, added into the HDR target (blend ONE, ONE) where the depth
// of the first pass is EQUAL. Alpha 0: the first pass's alpha stays.
// Defines: the material's maps (surface.inc); LIGHT_TYPE, one of LIGHT_POINT,
// LIGHT_SPOT, LIGHT_DIRECTIONAL, the one light type a program is compiled for (the
// light's own type word is replaced by it, so the other types' code folds away).
// FOG (fog.inc): the light scaled by the fog factor (the base pass adds the colour).
#include "bindings.h"
#include "frame.inc"
#include "surface.inc"
#include "lighting.inc"
#include "fog.inc"

#ifndef LIGHT_TYPE
#error "forward_light.frag is compiled for one LIGHT_TYPE"
#endif

layout(location = LOC_RENDERER) uniform vec4 u_light[5];   // lighting.inc's layout

layout(location = 0) out vec4 o_color;

void main()
{
    Surface s = surface_get();
    Light l = light_from(u_light);
    l.color_type.w = float(LIGHT_TYPE);
    vec3 c = shade_light(l, s.position, s.normal, s.diffuse, s.gloss, s.shininess);
#ifdef FOG
    c *= fog_factor(s.position.z);
#endif
    o_color = vec4(c, 0.0);
}
