/* results/device_profile.h: a figure's median and spread (the largest deviation from the
 * median: every repeat lies within it), the cache key (FNV-1a 64 of the GL strings,
 * pinned: a changed key orphans every cached profile) and the cache folder's choice,
 * and device.yaml written whole with every field. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "results/device_profile.h"
#include "common/fsutil.h"
#include "tempdir.h"

static void test_median_spread(void **state)
{
    (void)state;
    double m, s;
    double odd[] = {5, 1, 3};   /* median 3, farthest 5 - 3 = 2 ... and 3 - 1 = 2 */
    device_median_spread(odd, 3, &m, &s);
    assert_true(m == 3 && s == 2);
    assert_true(odd[0] == 5 && odd[1] == 1);   /* the input is left alone */
    double even[] = {10, 2, 4, 6};   /* median (4 + 6) / 2 = 5; farthest 10 */
    device_median_spread(even, 4, &m, &s);
    assert_true(m == 5 && s == 5);
    double one = 7;
    device_median_spread(&one, 1, &m, &s);
    assert_true(m == 7 && s == 0);
    device_median_spread(NULL, 0, &m, &s);
    assert_true(isnan(m) && isnan(s));
    double many[DEVICE_PROFILE_MAX_REPEATS + 5];
    for (size_t i = 0; i < sizeof many / sizeof *many; i++)
        many[i] = i < DEVICE_PROFILE_MAX_REPEATS ? 1 : 1000;   /* past the cap: not read */
    device_median_spread(many, sizeof many / sizeof *many, &m, &s);
    assert_true(m == 1 && s == 0);
}

static void llvmpipe(device_profile *p)
{
    memset(p, 0, sizeof *p);
    strcpy(p->vendor, "Mesa/X.org");
    strcpy(p->renderer, "llvmpipe (LLVM 15.0.6, 256 bits)");
    strcpy(p->version, "4.5 (Core Profile) Mesa 22.3.6");
    strcpy(p->glsl_version, "4.50");
    strcpy(p->backend, "egl-surfaceless");
}

static void test_key(void **state)
{
    (void)state;
    static device_profile p;
    char key[17], other[17];
    llvmpipe(&p);
    device_profile_key(&p, key);
    assert_string_equal(key, "6be8c0fa09da3103");   /* this machine's llvmpipe */
    /* every string is part of it, and a string's end is: "ab" + "" is not "a" + "b" */
    char *fields[] = {p.vendor, p.renderer, p.version, p.glsl_version, p.backend, p.device};
    for (size_t i = 0; i < 6; i++) {
        char keep[256];
        strcpy(keep, fields[i]);
        strcat(fields[i], "x");
        device_profile_key(&p, other);
        assert_string_not_equal(key, other);
        strcpy(fields[i], keep);
    }
    strcpy(p.version, "4.5 (Core Profile) Mesa 22.3.");
    strcpy(p.glsl_version, "64.50");
    device_profile_key(&p, other);
    assert_string_not_equal(key, other);
    /* the figures and the host are not: the same device and driver, the same file */
    llvmpipe(&p);
    double x[] = {1, 2, 3};
    assert_true(device_profile_add(&p, "fill_rgba8_1x", "Gsamples/s", x, 3));
    strcpy(p.host, "elsewhere");
    device_profile_key(&p, other);
    assert_string_equal(key, other);
}

static void test_cache_dir(void **state)
{
    (void)state;
    char dir[512], path[600];
    static device_profile p;
    llvmpipe(&p);
    setenv("XDG_CACHE_HOME", "/x/cache", 1);
    setenv("HOME", "/home/u", 1);
    assert_true(device_profile_cache_dir(dir, sizeof dir));
    assert_string_equal(dir, "/x/cache/shadesweep");
    assert_true(device_profile_cache_path(&p, path, sizeof path));
    assert_string_equal(path, "/x/cache/shadesweep/device-6be8c0fa09da3103.yaml");
    setenv("XDG_CACHE_HOME", "relative", 1);   /* the XDG spec: relative is ignored */
    assert_true(device_profile_cache_dir(dir, sizeof dir));
    assert_string_equal(dir, "/home/u/.cache/shadesweep");
    unsetenv("XDG_CACHE_HOME");
    assert_true(device_profile_cache_dir(dir, sizeof dir));
    assert_string_equal(dir, "/home/u/.cache/shadesweep");
    unsetenv("HOME");
    assert_false(device_profile_cache_dir(dir, sizeof dir));
    assert_false(device_profile_cache_path(&p, path, sizeof path));
    assert_false(device_profile_cache_dir(dir, 8));   /* too long for the buffer */
}

static void test_yaml(void **state)
{
    (void)state;
    char dir[128], path[256], err[512];
    assert_int_equal(temp_dir_make(dir, sizeof dir, "device_profile"), 0);
    snprintf(path, sizeof path, "%s/device.yaml", dir);
    static device_profile p;
    llvmpipe(&p);
    p.software = "llvmpipe";
    p.timing = "cpu-finish";
    p.width = p.height = 64;
    double x[] = {2, 4, 3};
    for (int i = 0; i < DEVICE_PROFILE_MAX_FIGURES; i++) {
        char name[32];
        snprintf(name, sizeof name, "figure_%d", i);
        assert_true(device_profile_add(&p, i ? name : "fill_rgba8_1x", "us", x, 3));
    }
    assert_false(device_profile_add(&p, "one_too_many", "us", x, 3));
    assert_true(device_profile_write_yaml(&p, path, err, sizeof err));
    assert_int_equal(count_entries(dir), 1);   /* no temporary left */
    size_t len;
    int e;
    char *text = fs_read_all(path, 0, &len, &e);
    assert_non_null(text);
    const char *want[] = {"key: ", "shadesweep: ", "date: ", "host: ", "cpu: ", "backend: ",
                          "device: ", "vendor: ", "renderer: ", "version: ", "glsl: ",
                          "software_rasterizer: llvmpipe", "timing: cpu-finish",
                          "quick: false", "target_width: 64", "figures:",
                          "  fill_rgba8_1x:\n    median: 3.0\n    spread: 1.0\n    unit: us\n"
                          "    repeats: 3\n"};
    for (size_t i = 0; i < sizeof want / sizeof *want; i++)
        if (!strstr(text, want[i]))
            fail_msg("device.yaml lacks '%s':\n%s", want[i], text);
    free(text);
    remove(path);
    remove(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_median_spread),
        cmocka_unit_test(test_key),
        cmocka_unit_test(test_cache_dir),
        cmocka_unit_test(test_yaml),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
