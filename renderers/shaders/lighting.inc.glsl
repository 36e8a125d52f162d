// Phong lighting as seed 000 appendix D gives it, shared by every renderer so that
// their images differ only by what a G-buffer loses:
//   I = A + att * spot * (D + g * S)
//   D = light * diffuse * max(N.L, 0)
//   S = light * max(R.V, 0)^n           (g: specular intensity x gloss map)
//   att: 1/d^2 | max(0, 1 - d/range) | 1/(a d^2 + b d + c)
//        | clamp(1 - (d/range)^4, 0, 1)^2 / d^2 (windowed: Karis 2013), and 0 beyond range
//   spot = (-L.A)^f inside the cone (-L.A > cos c), else 0
// Everything is in view space: the eye is at the origin.
// (A light's 5 vec4s and SHADOWS: the comment above struct Light below.)

#include "shadow.inc"

#define LIGHT_POINT 0
#define LIGHT_SPOT 1
#define LIGHT_DIRECTIONAL 2

// The light features the program is compiled for: LIGHT_TYPES, bit t for type t (1 point,
// 2 spot, 4 directional), and LIGHT_ATTENUATIONS, bit k for attenuation k (1
// inverse-square, 2 linear-range, 4 quadratic, 8 windowed). Every program gets the scene's (the
// program cache's common defines, renderers/frame/base.c); the code of the others is left
// out, so that a light costs only what its kind needs: on llvmpipe both sides of a
// branch run, masked, for every light a loop visits, and the fields they read are
// loaded. A light of a kind left out is never in the frame. Without them: everything.
#ifndef LIGHT_TYPES
#define LIGHT_TYPES 7
#endif
#ifndef LIGHT_ATTENUATIONS
#define LIGHT_ATTENUATIONS 15
#endif
#define HAS_SPOT ((LIGHT_TYPES & 2) != 0)
#define HAS_DIRECTIONAL ((LIGHT_TYPES & 4) != 0)

// 1/d^2 at d = 0 (a light on the surface) is infinite: d^2 is clamped here, so the
// light is as bright as at 1 cm and never Inf.
const float ATTENUATION_MIN_D2 = 1e-4;

// Inverse-square falloff windowed to zero at the range (Karis, "Real Shading in Unreal
// Engine 4", 2013): clamp(1 - (d/r)^4, 0, 1)^2 / d^2, d^2 clamped as 1/d^2's is. The
// window is 1 near the light and reaches 0 with zero slope at d = r, so the range that
// culls a light is also where its light ends: no edge at the volume's boundary.
float attenuation_windowed(float d2, float range)
{
    float q = d2 / max(range * range, 1e-30);
    float w = clamp(1.0 - q * q, 0.0, 1.0);
    return w * w / max(d2, ATTENUATION_MIN_D2);
}

// A light is 5 vec4s (the layout of forward-spml's buffer and of the per-light
// uniform u_light[5] of the other passes; renderers/frame/shading.h fills it):
//   [0] xyz position, w range           [1] rgb colour, w type (0 point, 1 spot, 2 dir.)
//   [2] xyz direction (unit, the way the light travels), w cos(spot angle)
//   [3] x spot exponent, y attenuation (0 inverse-square, 1 linear-range, 2 quadratic,
//       3 windowed),
//       z shadow-map layer + 1 (0: none; read only with SHADOWS, shadow.inc)
//   [4] xyz quadratic a, b, c
//   and with STOCHASTIC (lights.culling: stochastic) [3].w the light's culling range this
//   frame and [4].w its q (light_cull_range and stochastic_weight below)
//
// With SHADOWS defined, the light arriving at a point is also multiplied by its
// shadow-map lookup (shadow.inc): I = A + att * spot * shadow * (D + g * S).
struct Light {
    vec4 position_range;
    vec4 color_type;
    vec4 direction_cos;
    vec4 params;
    vec4 quadratic;
};

// Stochastic light culling (STOCHASTIC, a common define of the designs that cull so:
// lights.culling: stochastic; Tokuyoshi and Harada, "Stochastic Light Culling", JCGT
// 5(1), 2016; renderers/frame/stochastic.h fills the fields each frame). A point or spot
// light j is culled, and dropped here, beyond params.w, where I_j a(d) falls to
// culling_error x xi_j (never beyond its range); a light kept at distance d, its
// attenuation there att, is weighted by 1 / P(d), P(d) = min(1, att / q) with
// q = quadratic.w = culling_error / I_j: kept with probability P(d), so the expected image
// is the exact one. Within the culling range att >= xi_j q, so the weight is at most
// 1 / xi_j <= 2^24 (the clamp is against rounding alone): never a division by 0, never
// Inf. q = 0 (a directional light, a black one): weight 1. Without STOCHASTIC the range
// is the light's and nothing is weighted: the programs of exact culling are unchanged.
float light_cull_range(Light l)
{
#ifdef STOCHASTIC
    return l.params.w;
#else
    return l.position_range.w;
#endif
}

