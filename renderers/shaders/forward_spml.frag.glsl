// forward-spml (seed 003 4.1): one pass; ambient + emissive as forward_base.frag, and
// every visible light of the frame from a uniform buffer (the seed's constant buffer),
// looped here. A point or spot light whose squared distance exceeds its squared range
// is skipped before any other work (shade_light would give exactly zero there too).
// Defines: the material's maps (surface.inc); MAX_LIGHTS, the array size, chosen once
// per run from the run's largest light count (forward_spml.c); or LIGHTS_STORAGE:
// the lights from a storage buffer; FOG (fog.inc): the sum fogged; TRANSLUCENT (the
// translucent pass, renderers/frame/translucent.c): the output premultiplied by the surface's
// alpha, (c a, a), for blending ONE, ONE_MINUS_SRC_ALPHA over what lies behind.
#include "bindings.h"
#include "frame.inc"
#include "surface.inc"
#include "environment.inc"
#include "lighting.inc"
#include "fog.inc"

#ifdef LIGHTS_STORAGE
// forward.light_buffer: storage: the same packed lights, unsized (lights.inc's layout)
layout(std430, binding = BIND_SSBO_LIGHTS) readonly buffer LightBuffer {
    Light u_lights[];
};
#define MAX_LIGHTS 2147483647
#else
#ifndef MAX_LIGHTS
#error "forward_spml.frag needs MAX_LIGHTS"
#endif

layout(std140, binding = BIND_UBO_LIGHTS) uniform Lights {
    Light u_lights[MAX_LIGHTS];
};
#endif
layout(location = LOC_RENDERER) uniform int u_light_count;   // lights in u_lights this frame

layout(location = 0) out vec4 o_color;

void main()
{
    Surface s = surface_get();
    vec3 c = ambient_light(s.position, s.normal, s.diffuse, s.gloss, s.shininess,
                           s.occlusion) + s.emissive;
    int n = min(u_light_count, MAX_LIGHTS);
    for (int i = 0; i < n; i++) {
        Light l = u_lights[i];
        if (!light_in_range(l, s.position))
            continue;
        c += shade_light(l, s.position, s.normal, s.diffuse, s.gloss, s.shininess);
    }
    o_color = forward_output(c, s.position.z, s.alpha);
}
