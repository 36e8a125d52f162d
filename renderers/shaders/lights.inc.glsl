// The frame's packed lights in one shader storage buffer (std430; a Light is 5 vec4s,
// 80 bytes, lighting.inc's layout, filled by shading_pack_light), read by every
// renderer that loops over lights from a buffer (forward-plus; forward-spml's
// LIGHTS_STORAGE declares the same block itself). Needs lighting.inc and bindings.h.
layout(std430, binding = BIND_SSBO_LIGHTS) readonly buffer LightBuffer {
    Light b_lights[];
};

// Whether light i can reach view-space point P: a point or spot light within its range
// (the squared-range rejection every light loop makes before shade_light, which would
// give exactly zero beyond it), or a directional light. Reads only the light's position
// and range and its type, so that a rejected light costs two loads, not the whole Light.
bool light_reaches(uint i, vec3 P)
{
    vec4 pr = b_lights[i].position_range;
    vec3 d = pr.xyz - P;
#if HAS_DIRECTIONAL
    return !(dot(d, d) > pr.w * pr.w) || int(b_lights[i].color_type.w) == LIGHT_DIRECTIONAL;
#else
    return !(dot(d, d) > pr.w * pr.w);
#endif
}
