// The vertex shader of every pass that draws scene meshes (forward passes, the
// G-buffer pass, shadow maps later): view-space position, normal, tangent, uv.
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
    vec4 p = u_model_view * vec4(a_position, 1.0);
    v_position = p.xyz;
    v_normal = u_normal_matrix * a_normal;
    v_tangent = vec4(mat3(u_model_view) * a_tangent.xyz, a_tangent.w);
    v_uv = a_uv;
#ifdef VERTEX_COLOR
    v_color = a_color;
#endif
#ifdef UV2
    v_uv2 = a_uv2;
#endif
    gl_Position = u_proj * p;
}
