/* The environment light's sky, prefiltered cube map and irradiance (environment.h). */
#include "renderers/frame/environment.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <time.h>

static const double PI = 3.14159265358979323846;

/* The palette: linear RGB radiance at intensity 1. The horizon is about 1 (a neutral
 * studio white), the zenith a pale blue, the ground a warm grey; each side tends to the
 * horizon exponentially (scales 0.25 above, 0.05 below), so the sky is continuous and
 * the horizon glows a little. */
static const double HORIZON[3] = {1.0, 0.98, 0.95};
static const double ZENITH[3] = {0.45, 0.58, 0.85};
static const double GROUND[3] = {0.32, 0.3, 0.28};
static const double SKY_SCALE = 0.25, GROUND_SCALE = 0.05;

void environment_sky(const double d[3], double rgb[3])
{
    double y = d[1] < -1.0 ? -1.0 : d[1] > 1.0 ? 1.0 : d[1];
    const double *far = y >= 0.0 ? ZENITH : GROUND;
    double w = y >= 0.0 ? exp(-y / SKY_SCALE) : exp(y / GROUND_SCALE);   /* horizon's share */
    for (int c = 0; c < 3; c++)
        rgb[c] = far[c] + (HORIZON[c] - far[c]) * w;
}

void environment_texel_dir(int face, int s, int t, int size, double d[3])
{
    double a = 2.0 * (s + 0.5) / size - 1.0, b = 2.0 * (t + 0.5) / size - 1.0;
    double r[3];
    switch (face) {
    case 0: r[0] = 1.0; r[1] = -b; r[2] = -a; break;
    case 1: r[0] = -1.0; r[1] = -b; r[2] = a; break;
    case 2: r[0] = a; r[1] = 1.0; r[2] = b; break;
    case 3: r[0] = a; r[1] = -1.0; r[2] = -b; break;
    case 4: r[0] = a; r[1] = -b; r[2] = 1.0; break;
    default: r[0] = -a; r[1] = -b; r[2] = -1.0; break;
    }
    double n = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int k = 0; k < 3; k++)
        d[k] = r[k] / n;
}

/* The solid angle of the face rectangle from the origin to (x, y), face at distance 1. */
static double corner_area(double x, double y)
{
    return atan2(x * y, sqrt(x * x + y * y + 1.0));
}

/* The irradiance's SH9 from the sky sampled at the centres of SH_FACE^2 texels a face,
 * each weighted by its exact solid angle. */
enum { SH_FACE = 128 };

static void project_sh(float out[9][3])
{
    double acc[9][3] = {{0}};
    for (int f = 0; f < 6; f++)
        for (int t = 0; t < SH_FACE; t++)
            for (int s = 0; s < SH_FACE; s++) {
                double d[3], L[3];
                environment_texel_dir(f, s, t, SH_FACE, d);
                environment_sky(d, L);
                double x0 = 2.0 * s / SH_FACE - 1.0, x1 = 2.0 * (s + 1) / SH_FACE - 1.0;
                double y0 = 2.0 * t / SH_FACE - 1.0, y1 = 2.0 * (t + 1) / SH_FACE - 1.0;
                double dw = corner_area(x0, y0) - corner_area(x0, y1) -
                            corner_area(x1, y0) + corner_area(x1, y1);
                double x = d[0], y = d[1], z = d[2];
                /* the real SH basis Y_lm, l <= 2, in environment.h's order */
                double Y[9] = {0.282095, 0.488603 * y, 0.488603 * z, 0.488603 * x,
                               1.092548 * x * y, 1.092548 * y * z,
                               0.315392 * (3.0 * z * z - 1.0), 1.092548 * x * z,
                               0.546274 * (x * x - y * y)};
                for (int i = 0; i < 9; i++)
                    for (int c = 0; c < 3; c++)
                        acc[i][c] += L[c] * Y[i] * dw;
            }
    /* E(n) = sum A_l L_lm Y_lm(n), A = (pi, 2 pi / 3, pi / 4); out = E / pi, with Y_lm's
     * constant folded in so that the shader multiplies by the bare polynomial */
    static const double C[9] = {0.282095, 0.488603, 0.488603, 0.488603, 1.092548,
                                1.092548, 0.315392, 1.092548, 0.546274};
    static const double A[9] = {1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25,
                                0.25, 0.25};   /* A_l / pi */
    for (int i = 0; i < 9; i++)
        for (int c = 0; c < 3; c++)
            out[i][c] = (float)(A[i] * C[i] * acc[i][c]);
}

