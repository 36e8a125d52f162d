// Per-frame values every pass can read: uniform block binding 0 (renderers/frame/shading.h
// fills it as gpu_frame, std140).
#include "bindings.h"
layout(std140, binding = BIND_UBO_FRAME) uniform Frame {
    mat4 f_proj;
    mat4 f_inv_proj;
    vec4 f_ambient;    // rgb: ambient light (A = ambient x diffuse material)
    vec4 f_viewport;   // width, height, 1/width, 1/height
    vec4 f_sky;        // rgb: sky colour; w: 1 when the scene has a sky
    vec4 f_clip;       // near, far, 0, 0
#ifdef ENVIRONMENT
    // the environment light (environment.inc): only scenes with one have these (the
    // buffer is as long as the block: scene_gpu.c)
    mat4 f_view_to_world;   // the view matrix's inverse
    vec4 f_environment;     // x intensity, y the cube map's last lod
    vec4 f_environment_sh[9];   // rgb: irradiance / pi, 9 SH terms (environment.h)
#endif
};
