// One light over the G-buffer, added into the light accumulation (blend ONE, ONE):
// full-screen for directional lights (and for every light with light_volumes
// fullscreen), else over the pixels of the light's volume (light_volume.vert). The
// light is shaded by lighting.inc's shade_light(), the same function the forward
// renderers call, so that the two differ only by what the G-buffer loses.
//
// DEFERRED_LIGHT_TYPE: 0 point, 1 spot, 2 directional (only documents the variant:
// the light's own type field drives shade_light). SEPARATE_SPECULAR (seed 001):
// diffuse and specular go to two targets (lighting.inc's shade_light_split).
// LIGHT_PREPASS (deferred-lighting, compiled with SEPARATE_SPECULAR for the two
// outputs): the light buffer's diffuse and specular light, the light without the
// material (lighting.inc's light_prepass).
#include "bindings.h"
#include "frame.inc"
#include "lighting.inc"
#include "gbuffer.inc"

layout(location = LOC_RENDERER) uniform vec4 u_light[5];

#include "light_out.inc"

void main()
{
    GSurface g = gbuffer_load();
    Light l = light_from(u_light);
#if defined(LIGHT_PREPASS)
    // deferred-lighting's light buffer: the light alone, without the material, so that
    // shade_light = diffuse x (incoming ndl) + gloss x (incoming spec) sums exactly over
    // the lights in the material pass (deferred_lighting_material.frag)
    vec3 d = vec3(0.0), s = vec3(0.0);
    if (g.present)
        light_prepass(l, g.position, g.normal, g.shininess, g.f0, d, s);
    o_light = vec4(d, 0.0);
    o_specular = vec4(s, 0.0);
#elif defined(SEPARATE_SPECULAR)
    vec3 d = vec3(0.0), s = vec3(0.0);
    if (g.present)
        shade_light_split(l, g.position, g.normal, g.diffuse, g.gloss, g.shininess, d, s);
    o_light = vec4(d, 0.0);
    o_specular = vec4(s, 0.0);
#else
    vec3 c = vec3(0.0);
    if (g.present)
        c = shade_light(l, g.position, g.normal, g.diffuse, g.gloss, g.shininess);
    o_light = vec4(c, 0.0);
#endif
}
