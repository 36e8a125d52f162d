/* Device profiles: figures, cache key and files (results/device_profile.h). */
#include "results/device_profile.h"
#include "results/jsonout.h"
#include "results/yamlout.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void device_median_spread(const double *x, size_t n, double *median, double *spread)
{
    double s[DEVICE_PROFILE_MAX_REPEATS];
    if (n > DEVICE_PROFILE_MAX_REPEATS)
        n = DEVICE_PROFILE_MAX_REPEATS;
    if (n == 0) {
        *median = *spread = NAN;
        return;
    }
    memcpy(s, x, n * sizeof *x);
    qsort(s, n, sizeof *s, cmp_double);
    double m = n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
    *median = m;
    *spread = fmax(m - s[0], s[n - 1] - m);
}

bool device_profile_add(device_profile *p, const char *name, const char *unit,
                        const double *x, size_t n)
{
    if (p->nfigures == DEVICE_PROFILE_MAX_FIGURES)
        return false;
    device_figure *f = &p->figure[p->nfigures++];
    snprintf(f->name, sizeof f->name, "%s", name);
    f->unit = unit;
    f->repeats = (unsigned)(n > DEVICE_PROFILE_MAX_REPEATS ? DEVICE_PROFILE_MAX_REPEATS : n);
    device_median_spread(x, n, &f->median, &f->spread);
    return true;
}

void device_profile_set_gl(device_profile *p, const char *const gl[6])
{
    char *dst[] = {p->vendor, p->renderer, p->version, p->glsl_version, p->backend, p->device};
    for (size_t i = 0; i < 6; i++)
        snprintf(dst[i], DEVICE_PROFILE_STRING, "%s", gl[i] ? gl[i] : "");
}

void device_profile_key(const device_profile *p, char key[17])
{
    const char *parts[] = {p->vendor, p->renderer, p->version, p->glsl_version, p->backend,
                           p->device};
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < sizeof parts / sizeof *parts; i++)
        for (const char *c = parts[i];; c++) {
            h = (h ^ (unsigned char)(*c ? *c : '\n')) * 0x100000001b3ull;
            if (!*c)
                break;
        }
    snprintf(key, 17, "%016llx", (unsigned long long)h);
}

bool device_profile_cache_dir(char *dir, size_t n)
{
    const char *x = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    int k;
    if (x && x[0] == '/')
        k = snprintf(dir, n, "%s/shadesweep", x);
    else if (home && home[0] == '/')
        k = snprintf(dir, n, "%s/.cache/shadesweep", home);
    else
        return false;
    return k > 0 && (size_t)k < n;
}

bool device_profile_cache_path(const device_profile *p, char *path, size_t n)
{
    char dir[3800], key[17];
    if (!device_profile_cache_dir(dir, sizeof dir))
        return false;
    device_profile_key(p, key);
    int k = snprintf(path, n, "%s/device-%s.yaml", dir, key);
    return k > 0 && (size_t)k < n;
}

/* The profile's strings as (key, value) pairs, in the order both formats write them. */
#define PROFILE_STRINGS(X)                 \
    X("shadesweep", shadesweep_version)    \
    X("date", date)                        \
    X("host", host)                        \
    X("cpu", cpu)                          \
    X("backend", backend)                  \
    X("device", device)                    \
    X("vendor", vendor)                    \
    X("renderer", renderer)                \
    X("version", version)                  \
    X("glsl", glsl_version)

static void kv_str(yaml_out *y, const char *k, const char *v)
{
    yo_key(y, k);
    yo_str(y, v);
}

static void kv_num(yaml_out *y, const char *k, double v, bool integer)
{
    yo_key(y, k);
    if (integer)
        yo_i64(y, (int64_t)v);
    else
        yo_f64(y, v);
}

bool device_profile_write_yaml(const device_profile *p, const char *path, char *err,
                               size_t errlen)
{
    yaml_out *y = yo_open(path, err, errlen);
    if (!y)
        return false;
    char key[17];
    device_profile_key(p, key);
    yo_map_begin(y);
    kv_str(y, "key", key);
#define YAML_STRING(k, field) kv_str(y, k, p->field);
    PROFILE_STRINGS(YAML_STRING)
#undef YAML_STRING
    kv_str(y, "software_rasterizer", p->software);
    kv_str(y, "timing", p->timing);
    yo_key(y, "quick");
    yo_bool(y, p->quick);
    kv_num(y, "target_width", p->width, true);
    kv_num(y, "target_height", p->height, true);
    yo_key(y, "figures");
    yo_map_begin(y);
    for (size_t i = 0; i < p->nfigures; i++) {
        const device_figure *f = &p->figure[i];
        yo_key(y, f->name);
        yo_map_begin(y);
        kv_num(y, "median", f->median, false);
        kv_num(y, "spread", f->spread, false);
        kv_str(y, "unit", f->unit);
        kv_num(y, "repeats", f->repeats, true);
        yo_map_end(y);
    }
    yo_map_end(y);
    yo_map_end(y);
    return yo_commit(y, err, errlen);
}

void device_profile_print_json(const device_profile *p, FILE *out)
{
    bool first = true;
    char key[17];
    device_profile_key(p, key);
    fputs("{", out);
    json_member_string(out, &first, "key", key);
#define JSON_STRING(k, field) json_member_string(out, &first, k, p->field);
    PROFILE_STRINGS(JSON_STRING)
#undef JSON_STRING
    json_member_string(out, &first, "software_rasterizer", p->software);
    json_member_string(out, &first, "timing", p->timing);
    json_key(out, &first, "quick");
    fputs(p->quick ? "true" : "false", out);
    json_member_number(out, &first, "target_width", p->width);
    json_member_number(out, &first, "target_height", p->height);
    json_key(out, &first, "figures");
    fputs("{", out);
    bool ff = true;
    for (size_t i = 0; i < p->nfigures; i++) {
        const device_figure *f = &p->figure[i];
        bool fm = true;
        json_key(out, &ff, f->name);
        fputs("{", out);
        json_member_number(out, &fm, "median", f->median);
        json_member_number(out, &fm, "spread", f->spread);
        json_member_string(out, &fm, "unit", f->unit);
        json_member_number(out, &fm, "repeats", f->repeats);
        fputs("}", out);
    }
    fputs("}}\n", out);
}
