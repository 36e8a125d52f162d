// The surface a fragment of a scene mesh shows, from the material and its maps:
// shared by the forward passes and the G-buffer pass, so both see the same inputs.
// Defines: DIFFUSE_MAP, GLOSS_MAP, NORMAL_MAP, EMISSIVE_MAP (only the maps the
// material has are sampled: renderers compile only the variants a scene uses), and
// ALPHA_TEST (a MASK material of a file scene: fragments whose diffuse-map alpha is
// below u_alpha_cutoff are discarded; only that variant has a discard, so opaque
// materials keep early depth testing); TRANSLUCENT (a MATERIAL_BLEND material, drawn in
// the translucent pass): Surface.alpha = u_opacity x the diffuse map's alpha (1 otherwise).
// VERTEX_COLOR (a common define: the scene has coloured meshes): the vertex colour
// multiplies the diffuse colour, and its alpha the alpha test's and the coverage, as
// glTF's COLOR_0 multiplies the base colour.
#include "bindings.h"
layout(location = 0) in vec3 v_position;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec4 v_tangent;
layout(location = 3) in vec2 v_uv;
#ifdef VERTEX_COLOR
layout(location = 4) in vec4 v_color;
#endif
// UV2 (a common define: some material reads a map from the second uv set): the maps of
// u_uv1_maps (bit 0 diffuse, 1 gloss, 2 normal, 3 emissive) read v_uv2, the rest v_uv.
#ifdef UV2
layout(location = 5) in vec2 v_uv2;
layout(location = LOC_UV1_MAPS) uniform int u_uv1_maps;
vec2 map_uv(int bit)
{
    return (u_uv1_maps & bit) != 0 ? v_uv2 : v_uv;
}
#else
#define map_uv(bit) v_uv
#endif

// SHADING_PBR (a common define, lighting.inc): u_diffuse is the base colour, u_specular
// the metallic factor, u_shininess the roughness factor, and the gloss map glTF's packed
// ORM map (R occlusion, G roughness, B metallic; scenes/scene.h), whose occlusion counts
// by u_occlusion (the occlusion map's strength): 1 + strength (R - 1), which multiplies
// the ambient light only.
layout(location = 8) uniform vec3 u_diffuse;
layout(location = 9) uniform float u_specular;
layout(location = 10) uniform float u_shininess;
layout(location = 11) uniform vec3 u_emissive;
#ifdef ALPHA_TEST
layout(location = LOC_ALPHA_CUTOFF) uniform float u_alpha_cutoff;
#endif
#if defined(SHADING_PBR) && defined(GLOSS_MAP)
layout(location = LOC_OCCLUSION) uniform float u_occlusion;
#endif
#ifdef TRANSLUCENT
layout(location = LOC_OPACITY) uniform float u_opacity;
#endif

layout(binding = BIND_TEX_DIFFUSE) uniform sampler2D t_diffuse;
layout(binding = BIND_TEX_GLOSS) uniform sampler2D t_gloss;
layout(binding = BIND_TEX_NORMAL) uniform sampler2D t_normal;
layout(binding = BIND_TEX_EMISSIVE) uniform sampler2D t_emissive;

struct Surface {
    vec3 position;   // view space
    vec3 normal;     // view space, unit
    vec3 diffuse;
    float gloss;     // specular intensity x gloss map
    float shininess;
    vec3 emissive;
    float alpha;     // coverage (TRANSLUCENT), 1 otherwise
    float occlusion; // of the ambient light: the ORM map's (SHADING_PBR), 1 otherwise
};

// A unit vector from n, or `fallback` where n has no length (degenerate normals
// and tangents in meshes must not become NaN).
vec3 safe_normalize(vec3 n, vec3 fallback)
{
    float len2 = dot(n, n);
    return len2 > 1e-20 ? n * inversesqrt(len2) : fallback;
}

Surface surface_get()
{
    Surface s;
#ifdef ALPHA_TEST
    float alpha = 1.0;
#ifdef DIFFUSE_MAP
    alpha = texture(t_diffuse, map_uv(1)).a;
#endif
#ifdef VERTEX_COLOR
    alpha *= v_color.a;
#endif
    if (alpha < u_alpha_cutoff)
        discard;
#endif
    s.position = v_position;
    vec3 n = safe_normalize(v_normal, safe_normalize(-v_position, vec3(0.0, 0.0, 1.0)));
    if (!gl_FrontFacing)
        n = -n;   // two-sided: shells are seen from inside
#ifdef NORMAL_MAP
    vec3 t = v_tangent.xyz - n * dot(n, v_tangent.xyz);
    float tl2 = dot(t, t);
    if (tl2 > 1e-20) {
        t *= inversesqrt(tl2);
        vec3 b = cross(n, t) * v_tangent.w;
        vec3 m = texture(t_normal, map_uv(4)).xyz * 2.0 - 1.0;
        n = safe_normalize(t * m.x + b * m.y + n * m.z, n);
    }
#endif
    s.normal = n;
    s.diffuse = u_diffuse;
#ifdef DIFFUSE_MAP
    s.diffuse *= texture(t_diffuse, map_uv(1)).rgb;
#endif
#ifdef VERTEX_COLOR
    s.diffuse *= v_color.rgb;
#endif
    s.gloss = u_specular;
    s.shininess = u_shininess;
    s.occlusion = 1.0;
#if defined(GLOSS_MAP) && defined(SHADING_PBR)
    vec3 orm = texture(t_gloss, map_uv(2)).rgb;
    s.occlusion = 1.0 + u_occlusion * (orm.r - 1.0);
    s.shininess *= orm.g;
    s.gloss *= orm.b;
#elif defined(GLOSS_MAP)
    s.gloss *= texture(t_gloss, map_uv(2)).r;
#endif
    s.emissive = u_emissive;
#ifdef EMISSIVE_MAP
    vec4 e = texture(t_emissive, map_uv(8));   // rgb: colour, a: mask
    s.emissive *= e.rgb * e.a;
#endif
    s.alpha = 1.0;
#ifdef TRANSLUCENT
    s.alpha = clamp(u_opacity, 0.0, 1.0);
#ifdef DIFFUSE_MAP
    s.alpha *= texture(t_diffuse, map_uv(1)).a;
#endif
#ifdef VERTEX_COLOR
    s.alpha *= v_color.a;
#endif
#endif
    return s;
}
