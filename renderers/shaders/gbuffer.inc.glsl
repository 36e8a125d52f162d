// The G-buffer's accessors (seed 001: the layout lives in one place): what the
// G-buffer pass stores (gbuffer_store, with GBUFFER_WRITE defined before the include)
// and what the passes that read it load (gbuffer_load). renderers/deferred/deferred.c builds the
// layout and passes it as defines, each naming where a field lives
// (the defines, what each names, and the attachments gbK: the comment above the
// encodings below)

// The layout's defines, each naming where a field lives:
//
//   GB_POSITION_XY, GB_POSITION_Z   view-space position, e.g. gb0.xy and gb0.z
//   GB_DEPTH                        linear view depth -z (position = view ray x depth)
//                                   neither: the position is unprojected from the depth
//                                   buffer (t_depth)
//   GB_NORMAL_XY, GB_NORMAL_Z       the normal; GB_NORMAL_ENC says how it is coded:
//                                   0 float xyz, 1 unorm xyz (n * 0.5 + 0.5),
//                                   2 spheremap in GB_NORMAL_XY alone (seed 004)
//   GB_DIFFUSE                      rgb; absent in deferred-lighting's G-buffer (its
//                                   material pass reads the albedo from the material)
//   GB_GLOSS, GB_SHININESS          absent: no material has specular (gloss 0);
//                                   GB_SHININESS_UNORM: stored as n / 255
//   GB_EMISSIVE                     rgb; or GB_EMISSIVE_INTENSITY: e, emissive = e * diffuse
//                                   (seed 000); neither: no material is emissive
//   GB_OCCLUSION                    SHADING_PBR: the ambient occlusion (surface.inc); absent:
//                                   no material has an occlusion map (1)
//   GB_F0                           SHADING_PBR, deferred-lighting: the material's F0 (rgb),
//                                   which its light pre-pass needs for the specular light
// Under SHADING_PBR, diffuse is the base colour, gloss the metallic factor and shininess
// the roughness (lighting.inc), stored as they are (no GB_SHININESS_UNORM scaling).
//
// gbK is attachment K: an output of the G-buffer pass, a texelFetch of the pixel's
// texel (t_gbK, unit 4 + K) in the passes that read it. Every attachment is cleared to
// zero before the G-buffer pass; a zero normal (which no encoding produces for a unit
// vector) marks a pixel that no surface covers.
#define GB_NORMAL_FLOAT 0
#define GB_NORMAL_UNORM 1
#define GB_NORMAL_SPHEREMAP 2

// Lambert azimuthal equal-area projection (seed 004): a unit view-space normal to two
// values in [0, 1]. Normals facing straight away from the eye (z = -1) are the rim of
// the disc, where the direction of n.xy is lost; +x is taken there.
vec2 gb_spheremap_encode(vec3 n)
{
    float f = sqrt(max(8.0 * n.z + 8.0, 0.0));
    if (f < 1e-6)
        return vec2(1.0, 0.5);
    return n.xy / f + 0.5;
}

vec3 gb_spheremap_decode(vec2 enc)
{
    vec2 fenc = enc * 4.0 - 2.0;
    float f = dot(fenc, fenc);
    float g = sqrt(max(1.0 - f / 4.0, 0.0));
    return vec3(fenc * g, 1.0 - f / 2.0);
}

#ifdef GBUFFER_WRITE

#include "bindings.h"
layout(location = 0) out vec4 gb0;
layout(location = 1) out vec4 gb1;
layout(location = 2) out vec4 gb2;
layout(location = 3) out vec4 gb3;
layout(location = 4) out vec4 gb4;
layout(location = 5) out vec4 gb5;

