/* common/nvml.h against tests/unit/nvml_standin.c, a stand-in for libnvidia-ml.so.1 with
 * NVML's documented entry points returning scripted values and error codes (meson passes
 * its paths as NVML_STANDIN and NVML_STANDIN_PARTIAL, the latter without the throttle
 * reasons' entry point): values read, the device matched to GL_RENDERER, errors mapped
 * to NVML's messages, throttle bits decoded, the library absent. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/nvml.h"

static const char *const script[] = {"STANDIN_NVML_INIT", "STANDIN_NVML_NAMES",
    "STANDIN_NVML_SM", "STANDIN_NVML_MEM", "STANDIN_NVML_POWER", "STANDIN_NVML_TEMP",
    "STANDIN_NVML_THROTTLE", "STANDIN_NVML_UUID", "STANDIN_NVML_CALLS", "STANDIN_NVML_PCI"};

static int standin(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof script / sizeof *script; i++)
        unsetenv(script[i]);
    const char *lib = getenv("NVML_STANDIN");
    assert_non_null(lib);
    setenv("SHADESWEEP_NVML_LIBRARY", lib, 1);
    return 0;
}

static void test_values_read(void **state)
{
    (void)state;
    char why[256] = "";
    nvml *n = nvml_open("NVIDIA Stand-in/PCIe/SSE2", NULL, why, sizeof why);
    assert_non_null(n);
    assert_string_equal(nvml_device_name(n), "NVIDIA Stand-in");
    assert_string_equal(nvml_device_uuid(n), "GPU-00000000-stand-in");
    assert_string_equal(nvml_matched_by(n), "name");
    nvml_sample s;
    char notes[NVML_FIELDS][128];
    nvml_read(n, &s, notes);
    assert_true(s.sm_mhz == 1980 && s.mem_mhz == 2619 && s.temp_c == 61);
    assert_true(fabs(s.power_w - 312.456) < 1e-9);   /* milliwatts to watts */
    assert_true(s.throttle_known);
    assert_int_equal(s.throttle, 0x5);
    for (int i = 0; i < NVML_FIELDS; i++)
        assert_string_equal(notes[i], "");
    nvml_close(n);
    char line[320] = "x";
    nvml_availability(line, sizeof line);   /* a device: nothing to say */
    assert_string_equal(line, "");
}

static void test_device_matched_to_gl(void **state)
{
    (void)state;
    setenv("STANDIN_NVML_NAMES", "NVIDIA A100-SXM4-40GB|NVIDIA H100 80GB HBM3|"
           "NVIDIA H100 80GB HBM3", 1);
    setenv("STANDIN_NVML_PCI", "0:17:0|0:65:0|0:ca:0", 1);
    char why[256];
    /* by name: the first that GL_RENDERER names */
    nvml *n = nvml_open("NVIDIA H100 80GB HBM3/PCIe/SSE2", NULL, why, sizeof why);
    assert_non_null(n);
    assert_string_equal(nvml_device_name(n), "NVIDIA H100 80GB HBM3");
    assert_string_equal(nvml_matched_by(n), "name");
    nvml_close(n);
    /* by PCI address: two of a name told apart (the address wins over the name) */
    n = nvml_open("NVIDIA H100 80GB HBM3/PCIe/SSE2", "0000:ca:00.0", why, sizeof why);
    assert_non_null(n);
    assert_string_equal(nvml_matched_by(n), "pci");
    nvml_sample s;
    nvml_read(n, &s, NULL);
    nvml_close(n);
    n = nvml_open(NULL, "0000:17:00.0", why, sizeof why);
    assert_non_null(n);
    assert_string_equal(nvml_device_name(n), "NVIDIA A100-SXM4-40GB");
    assert_string_equal(nvml_matched_by(n), "pci");
    nvml_close(n);
    /* a device NVML cannot name is skipped; none it can: NVML's message */
    setenv("STANDIN_NVML_NAMES", "NVIDIA A100-SXM4-40GB|!4", 1);
    n = nvml_open(NULL, "0000:65:00.0", why, sizeof why);
    assert_non_null(n);
    assert_string_equal(nvml_device_name(n), "NVIDIA A100-SXM4-40GB");
    assert_string_equal(nvml_matched_by(n), "none");
    nvml_close(n);
    setenv("STANDIN_NVML_NAMES", "!4|!4", 1);
    assert_null(nvml_open(NULL, NULL, why, sizeof why));
    assert_string_equal(why, "NVML device 1: Insufficient Permissions");
    setenv("STANDIN_NVML_NAMES", "NVIDIA A100-SXM4-40GB|NVIDIA H100 80GB HBM3|"
           "NVIDIA H100 80GB HBM3", 1);
    /* a GL device NVML does not name (llvmpipe) at no NVML address: device 0, said so */
    n = nvml_open("llvmpipe (LLVM 15.0.7, 256 bits)", "0000:99:00.0", why, sizeof why);
    assert_non_null(n);
    assert_string_equal(nvml_device_name(n), "NVIDIA A100-SXM4-40GB");
    assert_string_equal(nvml_matched_by(n), "none");
    nvml_close(n);
}

