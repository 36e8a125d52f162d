// The frame's packed lights in one shader storage buffer (std430; a Light is 5 vec4s,
// 80 bytes, lighting.inc's layout, filled by shading_pack_light), read by every
// renderer that loops over lights from a buffer (forward-plus; forward-spml's
// LIGHTS_STORAGE declares the same block itself). Needs lighting.inc and bindings.h.
layout(std430, binding = BIND_SSBO_LIGHTS) readonly buffer LightBuffer {
    Light b_lights[];
};

// light_in_range (lighting.inc) of light i, loading only what that reads, so that a
// rejected light costs its position and range, not the whole Light.
bool light_reaches(uint i, vec3 P)
{
    return light_in_range(b_lights[i], P);
}
