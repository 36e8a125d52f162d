// The vertex shader of deferred light volumes (scene_gpu_draw_light_volume): a
// light's volume mesh (frontend.h "Light volumes"), position only, placed by
// u_model_view = view x the volume's model matrix. Nothing is passed on: light
// passes find their pixel's surface from gl_FragCoord (G-buffer texels, and the
// view ray through f_inv_proj of frame.inc).
layout(location = 0) in vec3 a_position;

layout(location = 0) uniform mat4 u_model_view;
layout(location = 1) uniform mat4 u_proj;

void main()
{
    gl_Position = u_proj * (u_model_view * vec4(a_position, 1.0));
}
