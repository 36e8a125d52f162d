/* Image I/O through the OpenImageIO shim: exact round trips, conversions, the
 * comparison metrics on images with known differences, and failure paths. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/unit/assert_near.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/fsutil.h"
#include "common/image_io.h"
#include "tests/unit/tempdir.h"

typedef struct fixture {
    char dir[64];
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (f == NULL)
        return -1;
    if (temp_dir_make(f->dir, sizeof f->dir, "test_image_io") != 0) {
        free(f);
        return -1;
    }
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    char err[256];
    bool ok = fs_remove_tree(f->dir, err, sizeof err);
    free(f);
    return ok ? 0 : -1;
}



static image make(int w, int h, int c, image_type t)
{
    image img = {w, h, c, t, NULL};
    size_t n = (size_t)w * (size_t)h * (size_t)c;
    img.pixels = calloc(n, t == IMAGE_F32 ? sizeof(float) : 1);
    assert_non_null(img.pixels);
    return img;
}

static size_t nvalues(const image *img)
{
    return (size_t)img->width * (size_t)img->height * (size_t)img->channels;
}

static uint8_t *u8(const image *img)
{
    return img->pixels;
}

static float *f32(const image *img)
{
    return img->pixels;
}

/* >>round trips */

static void test_png_u8_round_trip(void **state)
{
    fixture *f = *state;
    char err[512] = "", path[128];
    for (int c = 1; c <= 4; c++) {
        image a = make(7, 5, c, IMAGE_U8);
        for (size_t i = 0; i < nvalues(&a); i++)
            u8(&a)[i] = (uint8_t)((i * 37 + 11) % 256);
        snprintf(path, sizeof path, "%s/rt%d.png", f->dir, c);
        assert_true(image_write(path, &a, err, sizeof err));

        image b;
        if (!image_read(path, IMAGE_U8, &b, err, sizeof err)) {
            print_error("%s\n", err);
            fail();
        }
        assert_int_equal(b.width, 7);
        assert_int_equal(b.height, 5);
        assert_int_equal(b.channels, c);
        assert_int_equal(b.type, IMAGE_U8);
        assert_memory_equal(b.pixels, a.pixels, nvalues(&a));
        image_free(&b);
        image_free(&a);
    }
    assert_int_equal(count_entries(f->dir), 4); /* no temporary files */
}

/* image_decode: the same pixels from the file's bytes in memory (no extension: the PNG
 * signature picks the reader); bytes that are no image fail with the name given. */
static void test_decode_from_memory(void **state)
{
    fixture *f = *state;
    char err[512] = "", path[128];
    image a = make(6, 3, 4, IMAGE_U8);
    for (size_t i = 0; i < nvalues(&a); i++)
        u8(&a)[i] = (uint8_t)((i * 53 + 7) % 256);
    snprintf(path, sizeof path, "%s/mem.png", f->dir);
    assert_true(image_write(path, &a, err, sizeof err));
    FILE *in = fopen(path, "rb");
    assert_non_null(in);
    unsigned char bytes[4096];
    size_t n = fread(bytes, 1, sizeof bytes, in);
    fclose(in);
    assert_true(n > 8 && n < sizeof bytes);
    image b;
    if (!image_decode(bytes, n, "texture *0", IMAGE_U8, &b, err, sizeof err)) {
        print_error("%s\n", err);
        fail();
    }
    assert_int_equal(b.width, 6);
    assert_int_equal(b.height, 3);
    assert_int_equal(b.channels, 4);
    assert_memory_equal(b.pixels, a.pixels, nvalues(&a));
    image_free(&b);
    image_free(&a);
    static const char junk[] = "this is not an image";
    assert_false(image_decode(junk, sizeof junk, "junk.png", IMAGE_U8, &b, err, sizeof err));
    assert_true(strncmp(err, "junk.png: cannot read image: ", 29) == 0);
    assert_null(b.pixels);
    assert_false(image_decode(junk, 0, NULL, IMAGE_U8, &b, err, sizeof err));
    assert_string_equal(err, "embedded image: cannot read image: no bytes");
}

