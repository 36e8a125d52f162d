// The sky (scene_gpu_draw_sky), drawn with fullscreen.vert after the scene: a
// vertical gradient of the scene's sky colour along each pixel's view ray, from the
// colour itself at and below the horizon to SKY_ZENITH x the colour straight up
// (view space: "up" is the camera's +Y). fullscreen.vert puts it at z = w (depth 1,
// the far plane; compiled with FULLSCREEN_FAR), so that with the depth test LEQUAL
// against a depth buffer cleared to 1 it lands only where no geometry is.
// ENVIRONMENT (environment.light sky): the environment itself instead, in the pixel's
// world direction, from the prefiltered cube map's sharpest mip (roughness 0), as the
// glTF Sample Viewer shows its environment behind a model.
#include "frame.inc"
#include "environment.inc"

const float SKY_ZENITH = 0.6;

layout(location = 0) out vec4 o_color;

void main()
{
    // The pixel centre on the near plane (z_ndc = -1: finite for an infinite far plane).
    vec2 ndc = gl_FragCoord.xy * f_viewport.zw * 2.0 - 1.0;
    vec4 p = f_inv_proj * vec4(ndc, -1.0, 1.0);
    vec3 dir = normalize(p.xyz / p.w);
#ifdef ENVIRONMENT
    o_color = vec4(env_prefiltered(normalize(mat3(f_view_to_world) * dir), 0.0), 1.0);
#else
    float up = clamp(dir.y, 0.0, 1.0);
    o_color = vec4(f_sky.rgb * mix(1.0, SKY_ZENITH, up), 1.0);
#endif
}
