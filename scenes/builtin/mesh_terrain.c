/* Procedural meshes: heightfields and the seeded terrain (>>terrain). See scenes/mesh.h. */
#include "scenes/builtin/mesh_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/scene_fail.h"
#include "scenes/builtin/texture_gen.h"

/* >>terrain ---------------------------------------------------------------------------- */

void mesh_terrain_init(mesh_terrain *t, float size_x, float size_z, float height_scale,
                       uint32_t seed)
{
    memset(t, 0, sizeof *t);
    texture_noise_keys(seed, t->keys, MESH_TERRAIN_OCTAVES);
    float side = fmaxf(fabsf(size_x), fabsf(size_z));
    t->frequency = isfinite(side) && side > 0.0f ? 4.0f / side : 0.0f;
    t->height_scale = isfinite(height_scale) ? height_scale : 0.0f;
}

float mesh_terrain_height(float x, float z, void *terrain)
{
    const mesh_terrain *t = terrain;
    if (!isfinite(x))
        x = 0.0f;
    if (!isfinite(z))
        z = 0.0f;
    float h = texture_fbm2(x * t->frequency, z * t->frequency, t->keys, MESH_TERRAIN_OCTAVES,
                           0, 0);
    return t->height_scale * h;
}

bool mesh_heightfield_fn(float size_x, float size_z, uint32_t cells_x, uint32_t cells_z,
                         mesh_height_fn fn, void *user, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!mg_positive(size_x) || !mg_positive(size_z) || !fn)
        return scene_fail(err, errlen,
                          "mesh_heightfield: sizes must be positive and finite (got %g, %g)%s",
                          (double)size_x, (double)size_z,
                          fn ? "" : ", and a height function is needed");
    if (cells_x < 1 || cells_z < 1)
        return scene_fail(err, errlen,
                          "mesh_heightfield: needs at least 1 cell each way (got %u x %u)", cells_x,
                          cells_z);
    uint64_t cx = cells_x, cz = cells_z;
    if (!mg_alloc(out, (cx + 1) * (cz + 1), 6 * cx * cz, "mesh_heightfield", err, errlen))
        return false;
    /* Heights on the grid and one cell beyond it, each sampled once, so a vertex's normal
     * is made of its neighbours' very heights. */
    uint32_t gw = cells_x + 3, row = cells_x + 1;
    float *hg = malloc((size_t)gw * (cells_z + 3) * sizeof *hg);
    if (!hg) {
        mesh_free(out);
        return scene_fail(err, errlen, "mesh_heightfield: out of memory");
    }
    for (uint32_t k = 0; k < cells_z + 3; k++) {
        for (uint32_t i = 0; i < gw; i++) {
            float u = (float)((int32_t)i - 1) / (float)cells_x;
            float w = (float)((int32_t)k - 1) / (float)cells_z;
            float x = size_x * (u - 0.5f), z = size_z * (0.5f - w);
            float h = fn(x, z, user);
            if (!isfinite(h)) {
                scene_fail(err, errlen, "mesh_heightfield: the height function returned %g at "
                           "(%g, %g)", (double)h, (double)x, (double)z);
                free(hg);
                mesh_free(out);
                return false;
            }
            hg[(size_t)k * gw + i] = h;
            if (i >= 1 && i <= cells_x + 1 && k >= 1 && k <= cells_z + 1) {
                mesh_vertex *v = &out->vertices[(k - 1) * row + (i - 1)];
                sm_vec3_make(x, h, z, v->position);
                v->uv[0] = u;
                v->uv[1] = w;
            }
        }
    }
    double dx = (double)size_x / cells_x, dz = (double)size_z / cells_z;
    for (uint32_t k = 0; k <= cells_z; k++) {
        for (uint32_t i = 0; i <= cells_x; i++) {
            mesh_vertex *v = &out->vertices[k * row + i];
            const float *c = &hg[(size_t)(k + 1) * gw + (i + 1)];
            /* slopes dh/dx and dh/dz in double (differences of large heights must not
             * overflow), scaled down by the largest so the frame stays finite */
            double sx = ((double)c[1] - c[-1]) / (2.0 * dx);
            double sz = ((double)c[-(ptrdiff_t)gw] - c[gw]) / (2.0 * dz);   /* k grows to -z */
            double m = fmax(1.0, fmax(fabs(sx), fabs(sz)));
            sm_vec3 n = {(float)(-sx / m), (float)(1.0 / m), (float)(-sz / m)};
            sm_vec3 up = {0.0f, 1.0f, 0.0f};
            mg_set_normal(v, n, up);
            if (!(v->normal[1] > 0.0f))     /* a cliff steeper than float can tell */
                sm_vec3_copy(up, v->normal);
            /* dP/du along +x, dP/dv along -z */
            sm_vec3 dpdu = {(float)(1.0 / m), (float)(sx / m), 0.0f};
            sm_vec3 dpdv = {0.0f, (float)(-sz / m), (float)(-1.0 / m)};
            mg_set_frame(v, dpdu, dpdv);
        }
    }
    free(hg);
    uint32_t *ip = out->indices;
    for (uint32_t k = 0; k < cells_z; k++) {
        for (uint32_t i = 0; i < cells_x; i++) {
            uint32_t a = k * row + i, d = a + row;
            mg_tri(&ip, a, a + 1, d + 1);
            mg_tri(&ip, a, d + 1, d);
        }
    }
    mesh_compute_bounds(out);
    return true;
}

bool mesh_heightfield(float size_x, float size_z, uint32_t cells_x, uint32_t cells_z,
                      float height_scale, uint32_t seed, mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!(isfinite(height_scale) && height_scale >= 0.0f))
        return scene_fail(err, errlen,
                          "mesh_heightfield: height_scale must be >= 0 and finite (got %g)",
                          (double)height_scale);
    mesh_terrain t;
    mesh_terrain_init(&t, size_x, size_z, height_scale, seed);
    return mesh_heightfield_fn(size_x, size_z, cells_x, cells_z, mesh_terrain_height, &t, out,
                               err, errlen);
}
