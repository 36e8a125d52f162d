// forward-mpml's first pass (seed 000 4.6.2): depth, ambient and emissive in one pass,
// A = ambient light x diffuse material (appendix D), plus the emissive term. The
// lights are added by forward_light.frag in depth-EQUAL additive passes.
// Defines: the material's maps (surface.inc); FOG (fog.inc): the sum fogged, so that
// with the light passes' fog_factor the total is the fogged image; BASE_DIRECTIONAL n
// (only with forward.directional_in_base, for a scene with n directional lights): the
// frame's directional lights, u_base_count <= n of them in u_base_lights (lighting.inc's
// layout, 5 vec4s each), are shaded here too (before the fog), each as
// forward_light.frag would add it (with SHADOWS, through the light's shadow map), so
// they need no pass of their own.
#include "frame.inc"
#include "surface.inc"
#include "environment.inc"
#include "fog.inc"

#ifdef BASE_DIRECTIONAL
#include "bindings.h"
#include "lighting.inc"
layout(location = LOC_RENDERER) uniform int u_base_count;
layout(location = LOC_BASE_LIGHTS) uniform vec4 u_base_lights[5 * BASE_DIRECTIONAL];
#endif

layout(location = 0) out vec4 o_color;

void main()
{
    Surface s = surface_get();
    vec3 c = ambient_light(s.position, s.normal, s.diffuse, s.gloss, s.shininess,
                           s.occlusion) + s.emissive;
#ifdef BASE_DIRECTIONAL
    for (int i = 0; i < u_base_count && i < BASE_DIRECTIONAL; i++) {
        Light l = Light(u_base_lights[5 * i], u_base_lights[5 * i + 1],
                        u_base_lights[5 * i + 2], u_base_lights[5 * i + 3],
                        u_base_lights[5 * i + 4]);
        l.color_type.w = float(LIGHT_DIRECTIONAL);
        c += shade_light(l, s.position, s.normal, s.diffuse, s.gloss, s.shininess);
    }
#endif
#ifdef FOG
    c = fog_apply(c, s.position.z);
#endif
    o_color = vec4(c, 1.0);
}
