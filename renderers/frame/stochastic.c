/* Stochastic light culling's ranges (stochastic.h). */
#include "renderers/frame/stochastic.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* SplitMix64's finaliser (Steele, Lea and Flood 2014): a bijection of 64 bits whose
 * outputs of consecutive inputs pass BigCrush. */
static uint64_t mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

uint64_t stochastic_stream(uint32_t seed, double t)
{
    uint64_t bits;
    memcpy(&bits, &t, sizeof bits);
    return mix64(mix64((uint64_t)seed + 0x9e3779b97f4a7c15u) ^ bits);
}

double stochastic_xi(uint64_t stream, uint32_t index)
{
    uint64_t h = mix64(stream + ((uint64_t)index + 1u) * 0x9e3779b97f4a7c15u);
    return (double)((h >> 40) + 1u) / 16777216.0;   /* 24 bits: 2^-24 .. 1 */
}

/* lighting.inc's windowed attenuation, in double: clamp(1 - (d/r)^4, 0, 1)^2 / max(d^2,
 * 1e-4). */
static double windowed(double d, double range)
{
    double q = d * d / fmax(range * range, 1e-30);
    double w = fmin(fmax(1.0 - q * q, 0.0), 1.0);
    return w * w / fmax(d * d, 1e-4);
}

double stochastic_solve(const gpu_light *l, double threshold)
{
    const double min_d2 = 1e-4;   /* lighting.inc's ATTENUATION_MIN_D2 */
    double range = l->v[0][3], d = 0.0;
    if (!(threshold > 0.0))
        return range;
    switch ((int)l->v[3][1]) {
    case ATTENUATION_INVERSE_SQUARE:   /* 1 / max(d^2, 1e-4) */
        d = threshold * min_d2 > 1.0 ? 0.0 : sqrt(1.0 / threshold);
        break;
    case ATTENUATION_LINEAR_RANGE:   /* max(0, 1 - d / range) */
        d = threshold >= 1.0 ? 0.0 : range * (1.0 - threshold);
        break;
    case ATTENUATION_QUADRATIC: {   /* 1 / max(a d^2 + b d + c, 1e-6), a and b >= 0 */
        double a = l->v[4][0], b = l->v[4][1], q = 1.0 / threshold - l->v[4][2];
        if (threshold * 1e-6 > 1.0 || q < 0.0)
            d = 0.0;
        else if (a > 0.0 || b > 0.0)
            d = 2.0 * q / (b + sqrt(b * b + 4.0 * a * q));   /* the root, without cancelling */
        else
            d = range;   /* constant, and above the threshold */
        break;
    }
    default: {   /* windowed: from 1e4 at 0 down to 0 at the range, below 1/d^2 */
        if (windowed(0.0, range) < threshold)
            return 0.0;
        double lo = 0.0, hi = fmin(range, sqrt(1.0 / threshold));
        if (windowed(hi, range) >= threshold)
            return hi;
        for (int i = 0; i < 40; i++) {   /* 2^-40 of the bracket: past float's 24 bits */
            double mid = 0.5 * (lo + hi);
            if (windowed(mid, range) >= threshold)
                lo = mid;
            else
                hi = mid;
        }
        d = lo;
        break;
    }
    }
    return fmin(fmax(d, 0.0), range);
}

void stochastic_ranges(gpu_light *lights, const uint32_t *ids, uint32_t n, const scene *s,
                       float culling_error)
{
    double exposure = s->display.exposed ? s->display.exposure : 1.0;
    uint64_t stream = stochastic_stream(s->lights_seed, s->t);
    for (uint32_t k = 0; k < n; k++) {
        gpu_light *l = &lights[k];
        if ((int)l->v[1][3] == LIGHT_DIRECTIONAL)
            continue;   /* no range: every cell, every point, weight 1 */
        double peak = fmax(l->v[1][0], fmax(l->v[1][1], l->v[1][2])) * exposure;
        if (!(peak > 0.0) || !isfinite(peak)) {   /* no light to lose, or no bound on it */
            l->v[3][3] = peak > 0.0 ? l->v[0][3] : 0.0f;
            l->v[4][3] = 0.0f;
            continue;
        }
        double q = (double)culling_error / peak;
        l->v[3][3] = (float)stochastic_solve(l, q * stochastic_xi(stream, ids[k]));
        l->v[4][3] = (float)fmin(q, FLT_MAX);
    }
}
