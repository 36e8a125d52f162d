/* The scene cache (scenes/scene_cache.c): a file scene written and read back is the
 * scene its builder made, byte for byte; a cache file is refused, with its reason, when
 * its files changed or it was made for other options; and any bytes, with a checksum
 * that holds, are read without a crash (the sanitizer build runs this too). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "runner/manifest/hash.h"
#include "scenes/scene.h"
#include "tempdir.h"

#define BOX "/usr/share/assimp/models/glTF2/BoxTextured-glTF"
/* The header: magic 8, version 4, layout 4, key 8, payload size 8, checksum 8. */
#define HEADER 40
#define AT_SIZE 24
#define AT_SUM 32

static char dir[128], gltf[256], cache[256];
static scene_file_options opts;
static scene_file_info info;
static scene_file_list files;

static void *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    *n = (size_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *d = malloc(*n ? *n : 1);
    assert_non_null(d);
    assert_int_equal(fread(d, 1, *n, f), *n);
    fclose(f);
    return d;
}

static void spill(const char *path, const void *d, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(d, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

static int setup(void **state)
{
    (void)state;
    struct stat st;
    if (stat(BOX "/BoxTextured.gltf", &st) != 0)
        return 0;
    assert_int_equal(temp_dir_make(dir, sizeof dir, "scene-cache"), 0);
    char cmd[512];
    snprintf(cmd, sizeof cmd, "cp %s/* %s/", BOX, dir);
    assert_int_equal(system(cmd), 0);
    snprintf(gltf, sizeof gltf, "%s/BoxTextured.gltf", dir);
    snprintf(cache, sizeof cache, "%s/box.scene", dir);
    opts = (scene_file_options){.path = gltf, .fit = true, .lights_around = true};
    char err[512];
    assert_true(scene_file_check_list(&opts, &info, &files, err, sizeof err));
    assert_true(files.n >= 3);   /* the .gltf, its .bin and its image */
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    scene_file_list_free(&files);
    if (dir[0]) {
        char cmd[256];
        snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
        return system(cmd) == 0 ? 0 : -1;
    }
    return 0;
}

#define NEED_BOX()                                                                         \
    do {                                                                                   \
        if (!dir[0]) {                                                                     \
            fprintf(stderr, "assimp-testmodels is not installed (scripts/setup.sh)\n");    \
            skip();                                                                        \
        }                                                                                  \
    } while (0)

static const light_params lights = {.placement = PLACEMENT_NONE};

/* The scene built from the file, written to the cache as it is built. */
static scene *build_and_write(void)
{
    scene_source src = {.file = &opts};
    scene_cache_store to = {.path = cache, .o = &opts, .content_hash = info.hash,
                            .info = &info, .files = &files};
    char err[512];
    scene *s = scene_build_cache(&src, NULL, &to, &lights, 32, 24, err, sizeof err);
    assert_non_null(s);
    assert_true(to.written);
    assert_string_equal(to.note, "");
    return s;
}

static scene_cached *read_cache(scene_file_info *got, char *note, size_t len)
{
    return scene_cache_read(cache, &opts, info.hash, 32, 24, got, note, len);
}

static void test_round_trip(void **state)
{
    (void)state;
    NEED_BOX();
    scene *a = build_and_write();
    scene_file_info got;
    char note[600], err[512];
    scene_cached *c = read_cache(&got, note, sizeof note);
    assert_non_null(c);
    assert_string_equal(note, "");
    assert_memory_equal(&got, &info, sizeof info);
    scene_source src = {.file = &opts};
    scene *b = scene_build_cache(&src, c, NULL, &lights, 32, 24, err, sizeof err);
    assert_non_null(b);
    assert_string_equal(a->name, b->name);
    assert_int_equal(a->nmeshes, b->nmeshes);
    assert_int_equal(a->ntextures, b->ntextures);
    assert_int_equal(a->nmaterials, b->nmaterials);
    assert_int_equal(a->nobjects, b->nobjects);
    assert_int_equal(a->nlights_total, b->nlights_total);
    for (uint32_t i = 0; i < a->nmeshes; i++) {
        assert_int_equal(a->meshes[i].nvertices, b->meshes[i].nvertices);
        assert_int_equal(a->meshes[i].nindices, b->meshes[i].nindices);
        assert_memory_equal(a->meshes[i].vertices, b->meshes[i].vertices,
                            a->meshes[i].nvertices * sizeof *a->meshes[i].vertices);
        assert_memory_equal(a->meshes[i].indices, b->meshes[i].indices,
                            a->meshes[i].nindices * sizeof *a->meshes[i].indices);
    }
    for (uint32_t i = 0; i < a->ntextures; i++) {
        const texture_image *x = &a->textures[i], *y = &b->textures[i];
        assert_true(x->width == y->width && x->height == y->height &&
                    x->channels == y->channels);
        assert_memory_equal(x->data, y->data, (size_t)x->width * x->height * x->channels);
    }
    assert_memory_equal(a->materials, b->materials, a->nmaterials * sizeof *a->materials);
    assert_memory_equal(a->objects, b->objects, a->nobjects * sizeof *a->objects);
    assert_memory_equal(&a->cam, &b->cam, sizeof a->cam);
    assert_memory_equal(a->viewproj, b->viewproj, sizeof a->viewproj);
    scene_destroy(a);
    scene_destroy(b);
}

static void expect_refused(const char *why)
{
    scene_file_info got;
    char note[600];
    scene_cached *c = read_cache(&got, note, sizeof note);
    if (c)
        fail_msg("read a cache that should be refused (%s)", why);
    if (!strstr(note, why))
        fail_msg("note '%s', want '%s'", note, why);
    assert_non_null(strstr(note, ": ignored: "));
}

static void test_refusals(void **state)
{
    (void)state;
    NEED_BOX();
    scene_destroy(build_and_write());
    size_t n;
    unsigned char *good = slurp(cache, &n);
    /* another scale: the same file name read under other options */
    scene_file_options other = opts;
    other.fit = false;
    other.scale = 2.0f;
    scene_file_info got;
    char note[600];
    assert_null(scene_cache_read(cache, &other, info.hash, 32, 24, &got, note, sizeof note));
    assert_non_null(strstr(note, "its key does not match"));
    /* no file: no note */
    char none[300];
    snprintf(none, sizeof none, "%s/none.scene", dir);
    assert_null(scene_cache_read(none, &opts, info.hash, 32, 24, &got, note, sizeof note));
    assert_string_equal(note, "");
    /* an image the scene was made from, changed */
    char png[300];
    snprintf(png, sizeof png, "%s/CesiumLogoFlat.png", dir);
    size_t pn;
    unsigned char *img = slurp(png, &pn);
    img[pn / 2] ^= 1;
    spill(png, img, pn);
    expect_refused("the files it was made from have changed");
    img[pn / 2] ^= 1;
    spill(png, img, pn);
    free(img);
    /* a flipped byte, cut short, another magic */
    unsigned char *bad = malloc(n);
    memcpy(bad, good, n);
    bad[n - 7] ^= 0x10;
    spill(cache, bad, n);
    expect_refused("corrupt (its checksum does not match)");
    spill(cache, good, n - 1);
    expect_refused("truncated or grown");
    memcpy(bad, good, n);
    bad[0] = 'X';
    spill(cache, bad, n);
    expect_refused("bad magic");
    spill(cache, good, 10);
    expect_refused("bad magic");
    spill(cache, good, n);
    scene_cached *c = read_cache(&got, note, sizeof note);
    assert_non_null(c);
    scene_cached_free(c);
    free(bad);
    free(good);
}

/* Every byte of the payload changed in turn, and the payload cut at many lengths, each
 * with a header (size, checksum) that holds: read, refused or not, without a crash or a
 * leak, and a scene read is whole (its indices in range: scene_build_cache poses it). */
static void test_any_bytes(void **state)
{
    (void)state;
    NEED_BOX();
    scene_destroy(build_and_write());
    size_t n;
    unsigned char *good = slurp(cache, &n);
    unsigned char *bad = malloc(n);
    uint32_t read = 0, refused = 0;
    size_t step = (n - HEADER) / 300 + 1;
    for (size_t at = HEADER; at < n + step; at += step) {
        size_t len = at < n ? n : HEADER + (at - n) * 7 % (n - HEADER);
        memcpy(bad, good, n);
        if (at < n)
            bad[at] ^= (unsigned char)(0x81 + at);
        uint64_t size = len - HEADER, sum = fnv1a64(bad + HEADER, size);
        memcpy(bad + AT_SIZE, &size, 8);
        memcpy(bad + AT_SUM, &sum, 8);
        spill(cache, bad, len);
        scene_file_info got;
        char note[600], err[512];
        scene_cached *c = read_cache(&got, note, sizeof note);
        if (!c) {
            refused++;
            assert_non_null(strstr(note, ": ignored: "));
            continue;
        }
        read++;
        scene_source src = {.file = &opts};
        scene *s = scene_build_cache(&src, c, NULL, &lights, 32, 24, err, sizeof err);
        if (s) {
            for (uint32_t i = 0; i < s->nobjects; i++)
                assert_true(s->objects[i].mesh < s->nmeshes);
            scene_destroy(s);
        }
    }
    /* most bytes are floats and texels, which any value leaves a scene */
    assert_true(read > 0);
    assert_true(refused > 0);
    free(bad);
    free(good);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_any_bytes),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