void gbuffer_store(Surface s)
{
    // Outputs without an attachment are dropped; channels no slot uses stay zero.
    gb0 = vec4(0.0);
    gb1 = vec4(0.0);
    gb2 = vec4(0.0);
    gb3 = vec4(0.0);
    gb4 = vec4(0.0);
    gb5 = vec4(0.0);
#if defined(GB_POSITION_XY)
    GB_POSITION_XY = s.position.xy;
    GB_POSITION_Z = s.position.z;
#elif defined(GB_DEPTH)
    GB_DEPTH = -s.position.z;
#endif
#if GB_NORMAL_ENC == GB_NORMAL_SPHEREMAP
    GB_NORMAL_XY = gb_spheremap_encode(s.normal);
#elif GB_NORMAL_ENC == GB_NORMAL_UNORM
    GB_NORMAL_XY = s.normal.xy * 0.5 + 0.5;
    GB_NORMAL_Z = s.normal.z * 0.5 + 0.5;
#else
    GB_NORMAL_XY = s.normal.xy;
    GB_NORMAL_Z = s.normal.z;
#endif
#ifdef GB_DIFFUSE
    GB_DIFFUSE = s.diffuse;
#endif
#ifdef GB_GLOSS
    GB_GLOSS = s.gloss;
#endif
#ifdef GB_SHININESS
#ifdef GB_SHININESS_UNORM
    GB_SHININESS = s.shininess / 255.0;
#else
    GB_SHININESS = s.shininess;
#endif
#endif
#if defined(GB_EMISSIVE)
    GB_EMISSIVE = s.emissive;
#elif defined(GB_EMISSIVE_INTENSITY)
    GB_EMISSIVE_INTENSITY = max(s.emissive.r, max(s.emissive.g, s.emissive.b));
#endif
#ifdef GB_OCCLUSION
    GB_OCCLUSION = s.occlusion;
#endif
#ifdef GB_F0
    GB_F0 = mix(vec3(0.04), s.diffuse, s.gloss);   // lighting.inc's pbr_f0
#endif
}

#else // reading

// The pixel read: the fragment's own, or (a compute shader, tiled_deferred.comp) what
// GB_FRAG_XY is defined to be, the pixel's centre.
#ifndef GB_FRAG_XY
#define GB_FRAG_XY gl_FragCoord.xy
#endif

// MSAA (GB_MSAA): the attachments are multisampled (msaa.inc).
#include "msaa.inc"
layout(binding = BIND_TEX_GBUFFER0 + 0) uniform GB_SAMPLER t_gb0;
layout(binding = BIND_TEX_GBUFFER0 + 1) uniform GB_SAMPLER t_gb1;
layout(binding = BIND_TEX_GBUFFER0 + 2) uniform GB_SAMPLER t_gb2;
layout(binding = BIND_TEX_GBUFFER0 + 3) uniform GB_SAMPLER t_gb3;
layout(binding = BIND_TEX_GBUFFER0 + 4) uniform GB_SAMPLER t_gb4;
layout(binding = BIND_TEX_GBUFFER0 + 5) uniform GB_SAMPLER t_gb5;
layout(binding = BIND_TEX_DEPTH) uniform GB_SAMPLER t_depth;

#define gb0 texelFetch(t_gb0, ivec2(GB_FRAG_XY), GB_SAMPLE)
#define gb1 texelFetch(t_gb1, ivec2(GB_FRAG_XY), GB_SAMPLE)
#define gb2 texelFetch(t_gb2, ivec2(GB_FRAG_XY), GB_SAMPLE)
#define gb3 texelFetch(t_gb3, ivec2(GB_FRAG_XY), GB_SAMPLE)
#define gb4 texelFetch(t_gb4, ivec2(GB_FRAG_XY), GB_SAMPLE)
#define gb5 texelFetch(t_gb5, ivec2(GB_FRAG_XY), GB_SAMPLE)

struct GSurface {
    bool present;      // a surface covers the pixel
    vec3 position;     // view space
    vec3 normal;       // view space, unit
    vec3 diffuse;
    float gloss;
    float shininess;
    vec3 emissive;
    float occlusion;   // of the ambient light (GB_OCCLUSION), 1 otherwise
    vec3 f0;           // GB_F0 (deferred-lighting under SHADING_PBR), 0.04 otherwise
};

