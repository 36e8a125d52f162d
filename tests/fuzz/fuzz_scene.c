/* libFuzzer target for scene files (scenes/file/file_assimp.c through assimp): glTF, GLB,
 * OBJ + MTL.
 *
 * Each input: its first byte picks the scene file's name (s.gltf, s.glb, s.obj); the
 * rest, up to a line "#@@", is that file, and what follows is written as the file it
 * may reference (b.bin, b.mtl and b.png all get those bytes). The files go into a
 * private temporary folder and scene_file_check loads and checks them (no GL). A
 * crash, a sanitizer report, a leak or a hang is a finding, and so is a broken
 * contract, which aborts:
 *   - a refusal has a one-line message that names the scene file;
 *   - checking the same files twice gives the same verdict and, on success, the same
 *     content hash and counts.
 *
 * Built with clang -fsanitize=fuzzer (scripts/fuzz.sh); the same file with replay.c
 * as main() runs the seeds (tests/fuzz/scene_seeds/) in every build (tests/fuzz/meson.build). */
#include <errno.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "scenes/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char dir[64];

static void contract(bool ok, const char *what, const char *detail)
{
    if (ok)
        return;
    fprintf(stderr, "fuzz_scene: contract broken: %s%s%s\n", what, detail ? ": " : "",
            detail ? detail : "");
    abort();
}

static const char *const companions[] = {"b.bin", "b.mtl", "b.png"};
static const char *const names[] = {"s.gltf", "s.glb", "s.obj"};

static void cleanup(void)
{
    char p[128];
    for (size_t i = 0; i < 3; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, companions[i]);
        unlink(p);
        snprintf(p, sizeof p, "%s/%s", dir, names[i]);
        unlink(p);
    }
    rmdir(dir);
}

static void put(const char *name, const uint8_t *d, size_t n)
{
    char p[128];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "wb");
    contract(f && fwrite(d, 1, n, f) == n && fclose(f) == 0, "cannot write", p);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!dir[0]) {
        /* the first free of fuzz_scene.000001, ...: not mkdtemp's random letters, which
         * the loader's path code may branch on, so that the path is no reason for a
         * seeded run (FUZZ_SEED) to see other coverage than the last one */
        const char *tmp = getenv("TMPDIR");
        bool made = false;
        for (unsigned k = 1; k < 1000000 && !made; k++) {
            snprintf(dir, sizeof dir, "%.40s/fuzz_scene.%06u", tmp && tmp[0] ? tmp : "/tmp", k);
            made = mkdir(dir, 0700) == 0;
            contract(made || errno == EEXIST, "mkdir", dir);
        }
        contract(made, "no free folder name", dir);
        atexit(cleanup);
    }
    if (size == 0)
        return 0;
    const char *name = names[data[0] % 3];
    data++;
    size--;
    size_t main_len = size;
    for (size_t i = 0; i + 4 <= size; i++)
        if (memcmp(data + i, "#@@\n", 4) == 0 && (i == 0 || data[i - 1] == '\n')) {
            main_len = i;
            break;
        }
    char p[128];
    for (size_t i = 0; i < 3; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, names[i]);
        unlink(p);
    }
    put(name, data, main_len);
    size_t rest = main_len < size ? main_len + 4 : size;
    for (size_t i = 0; i < 3; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, companions[i]);
        unlink(p);
        if (rest < size)
            put(companions[i], data + rest, size - rest);
    }
    snprintf(p, sizeof p, "%s/%s", dir, name);
    scene_file_options o = {.path = p, .scale = 1.0f, .up = SCENE_UP_Y, .camera = "orbit"};
    scene_file_info a, b;
    char e1[1024] = "", e2[1024] = "";
    bool ok1 = scene_file_check(&o, &a, e1, sizeof e1);
    bool ok2 = scene_file_check(&o, &b, e2, sizeof e2);
    contract(ok1 == ok2, "two checks of the same files disagree", ok1 ? e2 : e1);
    if (!ok1) {
        contract(strncmp(e1, p, strlen(p)) == 0, "a refusal does not name the file", e1);
        contract(strchr(e1, '\n') == NULL, "a refusal is more than one line", e1);
        contract(strcmp(e1, e2) == 0, "two refusals differ", e2);
    } else {
        contract(a.hash == b.hash && a.triangles == b.triangles && a.objects == b.objects &&
                 a.files == b.files, "two checks give different results", p);
    }
    return 0;
}
