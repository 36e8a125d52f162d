/* The error reference's image arithmetic (results/image_ref.h) on small synthetic
 * images with exact expected values: the K x K box filter, the display conversion,
 * the edge rule and the edge-weighted RMSE. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "common/image_io.h"
#include "results/image_ref.h"

/* K = 2 on a 4x2 source (one RGBA value per pixel, v = x + 4 y, channel c adds 10 c):
 * each output pixel is the mean of its 2x2 block, exactly. */
static void test_box_filter_k2(void **state)
{
    (void)state;
    float src[4 * 2 * 4], dst[2 * 1 * 4];
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 4; x++)
            for (int c = 0; c < 4; c++)
                src[(y * 4 + x) * 4 + c] = (float)(x + 4 * y + 10 * c);
    assert_true(image_box_filter(src, 2, 1, 2, dst));
    /* block 0: x 0-1, y 0-1: (0 + 1 + 4 + 5) / 4 = 2.5; block 1: (2 + 3 + 6 + 7) / 4 = 4.5 */
    for (int c = 0; c < 4; c++) {
        assert_true(dst[c] == 2.5f + 10.0f * (float)c);
        assert_true(dst[4 + c] == 4.5f + 10.0f * (float)c);
    }
}

/* K = 4: a 4x4 block of which 4 pixels are 1 and 12 are 0 gives 0.25; linear HDR values
 * above 1 are averaged as they are (no clamp before the filter): 16 and 15 zeros give 1. */
static void test_box_filter_k4_linear(void **state)
{
    (void)state;
    float src[8 * 4 * 4] = {0}, dst[2 * 1 * 4];
    for (int x = 0; x < 4; x++)
        src[(0 * 8 + x) * 4 + 0] = 1.0f;     /* block 0, red: its top row */
    src[(3 * 8 + 7) * 4 + 1] = 16.0f;        /* block 1, green: one pixel of 16 */
    assert_true(image_box_filter(src, 2, 1, 4, dst));
    assert_true(dst[0] == 0.25f && dst[1] == 0.0f && dst[2] == 0.0f && dst[3] == 0.0f);
    assert_true(dst[4] == 0.0f && dst[5] == 1.0f && dst[6] == 0.0f && dst[7] == 0.0f);
    /* K = 1 is a copy */
    float one[2 * 4];
    assert_true(image_box_filter(src, 2, 1, 1, one));
    assert_memory_equal(one, src, sizeof one);
    assert_false(image_box_filter(src, 2, 1, 0, dst));
    assert_false(image_box_filter(src, 0, 1, 2, dst));
}

/* The resolve's clamp and the RGBA8 rounding; flip turns GL's bottom-first rows. */
static void test_display(void **state)
{
    (void)state;
    const float src[2 * 1 * 4] = {-1.0f, 0.2f, 2.0f, 0.5f, NAN, 1.0f, 51.0f / 255.0f, 7.0f};
    uint8_t out[8];
    image_display_rgba8(src, 2, 1, false, 1.0f, false, out);
    const uint8_t want[8] = {0, 51, 255, 255, 0, 255, 51, 255};
    assert_memory_equal(out, want, sizeof want);

    const float rows[1 * 2 * 4] = {0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f};
    uint8_t flipped[8];
    image_display_rgba8(rows, 1, 2, true, 1.0f, false, flipped);
    const uint8_t want_flipped[8] = {255, 255, 255, 255, 0, 0, 0, 255};
    assert_memory_equal(flipped, want_flipped, sizeof want_flipped);
}

/* PBR Neutral and sRGB against values computed by hand from the tone mapper's
 * specification (Khronos, 2024) and IEC 61966-2-1, independently of image_ref.c:
 *   (0.5, 0.5, 0.5): f = 0.04 (min > 0.08), peak 0.46 <= 0.76: 0.46, sRGB 181/255
 *   (2, 1, 0.5): f = 0.04, p = 1.96, pn = 1 - 0.24^2 / 1.44 = 0.96, g = 1 / 1.15:
 *                (0.96, 0.534091, 0.321136), sRGB (250, 193, 154)/255
 *   (0.1, 0.04, 0.04): f = 0.04 - 0.04^2 / 0.16 = 0.03: (0.07, 0.01, 0.01)
 * exposure 0.5 halves the input first (the same colours given twice as bright). */
static void test_pbr_neutral(void **state)
{
    (void)state;
    float a[3] = {0.5f, 0.5f, 0.5f}, b[3] = {2.0f, 1.0f, 0.5f}, c[3] = {0.1f, 0.04f, 0.04f};
    image_pbr_neutral(a);
    image_pbr_neutral(b);
    image_pbr_neutral(c);
    for (int k = 0; k < 3; k++)
        assert_float_equal(a[k], 0.46f, 1e-6f);
    assert_float_equal(b[0], 0.96f, 1e-5f);
    assert_float_equal(b[1], 0.534091f, 1e-5f);
    assert_float_equal(b[2], 0.321136f, 1e-5f);
    assert_float_equal(c[0], 0.07f, 1e-6f);
    assert_float_equal(c[1], 0.01f, 1e-6f);
    assert_float_equal(image_srgb_encode(0.002f), 0.002f * 12.92f, 1e-7f);
    assert_float_equal(image_srgb_encode(1.0f), 1.0f, 1e-6f);
    const float src[2 * 4] = {1.0f, 1.0f, 1.0f, 1.0f, 4.0f, 2.0f, 1.0f, 1.0f};
    uint8_t out[8];
    image_display_rgba8(src, 2, 1, false, 0.5f, true, out);
    const uint8_t want[8] = {181, 181, 181, 255, 250, 193, 154, 255};
    assert_memory_equal(out, want, sizeof want);
}