/* Van der Corput's radical inverse in base 2 (the Hammersley set's second coordinate). */
static double radical_inverse(uint32_t i)
{
    i = (i << 16) | (i >> 16);
    i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
    i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
    i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
    i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
    return (double)i * (1.0 / 4294967296.0);
}

/* One texel of a prefiltered mip: the sky convolved with the GGX lobe of alpha a about
 * N (= V = R), importance-sampled, each sample weighted by N.L (Karis 2013). h holds the
 * samples' half vectors in N's frame (x, y, z: z along N). */
static void prefilter_texel(const double N[3], const double (*h)[3], int n, float *out)
{
    /* a frame about N: T, B, N */
    double up[3] = {0.0, 0.0, 1.0};
    if (fabs(N[2]) > 0.999) {
        up[0] = 1.0;
        up[2] = 0.0;
    }
    double T[3] = {up[1] * N[2] - up[2] * N[1], up[2] * N[0] - up[0] * N[2],
                   up[0] * N[1] - up[1] * N[0]};
    double tl = sqrt(T[0] * T[0] + T[1] * T[1] + T[2] * T[2]);
    for (int k = 0; k < 3; k++)
        T[k] /= tl;
    double B[3] = {N[1] * T[2] - N[2] * T[1], N[2] * T[0] - N[0] * T[2],
                   N[0] * T[1] - N[1] * T[0]};
    double sum[3] = {0.0, 0.0, 0.0}, w = 0.0;
    for (int i = 0; i < n; i++) {
        double H[3], L[3], c[3];
        for (int k = 0; k < 3; k++)
            H[k] = h[i][0] * T[k] + h[i][1] * B[k] + h[i][2] * N[k];
        double ndh = h[i][2];   /* N.H = V.H */
        for (int k = 0; k < 3; k++)
            L[k] = 2.0 * ndh * H[k] - N[k];
        double ndl = 2.0 * ndh * ndh - 1.0;
        if (!(ndl > 0.0))
            continue;
        environment_sky(L, c);
        for (int k = 0; k < 3; k++)
            sum[k] += c[k] * ndl;
        w += ndl;
    }
    for (int k = 0; k < 3; k++)
        out[k] = (float)(w > 0.0 ? sum[k] / w : 0.0);
}

static bool build(environment_maps *m)
{
    double (*h)[3] = malloc(sizeof *h * ENVIRONMENT_SAMPLES);
    if (!h)
        return false;
    bool ok = true;
    for (int k = 0; k < ENVIRONMENT_LEVELS; k++) {
        int size = ENVIRONMENT_FACE >> k;
        m->level[k] = malloc(sizeof(float) * 3 * 6 * (size_t)size * (size_t)size);
        if (!m->level[k]) {
            ok = false;
            break;
        }
        double r = (double)k / (ENVIRONMENT_LEVELS - 1), a = r * r;
        for (int i = 0; i < ENVIRONMENT_SAMPLES; i++) {   /* GGX's half vectors, alpha a */
            double u = (double)i / ENVIRONMENT_SAMPLES, v = radical_inverse((uint32_t)i);
            double phi = 2.0 * PI * u;
            double ct = sqrt((1.0 - v) / (1.0 + (a * a - 1.0) * v));
            double st = sqrt(1.0 - ct * ct);
            h[i][0] = st * cos(phi);
            h[i][1] = st * sin(phi);
            h[i][2] = ct;
        }
        for (int f = 0; f < 6; f++)
            for (int t = 0; t < size; t++)
                for (int s = 0; s < size; s++) {
                    double d[3];
                    environment_texel_dir(f, s, t, size, d);
                    float *out = m->level[k] + (((size_t)f * size + t) * size + s) * 3;
                    if (k == 0) {   /* roughness 0: the sky itself */
                        double c[3];
                        environment_sky(d, c);
                        for (int j = 0; j < 3; j++)
                            out[j] = (float)c[j];
                    } else {
                        prefilter_texel(d, (const double(*)[3])h, ENVIRONMENT_SAMPLES, out);
                    }
                }
    }
    free(h);
    if (ok)
        project_sh(m->sh);
    return ok;
}

const environment_maps *environment_get(void)
{
    static environment_maps maps;
    static bool built;
    if (built)
        return &maps;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    if (!build(&maps)) {
        for (int k = 0; k < ENVIRONMENT_LEVELS; k++) {
            free(maps.level[k]);
            maps.level[k] = NULL;
        }
        return NULL;
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    maps.seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    built = true;
    return &maps;
}