static void test_exr_f32_round_trip(void **state)
{
    fixture *f = *state;
    char err[512] = "", path[128];
    image a = make(6, 4, 4, IMAGE_F32);
    for (size_t i = 0; i < nvalues(&a); i++)
        f32(&a)[i] = (float)((double)i * 0.37 - 3.1) * (i % 3 == 0 ? 1000.0f : 0.001f);
    f32(&a)[5] = 1.0f / 3.0f;
    f32(&a)[6] = 1e-30f;
    snprintf(path, sizeof path, "%s/rt.exr", f->dir);
    assert_true(image_write(path, &a, err, sizeof err));

    image b;
    assert_true(image_read(path, IMAGE_F32, &b, err, sizeof err));
    assert_int_equal(b.width, 6);
    assert_int_equal(b.height, 4);
    assert_int_equal(b.channels, 4);
    assert_int_equal(b.type, IMAGE_F32);
    assert_memory_equal(b.pixels, a.pixels, nvalues(&a) * sizeof(float));
    image_free(&b);
    image_free(&a);
    assert_int_equal(count_entries(f->dir), 1);
}

/* Floats into an 8-bit format: clamped to [0,1], scaled by 255, rounded. */
static void test_png_from_f32(void **state)
{
    fixture *f = *state;
    char err[512] = "", path[128];
    image a = make(5, 1, 1, IMAGE_F32);
    const float v[5] = {0.0f, 0.25f, 1.0f, 2.0f, -1.0f};
    memcpy(a.pixels, v, sizeof v);
    snprintf(path, sizeof path, "%s/conv.png", f->dir);
    if (!image_write(path, &a, err, sizeof err)) {
        print_error("%s\n", err);
        fail();
    }

    image b;
    assert_true(image_read(path, IMAGE_U8, &b, err, sizeof err));
    const uint8_t want[5] = {0, 64, 255, 255, 0};
    assert_memory_equal(b.pixels, want, 5);
    image_free(&b);

    /* and an 8-bit file read as floats comes back as v/255 */
    assert_true(image_read(path, IMAGE_F32, &b, err, sizeof err));
    assert_int_equal(b.type, IMAGE_F32);
    for (int i = 0; i < 5; i++)
        assert_near(f32(&b)[i], want[i] / 255.0, 1e-7);
    image_free(&b);
    image_free(&a);
}

/* >>compare */

static void test_compare_identical(void **state)
{
    (void)state;
    char err[256];
    image a = make(8, 8, 3, IMAGE_U8);
    for (size_t i = 0; i < nvalues(&a); i++)
        u8(&a)[i] = (uint8_t)(i * 7);
    image_error e;
    assert_true(image_compare(&a, &a, &e, err, sizeof err));
    assert_true(e.rmse == 0.0);
    assert_true(isinf(e.psnr_db) && e.psnr_db > 0);
    assert_true(e.max_abs == 0.0);
    assert_true(e.frac_over_1_255 == 0.0);
    assert_int_equal(e.nonfinite, 0);
    image_free(&a);
}

static void test_compare_f32_offset(void **state)
{
    (void)state;
    char err[256];
    image a = make(16, 9, 4, IMAGE_F32), b = make(16, 9, 4, IMAGE_F32);
    for (size_t i = 0; i < nvalues(&a); i++) {
        f32(&a)[i] = (float)(i % 17) / 17.0f;
        f32(&b)[i] = f32(&a)[i] + 0.1f;
    }
    image_error e;
    assert_true(image_compare(&a, &b, &e, err, sizeof err));
    assert_near(e.rmse, 0.1, 1e-6);
    assert_near(e.max_abs, 0.1, 1e-6);
    assert_near(e.psnr_db, 20.0, 1e-4); /* 20 log10(1/0.1) */
    assert_true(e.frac_over_1_255 == 1.0);
    assert_int_equal(e.nonfinite, 0);
    image_free(&a);
    image_free(&b);
}

