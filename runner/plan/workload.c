/* The workload a run measured (workload.h). */
#include "runner/plan/workload.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "results/csv.h"
#include "common/image_io.h"
#include "results/numfmt.h"

bool workload_reach_stats(const uint32_t *counts, size_t n, uint32_t nlights,
                          workload_reach *out)
{
    *out = (workload_reach){NAN, NAN, NAN, NAN, 0};
    /* a histogram: counts are at most the frame's lights, and sorting W x H is dearer */
    uint64_t *hist = calloc((size_t)nlights + 1u, sizeof *hist);
    if (!hist)
        return false;
    uint64_t covered = 0;
    double sum = 0;
    for (size_t i = 0; i < n; i++) {
        if (counts[i] == UINT32_MAX)
            continue;
        uint32_t c = counts[i] > nlights ? nlights : counts[i];   /* never, by the shader */
        hist[c]++;
        sum += c;
        covered++;
    }
    if (covered) {
        /* nearest rank: the smallest value with at least ceil(q N) pixels at or below */
        uint64_t r50 = (covered + 1) / 2, r99 = (uint64_t)ceil(0.99 * (double)covered);
        uint64_t below = 0;
        for (uint32_t c = 0; c <= nlights; c++) {
            if (!hist[c])
                continue;
            if (below < r50 && below + hist[c] >= r50)
                out->p50 = c;
            if (below < r99 && below + hist[c] >= r99)
                out->p99 = c;
            below += hist[c];
            out->max = c;
        }
        out->mean = sum / (double)covered;
        out->covered = covered;
    }
    free(hist);
    return true;
}

bool workload_brute_force(double reach_mean, double lights, char *msg, size_t len)
{
    msg[0] = 0;
    if (!isfinite(reach_mean) || !isfinite(lights) || lights < WORKLOAD_WARN_MIN_LIGHTS ||
        !(reach_mean > lights / 2))
        return false;
    snprintf(msg, len,
             "every light reaches most pixels: the workload is brute force whatever the "
             "renderer (mean %.1f of %.0f lights a pixel); a smaller lights.radius or "
             "lights.overlap makes culling matter",
             reach_mean, lights);
    return true;
}

bool workload_heat_map(const char *path, const uint32_t *counts, int width, int height,
                       uint32_t nlights, char *err, size_t errlen)
{
    image img = {.width = width, .height = height, .channels = 3, .type = IMAGE_U8};
    uint8_t *px = malloc((size_t)width * (size_t)height * 3u);
    if (!px) {
        snprintf(err, errlen, "out of memory for a %dx%d heat map", width, height);
        return false;
    }
    for (int y = 0; y < height; y++) {
        const uint32_t *row = counts + (size_t)(height - 1 - y) * (size_t)width;   /* GL's */
        for (int x = 0; x < width; x++) {
            uint8_t *o = px + ((size_t)y * (size_t)width + (size_t)x) * 3u;
            if (row[x] == UINT32_MAX) {
                o[0] = o[1] = 0, o[2] = 255;
                continue;
            }
            double v = nlights ? 255.0 * (double)row[x] / (double)nlights : 0;
            o[0] = o[1] = o[2] = (uint8_t)(v > 255 ? 255 : lround(v));
        }
    }
    img.pixels = px;
    bool ok = image_write(path, &img, err, errlen);
    free(px);
    return ok;
}

static const char *const light_columns[] = {
    "light", "kind", "x", "y", "z", "range", "r", "g", "b",
    "dir_x", "dir_y", "dir_z", "cone_rad", "on_s",
};

/* A float as the shortest decimal that strtof reads back to it (0.1f as "0.1"). */
static void csv_float(csv_writer *w, float v)
{
    char text[64];
    num_plain_float(v, text, sizeof text);
    csv_str(w, text);
}

/* When light i turns on (light_count_at's inverse); NAN: never. */
static double light_on_s(const light_count *c, uint32_t i)
{
    if (i >= c->max)
        return NAN;
    if (!c->growth || i < c->start)
        return 0;
    if (c->step == 0)
        return NAN;
    uint64_t k = ((uint64_t)i + 1 - c->start + c->step - 1) / c->step;   /* ceil */
    return (double)k * c->every;
}

bool workload_lights_csv(const char *path, const scene *s, char *err, size_t errlen)
{
    static const char *const kinds[] = {"point", "spot", "directional"};
    csv_writer *w = csv_open(path, light_columns, sizeof light_columns / sizeof *light_columns,
                             err, errlen);
    if (!w)
        return false;
    bool ok = true;
    for (uint32_t i = 0; ok && i < s->nlights_total; i++) {
        const scene_light *l = &s->lights[i];
        bool dir = l->type == LIGHT_DIRECTIONAL, spot = l->type == LIGHT_SPOT;
        csv_u64(w, i);
        csv_str(w, (unsigned)l->type < 3 ? kinds[l->type] : "unknown");
        for (int k = 0; k < 3; k++)
            dir ? csv_empty(w) : csv_float(w, l->position[k]);
        dir ? csv_empty(w) : csv_float(w, l->radius);
        for (int k = 0; k < 3; k++)
            csv_float(w, l->color[k]);
        for (int k = 0; k < 3; k++)
            spot || dir ? csv_float(w, l->direction[k]) : csv_empty(w);
        spot ? csv_float(w, l->spot_angle) : csv_empty(w);
        double on = light_on_s(&s->count, i);
        isfinite(on) ? csv_g(w, on) : csv_empty(w);
        ok = csv_end_row(w);
    }
    if (!ok) {
        csv_abort(w);
        snprintf(err, errlen, "%s: a row of the wrong width (a bug)", path);
        return false;
    }
    return csv_commit(w, err, errlen);
}
