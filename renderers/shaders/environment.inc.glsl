// The ambient term of every renderer: what lights a surface besides the scene's lights,
// evaluated once a shaded sample wherever a renderer starts a pixel's light (its ambient
// pass, base pass or shading loop), so that every renderer does the same work for it.
//   ambient_light(P, N, diffuse, gloss, shininess, occlusion)
// takes Surface's fields (view space; under SHADING_PBR diffuse, gloss and shininess are
// the base colour, metallic and roughness).
// (Without ENVIRONMENT and with it, by Karis's split sum: the comment above
// ambient_light below.)
#include "frame.inc"

#ifdef ENVIRONMENT
#include "bindings.h"
layout(binding = BIND_TEX_ENVIRONMENT) uniform samplerCube t_environment;

// lighting.inc's floor on the roughness (at 0 the lobe is a delta)
const float ENV_MIN_ROUGHNESS = 0.045;

// E(n) / pi times the intensity, n unit in world space
vec3 env_irradiance(vec3 n)
{
    vec3 e = f_environment_sh[0].rgb + f_environment_sh[1].rgb * n.y +
             f_environment_sh[2].rgb * n.z + f_environment_sh[3].rgb * n.x +
             f_environment_sh[4].rgb * (n.x * n.y) + f_environment_sh[5].rgb * (n.y * n.z) +
             f_environment_sh[6].rgb * (3.0 * n.z * n.z - 1.0) +
             f_environment_sh[7].rgb * (n.x * n.z) +
             f_environment_sh[8].rgb * (n.x * n.x - n.y * n.y);
    return max(e, vec3(0.0));
}

// The sky in world direction r convolved with the GGX lobe of `roughness`, times the
// intensity
vec3 env_prefiltered(vec3 r, float roughness)
{
    return textureLod(t_environment, r, roughness * f_environment.y).rgb * f_environment.x;
}

// Karis 2014's fit: the split sum's second factor is F0 x A + B
vec2 env_brdf(float roughness, float ndv)
{
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * ndv)) * r.x + r.y;
    return vec2(-1.04, 1.04) * a004 + r.zw;
}
#endif

// Without ENVIRONMENT: the scene's constant ambient light, A = ambient x diffuse x
// occlusion (seed 000 appendix D), exactly as it always was.
//
// ENVIRONMENT (a common define: environment.light sky, renderers/frame/environment.h): the
// procedural sky in place of the ambient light, by Karis's split sum (2013), as the glTF
// Sample Viewer lights a model by its environment map:
//   SHADING_PBR  (irradiance(N) c_diff + prefiltered(R, roughness) (F0 A + B)) x occlusion
//                c_diff = base (1 - metallic), F0 = mix(0.04, base, metallic)
//   Phong        (irradiance(N) diffuse + gloss prefiltered(R, r)) x occlusion,
//                r = sqrt(alpha), alpha = sqrt(2 / (n + 2)): the GGX roughness whose lobe
//                matches the exponent n (the mapping of built-in materials under pbr,
//                scenes/scene_build.c); gloss reflects the environment as the specular
//                intensity does a light, with no Fresnel (Phong has none)
// irradiance: E(N) / pi from the Frame block's 9 SH terms; prefiltered: the cube map's
// mip roughness x (levels - 1), each mip the sky convolved with the GGX lobe of its
// roughness; A, B: Karis's analytic fit of the environment BRDF ("Physically Based
// Shading on Mobile", 2014), an expression rather than a LUT: no texture read, no
// texture unit in the compute shaders, the same few operations everywhere. N and R are
// turned to world space (the sky's, y up) by f_view_to_world.
vec3 ambient_light(vec3 P, vec3 N, vec3 diffuse, float gloss, float shininess,
                   float occlusion)
{
#ifndef ENVIRONMENT
    return f_ambient.rgb * diffuse * occlusion;
#else
    mat3 to_world = mat3(f_view_to_world);
    vec3 V = normalize(-P);
    vec3 Nw = normalize(to_world * N);
    vec3 Rw = normalize(to_world * reflect(-V, N));
#ifdef SHADING_PBR
    float roughness = clamp(shininess, ENV_MIN_ROUGHNESS, 1.0);
    vec2 ab = env_brdf(roughness, clamp(abs(dot(N, V)), 0.0, 1.0));
    vec3 f0 = mix(vec3(0.04), diffuse, gloss);   // lighting.inc's pbr_f0
    return (env_irradiance(Nw) * diffuse * (1.0 - gloss) +
            env_prefiltered(Rw, roughness) * (f0 * ab.x + ab.y)) * occlusion;
#else
    float roughness = sqrt(sqrt(2.0 / (max(shininess, 0.0) + 2.0)));
    return (env_irradiance(Nw) * diffuse + gloss * env_prefiltered(Rw, roughness)) *
           occlusion;
#endif
#endif
}
