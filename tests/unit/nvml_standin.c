/* A stand-in for libnvidia-ml.so.1 (tests only; common/nvml.h loads it through
 * SHADESWEEP_NVML_LIBRARY): the entry points shadesweep uses, with NVML's documented
 * signatures, returning what the environment scripts, read at each call:
 *   STANDIN_NVML_INIT   nvmlInit_v2's return code (0)    STANDIN_NVML_NAMES  the devices'
 *   names, '|'-separated ("NVIDIA Stand-in"; "": none; "!N": error N)   STANDIN_NVML_SM, _MEM (MHz),
 *   _POWER (mW), _TEMP (C), _THROTTLE (the mask, 0x.. allowed): the values, or
 *   "!N": that call returns code N.   STANDIN_NVML_UUID    nvmlDeviceGetUUID's text.
 *   STANDIN_NVML_CALLS  a file: one line per nvmlInit_v2 and nvmlShutdown call.
 *   STANDIN_NVML_PCI    the devices' PCI addresses, '|'-separated ("0:1:0" each by default).
 * Built with -DSTANDIN_NO_THROTTLE it lacks nvmlDeviceGetCurrentClocksThrottleReasons. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXPORT __attribute__((visibility("default")))

/* NVML's signatures (nvmlReturn_t is an int, nvmlDevice_t an opaque pointer) */
EXPORT int nvmlInit_v2(void);
EXPORT int nvmlShutdown(void);
EXPORT int nvmlDeviceGetCount_v2(unsigned *count);
EXPORT int nvmlDeviceGetHandleByIndex_v2(unsigned index, void **device);
EXPORT int nvmlDeviceGetName(void *device, char *name, unsigned length);
EXPORT int nvmlDeviceGetUUID(void *device, char *uuid, unsigned length);
EXPORT int nvmlDeviceGetClockInfo(void *device, int type, unsigned *clock);
EXPORT int nvmlDeviceGetPowerUsage(void *device, unsigned *power);
EXPORT int nvmlDeviceGetTemperature(void *device, int sensor, unsigned *temp);
EXPORT int nvmlDeviceGetCurrentClocksThrottleReasons(void *device, unsigned long long *mask);
EXPORT const char *nvmlErrorString(int result);

/* nvmlPciInfo_t as NVML documents it */
typedef struct {
    char busIdLegacy[16];
    unsigned domain, bus, device, pciDeviceId, pciSubSystemId;
    char busId[32];
} nvmlPciInfo_t;
EXPORT int nvmlDeviceGetPciInfo_v3(void *device, nvmlPciInfo_t *pci);

static const char *env(const char *name, const char *dflt)
{
    const char *v = getenv(name);
    return v ? v : dflt;
}

/* The scripted value of `name`: 0 and *out, or "!N"'s N. */
static int scripted(const char *name, const char *dflt, unsigned long long *out)
{
    const char *v = env(name, dflt);
    if (v[0] == '!')
        return atoi(v + 1);
    *out = strtoull(v, NULL, 0);
    return 0;
}

static void log_call(const char *what)
{
    const char *path = getenv("STANDIN_NVML_CALLS");
    FILE *f = path ? fopen(path, "a") : NULL;
    if (f) {
        fprintf(f, "%s\n", what);
        fclose(f);
    }
}

EXPORT int nvmlInit_v2(void)
{
    log_call("init");
    return atoi(env("STANDIN_NVML_INIT", "0"));
}

EXPORT int nvmlShutdown(void)
{
    log_call("shutdown");
    return 0;
}

static unsigned ndevices(void)
{
    const char *v = env("STANDIN_NVML_NAMES", "NVIDIA Stand-in");
    if (!v[0])
        return 0;
    unsigned n = 1;
    for (; *v; v++)
        n += *v == '|';
    return n;
}

EXPORT int nvmlDeviceGetCount_v2(unsigned *count)
{
    *count = ndevices();
    return 0;
}

EXPORT int nvmlDeviceGetHandleByIndex_v2(unsigned index, void **device)
{
    if (index >= ndevices())
        return 2;   /* NVML_ERROR_INVALID_ARGUMENT */
    *device = (void *)(uintptr_t)(index + 1);
    return 0;
}

EXPORT int nvmlDeviceGetName(void *device, char *name, unsigned length)
{
    const char *v = env("STANDIN_NVML_NAMES", "NVIDIA Stand-in");
    for (unsigned i = 1; i < (unsigned)(uintptr_t)device; i++)
        v = strchr(v, '|') + 1;
    size_t n = strcspn(v, "|");
    if (v[0] == '!')   /* "!N": this device's name is error N */
        return atoi(v + 1);
    if (n >= length)
        return 7;   /* NVML_ERROR_INSUFFICIENT_SIZE */
    memcpy(name, v, n);
    name[n] = '\0';
    return 0;
}

EXPORT int nvmlDeviceGetPciInfo_v3(void *device, nvmlPciInfo_t *pci)
{
    const char *v = env("STANDIN_NVML_PCI", "");
    for (unsigned i = 1; i < (unsigned)(uintptr_t)device && strchr(v, '|'); i++)
        v = strchr(v, '|') + 1;
    memset(pci, 0, sizeof *pci);
    if (sscanf(v, "%x:%x:%x", &pci->domain, &pci->bus, &pci->device) != 3)
        pci->bus = 1;
    snprintf(pci->busId, sizeof pci->busId, "%08X:%02X:%02X.0", pci->domain, pci->bus,
             pci->device);
    return 0;
}

EXPORT int nvmlDeviceGetUUID(void *device, char *uuid, unsigned length)
{
    (void)device;
    snprintf(uuid, length, "%s", env("STANDIN_NVML_UUID", "GPU-00000000-stand-in"));
    return 0;
}

EXPORT int nvmlDeviceGetClockInfo(void *device, int type, unsigned *clock)
{
    (void)device;
    unsigned long long v = 0;
    if (type != 1 && type != 2)
        return 2;
    int r = scripted(type == 1 ? "STANDIN_NVML_SM" : "STANDIN_NVML_MEM",
                     type == 1 ? "1980" : "2619", &v);
    *clock = (unsigned)v;
    return r;
}

EXPORT int nvmlDeviceGetPowerUsage(void *device, unsigned *power)
{
    (void)device;
    unsigned long long v = 0;
    int r = scripted("STANDIN_NVML_POWER", "312456", &v);
    *power = (unsigned)v;
    return r;
}

EXPORT int nvmlDeviceGetTemperature(void *device, int sensor, unsigned *temp)
{
    (void)device;
    unsigned long long v = 0;
    if (sensor != 0)
        return 2;
    int r = scripted("STANDIN_NVML_TEMP", "61", &v);
    *temp = (unsigned)v;
    return r;
}

#ifndef STANDIN_NO_THROTTLE
EXPORT int nvmlDeviceGetCurrentClocksThrottleReasons(void *device, unsigned long long *mask)
{
    (void)device;
    return scripted("STANDIN_NVML_THROTTLE", "0x5", mask);
}
#endif

EXPORT const char *nvmlErrorString(int result)
{
    switch (result) {
    case 0: return "Success";
    case 3: return "Not Supported";
    case 4: return "Insufficient Permissions";
    case 9: return "Driver Not Loaded";
    default: return "Unknown Error";
    }
}
