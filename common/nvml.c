/* NVML read at run time (common/nvml.h). The declarations below follow NVML's public
 * documentation (nvml.h of the CUDA toolkit): every entry point returns an
 * nvmlReturn_t (0: NVML_SUCCESS) and takes an opaque nvmlDevice_t. */
#define _GNU_SOURCE
#include "common/nvml.h"

#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

typedef int nvml_ret;
typedef void *nvml_device;

enum { NVML_CLOCK_SM = 1, NVML_CLOCK_MEM = 2, NVML_TEMPERATURE_GPU = 0 };
enum { NAME_LEN = 96, UUID_LEN = 96 };   /* NVML_DEVICE_{NAME,UUID}_V2_BUFFER_SIZE */

/* nvmlPciInfo_t (nvmlDeviceGetPciInfo_v3): busIdLegacy[16], then the numbers */
typedef struct nvml_pci {
    char bus_id_legacy[16];
    unsigned domain, bus, device, pci_device_id, pci_subsystem_id;
    char bus_id[32];
} nvml_pci;

struct nvml {
    void *lib;
    nvml_device dev;
    const char *matched;
    char name[NAME_LEN], uuid[UUID_LEN];
    nvml_ret (*shutdown)(void);
    nvml_ret (*clock)(nvml_device, int, unsigned *);
    nvml_ret (*power)(nvml_device, unsigned *);
    nvml_ret (*temp)(nvml_device, int, unsigned *);
    nvml_ret (*throttle)(nvml_device, unsigned long long *);
    const char *(*error_string)(nvml_ret);
};

/* NVML's documented return codes, for a library without nvmlErrorString. */
const char *nvml_error_message(const nvml *n, int code)
{
    if (n && n->error_string) {
        const char *s = n->error_string(code);
        if (s)
            return s;
    }
    switch (code) {
    case 0: return "Success";
    case 1: return "Uninitialized";
    case 2: return "Invalid Argument";
    case 3: return "Not Supported";
    case 4: return "Insufficient Permissions";
    case 6: return "Not Found";
    case 9: return "Driver Not Loaded";
    case 12: return "Library Not Found";
    case 13: return "Function Not Found";
    case 15: return "GPU is lost";
    default: return "Unknown Error";
    }
}

static void *sym(void *lib, const char *name, char *why, size_t len)
{
    void *p = dlsym(lib, name);
    if (!p && why)
        snprintf(why, len, "%s not found in the library", name);
    return p;
}

#define FAIL(...) do { snprintf(why, whylen, __VA_ARGS__); goto fail; } while (0)

