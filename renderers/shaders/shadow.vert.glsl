// The shadows pass (renderers/frame/shadow.c): a scene mesh into one layer of the shadow-map
// pool, depth only. u_model_view_proj takes the object to the light's clip space
// (scene_gpu_draw_object_depth). Only the position attribute is read, and with SKINNING
// a skinned mesh's joints and weights (skin.inc, as mesh.vert).
layout(location = 0) in vec3 a_position;
#ifdef SKINNING
#include "skin.inc"
layout(location = 6) in uvec4 a_joints;
layout(location = 7) in vec4 a_weights;
#endif

layout(location = 0) uniform mat4 u_model_view_proj;

void main()
{
#ifdef SKINNING
    vec3 position = (skin_matrix(a_joints, a_weights) * vec4(a_position, 1.0)).xyz;
#else
    vec3 position = a_position;
#endif
    gl_Position = u_model_view_proj * vec4(position, 1.0);
}
