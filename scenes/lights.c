#include "scenes/lights.h"

#include <math.h>
#include <stddef.h>

#define PI_D 3.14159265358979323846

uint32_t light_count_max(const light_count *c)
{
    return c->growth ? c->max : c->start;
}

uint32_t light_count_at(const light_count *c, double t)
{
    if (!c->growth)
        return c->start;
    if (!(t > 0) || c->every <= 0)   /* also catches NaN */
        return c->start < c->max ? c->start : c->max;
    double steps = floor(t / c->every);
    double n = (double)c->start + (double)c->step * steps;
    return n >= (double)c->max ? c->max : (uint32_t)n;
}

const char *const light_placement_names[] = {"random", "none", "grid", "scene", "surface",
                                             NULL};

const char *light_placement_name(light_placement p)
{
    return (unsigned)p <= PLACEMENT_SURFACE ? light_placement_names[p] : "?";
}

/* Each light's share of the box's measure (volume, area or length: the box's positive
 * extents), times k, is the measure of its ball: 4/3 pi r^3 in 3D, pi r^2 in 2D, 2 r in 1D. */
float lights_overlap_radius(uint32_t n, float k, const float bmin[3], const float bmax[3])
{
    if (n == 0 || !(k > 0.0f) || !isfinite(k))
        return 0.0f;
    double measure = 1.0;
    int dims = 0;
    for (int c = 0; c < 3; c++) {
        double e = (double)bmax[c] - (double)bmin[c];
        if (!isfinite(e) || e < 0.0)
            return 0.0f;
        if (e > 0.0) {
            measure *= e;
            dims++;
        }
    }
    double per_light = (double)k * measure / (double)n;   /* each light's share x k */
    switch (dims) {
    case 3: return (float)cbrt(3.0 * per_light / (4.0 * PI_D));   /* n 4/3 pi r^3 / V = k */
    case 2: return (float)sqrt(per_light / PI_D);                  /* n pi r^2 / A = k */
    case 1: return (float)(per_light / 2.0);                        /* n 2r / L = k */
    default: return 0.0f;
    }
}
