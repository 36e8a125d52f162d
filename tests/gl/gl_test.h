#pragma once
/* Shared by the GL tests.
 *   egl_display_available()  whether Mesa's surfaceless EGL platform gives a display
 *                            here at all, and if not why (for the skip message);
 *                            independent of the code under test. Like the contexts, it
 *                            never terminates the display: eglTerminate would unload
 *                            Mesa's driver mid-process (see context_egl.c).
 *   gl_test_context()        the debug context (every GL error counted) with its
 *                            off-screen framebuffer at w x h that most tests draw in.
 *   find_pass()              a frame's pass by name, or NULL.
 *   plan_pass()              a renderer's planned pass (renderer_describe) by name, or NULL.
 *   total_draws()            a frame's draw calls over all its passes.
 *   GL_TEST_SKIP_WITHOUT_EGL()  in main: exit 77 (skipped) with the reason when there is
 *                            no EGL display.
 *   GL_TEST_MAIN(ctx, w, h, tests...)  the whole main() of a test whose cmocka tests
 *                            share one debug context in the file's `ctx`, made at w x h
 *                            before the first and destroyed after the last.
 *   gl_test_expect_agree()   two images agree within the test's tolerances, no pixel
 *                            non-finite; the numbers printed when not (or always).
 *   test_renderer_create()   renderer_create with the key members the test left zero
 *                            at their defaults (renderer_options_complete). */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "renderers/gl/context.h"
#include "renderers/renderer.h"
#include "results/image_ref.h"

#define GL_TEST_SKIP_WITHOUT_EGL()                                                         \
    do {                                                                                   \
        char why_[256];                                                                    \
        if (!egl_display_available(why_, sizeof why_)) {                                   \
            fprintf(stderr, "SKIP: %s\n", why_);                                           \
            return 77;                                                                     \
        }                                                                                  \
    } while (0)

#define GL_TEST_MAIN(CTX, W, H, ...)                                                       \
    static int gl_test_setup_(void **state)                                                \
    {                                                                                      \
        (void)state;                                                                       \
        CTX = gl_test_context(W, H);                                                       \
        return CTX ? 0 : -1;                                                               \
    }                                                                                      \
    static int gl_test_teardown_(void **state)                                             \
    {                                                                                      \
        (void)state;                                                                       \
        gl_context_destroy(CTX);                                                           \
        return 0;                                                                          \
    }                                                                                      \
    int main(void)                                                                         \
    {                                                                                      \
        GL_TEST_SKIP_WITHOUT_EGL();                                                        \
        const struct CMUnitTest tests_[] = {__VA_ARGS__};                                  \
        return cmocka_run_group_tests(tests_, gl_test_setup_, gl_test_teardown_);          \
    }

static inline bool egl_display_available(char *why, size_t len)
{
    const char *ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!ext || !strstr(ext, "EGL_MESA_platform_surfaceless")) {
        snprintf(why, len, "no EGL_MESA_platform_surfaceless among the EGL client extensions");
        return false;
    }
    PFNEGLGETPLATFORMDISPLAYEXTPROC get =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay d = get ? get(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL)
                       : EGL_NO_DISPLAY;
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, NULL, NULL)) {
        snprintf(why, len, "no surfaceless EGL display can be initialized (EGL error 0x%x)",
                 (unsigned)eglGetError());
        return false;
    }
    return true;
}

/* A surfaceless EGL debug context at w x h, or NULL with the reason printed. */
static inline gl_context *gl_test_context(int w, int h)
{
    char err[512];
    gl_context_desc d = {.backend = GL_BACKEND_EGL, .device = -1, .debug = true,
                         .width = w, .height = h};
    gl_context *ctx = gl_context_create(&d, err, sizeof err);
    if (!ctx)
        print_error("context: %s\n", err);
    return ctx;
}

static inline const pass_stats *find_pass(const frame_stats *fs, const char *name)
{
    for (size_t i = 0; i < fs->npasses; i++)
        if (strcmp(fs->pass[i].name, name) == 0)
            return &fs->pass[i];
    return NULL;
}

static inline uint64_t total_draws(const frame_stats *fs)
{
    uint64_t n = 0;
    for (size_t i = 0; i < fs->npasses; i++)
        n += fs->pass[i].draw_calls;
    return n;
}

static inline const pass_plan_entry *plan_pass(const pass_plan *p, const char *name)
{
    for (size_t i = 0; i < p->npasses; i++)
        if (strcmp(p->pass[i].name, name) == 0)
            return &p->pass[i];
    return NULL;
}

/* a and b agree: RMSE below rmse_max and no channel off by more than max_abs (both in
 * 0..1), no non-finite pixel; the numbers are printed when they do not (always with
 * verbose, for the test's log). */
static inline void gl_test_expect_agree(const char *what, const image *a, const image *b,
                                        double rmse_max, double max_abs, bool verbose)
{
    image_error e;
    char err[256];
    assert_true(image_compare(a, b, &e, err, sizeof err));
    if (verbose || e.rmse >= rmse_max || e.max_abs > max_abs)
        print_message("%s: rmse %.3f/255, max %.1f/255, %.4f of pixels off by > 1/255\n", what,
                      e.rmse * 255, e.max_abs * 255, e.frac_over_1_255);
    assert_true(e.rmse < rmse_max);
    assert_true(e.max_abs <= max_abs);
    assert_int_equal(e.nonfinite, 0);
}

/* renderer_create with o's zero key members at their defaults. */
static inline renderer *test_renderer_create(const char *kind, const renderer_options *o,
                                             char *err, size_t errlen)
{
    renderer_options c = *o;
    renderer_options_complete(&c);
    return renderer_create(kind, &c, err, errlen);
}
