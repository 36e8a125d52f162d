// Per-frame values every pass can read: uniform block binding 0 (renderers/shading.h
// fills it as gpu_frame, std140).
#include "bindings.h"
layout(std140, binding = BIND_UBO_FRAME) uniform Frame {
    mat4 f_proj;
    mat4 f_inv_proj;
    vec4 f_ambient;    // rgb: ambient light (A = ambient x diffuse material)
    vec4 f_viewport;   // width, height, 1/width, 1/height
    vec4 f_sky;        // rgb: sky colour; w: 1 when the scene has a sky
    vec4 f_clip;       // near, far, 0, 0
};
