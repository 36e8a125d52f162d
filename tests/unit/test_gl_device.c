/* results/gl_device.h: which GL strings name a software rasterizer, over strings as the
 * drivers print them (GL_RENDERER, GL_VENDOR, GL_VERSION). The GPU strings must not be
 * flagged: NVIDIA's of the committed H200 session (docs/results/gpu-h200.md), and two
 * Mesa GPU drivers whose strings say "Mesa" or "LLVM" as llvmpipe's do. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "results/gl_device.h"

static void is_soft(const char *renderer, const char *vendor, const char *version,
                    const char *name)
{
    const char *got = gl_software_rasterizer(renderer, vendor, version);
    if (!got || strcmp(got, name) != 0)
        fail_msg("'%s' / '%s': want %s, got %s", renderer, vendor, name, got ? got : "NULL");
}

static void is_gpu(const char *renderer, const char *vendor, const char *version)
{
    const char *got = gl_software_rasterizer(renderer, vendor, version);
    if (got)
        fail_msg("'%s' / '%s' flagged as %s", renderer ? renderer : "(none)",
                 vendor ? vendor : "(none)", got);
}

static void test_mesa_software(void **state)
{
    (void)state;
    /* this machine's, and CI's (meta.yaml of docs/results/2026-12-0[23]-llvmpipe) */
    is_soft("llvmpipe (LLVM 15.0.6, 256 bits)", "Mesa/X.org",
            "4.5 (Core Profile) Mesa 22.3.6", "llvmpipe");
    is_soft("llvmpipe (LLVM 17.0.6, 128 bits)", "Mesa", "4.5 (Core Profile) Mesa 24.0.5",
            "llvmpipe");
    is_soft("softpipe", "Mesa/X.org", "3.3 (Core Profile) Mesa 22.3.6", "softpipe");
    is_soft("softpipe", "Mesa", "4.5 (Core Profile) Mesa 24.0.5", "softpipe");
    is_soft("zink Vulkan 1.3(llvmpipe (LLVM 15.0.6, 256 bits) (MESA_LLVMPIPE))", "Mesa",
            "4.6 (Core Profile) Mesa 23.1.0", "llvmpipe");
    is_soft("zink (lavapipe)", "Mesa", "4.6 (Core Profile) Mesa 23.0.0", "lavapipe");
    is_soft("Software Rasterizer", "Mesa Project", "2.1 Mesa 11.2.2", "swrast");
    is_soft("Mesa OffScreen", "Brian Paul", "2.1 Mesa 11.2.2", "OSMesa");
    is_soft("Mesa DRI swrast", "Mesa Project", "2.1 Mesa 9.2.1", "swrast");
}

static void test_other_software(void **state)
{
    (void)state;
    is_soft("Google SwiftShader", "Google Inc.", "OpenGL ES 3.0 SwiftShader 4.1.0.7",
            "SwiftShader");
    is_soft("ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device (Subzero) (0x0000C0DE)), "
            "SwiftShader driver-5.0.0)", "Google Inc. (Google)",
            "OpenGL ES 3.0.0 (ANGLE 2.1.0)", "SwiftShader");
    is_soft("ANGLE (Microsoft, Microsoft Basic Render Driver Direct3D11 vs_5_0 ps_5_0, "
            "D3D11)", "Google Inc. (Microsoft)", "OpenGL ES 3.0.0 (ANGLE 2.1.0)", "WARP");
    is_soft("D3D12 (Microsoft Basic Render Driver)", "Microsoft Corporation",
            "3.3 (Core Profile) Mesa 22.3.6", "WARP");
    is_soft("Apple Software Renderer", "Apple Inc.", "4.1 APPLE-18.5.9",
            "a software renderer");
}

static void test_gpus_are_not_flagged(void **state)
{
    (void)state;
    /* docs/results/gpu-h200.md: the committed GPU session */
    is_gpu("NVIDIA H200/PCIe/SSE2", "NVIDIA Corporation", "4.5.0 NVIDIA 580.159.04");
    is_gpu("NVIDIA GeForce RTX 4090/PCIe/SSE2", "NVIDIA Corporation",
           "4.6.0 NVIDIA 550.54.14");
    /* Mesa's GPU drivers: "Mesa" and "LLVM" in their strings too */
    is_gpu("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.6, DRM 3.54, 6.5.0)", "AMD",
           "4.6 (Core Profile) Mesa 23.2.1");
    is_gpu("Mesa Intel(R) UHD Graphics 620 (KBL GT2)", "Intel",
           "4.6 (Core Profile) Mesa 22.3.6");
    is_gpu("AMD Radeon Graphics (renoir, LLVM 15.0.7, DRM 3.49, 6.1.0)", "AMD",
           "4.6 (Core Profile) Mesa 22.3.6");
    is_gpu("D3D12 (NVIDIA GeForce RTX 3080)", "Microsoft Corporation",
           "4.2 (Core Profile) Mesa 23.0.4");
    is_gpu("ANGLE (NVIDIA, NVIDIA GeForce RTX 3080 Direct3D11 vs_5_0 ps_5_0, D3D11)",
           "Google Inc. (NVIDIA)", "OpenGL ES 3.0.0 (ANGLE 2.1.0)");
    /* nothing to tell from: not flagged */
    is_gpu(NULL, NULL, NULL);
    is_gpu("", "", "");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mesa_software),
        cmocka_unit_test(test_other_software),
        cmocka_unit_test(test_gpus_are_not_flagged),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