nvml *nvml_open(const char *gl_renderer, const char *gl_pci, char *why, size_t whylen)
{
    const char *path = getenv("SHADESWEEP_NVML_LIBRARY");
    if (!path || !path[0])
        path = "libnvidia-ml.so.1";
    /* never unloaded: a driver's library may not survive it (nvml_close) */
    void *lib = dlopen(path, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (!lib) {
        snprintf(why, whylen, "%s cannot be loaded (no NVIDIA driver)", path);
        return NULL;
    }
    nvml *n = calloc(1, sizeof *n);
    bool inited = false;
    if (!n)
        FAIL("out of memory");
    n->lib = lib;
    nvml_ret (*init)(void) = (nvml_ret (*)(void))sym(lib, "nvmlInit_v2", why, whylen);
    nvml_ret (*count)(unsigned *) =
        (nvml_ret (*)(unsigned *))sym(lib, "nvmlDeviceGetCount_v2", why, whylen);
    nvml_ret (*handle)(unsigned, nvml_device *) =
        (nvml_ret (*)(unsigned, nvml_device *))sym(lib, "nvmlDeviceGetHandleByIndex_v2", why, whylen);
    nvml_ret (*name)(nvml_device, char *, unsigned) =
        (nvml_ret (*)(nvml_device, char *, unsigned))sym(lib, "nvmlDeviceGetName", why, whylen);
    nvml_ret (*pci)(nvml_device, nvml_pci *) =
        (nvml_ret (*)(nvml_device, nvml_pci *))dlsym(lib, "nvmlDeviceGetPciInfo_v3");
    nvml_ret (*uuid)(nvml_device, char *, unsigned) =
        (nvml_ret (*)(nvml_device, char *, unsigned))dlsym(lib, "nvmlDeviceGetUUID");
    n->error_string = (const char *(*)(nvml_ret))dlsym(lib, "nvmlErrorString");
    n->shutdown = (nvml_ret (*)(void))sym(lib, "nvmlShutdown", why, whylen);
    n->clock = (nvml_ret (*)(nvml_device, int, unsigned *))sym(lib, "nvmlDeviceGetClockInfo", why, whylen);
    n->power = (nvml_ret (*)(nvml_device, unsigned *))sym(lib, "nvmlDeviceGetPowerUsage", why, whylen);
    n->temp = (nvml_ret (*)(nvml_device, int, unsigned *))sym(lib, "nvmlDeviceGetTemperature", why, whylen);
    n->throttle = (nvml_ret (*)(nvml_device, unsigned long long *))
        sym(lib, "nvmlDeviceGetCurrentClocksThrottleReasons", why, whylen);
    if (!init || !count || !handle || !name || !n->shutdown || !n->clock || !n->power ||
        !n->temp || !n->throttle)
        goto fail;   /* why: the missing entry point */
    nvml_ret r = init();
    if (r != 0)
        FAIL("nvmlInit_v2: %s", nvml_error_message(n, r));
    inited = true;
    unsigned ndev = 0;
    if ((r = count(&ndev)) != 0)
        FAIL("nvmlDeviceGetCount_v2: %s", nvml_error_message(n, r));
    if (ndev == 0)
        FAIL("NVML sees no NVIDIA device");
    /* the device the GL context runs on: the one at its PCI address, else the first
     * whose NVML name is inside GL_RENDERER ("NVIDIA H100 80GB HBM3/PCIe/SSE2"), else 0 */
    unsigned want[3], by_name = ndev;
    bool by_pci = gl_pci && pci && sscanf(gl_pci, "%x:%x:%x", &want[0], &want[1], &want[2]) == 3;
    bool have = false;   /* a device NVML answered for (one it cannot is skipped) */
    n->matched = "none";
    for (unsigned i = 0; i < ndev; i++) {
        nvml_device d;
        char nm[NAME_LEN] = "";
        if ((r = handle(i, &d)) != 0 || (r = name(d, nm, sizeof nm)) != 0) {
            snprintf(why, whylen, "NVML device %u: %s", i, nvml_error_message(n, r));
            continue;
        }
        nm[sizeof nm - 1] = '\0';
        union { nvml_pci p; char room[512]; } pi;   /* room: should a driver's be longer */
        if (by_pci && pci(d, &pi.p) == 0 && pi.p.domain == want[0] && pi.p.bus == want[1] &&
            pi.p.device == want[2]) {
            n->dev = d;
            n->matched = "pci";
            have = true;
            memcpy(n->name, nm, sizeof nm);
            break;
        }
        bool m = gl_renderer && nm[0] && strcasestr(gl_renderer, nm);
        if (!have || (m && by_name == ndev)) {
            have = true;
            n->dev = d;
            n->matched = m ? "name" : "none";
            memcpy(n->name, nm, sizeof nm);
            by_name = m ? i : by_name;
        }
    }
    if (!have)
        goto fail;   /* why: the last device's error */
    if (!uuid || uuid(n->dev, n->uuid, sizeof n->uuid) != 0)
        n->uuid[0] = '\0';
    n->uuid[sizeof n->uuid - 1] = '\0';
    return n;
fail:
    if (inited)
        n->shutdown();
    free(n);
    dlclose(lib);
    return NULL;
}

void nvml_close(nvml *n)
{
    if (!n)
        return;
    n->shutdown();
    dlclose(n->lib);
    free(n);
}

const char *nvml_device_name(const nvml *n) { return n->name; }
const char *nvml_device_uuid(const nvml *n) { return n->uuid; }
const char *nvml_matched_by(const nvml *n) { return n->matched; }

bool nvml_drm_pci(const char *sysfs, const char *drm_file, char *bus_id, size_t len)
{
    const char *base = drm_file ? strrchr(drm_file, '/') : NULL;
    if (!base || strncmp(drm_file, "/dev/dri/", 9) != 0)
        return false;
    char link[512], target[512];
    snprintf(link, sizeof link, "%s/class/drm/%s/device", sysfs ? sysfs : "/sys", base + 1);
    ssize_t k = readlink(link, target, sizeof target - 1);
    if (k <= 0)
        return false;
    target[k] = '\0';
    const char *last = strrchr(target, '/');
    last = last ? last + 1 : target;
    unsigned d, b, s, f;
    if (sscanf(last, "%x:%x:%x.%x", &d, &b, &s, &f) != 4)
        return false;
    snprintf(bus_id, len, "%04x:%02x:%02x.%x", d, b, s, f);
    return true;
}

static double read_u(nvml *n, nvml_ret r, unsigned v, double scale, const char *what,
                     char *note)
{
    if (r == 0) {
        if (note)
            note[0] = '\0';
        return v * scale;
    }
    if (note)
        snprintf(note, 128, "%s: %s", what, nvml_error_message(n, r));
    return NAN;
}

void nvml_read(nvml *n, nvml_sample *s, char (*notes)[128])
{
    unsigned v = 0;
    nvml_ret r = n->clock(n->dev, NVML_CLOCK_SM, &v);
    s->sm_mhz = read_u(n, r, v, 1, "nvmlDeviceGetClockInfo(SM)", notes ? notes[0] : NULL);
    v = 0;
    r = n->clock(n->dev, NVML_CLOCK_MEM, &v);
    s->mem_mhz = read_u(n, r, v, 1, "nvmlDeviceGetClockInfo(MEM)", notes ? notes[1] : NULL);
    v = 0;
    r = n->power(n->dev, &v);   /* milliwatts */
    s->power_w = read_u(n, r, v, 1e-3, "nvmlDeviceGetPowerUsage", notes ? notes[2] : NULL);
    v = 0;
    r = n->temp(n->dev, NVML_TEMPERATURE_GPU, &v);
    s->temp_c = read_u(n, r, v, 1, "nvmlDeviceGetTemperature(GPU)", notes ? notes[3] : NULL);
    unsigned long long mask = 0;
    r = n->throttle(n->dev, &mask);
    s->throttle_known = r == 0;
    s->throttle = r == 0 ? mask : 0;
    read_u(n, r, 0, 0, "nvmlDeviceGetCurrentClocksThrottleReasons", notes ? notes[4] : NULL);
}

/* nvmlClocksThrottleReason* of NVML's documentation, bit by bit */
static const char *const throttle_bits[] = {
    "gpu_idle",                   /* 0x1 */
    "applications_clocks_setting",/* 0x2 */
    "sw_power_cap",               /* 0x4 */
    "hw_slowdown",                /* 0x8 */
    "sync_boost",                 /* 0x10 */
    "sw_thermal_slowdown",        /* 0x20 */
    "hw_thermal_slowdown",        /* 0x40 */
    "hw_power_brake_slowdown",    /* 0x80 */
    "display_clock_setting",      /* 0x100 */
};

size_t nvml_throttle_names(uint64_t mask, const char **names, char (*buf)[16], size_t max)
{
    size_t k = 0;
    for (unsigned b = 0; b < 64 && k < max; b++) {
        if (!(mask >> b & 1))
            continue;
        if (b < sizeof throttle_bits / sizeof *throttle_bits) {
            names[k++] = throttle_bits[b];
        } else {
            snprintf(buf[k], sizeof buf[k], "bit_%u", b);
            names[k] = buf[k];
            k++;
        }
    }
    return k;
}

void nvml_availability(char *line, size_t len)
{
    char why[256];
    nvml *n = nvml_open(NULL, NULL, why, sizeof why);
    if (n) {
        line[0] = '\0';
        nvml_close(n);
        return;
    }
    snprintf(line, len, "clocks: not recorded: %s", why);
}