float stochastic_weight(Light l, float att)
{
    float q = l.quadratic.w;
    return q > 0.0 ? clamp(q / max(att, 1e-30), 1.0, 16777216.0) : 1.0;
}

// Whether light l can reach view-space point P: a point or spot light within its range
// (the squared-range rejection every light loop makes before shade_light, which would
// give exactly zero beyond it; its culling range with STOCHASTIC), or a directional
// light. Reads only its position, range and (with directional lights in the scene) type.
bool light_in_range(Light l, vec3 P)
{
    vec3 d = l.position_range.xyz - P;
    float r = light_cull_range(l);
#if HAS_DIRECTIONAL
    return !(dot(d, d) > r * r) || int(l.color_type.w) == LIGHT_DIRECTIONAL;
#else
    return !(dot(d, d) > r * r);
#endif
}

// Light arriving at view-space point P (attenuation and spot cone applied), and the
// unit vector L towards it; zero beyond the light's range or outside its cone.
vec3 light_incoming(Light l, vec3 P, vec3 N, out vec3 L)
{
#if HAS_SPOT || HAS_DIRECTIONAL
    int type = int(l.color_type.w);
#endif
#if HAS_DIRECTIONAL
    if (type == LIGHT_DIRECTIONAL) {
        L = -l.direction_cos.xyz;
        return l.color_type.rgb;
    }
#endif
    vec3 d = l.position_range.xyz - P;
    float d2 = dot(d, d);
    float range = l.position_range.w, cut = light_cull_range(l);
    if (d2 > cut * cut) {
        L = N;
        return vec3(0.0);
    }
    float dist = sqrt(d2);
    // A light exactly on the surface lights it head-on rather than from nowhere.
    L = dist > 0.0 ? d / dist : N;
    float att;
#if LIGHT_ATTENUATIONS == 1
    att = 1.0 / max(d2, ATTENUATION_MIN_D2);
#elif LIGHT_ATTENUATIONS == 2
    att = max(0.0, 1.0 - dist / range);
#elif LIGHT_ATTENUATIONS == 4
    att = 1.0 / max(l.quadratic.x * d2 + l.quadratic.y * dist + l.quadratic.z, 1e-6);
#elif LIGHT_ATTENUATIONS == 8
    att = attenuation_windowed(d2, range);
#else
    int kind = int(l.params.y);
    if (kind == 0)
        att = 1.0 / max(d2, ATTENUATION_MIN_D2);
    else if (kind == 1)
        att = max(0.0, 1.0 - dist / range);
    else if (kind == 2)
        att = 1.0 / max(l.quadratic.x * d2 + l.quadratic.y * dist + l.quadratic.z, 1e-6);
    else
        att = attenuation_windowed(d2, range);
#endif
#ifdef STOCHASTIC
    att *= stochastic_weight(l, att);   // 1 / P(d), of the distance's attenuation alone
#endif
#if HAS_SPOT
    if (type == LIGHT_SPOT) {
        float c = dot(-L, l.direction_cos.xyz);
        att *= c > l.direction_cos.w ? pow(c, l.params.x) : 0.0;
    }
#endif
    return l.color_type.rgb * att;
}

// light_incoming, times the light's shadow-map lookup with SHADOWS: what both shading
// models light a point with.
vec3 light_arriving(Light l, vec3 P, vec3 N, out vec3 L)
{
    vec3 incoming = light_incoming(l, P, N, L);
#ifdef SHADOWS
    // Only where the light arrives at all: no lookup outside its range or cone.
    if (l.params.z > 0.5 && any(greaterThan(incoming, vec3(0.0))))
        incoming *= shadow_visibility(int(l.params.z + 0.5) - 1, P);
#endif
    return incoming;
}

#ifdef SHADING_PBR
// SHADING_PBR (a common define: shading.model pbr): glTF 2.0's metallic-roughness model,
// the specification's Appendix B, for light `incoming` arriving from L:
//   f = (1 - F) c_diff / pi + F D Vis      c_diff = base (1 - metallic)
//   F = F0 + (1 - F0) (1 - V.H)^5          F0 = mix(0.04, base, metallic)
//   D = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2),   a = roughness^2
//   Vis = 1 / ((N.L + sqrt(a^2 + (1 - a^2) (N.L)^2)) (|N.V| + sqrt(a^2 + (1 - a^2) (N.V)^2)))
// and the light's contribution is incoming x f x N.L, 0 where N.L <= 0. shade_light's
// (diffuse, gloss, shininess) are then (base colour, metallic, roughness): the Surface's
// and G-buffer's fields keep their names and carry these (scenes/scene.h).
// The roughness is clamped below at PBR_MIN_ROUGHNESS (Filament's floor for 32-bit
// floats): at 0, D is a delta (0/0 at N.H = 1).
const float PBR_PI = 3.14159265358979;
const float PBR_MIN_ROUGHNESS = 0.045;

vec3 pbr_f0(vec3 base, float metallic)
{
    return mix(vec3(0.04), base, metallic);
}

