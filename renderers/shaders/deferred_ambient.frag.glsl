// Ambient and emissive (seed 000 4.5.5): one full-screen pass (fullscreen.vert) that
// starts the light accumulation: ambient x diffuse + emissive, written (not blended)
// over every pixel, alpha 1. Pixels that no surface covers get black, as a forward
// renderer's cleared target has them. With SEPARATE_SPECULAR the specular target is
// started at zero by the same pass.
#include "frame.inc"
#include "gbuffer.inc"
#include "environment.inc"

#include "light_out.inc"

void main()
{
    GSurface g = gbuffer_load();
    vec3 a = ambient_light(g.position, g.normal, g.diffuse, g.gloss, g.shininess, g.occlusion);
#ifdef ENVIRONMENT
    a = g.present ? a : vec3(0.0);   // the environment's specular needs no diffuse colour
#endif
    o_light = vec4(a + g.emissive, 1.0);
#ifdef SEPARATE_SPECULAR
    o_specular = vec4(0.0);
#endif
}
