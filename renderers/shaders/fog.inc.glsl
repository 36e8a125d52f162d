// Fog from depth (seed 000 4.5.12; the manifest's fog.*): a surface at view depth z
// (view-space -z, the distance along the view axis) keeps f = exp(-density z) of its
// light and takes 1 - f of the fog colour:
//
//     fogged = f x light + (1 - f) x colour
//
// Seed 000 reads the G-buffer's per-pixel depth into "a modified linear fog equation"
// without giving it; this is the exponential form (OpenGL's GL_EXP fog), one
// parameter, never negative, 1 at the eye. Only programs compiled with FOG see any of
// this; renderer_base_fog_uniform sets u_fog once per program.
//   forward, one pass (forward-spml, forward-plus, clustered): fog_apply on the sum;
//   forward-mpml: the base pass fog_apply, each additive light pass x fog_factor, so
//     the sum is f x (ambient + emissive + lights) + (1 - f) x colour;
//   deferred: deferred_fog.frag after the lights, from the depth buffer.
#ifdef FOG
#include "bindings.h"
layout(location = LOC_FOG) uniform vec4 u_fog;   // rgb: colour, w: density

// view_z: the view-space z of the surface (negative in front of the eye)
float fog_factor(float view_z)
{
    return exp(-u_fog.w * max(-view_z, 0.0));
}

vec3 fog_apply(vec3 light, float view_z)
{
    float f = fog_factor(view_z);
    return light * f + u_fog.rgb * (1.0 - f);
}
#endif

// What a one-pass forward shader (forward-spml, forward-plus, clustered) writes for the
// light c of a surface at view depth view_z: fogged with FOG, and premultiplied by the
// surface's alpha in the translucent pass (TRANSLUCENT); opaque otherwise.
vec4 forward_output(vec3 c, float view_z, float alpha)
{
#ifdef FOG
    c = fog_apply(c, view_z);
#endif
#ifdef TRANSLUCENT
    return vec4(c * alpha, alpha);
#else
    return vec4(c, 1.0);
#endif
}
