/* Procedural meshes: the light volumes (>>light-volumes), a sphere and a cone that enclose
 * the light's true shape. See scenes/mesh.h. */
#include "scenes/builtin/mesh_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/scene_fail.h"

/* >>light-volumes ---------------------------------------------------------------------- */

#define LIGHT_VOLUME_MARGIN 1e-4

/* The smallest distance from the origin to a triangle's plane (positive: the origin is
 * on the inner side of every face), in double from the float positions. */
static double min_face_distance(const mesh *m, double scale)
{
    double dmin = INFINITY;
    for (uint32_t t = 0; t + 2 < m->nindices; t += 3) {
        double p[3][3];
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 3; i++)
                p[k][i] = (double)(float)(m->vertices[m->indices[t + k]].position[i] * scale);
        double e1[3], e2[3], n[3];
        for (int i = 0; i < 3; i++) {
            e1[i] = p[1][i] - p[0][i];
            e2[i] = p[2][i] - p[0][i];
        }
        mg_cross_d(e1, e2, n);
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double d = (n[0] * p[0][0] + n[1] * p[0][1] + n[2] * p[0][2]) / len;
        if (d < dmin)
            dmin = d;
    }
    return dmin;
}

bool mesh_light_sphere(uint32_t slices, uint32_t stacks, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (slices < 3 || stacks < 2)
        return scene_fail(err, errlen,
                          "mesh_light_sphere: needs slices >= 3 and stacks >= 2 (got %u, %u)",
                          slices, stacks);
    if (!mesh_sphere(1.0f, slices, stacks, out, err, errlen))
        return false;
    /* Scale so that every face plane is at least 1 + margin out, checking the rounded
     * float positions (the quads' two triangles are coplanar only up to rounding). */
    double d = min_face_distance(out, 1.0);
    double scale = (1.0 + LIGHT_VOLUME_MARGIN) / d;
    while (min_face_distance(out, scale) < 1.0 + 0.5 * LIGHT_VOLUME_MARGIN)
        scale *= 1.0 + 1e-6;
    for (uint32_t i = 0; i < out->nvertices; i++)
        for (int k = 0; k < 3; k++)
            out->vertices[i].position[k] = (float)(out->vertices[i].position[k] * scale);
    mesh_compute_bounds(out);
    return true;
}

bool mesh_light_cone(float half_angle, uint32_t segments, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!(isfinite(half_angle) && half_angle > 0.0f && half_angle < SM_PI_2))
        return scene_fail(err, errlen,
                          "mesh_light_cone: half_angle must be in (0, pi/2) radians (got %g)",
                          (double)half_angle);
    if (segments < 3)
        return scene_fail(err, errlen, "mesh_light_cone: needs segments >= 3 (got %u)", segments);
    /* The pyramid with its apex m behind the origin and its base m beyond z = -1,
     * inradius tan(half_angle) (1 + 2m) there: at z = -1 its inradius is
     * tan(half_angle) (1 + m), so apex and base circle of the true cone, and with them
     * their hull, are strictly inside. (Scaling about the apex would not do: a cone is
     * its own image, and its sides would stay tangent.) */
    double m = LIGHT_VOLUME_MARGIN;
    double r = tan((double)half_angle) * (1.0 + 2.0 * m) / cos(PI_D / (double)segments);
    float radius = (float)r, height = (float)(1.0 + 2.0 * m);
    if (!mg_positive(radius))
        return scene_fail(err, errlen, "mesh_light_cone: half_angle %g too close to pi/2",
                          (double)half_angle);
    if (!mesh_cone(radius, height, segments, true, out, err, errlen))
        return false;
    for (uint32_t i = 0; i < out->nvertices; i++)
        out->vertices[i].position[2] += (float)m;
    mesh_compute_bounds(out);
    return true;
}
