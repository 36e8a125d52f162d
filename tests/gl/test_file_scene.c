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
#include <unistd.h>

#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "common/image_io.h"
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
    renderer *r = test_renderer_create(kind, &o, err, sizeof err);
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
    scene_file_options fo = {.path = path, .camera = "orbit"};   /* hold: a turn's eighth */
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
    static const char *const others[] = {"forward-mpml", "deferred", "deferred-lighting",
                                         "visibility"};
    for (size_t i = 0; i < sizeof others / sizeof others[0]; i++) {
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

// >>alpha test

/* A 2 x 2 quad facing a file camera 3 units away, lit by a KHR_lights_punctual
 * directional light, textured with an 8 x 8 image whose left half has alpha 0. */
static const char QUAD_GLTF[] =
    "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_lights_punctual\"],"
    "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"directional\","
    "\"color\":[1,1,1],\"intensity\":0.8}]}},"
    "\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2]}],"
    "\"nodes\":[{\"mesh\":0},{\"name\":\"sun\",\"extensions\":{\"KHR_lights_punctual\":"
    "{\"light\":0}}},{\"name\":\"cam\",\"translation\":[0,0,3],\"camera\":0}],"
    "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":0.1,"
    "\"zfar\":10,\"aspectRatio\":1.3333333}}],"
    "\"images\":[{\"uri\":\"mask.png\"}],\"textures\":[{\"source\":0}],"
    "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},"
    "\"metallicFactor\":0},\"alphaMode\":\"%s\",\"alphaCutoff\":0.5}],"
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
    "\"TEXCOORD_0\":2},\"indices\":3,\"material\":0}]}],"
    "\"buffers\":[{\"byteLength\":140,\"uri\":\"quad.bin\"}],"
    "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
    "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":48},"
    "{\"buffer\":0,\"byteOffset\":96,\"byteLength\":32},"
    "{\"buffer\":0,\"byteOffset\":128,\"byteLength\":12}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
    "\"min\":[-1,-1,0],\"max\":[1,1,0]},"
    "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
    "{\"bufferView\":2,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
    "{\"bufferView\":3,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}]}";

static void write_bytes(const char *path, const void *p, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(p, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

/* Renders the quad (alphaMode `mode`) with every renderer; they agree; the fraction of
 * pixels showing it. */
static double quad_coverage(const char *dir, const char *mode)
{
    char path[512], text[4096], err[1024];
    snprintf(text, sizeof text, QUAD_GLTF, mode);
    snprintf(path, sizeof path, "%s/quad-%s.gltf", dir, mode);
    write_bytes(path, text, strlen(text));
    scene_file_options fo = {.path = path, .camera = "cam"};
    light_params lp = {.placement = PLACEMENT_SCENE,
                       .count = {.start = LIGHT_COUNT_ALL, .max = LIGHT_COUNT_ALL}};
    scene_source src = {.file = &fo};
    scene *s = scene_build_source(&src, &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    assert_int_equal(s->materials[s->objects[0].material].alpha,
                     strcmp(mode, "MASK") == 0    ? MATERIAL_MASK
                     : strcmp(mode, "BLEND") == 0 ? MATERIAL_BLEND
                                                  : MATERIAL_OPAQUE);
    if (strcmp(mode, "BLEND") == 0)   /* the base colour factor's alpha, 1 by default */
        assert_true(s->materials[s->objects[0].material].opacity == 1.0f);
    image ref = {0}, img = {0};
    assert_true(render("forward-spml", s, &ref));
    static const char *const others[] = {"forward-mpml", "deferred", "deferred-lighting",
                                         "visibility"};
    for (size_t i = 0; i < sizeof others / sizeof others[0]; i++) {
        assert_true(render(others[i], s, &img));
        image_error e;
        assert_true(image_compare(&img, &ref, &e, err, sizeof err));
        assert_true(e.rmse < RMSE_MAX && e.max_abs <= MAX_ABS_MAX);
        image_free(&img);
    }
    double c = covered(&ref);
    image_free(&ref);
    scene_destroy(s);
    return c;
}

/* alphaMode MASK: the texels under the cutoff are not drawn, in every renderer. The
 * quad covers (1 / (3 tan 0.4)) x (1 / (3 tan 0.4 x 4/3)) = 0.467 of the screen, its
 * opaque half 0.233. */
static void test_alpha_mask(void **state)
{
    (void)state;
    char dir[] = "/tmp/file_scene_mask.XXXXXX", path[512], err[512];
    assert_non_null(mkdtemp(dir));
    float bin[35] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0,   /* positions */
                     0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1,       /* normals */
                     0, 1, 1, 1, 1, 0, 0, 0};                  /* uv, v down the image */
    uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    memcpy(&bin[32], idx, sizeof idx);
    snprintf(path, sizeof path, "%s/quad.bin", dir);
    write_bytes(path, bin, 140);
    unsigned char px[8 * 8 * 4];
    for (int i = 0; i < 64; i++) {
        px[4 * i] = px[4 * i + 1] = px[4 * i + 2] = 255;
        px[4 * i + 3] = (i % 8) < 4 ? 0 : 255;
    }
    image mask = {8, 8, 4, IMAGE_U8, px};
    snprintf(path, sizeof path, "%s/mask.png", dir);
    assert_true(image_write(path, &mask, err, sizeof err));
    double opaque = quad_coverage(dir, "OPAQUE"), masked = quad_coverage(dir, "MASK");
    /* alphaMode BLEND: translucent (the translucent pass), coverage = the filtered
     * texels' alpha: the opaque half, plus the band where the 8 x 8 map's filtering
     * (trilinear, mipmapped) blends the two halves, and never the alpha-0 left quarter
     * (drawn opaque, the whole quad would show): 0.2889 on llvmpipe */
    double blended = quad_coverage(dir, "BLEND");
    fprintf(stderr, "quad: %.4f of the pixels opaque, %.4f masked, %.4f blended\n", opaque,
            masked, blended);
    assert_true(fabs(opaque - 0.467) < 0.02);
    assert_true(fabs(masked - 0.233) < 0.02);
    assert_true(blended > masked - 0.01 && blended < 0.75 * opaque);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

GL_TEST_MAIN(ctx, W, H,
             cmocka_unit_test(test_engine),
             cmocka_unit_test(test_textured_box),
             cmocka_unit_test(test_alpha_mask))
