#include "scenes/lights.h"

#include <math.h>

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