/* A DRM device file's PCI address, from a sysfs made here. */
static void test_drm_pci(void **state)
{
    (void)state;
    char root[] = "/tmp/shadesweep-sysfs-XXXXXX";
    assert_non_null(mkdtemp(root));
    char dir[256], link[300];
    snprintf(dir, sizeof dir, "%s/class", root);
    assert_int_equal(mkdir(dir, 0700), 0);
    snprintf(dir, sizeof dir, "%s/class/drm", root);
    assert_int_equal(mkdir(dir, 0700), 0);
    snprintf(dir, sizeof dir, "%s/class/drm/card1", root);
    assert_int_equal(mkdir(dir, 0700), 0);
    snprintf(link, sizeof link, "%s/device", dir);
    assert_int_equal(symlink("../../../0000:00:01.0/0000:CA:00.0", link), 0);
    char bus[32] = "";
    assert_true(nvml_drm_pci(root, "/dev/dri/card1", bus, sizeof bus));
    assert_string_equal(bus, "0000:ca:00.0");
    assert_false(nvml_drm_pci(root, "/dev/dri/card2", bus, sizeof bus));   /* not there */
    assert_false(nvml_drm_pci(root, "EGL_MESA_device_software", bus, sizeof bus));
    assert_false(nvml_drm_pci(root, NULL, bus, sizeof bus));
    unlink(link);
    rmdir(dir);
    snprintf(dir, sizeof dir, "%s/class/drm", root);
    rmdir(dir);
    snprintf(dir, sizeof dir, "%s/class", root);
    rmdir(dir);
    rmdir(root);
}

static void test_errors_mapped(void **state)
{
    (void)state;
    setenv("STANDIN_NVML_POWER", "!3", 1);      /* NVML_ERROR_NOT_SUPPORTED */
    setenv("STANDIN_NVML_THROTTLE", "!4", 1);   /* NVML_ERROR_NO_PERMISSION */
    setenv("STANDIN_NVML_SM", "1410", 1);
    char why[256];
    nvml *n = nvml_open(NULL, NULL, why, sizeof why);
    assert_non_null(n);
    nvml_sample s;
    char notes[NVML_FIELDS][128];
    nvml_read(n, &s, notes);
    assert_true(s.sm_mhz == 1410 && s.mem_mhz == 2619 && s.temp_c == 61);
    assert_true(isnan(s.power_w));
    assert_false(s.throttle_known);
    assert_string_equal(notes[0], "");
    assert_string_equal(notes[2], "nvmlDeviceGetPowerUsage: Not Supported");
    assert_string_equal(notes[4],
                        "nvmlDeviceGetCurrentClocksThrottleReasons: Insufficient Permissions");
    nvml_read(n, &s, NULL);   /* no notes wanted */
    assert_true(s.sm_mhz == 1410);
    nvml_close(n);

    /* nvmlInit_v2 fails: no reader, NVML's message, and no nvmlShutdown after it */
    char calls[] = "/tmp/shadesweep-nvml-calls-XXXXXX";
    int fd = mkstemp(calls);
    assert_true(fd >= 0);
    close(fd);
    setenv("STANDIN_NVML_CALLS", calls, 1);
    setenv("STANDIN_NVML_INIT", "9", 1);   /* NVML_ERROR_DRIVER_NOT_LOADED */
    assert_null(nvml_open(NULL, NULL, why, sizeof why));
    assert_string_equal(why, "nvmlInit_v2: Driver Not Loaded");
    /* no device: nvmlShutdown balances nvmlInit_v2 */
    setenv("STANDIN_NVML_INIT", "0", 1);
    setenv("STANDIN_NVML_NAMES", "", 1);
    assert_null(nvml_open(NULL, NULL, why, sizeof why));
    assert_string_equal(why, "NVML sees no NVIDIA device");
    char line[320];
    nvml_availability(line, sizeof line);
    assert_string_equal(line, "clocks: not recorded: NVML sees no NVIDIA device");
    FILE *f = fopen(calls, "r");
    assert_non_null(f);
    char got[128] = "";
    size_t nread = fread(got, 1, sizeof got - 1, f);
    fclose(f);
    got[nread] = '\0';
    unlink(calls);
    assert_string_equal(got, "init\ninit\nshutdown\ninit\nshutdown\n");

    /* codes without the library's nvmlErrorString: NVML's documented texts */
    assert_string_equal(nvml_error_message(NULL, 3), "Not Supported");
    assert_string_equal(nvml_error_message(NULL, 15), "GPU is lost");
    assert_string_equal(nvml_error_message(NULL, 999), "Unknown Error");
}

