#pragma once
/* GPU clocks, power, temperature and throttle reasons from NVIDIA's management library
 * (NVML), loaded at run time: no link-time dependency and no NVIDIA header (nvml.c
 * declares the few entry points from NVML's public documentation). shadesweep reads
 * clocks and never sets them. SHADESWEEP_NVML_LIBRARY (tests only) names the library
 * to load instead of libnvidia-ml.so.1. docs/notes/timing.md says how trials use it. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct nvml nvml;

/* One reading; a quantity NVML could not give is NAN (throttle: known false). */
typedef struct nvml_sample {
    double sm_mhz, mem_mhz, power_w, temp_c;
    uint64_t throttle;         /* nvmlClocksThrottleReasons bits */
    bool throttle_known;
} nvml_sample;

#define NVML_FIELDS 5          /* sm_mhz, mem_mhz, power_w, temp_c, throttle */

/* Loads the library, initialises it and picks the GL context's device: the one at PCI
 * address gl_pci ("0000:17:00.0", nvml_drm_pci's; NULL: unknown), else the first whose
 * NVML name appears in gl_renderer (case-insensitive; NULL: none), else device 0. NULL
 * with `why` set when there is no library, no device or NVML fails. */
nvml *nvml_open(const char *gl_renderer, const char *gl_pci, char *why, size_t whylen);
void nvml_close(nvml *n);      /* nvmlShutdown and dlclose; NULL is fine */

const char *nvml_device_name(const nvml *n);
const char *nvml_device_uuid(const nvml *n);   /* "" when NVML gave none */
const char *nvml_matched_by(const nvml *n);    /* "pci", "name" or "none" (device 0) */

/* The PCI address ("0000:17:00.0") of a DRM device file ("/dev/dri/card1", meta.yaml's
 * gl.device) from <sysfs>/class/drm/<name>/device (sysfs NULL: "/sys"); false when it
 * is not a DRM file or sysfs does not say. */
bool nvml_drm_pci(const char *sysfs, const char *drm_file, char *bus_id, size_t len);

/* Reads every quantity now. notes[i] (NVML_FIELDS of them, each `len` bytes; NULL: not
 * wanted) gets "nvmlDeviceGetPowerUsage: Not Supported" for a quantity that failed,
 * "" for one read. */
void nvml_read(nvml *n, nvml_sample *s, char (*notes)[128]);

/* The names of the throttle bits set in mask (NVML's, without the prefix: "gpu_idle",
 * "sw_power_cap", ...; an undocumented bit as "bit_N"), at most max; their count. */
size_t nvml_throttle_names(uint64_t mask, const char **names, char (*buf)[16], size_t max);

/* NVML's message for a return code (nvmlErrorString when the library has it). */
const char *nvml_error_message(const nvml *n, int code);

/* The line a sweep prints once: "" when NVML has a device, else why there are no clocks. */
void nvml_availability(char *line, size_t len);
