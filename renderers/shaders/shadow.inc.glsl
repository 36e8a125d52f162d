// Shadow-map lookups (seed 000 4.5.6 for deferred, 4.6.4 for forward), included by
// lighting.inc so that every renderer shades a shadowed light with the same code.
// Everything here exists only with SHADOWS defined (renderers define it, and
// MAX_SHADOWS, only for programs that light with shadow-casting lights).
// (The Shadows block, t_shadow, a light's layer and what lies outside the map: the
// comment above the Shadows block below.)
#ifdef SHADOWS
#ifndef MAX_SHADOWS
#error "SHADOWS needs MAX_SHADOWS, the size of the shadow-map pool"
#endif

#include "bindings.h"
//   Shadows   uniform block binding 2 (renderers/frame/shadow.c fills it per frame): per
//             layer of the pool, the matrix from VIEW space to the layer's shadow-map
//             coordinates: xy in [0, 1] across the map, z the depth [0, 1] the map
//             stores. Deferred (4.5.6) goes view -> world -> light projection space
//             from the G-buffer's position; the forward passes do the same from the
//             interpolated view-space position, so both read the same texel.
//   t_shadow  texture unit 12: the pool, a 2D array of DEPTH_COMPONENT32F, compare mode
//             REF_TO_TEXTURE with LEQUAL and linear filtering: each lookup is 2x2
//             percentage-closer filtering (the hardware shadow mapping 4.6.4 names).
//
// A light's layer is Light.params.z - 1 (lighting.inc; params.z = 0: no shadow map, the
// value shading_pack_light leaves). Points outside
// the map (x, y or z out of [0, 1], or behind a spot's apex) are lit: a spot's cone lies
// inside its map and beyond its far plane (its range) it lights nothing anyway; a
// directional map covers every visible receiver.
layout(std140, binding = BIND_UBO_SHADOWS) uniform Shadows {
    mat4 u_shadow_matrix[MAX_SHADOWS];
};
layout(binding = BIND_TEX_SHADOW) uniform sampler2DArrayShadow t_shadow;

// 1 lit, 0 in shadow, between on the filtered edge of a shadow.
float shadow_visibility(int layer, vec3 P)
{
    if (layer < 0 || layer >= MAX_SHADOWS)
        return 1.0;
    vec4 p = u_shadow_matrix[layer] * vec4(P, 1.0);
    if (!(p.w > 0.0))
        return 1.0;
    vec3 c = p.xyz / p.w;
    if (any(lessThan(c, vec3(0.0))) || any(greaterThan(c, vec3(1.0))))
        return 1.0;
    // Explicit zero gradients: the lookup may sit in non-uniform control flow, and the
    // pool has one level anyway.
    return textureGrad(t_shadow, vec4(c.xy, float(layer), c.z), vec2(0.0), vec2(0.0));
}
#endif