static void test_throttle_decoded(void **state)
{
    (void)state;
    const char *names[8];
    char buf[8][16];
    size_t k = nvml_throttle_names(0x1 | 0x4 | 0x8 | 0x40 | 0x100 | (1ull << 40), names, buf, 8);
    assert_int_equal(k, 6);
    assert_string_equal(names[0], "gpu_idle");
    assert_string_equal(names[1], "sw_power_cap");
    assert_string_equal(names[2], "hw_slowdown");
    assert_string_equal(names[3], "hw_thermal_slowdown");
    assert_string_equal(names[4], "display_clock_setting");
    assert_string_equal(names[5], "bit_40");   /* not in NVML's documentation */
    k = nvml_throttle_names(0x2 | 0x10 | 0x20 | 0x80, names, buf, 8);
    assert_int_equal(k, 4);
    assert_string_equal(names[0], "applications_clocks_setting");
    assert_string_equal(names[1], "sync_boost");
    assert_string_equal(names[2], "sw_thermal_slowdown");
    assert_string_equal(names[3], "hw_power_brake_slowdown");
    assert_int_equal(nvml_throttle_names(0, names, buf, 8), 0);
    assert_int_equal(nvml_throttle_names(0x1ff, names, buf, 2), 2);   /* at most max */
}

static void test_library_absent(void **state)
{
    (void)state;
    char why[256], line[320];
    setenv("SHADESWEEP_NVML_LIBRARY", "/nonexistent/libnvidia-ml.so.1", 1);
    assert_null(nvml_open(NULL, NULL, why, sizeof why));
    assert_string_equal(why, "/nonexistent/libnvidia-ml.so.1 cannot be loaded (no NVIDIA driver)");
    nvml_availability(line, sizeof line);
    assert_string_equal(line, "clocks: not recorded: /nonexistent/libnvidia-ml.so.1 cannot be "
                              "loaded (no NVIDIA driver)");
    /* a library without an entry point shadesweep needs: refused, by name */
    setenv("SHADESWEEP_NVML_LIBRARY", getenv("NVML_STANDIN_PARTIAL"), 1);
    assert_null(nvml_open(NULL, NULL, why, sizeof why));
    assert_string_equal(why, "nvmlDeviceGetCurrentClocksThrottleReasons not found in the library");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_values_read, standin),
        cmocka_unit_test_setup(test_device_matched_to_gl, standin),
        cmocka_unit_test_setup(test_drm_pci, standin),
        cmocka_unit_test_setup(test_errors_mapped, standin),
        cmocka_unit_test_setup(test_throttle_decoded, standin),
        cmocka_unit_test_setup(test_library_absent, standin),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