static void fill_gray(uint8_t *px, size_t i, uint8_t v)
{
    px[i * 4 + 0] = px[i * 4 + 1] = px[i * 4 + 2] = v;
    px[i * 4 + 3] = 255;
}

/* 4x3, columns 0-1 at 100 and 2-3 at 126: a step of 26/255 > 0.1 marks columns 1 and
 * 2 (6 pixels); at 125, a step of 25/255 < 0.1 marks none. */
static void test_edge_mask_threshold(void **state)
{
    (void)state;
    uint8_t px[4 * 3 * 4], mask[12];
    image ref = {.width = 4, .height = 3, .channels = 4, .type = IMAGE_U8, .pixels = px};
    for (size_t i = 0; i < 12; i++)
        fill_gray(px, i, i % 4 < 2 ? 100 : 126);
    assert_int_equal(image_edge_mask(&ref, mask), 6);
    for (size_t i = 0; i < 12; i++)
        assert_int_equal(mask[i], i % 4 == 1 || i % 4 == 2);
    for (size_t i = 0; i < 12; i++)
        fill_gray(px, i, i % 4 < 2 ? 100 : 125);
    assert_int_equal(image_edge_mask(&ref, mask), 0);
    /* luminance, not a channel: pure blue of 255 on black is 0.0722 (no edge), pure
     * red of 255 is 0.2126 (an edge) */
    memset(px, 0, sizeof px);
    for (size_t i = 0; i < 12; i++)
        px[i * 4 + 3] = 255;
    px[5 * 4 + 2] = 255;
    assert_int_equal(image_edge_mask(&ref, mask), 0);
    px[5 * 4 + 0] = 255;   /* pixel (1, 1) and its four neighbours */
    assert_int_equal(image_edge_mask(&ref, mask), 5);
}

/* Edge RMSE: the same definition as image_compare's rmse (every channel, v / 255),
 * over the reference's edge pixels only. */
static void test_edge_rmse(void **state)
{
    (void)state;
    uint8_t r[4 * 3 * 4], a[4 * 3 * 4];
    image ref = {.width = 4, .height = 3, .channels = 4, .type = IMAGE_U8, .pixels = r};
    image run = {.width = 4, .height = 3, .channels = 4, .type = IMAGE_U8, .pixels = a};
    for (size_t i = 0; i < 12; i++)
        fill_gray(r, i, i % 4 < 2 ? 0 : 255);   /* edges: columns 1 and 2 */
    memcpy(a, r, sizeof a);
    double rmse = -1;
    size_t edges = 0;
    char err[200];
    assert_true(image_edge_rmse(&run, &ref, &rmse, &edges, err, sizeof err));
    assert_true(rmse == 0.0);
    assert_int_equal(edges, 6);
    /* one edge pixel off by 51 in red, one non-edge pixel off by 25 in green */
    a[(0 * 4 + 1) * 4 + 0] = 51;
    a[(2 * 4 + 3) * 4 + 1] = 230;
    assert_true(image_edge_rmse(&run, &ref, &rmse, &edges, err, sizeof err));
    assert_int_equal(edges, 6);
    assert_true(fabs(rmse - sqrt(0.2 * 0.2 / 24.0)) < 1e-15);
    image_error e;
    assert_true(image_compare(&run, &ref, &e, err, sizeof err));
    const double d = 25.0 / 255.0;
    assert_true(fabs(e.rmse - sqrt((0.2 * 0.2 + d * d) / 48.0)) < 1e-15);
    assert_true(rmse > e.rmse);

    /* no edge: NAN, never a crash, and the count 0 */
    memset(r, 128, sizeof r);
    assert_true(image_edge_rmse(&run, &ref, &rmse, &edges, err, sizeof err));
    assert_true(isnan(rmse));
    assert_int_equal(edges, 0);

    /* sizes or types that differ are refused with a message */
    image small = {.width = 2, .height = 3, .channels = 4, .type = IMAGE_U8, .pixels = a};
    assert_false(image_edge_rmse(&small, &ref, &rmse, &edges, err, sizeof err));
    assert_non_null(strstr(err, "one size"));
    image f = {.width = 4, .height = 3, .channels = 4, .type = IMAGE_F32, .pixels = a};
    assert_false(image_edge_rmse(&f, &ref, &rmse, &edges, err, sizeof err));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_filter_k2),
        cmocka_unit_test(test_box_filter_k4_linear),
        cmocka_unit_test(test_display),
        cmocka_unit_test(test_pbr_neutral),
        cmocka_unit_test(test_edge_mask_threshold),
        cmocka_unit_test(test_edge_rmse),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