static void test_compare_u8_offset(void **state)
{
    (void)state;
    char err[256];
    image a = make(10, 10, 3, IMAGE_U8), b = make(10, 10, 3, IMAGE_U8);
    for (size_t i = 0; i < nvalues(&a); i++) {
        u8(&a)[i] = (uint8_t)(i % 253);
        u8(&b)[i] = (uint8_t)(u8(&a)[i] + 3);
    }
    image_error e;
    assert_true(image_compare(&a, &b, &e, err, sizeof err));
    assert_near(e.rmse, 3.0 / 255.0, 1e-12);
    assert_near(e.max_abs, 3.0 / 255.0, 1e-12);
    assert_near(e.psnr_db, 20.0 * log10(255.0 / 3.0), 1e-9);
    assert_true(e.frac_over_1_255 == 1.0);
    image_free(&a);
    image_free(&b);
}

/* One pixel off by 10, one off by exactly 1 (not more than 1/255): 1 of 100 pixels. */
static void test_compare_single_pixel(void **state)
{
    (void)state;
    char err[256];
    image a = make(10, 10, 3, IMAGE_U8), b = make(10, 10, 3, IMAGE_U8);
    for (size_t i = 0; i < nvalues(&a); i++)
        u8(&a)[i] = u8(&b)[i] = 100;
    u8(&b)[3 * 42 + 1] = 110;
    u8(&b)[3 * 7 + 2] = 99;
    image_error e;
    assert_true(image_compare(&a, &b, &e, err, sizeof err));
    assert_true(e.frac_over_1_255 == 0.01);
    assert_near(e.rmse, sqrt((100.0 + 1.0) / (255.0 * 255.0) / 300.0), 1e-15);
    assert_near(e.max_abs, 10.0 / 255.0, 1e-15);

    /* the same with floats */
    image fa = make(10, 10, 3, IMAGE_F32), fb = make(10, 10, 3, IMAGE_F32);
    for (size_t i = 0; i < nvalues(&fa); i++)
        f32(&fa)[i] = f32(&fb)[i] = 0.5f;
    f32(&fb)[3 * 13] = 0.25f;
    f32(&fb)[3 * 14] = 0.5f + 0.5f / 255.0f; /* within 1/255: not counted */
    assert_true(image_compare(&fa, &fb, &e, err, sizeof err));
    assert_true(e.frac_over_1_255 == 0.01);
    assert_near(e.max_abs, 0.25, 0);
    image_free(&fa);
    image_free(&fb);
    image_free(&a);
    image_free(&b);
}

static void test_compare_mixed_types(void **state)
{
    (void)state;
    char err[256];
    image a = make(4, 4, 1, IMAGE_U8), b = make(4, 4, 1, IMAGE_F32);
    for (size_t i = 0; i < 16; i++) {
        u8(&a)[i] = (uint8_t)(i * 16);
        f32(&b)[i] = (float)(i * 16) / 255.0f;
    }
    image_error e;
    assert_true(image_compare(&a, &b, &e, err, sizeof err));
    assert_true(e.rmse < 1e-7);
    assert_true(e.frac_over_1_255 == 0.0);
    image_free(&a);
    image_free(&b);
}

static void test_nonfinite(void **state)
{
    (void)state;
    char err[256];
    image a = make(4, 4, 3, IMAGE_F32), b = make(4, 4, 3, IMAGE_F32);
    for (size_t i = 0; i < nvalues(&a); i++)
        f32(&a)[i] = f32(&b)[i] = 0.5f;
    assert_int_equal(image_count_nonfinite(&a), 0);
    f32(&a)[0] = NAN;
    f32(&a)[1] = NAN;   /* same pixel as [0] */
    f32(&a)[20] = INFINITY;
    f32(&a)[47] = -INFINITY;
    assert_int_equal(image_count_nonfinite(&a), 4);
    f32(&b)[30] = NAN;
    assert_int_equal(image_count_nonfinite(&b), 1);

    image_error e;
    assert_true(image_compare(&a, &b, &e, err, sizeof err));
    assert_int_equal(e.nonfinite, 5);
    /* the finite values agree: no error among them; 4 pixels hold a non-finite value */
    assert_true(e.rmse == 0.0);
    assert_true(e.max_abs == 0.0);
    assert_near(e.frac_over_1_255, 4.0 / 16.0, 0);

    image c = make(2, 2, 3, IMAGE_U8);
    assert_int_equal(image_count_nonfinite(&c), 0);
    image_free(&a);
    image_free(&b);
    image_free(&c);
}

