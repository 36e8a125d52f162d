/* Seed 002's bandwidth model, equations 4-7 (results/bandwidth.h has the variables). */
#include "results/bandwidth.h"

double s002_building_bytes(const s002_vars *v)
{
    double per_pixel = v->z_bytes * (v->overdraw + v->sorting) +
                       v->t_bytes * v->t_building * v->sorting +
                       v->n_mrt * v->mrt_bytes * v->sorting;
    return v->w * v->h * per_pixel + v->c_geometry;
}

double s002_shading_bytes(const s002_vars *v)
{
    double per_pixel = 2.0 * v->bb_bytes            /* the back buffer read and written */
                       + v->t_shading * v->t_bytes + v->n_mrt * v->mrt_bytes;
    return v->w * v->h * v->n * per_pixel;
}

double s002_bandwidth(const s002_vars *v, double fps)
{
    return (s002_building_bytes(v) + s002_shading_bytes(v)) * fps;
}

double s002_bandwidth_approx_gbps(double n_mrt, double mrt_bytes)
{
    return n_mrt * mrt_bytes / 2.0 + 10.0;
}

double s002_mrt_write_bytes(double bytes_per_pixel, double written_samples)
{
    return bytes_per_pixel * written_samples;
}

double s002_mrt_read_bytes(double bytes_per_pixel, double shaded_samples)
{
    return bytes_per_pixel * shaded_samples;
}