// What multiplies pbr_light's kd: c_diff (1 - F0).
vec3 pbr_diffuse(vec3 base, float metallic)
{
    return base * (1.0 - metallic) * (1.0 - pbr_f0(base, metallic));
}

// The light's contribution in two parts, the material's F0 factored out of the diffuse
// one, which is what deferred-lighting's light buffer sums without the material:
//   kd = incoming N.L (1 - s) / pi,  s = (1 - V.H)^5   (so that (1 - F) = (1 - F0)(1 - s))
//   spec = incoming N.L D Vis F
// shade_light = pbr_diffuse(base, metallic) x kd + spec.
void pbr_light(Light l, vec3 P, vec3 N, float roughness, vec3 f0, out vec3 kd, out vec3 spec)
{
    vec3 L;
    vec3 incoming = light_arriving(l, P, N, L);
    kd = spec = vec3(0.0);
    float ndl = dot(N, L);
    if (!(ndl > 0.0))
        return;
    vec3 V = normalize(-P);
    vec3 h = L + V;   // zero only for a light straight behind the surface's viewer
    vec3 H = dot(h, h) > 1e-12 ? normalize(h) : N;
    float vdh = clamp(dot(V, H), 0.0, 1.0);
    float ndh = clamp(dot(N, H), 0.0, 1.0);
    float ndv = abs(dot(N, V));
    float a = max(roughness, PBR_MIN_ROUGHNESS);
    float a2 = (a * a) * (a * a);
    float m = 1.0 - vdh;
    float s = (m * m) * (m * m) * m;
    float f = ndh * ndh * (a2 - 1.0) + 1.0;
    float d = a2 / (PBR_PI * f * f);
    float vis = 1.0 / ((ndl + sqrt(a2 + (1.0 - a2) * ndl * ndl)) *
                       (ndv + sqrt(a2 + (1.0 - a2) * ndv * ndv)));
    vec3 li = incoming * ndl;
    kd = li * ((1.0 - s) / PBR_PI);
    spec = li * (d * vis) * (f0 + (1.0 - f0) * s);
}

vec3 shade_light(Light l, vec3 P, vec3 N, vec3 base, float metallic, float roughness)
{
    vec3 kd, spec;
    pbr_light(l, P, N, roughness, pbr_f0(base, metallic), kd, spec);
    return pbr_diffuse(base, metallic) * kd + spec;
}

// shade_light's diffuse and specular parts apart (deferred.separate_specular).
void shade_light_split(Light l, vec3 P, vec3 N, vec3 base, float metallic, float roughness,
                       out vec3 d, out vec3 s)
{
    pbr_light(l, P, N, roughness, pbr_f0(base, metallic), d, s);
    d *= pbr_diffuse(base, metallic);
}

// deferred-lighting's light buffer (LIGHT_PREPASS): the light without the material, kd
// and spec of pbr_light; its material pass adds pbr_diffuse x sum kd + sum spec.
void light_prepass(Light l, vec3 P, vec3 N, float roughness, vec3 f0, out vec3 d, out vec3 s)
{
    pbr_light(l, P, N, roughness, f0, d, s);
}

#else

// The light's contribution at a surface point: att * spot * (D + g * S).
vec3 shade_light(Light l, vec3 P, vec3 N, vec3 diffuse, float gloss, float shininess)
{
    vec3 L;
    vec3 incoming = light_arriving(l, P, N, L);
    float ndl = max(dot(N, L), 0.0);
    vec3 V = normalize(-P);
    vec3 R = reflect(-L, N);
    float rv = max(dot(R, V), 0.0);
    // pow(0, 0) is undefined in GLSL: an exponent of 0 means a constant highlight.
    float spec = ndl > 0.0 ? (shininess > 0.0 ? pow(rv, shininess) : 1.0) : 0.0;
    return incoming * (diffuse * ndl + gloss * spec);
}

// shade_light's diffuse and specular parts apart (deferred.separate_specular): it is
// linear in the diffuse colour and in the gloss, so two evaluations, one without each.
void shade_light_split(Light l, vec3 P, vec3 N, vec3 diffuse, float gloss, float shininess,
                       out vec3 d, out vec3 s)
{
    d = shade_light(l, P, N, diffuse, 0.0, shininess);
    s = shade_light(l, P, N, vec3(0.0), gloss, shininess);
}

// deferred-lighting's light buffer (LIGHT_PREPASS): the light without the material,
// incoming x N.L and incoming x spec, which its material pass multiplies by the diffuse
// colour and the gloss (f0 is the metallic-roughness model's only).
void light_prepass(Light l, vec3 P, vec3 N, float shininess, vec3 f0, out vec3 d, out vec3 s)
{
    d = shade_light(l, P, N, vec3(1.0), 0.0, shininess);
    s = shade_light(l, P, N, vec3(0.0), 1.0, shininess);
}
#endif

Light light_from(vec4 v[5])
{
    return Light(v[0], v[1], v[2], v[3], v[4]);
}
