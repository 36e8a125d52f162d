// The shadows pass (renderers/shadow.c): a scene mesh into one layer of the shadow-map
// pool, depth only. u_model_view_proj takes the object to the light's clip space
// (scene_gpu_draw_object_depth). Only the position attribute is read.
layout(location = 0) in vec3 a_position;

layout(location = 0) uniform mat4 u_model_view_proj;

void main()
{
    gl_Position = u_model_view_proj * vec4(a_position, 1.0);
}
