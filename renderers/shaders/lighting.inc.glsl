// Phong lighting as seed 000 appendix D gives it, shared by every renderer so that
// their images differ only by what a G-buffer loses:
//   I = A + att * spot * (D + g * S)
//   D = light * diffuse * max(N.L, 0)
//   S = light * max(R.V, 0)^n           (g: specular intensity x gloss map)
//   att: 1/d^2 | max(0, 1 - d/range) | 1/(a d^2 + b d + c), and 0 beyond range
//   spot = (-L.A)^f inside the cone (-L.A > cos c), else 0
// Everything is in view space: the eye is at the origin.
//
// A light is 5 vec4s (the layout of forward-spml's buffer and of the per-light
// uniform u_light[5] of the other passes; renderers/shading.h fills it):
//   [0] xyz position, w range           [1] rgb colour, w type (0 point, 1 spot, 2 dir.)
//   [2] xyz direction (unit, the way the light travels), w cos(spot angle)
//   [3] x spot exponent, y attenuation (0 inverse-square, 1 linear-range, 2 quadratic),
//       z shadow-map layer + 1 (0: none; read only with SHADOWS, shadow.inc)
//   [4] xyz quadratic a, b, c
//
// With SHADOWS defined, the light arriving at a point is also multiplied by its
// shadow-map lookup (shadow.inc): I = A + att * spot * shadow * (D + g * S).

#include "shadow.inc"

#define LIGHT_POINT 0
#define LIGHT_SPOT 1
#define LIGHT_DIRECTIONAL 2

// The light features the program is compiled for: LIGHT_TYPES, bit t for type t (1 point,
// 2 spot, 4 directional), and LIGHT_ATTENUATIONS, bit k for attenuation k (1
// inverse-square, 2 linear-range, 4 quadratic). Every program gets the scene's (the
// program cache's common defines, renderers/base.c); the code of the others is left
// out, so that a light costs only what its kind needs: on llvmpipe both sides of a
// branch run, masked, for every light a loop visits, and the fields they read are
// loaded. A light of a kind left out is never in the frame. Without them: everything.
#ifndef LIGHT_TYPES
#define LIGHT_TYPES 7
#endif
#ifndef LIGHT_ATTENUATIONS
#define LIGHT_ATTENUATIONS 7
#endif
#define HAS_SPOT ((LIGHT_TYPES & 2) != 0)
#define HAS_DIRECTIONAL ((LIGHT_TYPES & 4) != 0)

// 1/d^2 at d = 0 (a light on the surface) is infinite: d^2 is clamped here, so the
// light is as bright as at 1 cm and never Inf.
const float ATTENUATION_MIN_D2 = 1e-4;

struct Light {
    vec4 position_range;
    vec4 color_type;
    vec4 direction_cos;
    vec4 params;
    vec4 quadratic;
};

// Whether light l can reach view-space point P: a point or spot light within its range
// (the squared-range rejection every light loop makes before shade_light, which would
// give exactly zero beyond it), or a directional light. Reads only its position, range
// and (with directional lights in the scene) type.
bool light_in_range(Light l, vec3 P)
{
    vec3 d = l.position_range.xyz - P;
    float r = l.position_range.w;
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
    float range = l.position_range.w;
    if (d2 > range * range) {
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
#else
    int kind = int(l.params.y);
    if (kind == 0)
        att = 1.0 / max(d2, ATTENUATION_MIN_D2);
    else if (kind == 1)
        att = max(0.0, 1.0 - dist / range);
    else
        att = 1.0 / max(l.quadratic.x * d2 + l.quadratic.y * dist + l.quadratic.z, 1e-6);
#endif
#if HAS_SPOT
    if (type == LIGHT_SPOT) {
        float c = dot(-L, l.direction_cos.xyz);
        att *= c > l.direction_cos.w ? pow(c, l.params.x) : 0.0;
    }
#endif
    return l.color_type.rgb * att;
}

// The light's contribution at a surface point: att * spot * (D + g * S).
vec3 shade_light(Light l, vec3 P, vec3 N, vec3 diffuse, float gloss, float shininess)
{
    vec3 L;
    vec3 incoming = light_incoming(l, P, N, L);
#ifdef SHADOWS
    // Only where the light arrives at all: no lookup outside its range or cone.
    if (l.params.z > 0.5 && any(greaterThan(incoming, vec3(0.0))))
        incoming *= shadow_visibility(int(l.params.z + 0.5) - 1, P);
#endif
    float ndl = max(dot(N, L), 0.0);
    vec3 V = normalize(-P);
    vec3 R = reflect(-L, N);
    float rv = max(dot(R, V), 0.0);
    // pow(0, 0) is undefined in GLSL: an exponent of 0 means a constant highlight.
    float spec = ndl > 0.0 ? (shininess > 0.0 ? pow(rv, shininess) : 1.0) : 0.0;
    return incoming * (diffuse * ndl + gloss * spec);
}

Light light_from(vec4 v[5])
{
    return Light(v[0], v[1], v[2], v[3], v[4]);
}
