// The vertex shader of every pass that draws scene meshes (forward passes, the
// G-buffer pass, shadow maps later): view-space position, normal, tangent, uv.
// SKINNING: a skinned mesh's position, normal and tangent blended by its joints first
// (skin.inc), in every pass that draws it.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_tangent;
layout(location = 3) in vec2 a_uv;
#ifdef VERTEX_COLOR
// a mesh's vertex colours (scene_gpu.h), white for a mesh without; only in a scene that
// has some (renderer_base_scene's common define)
layout(location = 4) in vec4 a_color;
layout(location = 4) out vec4 v_color;
#endif
#ifdef UV2
// a mesh's second uv set (scene_gpu.h), (0, 0) for a mesh without; only in a scene whose
// materials read a map from it (a common define)
layout(location = 5) in vec2 a_uv2;
layout(location = 5) out vec2 v_uv2;
#endif

#ifdef SKINNING
#include "skin.inc"
// a skinned mesh's joints and weights (scene_gpu.h); weights 0 for a mesh without
layout(location = 6) in uvec4 a_joints;
layout(location = 7) in vec4 a_weights;
#endif

layout(location = 0) uniform mat4 u_model_view;
layout(location = 1) uniform mat4 u_proj;
layout(location = 2) uniform mat3 u_normal_matrix;   // locations 2, 3, 4

// forward-mpml's light passes test depth EQUAL against the base pass: every pass
// must compute bit-identical positions (llvmpipe does anyway; GPUs need this).
invariant gl_Position;

layout(location = 0) out vec3 v_position;   // view space
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec4 v_tangent;
layout(location = 3) out vec2 v_uv;

void main()
{
#ifdef SKINNING
    mat4 skin = skin_matrix(a_joints, a_weights);
    vec3 position = (skin * vec4(a_position, 1.0)).xyz;
    vec3 normal = mat3(skin) * a_normal;
    vec3 tangent = mat3(skin) * a_tangent.xyz;
#else
    vec3 position = a_position, normal = a_normal, tangent = a_tangent.xyz;
#endif
    vec4 p = u_model_view * vec4(position, 1.0);
    v_position = p.xyz;
    v_normal = u_normal_matrix * normal;
    v_tangent = vec4(mat3(u_model_view) * tangent, a_tangent.w);
    v_uv = a_uv;
#ifdef VERTEX_COLOR
    v_color = a_color;
#endif
#ifdef UV2
    v_uv2 = a_uv2;
#endif
    gl_Position = u_proj * p;
}