// The view ray through this pixel's centre, scaled to z = -1: the frustum-corner rays
// of seed 004 interpolated to the pixel, computed from the pixel directly so that
// full-screen passes and light volumes get the same ray.
vec3 gb_view_ray()
{
    vec2 ndc = GB_FRAG_XY * f_viewport.zw * 2.0 - 1.0;
    vec4 p = f_inv_proj * vec4(ndc, 1.0, 1.0);
    return p.xyz / -p.z;
}

GSurface gbuffer_load()
{
    GSurface g;
#if GB_NORMAL_ENC == GB_NORMAL_SPHEREMAP
    vec2 enc = GB_NORMAL_XY;
    vec2 fenc = enc * 4.0 - 2.0;
    // A unit normal codes inside the disc |fenc| <= 2; the cleared (0, 0) is far outside.
    g.present = dot(fenc, fenc) < 6.0;
    vec3 n = gb_spheremap_decode(enc);
#elif GB_NORMAL_ENC == GB_NORMAL_UNORM
    vec3 n = vec3(GB_NORMAL_XY, GB_NORMAL_Z) * 2.0 - 1.0;
    g.present = abs(dot(n, n) - 1.0) < 0.5;
#else
    vec3 n = vec3(GB_NORMAL_XY, GB_NORMAL_Z);
    g.present = abs(dot(n, n) - 1.0) < 0.5;
#endif
    float len2 = dot(n, n);
    g.normal = len2 > 1e-20 ? n * inversesqrt(len2) : vec3(0.0, 0.0, 1.0);
#if defined(GB_POSITION_XY)
    g.position = vec3(GB_POSITION_XY, GB_POSITION_Z);
#elif defined(GB_DEPTH)
    g.position = gb_view_ray() * GB_DEPTH;
#else
    float d = texelFetch(t_depth, ivec2(GB_FRAG_XY), GB_SAMPLE).r;
    vec2 ndc = GB_FRAG_XY * f_viewport.zw * 2.0 - 1.0;
    vec4 p = f_inv_proj * vec4(ndc, d * 2.0 - 1.0, 1.0);
    g.position = p.xyz / p.w;
#endif
#ifdef GB_DIFFUSE
    g.diffuse = GB_DIFFUSE;
#else
    g.diffuse = vec3(0.0);   // deferred-lighting's G-buffer holds no albedo
#endif
#ifdef GB_GLOSS
    g.gloss = GB_GLOSS;
#else
    g.gloss = 0.0;
#endif
#ifdef GB_SHININESS
#ifdef GB_SHININESS_UNORM
    g.shininess = GB_SHININESS * 255.0;
#else
    g.shininess = GB_SHININESS;
#endif
#else
    g.shininess = 1.0;
#endif
#if defined(GB_EMISSIVE)
    g.emissive = GB_EMISSIVE;
#elif defined(GB_EMISSIVE_INTENSITY)
    g.emissive = GB_EMISSIVE_INTENSITY * g.diffuse;
#else
    g.emissive = vec3(0.0);
#endif
#ifdef GB_OCCLUSION
    g.occlusion = GB_OCCLUSION;
#else
    g.occlusion = 1.0;
#endif
#ifdef GB_F0
    g.f0 = GB_F0;
#else
    g.f0 = vec3(0.04);
#endif
    if (!g.present) {
        // Nothing to light: values that keep every light's arithmetic finite.
        g.position = vec3(0.0, 0.0, -1.0);
        g.normal = vec3(0.0, 0.0, 1.0);
        g.diffuse = vec3(0.0);
        g.gloss = 0.0;
        g.shininess = 1.0;
        g.emissive = vec3(0.0);
    }
    return g;
}

#endif
