#pragma once
/* A device profile (`shadesweep probe`, issue 38): what the GL device under a run can
 * do, measured by microbenchmarks (renderers/probe/probe.c), with the GL strings,
 * driver, host and version; written as device.yaml. This half is the arithmetic and
 * the files, no GL: each figure's median and spread over repeats, the cache key (a
 * hash of the GL strings) and the cache's path, the YAML and the JSON. What each figure
 * measures: docs/notes/device-profile.md. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

enum { DEVICE_PROFILE_MAX_FIGURES = 48, DEVICE_PROFILE_MAX_REPEATS = 32, DEVICE_PROFILE_STRING = 256 };

typedef struct device_figure {
    char name[48];       /* "fill_rgba8_1x", "bandwidth_copy", ... */
    const char *unit;    /* "Gsamples/s", "GB/s", "Gflop/s", "us", "ns" */
    double median;       /* of the repeats */
    double spread;       /* the largest |repeat - median|: every repeat lies within it */
    unsigned repeats;
} device_figure;

typedef struct device_profile {
    /* the GL strings, backend and EGL device: device_profile_set_gl */
    char vendor[DEVICE_PROFILE_STRING], renderer[DEVICE_PROFILE_STRING];
    char version[DEVICE_PROFILE_STRING], glsl_version[DEVICE_PROFILE_STRING];
    char backend[DEVICE_PROFILE_STRING], device[DEVICE_PROFILE_STRING];
    char host[256], cpu[256], shadesweep_version[64], date[32];
    const char *software;   /* gl_software_rasterizer's name, NULL for a GPU */
    const char *timing;     /* "gpu-timer" (GL_TIME_ELAPSED) or "cpu-finish" */
    bool quick;
    int width, height;      /* the fill targets' size */
    size_t nfigures;
    device_figure figure[DEVICE_PROFILE_MAX_FIGURES];
} device_profile;

/* Median of x[0..n) and the largest absolute deviation from it (x is not modified).
 * n == 0: both NAN; n > DEVICE_PROFILE_MAX_REPEATS: only the first that many. */
void device_median_spread(const double *x, size_t n, double *median, double *spread);

/* Adds a figure from its repeats; false when the table is full. */
bool device_profile_add(device_profile *p, const char *name, const char *unit,
                        const double *x, size_t n);

/* Sets vendor, renderer, version, glsl_version, backend and device from gl[0..5], in
 * that order (NULL: ""; each cut to DEVICE_PROFILE_STRING - 1 bytes). */
void device_profile_set_gl(device_profile *p, const char *const gl[6]);

/* The cache key of a device and driver: 16 hex digits of FNV-1a 64 over the GL
 * strings (vendor, renderer, version, GLSL version) and the backend and device, each
 * ended by a newline. */
void device_profile_key(const device_profile *p, char key[17]);

/* The cache folder: $XDG_CACHE_HOME/shadesweep, else $HOME/.cache/shadesweep; false
 * when neither is set (absolute). */
bool device_profile_cache_dir(char *dir, size_t n);
/* <cache folder>/device-<key>.yaml; false as device_profile_cache_dir. */
bool device_profile_cache_path(const device_profile *p, char *path, size_t n);

/* device.yaml through results/yamlout.h (appears whole or not at all). */
bool device_profile_write_yaml(const device_profile *p, const char *path, char *err,
                               size_t errlen);
/* The same fields as one JSON object. */
void device_profile_print_json(const device_profile *p, FILE *out);
