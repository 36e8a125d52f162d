/* File scenes on the GPU: a glTF file (assimp-testmodels' 2CylinderEngine: 34 meshes
 * under rotated and scaled nodes; BoxTextured: a texture from a .glb) rendered by
 * every renderer, which agree within RMSE 1/255 and max error 4/255 as on the catalog
 * scenes (test_agreement.c); the picture holds the model (a known fraction of pixels
 * that are not the background). Debug contexts: any GL error fails. */
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

#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "results/image_io.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

enum { W = 160, H = 120 };
#define RMSE_MAX (1.0 / 255.0)
#define MAX_ABS_MAX (4.0 / 255.0)
#define MODELS "/usr/share/assimp/models/glTF2"

static gl_context *ctx;

static bool render(const char *kind, scene *s, image *out)
{
    char err[512];
    const gl_info *gi = gl_context_info(ctx);
    renderer_options o = {
        .width = W, .height = H, .queries = true,
        .timer_query = gi->timer_query, .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size,
        .gbuffer = GBUFFER_REFERENCE, .light_volumes = LIGHT_VOLUMES_STENCIL,
    };
    renderer *r = renderer_create(kind, &o, err, sizeof err);
    if (!r || !renderer_prepare(r, s, err, sizeof err)) {
        print_error("%s: %s\n", kind, err);
        renderer_destroy(r);
        return false;
    }
    frame_stats fs;
    renderer_draw(r, s, &fs);
    gl.Finish();
    renderer_collect(r, &fs);
    out->width = W;
    out->height = H;
    out->channels = 4;
    out->type = IMAGE_U8;
    out->pixels = malloc((size_t)W * H * 4);
    bool ok = gl_context_read_rgba8(ctx, out->pixels, err, sizeof err);
    renderer_destroy(r);
    gl_context_poll_errors(ctx, kind);
    return ok && gl_context_error_count(ctx) == 0;
}

/* Pixels whose colour is not the corner pixel's (the background: no sky in a file
 * scene, so the clear colour). */
static double covered(const image *img)
{
    const unsigned char *p = img->pixels;
    size_t n = (size_t)img->width * img->height, k = 0;
    for (size_t i = 0; i < n; i++)
        k += memcmp(p + 4 * i, p, 3) != 0;
    return (double)k / (double)n;
}

static void run_file(const char *path, double cover_lo, double cover_hi)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        fprintf(stderr, "%s: missing (assimp-testmodels, scripts/setup.sh)\n", path);
        skip();
    }
    scene_file_options fo = {.path = path};
    scene_file_info info;
    char err[1024];
    if (!scene_file_check(&fo, &info, err, sizeof err))
        fail_msg("%s", err);
    float size = 0.0f;
    for (int k = 0; k < 3; k++)
        size = fmaxf(size, info.bounds_max[k] - info.bounds_min[k]);
    light_params lp = {.placement = PLACEMENT_RANDOM, .seed = 5, .rng = RNG_PCG32,
                       .count = {.start = 16, .max = 16}, .radius = 0.6f * size,
                       .color_max = 0.8f, .attenuation = ATTENUATION_LINEAR_RANGE};
    scene_source src = {.file = &fo};
    scene *s = scene_build_source(&src, &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    camera_params cp;
    camera_params_init(&cp);
    cp.hold = 0.125f;   /* an eighth of a turn: the model from an angle */
    assert_true(scene_set_camera(s, &cp, err, sizeof err));

    image ref = {0}, img = {0};
    assert_true(render("forward-spml", s, &ref));
    double c = covered(&ref);
    fprintf(stderr, "%s: %.4f of the pixels show the model\n", path, c);
    assert_true(c >= cover_lo && c <= cover_hi);
    static const char *const others[] = {"forward-mpml", "deferred"};
    for (int i = 0; i < 2; i++) {
        assert_true(render(others[i], s, &img));
        image_error e;
        assert_true(image_compare(&img, &ref, &e, err, sizeof err));
        if (e.rmse >= RMSE_MAX || e.max_abs > MAX_ABS_MAX)
            print_error("%s: %s vs forward-spml: rmse %.3f/255, max %.1f/255\n", path,
                        others[i], e.rmse * 255, e.max_abs * 255);
        assert_true(e.rmse < RMSE_MAX);
        assert_true(e.max_abs <= MAX_ABS_MAX);
        assert_int_equal(e.nonfinite, 0);
        image_free(&img);
    }
    image_free(&ref);
    scene_destroy(s);
}

static void test_engine(void **state)
{
    (void)state;
    /* 0.1198 on llvmpipe: the engine's silhouette within its screen bounds (NDC x
     * -0.39..0.59, y -0.42..0.35 from this eye) */
    run_file(MODELS "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", 0.10, 0.14);
}

static void test_textured_box(void **state)
{
    (void)state;
    /* 0.2896 on llvmpipe */
    run_file(MODELS "/BoxTextured-glTF-Binary/BoxTextured.glb", 0.27, 0.31);
}

static int setup(void **state)
{
    (void)state;
    ctx = gl_test_context(W, H);
    return ctx ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    gl_context_destroy(ctx);
    return 0;
}

int main(void)
{
    char why[256];
    if (!egl_display_available(why, sizeof why)) {
        fprintf(stderr, "SKIP: %s\n", why);
        return 77;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_engine),
        cmocka_unit_test(test_textured_box),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