static void test_compare_size_mismatch(void **state)
{
    (void)state;
    char err[256] = "";
    image a = make(4, 4, 3, IMAGE_U8), b = make(4, 5, 3, IMAGE_U8), c = make(4, 4, 4, IMAGE_U8);
    image_error e;
    assert_false(image_compare(&a, &b, &e, err, sizeof err));
    assert_non_null(strstr(err, "4x4"));
    assert_non_null(strstr(err, "4x5"));
    err[0] = '\0';
    assert_false(image_compare(&a, &c, &e, err, sizeof err));
    assert_non_null(strstr(err, "3 channels"));
    assert_non_null(strstr(err, "4 channels"));
    image_free(&a);
    image_free(&b);
    image_free(&c);
}

/* >>failures */

static void test_write_failures_leave_nothing(void **state)
{
    fixture *f = *state;
    char err[512], path[256];
    image a = make(3, 3, 3, IMAGE_U8);

    /* a directory that is a regular file (fails even for root) */
    snprintf(path, sizeof path, "%s/file.txt", f->dir);
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fclose(fp);
    snprintf(path, sizeof path, "%s/file.txt/x.png", f->dir);
    err[0] = '\0';
    assert_false(image_write(path, &a, err, sizeof err));
    assert_non_null(strstr(err, path));
    assert_int_equal(count_entries(f->dir), 1); /* only file.txt */

    /* a directory that does not exist */
    snprintf(path, sizeof path, "%s/nope/x.exr", f->dir);
    err[0] = '\0';
    assert_false(image_write(path, &a, err, sizeof err));
    assert_non_null(strstr(err, path));
    assert_non_null(strstr(err, "No such file"));
    assert_false(fs_exists(path));

    /* a format nobody writes */
    snprintf(path, sizeof path, "%s/x.notaformat", f->dir);
    err[0] = '\0';
    assert_false(image_write(path, &a, err, sizeof err));
    assert_true(strlen(err) > 0);
    snprintf(path, sizeof path, "%s/noext", f->dir);
    err[0] = '\0';
    assert_false(image_write(path, &a, err, sizeof err));
    assert_true(strlen(err) > 0);
    assert_int_equal(count_entries(f->dir), 1);

    /* no pixels */
    image none = {3, 3, 3, IMAGE_U8, NULL};
    snprintf(path, sizeof path, "%s/x.png", f->dir);
    assert_false(image_write(path, &none, err, sizeof err));
    assert_int_equal(count_entries(f->dir), 1);
    image_free(&a);
}

static void test_read_failures(void **state)
{
    fixture *f = *state;
    char err[512] = "", path[256];
    image b;
    snprintf(path, sizeof path, "%s/missing.png", f->dir);
    assert_false(image_read(path, IMAGE_U8, &b, err, sizeof err));
    assert_non_null(strstr(err, path));
    assert_non_null(strstr(err, "No such file"));
    assert_null(b.pixels);
    image_free(&b); /* harmless after a failure */

    snprintf(path, sizeof path, "%s/garbage.png", f->dir);
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fputs("this is not a PNG file\n", fp);
    fclose(fp);
    err[0] = '\0';
    assert_false(image_read(path, IMAGE_F32, &b, err, sizeof err));
    assert_true(strlen(err) > 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_png_u8_round_trip, setup, teardown),
        cmocka_unit_test_setup_teardown(test_exr_f32_round_trip, setup, teardown),
        cmocka_unit_test_setup_teardown(test_decode_from_memory, setup, teardown),
        cmocka_unit_test_setup_teardown(test_png_from_f32, setup, teardown),
        cmocka_unit_test(test_compare_identical),
        cmocka_unit_test(test_compare_f32_offset),
        cmocka_unit_test(test_compare_u8_offset),
        cmocka_unit_test(test_compare_single_pixel),
        cmocka_unit_test(test_compare_mixed_types),
        cmocka_unit_test(test_nonfinite),
        cmocka_unit_test(test_compare_size_mismatch),
        cmocka_unit_test_setup_teardown(test_write_failures_leave_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_read_failures, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
