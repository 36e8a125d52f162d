// deferred-lighting's material pass (the light pre-pass's second geometry pass, Engel
// 2008): each visible opaque object drawn again (mesh.vert, depth EQUAL against the
// G-buffer pass's depth, no writes) with its material, reading the light buffer at its
// own pixel:
//   colour = ambient x diffuse + emissive + diffuse x L_diffuse + gloss x L_specular
// where L_diffuse = sum of incoming x max(N.L, 0) and L_specular = sum of incoming x
// spec over the lights (deferred_light.frag with LIGHT_PREPASS), which is lighting.inc's
// sum of shade_light factored. Defines: the material's maps (surface.inc); msaa > 1:
// GB_MSAA and GB_SAMPLE gl_SampleID (msaa.inc), the light buffer multisampled and read
// at the fragment's own sample, which makes the pass run per sample.
#include "bindings.h"
#include "frame.inc"
#include "surface.inc"
#include "lighting.inc"
#include "environment.inc"

#include "msaa.inc"
layout(binding = BIND_TEX_LIGHT_DIFFUSE) uniform GB_SAMPLER t_light_diffuse;
layout(binding = BIND_TEX_LIGHT_SPECULAR) uniform GB_SAMPLER t_light_specular;

layout(location = 0) out vec4 o_color;

void main()
{
    Surface s = surface_get();
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 ld = texelFetch(t_light_diffuse, px, GB_SAMPLE).rgb;
    vec3 ls = texelFetch(t_light_specular, px, GB_SAMPLE).rgb;
    // A light buffer that overflowed (RGBA16F beyond 65504) holds Inf: a material channel
    // of 0 takes none of it (0 x Inf would be NaN), as forward's 0 x light is 0.
#ifdef SHADING_PBR
    // lighting.inc's pbr_light summed: the diffuse part without the material's
    // c_diff (1 - F0), the specular part whole (its F0 came from the G-buffer)
    vec3 kd = pbr_diffuse(s.diffuse, s.gloss);
    vec3 c = ambient_light(s.position, s.normal, s.diffuse, s.gloss, s.shininess,
                           s.occlusion) + s.emissive +
             mix(kd * ld, vec3(0.0), equal(kd, vec3(0.0))) + ls;
#else
    vec3 c = ambient_light(s.position, s.normal, s.diffuse, s.gloss, s.shininess,
                           s.occlusion) + s.emissive +
             mix(s.diffuse * ld, vec3(0.0), equal(s.diffuse, vec3(0.0))) +
             (s.gloss > 0.0 ? s.gloss * ls : vec3(0.0));
#endif
    o_color = vec4(c, 1.0);
}
