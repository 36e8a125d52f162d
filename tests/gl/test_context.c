/* GL contexts (renderers/gl/context.h) and the loader (renderers/gl/loader.h)
 * on whatever headless GL this machine has (llvmpipe in CI). Exits 77 (skip)
 * when no EGL display can be created at all. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "config.h"
#include "renderers/gl/context.h"
#include "tests/gl/gl_test.h"
#include "renderers/gl/loader.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

// >>helpers



static gl_context *create(gl_backend backend, int device, bool debug, int w, int h)
{
    char err[512] = "";
    gl_context_desc desc = {.backend = backend, .device = device, .debug = debug,
                            .width = w, .height = h};
    gl_context *ctx = gl_context_create(&desc, err, sizeof err);
    if (!ctx)
        fail_msg("gl_context_create(%dx%d) failed: %s", w, h, err);
    return ctx;
}

/* Expects creation to fail; returns the message. */
static void create_fails(gl_backend backend, int device, int w, int h, char *err, size_t errlen)
{
    gl_context_desc desc = {.backend = backend, .device = device, .debug = true,
                            .width = w, .height = h};
    err[0] = '\0';
    gl_context *ctx = gl_context_create(&desc, err, errlen);
    if (ctx) {
        gl_context_destroy(ctx);
        fail_msg("gl_context_create(%dx%d) succeeded, expected a failure", w, h);
    }
}

/* Redirects stderr (fd 2) into a temporary file until capture_end. */
typedef struct capture {
    int saved;
    FILE *tmp;
} capture;

static void capture_begin(capture *c)
{
    fflush(stderr);
    c->tmp = tmpfile();
    assert_non_null(c->tmp);
    c->saved = dup(2);
    assert_true(c->saved >= 0);
    assert_true(dup2(fileno(c->tmp), 2) >= 0);
}

/* Restores stderr, echoes what was captured to it, and returns it (free it). */
static char *capture_end(capture *c)
{
    fflush(stderr);
    assert_true(dup2(c->saved, 2) >= 0);
    close(c->saved);
    long n = ftell(c->tmp);
    assert_true(n >= 0);
    char *s = calloc((size_t)n + 1, 1);
    assert_non_null(s);
    rewind(c->tmp);
    assert_int_equal(fread(s, 1, (size_t)n, c->tmp), (size_t)n);
    fclose(c->tmp);
    fputs(s, stderr);
    return s;
}

/* Runs the body with SHADESWEEP_GL_DEBUG unset (the test suite sets it). */
static char *saved_debug_env;

static void debug_env_unset(void)
{
    const char *v = getenv("SHADESWEEP_GL_DEBUG");
    saved_debug_env = v ? strdup(v) : NULL;
    unsetenv("SHADESWEEP_GL_DEBUG");
}

static void debug_env_restore(void)
{
    if (saved_debug_env)
        setenv("SHADESWEEP_GL_DEBUG", saved_debug_env, 1);
    free(saved_debug_env);
    saved_debug_env = NULL;
}

static void assert_all_functions_loaded(void)
{
#define GL_FUNC(ret, name, params) \
    if (!gl.name)                  \
        fail_msg("gl." #name " is NULL after context creation");
#include "renderers/gl/gl_funcs.h"
#undef GL_FUNC
}

static void assert_pixel(const uint8_t *px, int w, int x, int y, const uint8_t want[4])
{
    const uint8_t *p = px + ((size_t)y * (size_t)w + (size_t)x) * 4;
    if (memcmp(p, want, 4) != 0)
        fail_msg("pixel (%d,%d) from the top is %u,%u,%u,%u, expected %u,%u,%u,%u", x, y, p[0],
                 p[1], p[2], p[3], want[0], want[1], want[2], want[3]);
}

/* Clears the whole framebuffer to A, the top half (rows 0..h/2-1 counted from the
 * top) to B with a scissor, and the bottom-left pixel to C; reads it back and
 * checks every pixel. Catches flipped rows, flipped columns, and padding. */
static void check_readback(gl_context *ctx, int w, int h)
{
    static const uint8_t A[4] = {51, 102, 153, 255}, B[4] = {0, 255, 0, 255},
                         C[4] = {255, 0, 0, 255};
    gl.ClearColor(0.2f, 0.4f, 0.6f, 1.0f);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);

    size_t n = (size_t)w * (size_t)h * 4;
    uint8_t *px = malloc(n);
    assert_non_null(px);
    char err[256] = "";
    memset(px, 0xAB, n);
    assert_true(gl_context_read_rgba8(ctx, px, err, sizeof err));
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            assert_pixel(px, w, x, y, A);

    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(0, h - h / 2, w, h / 2);   /* GL counts rows from the bottom */
    gl.ClearColor(0.0f, 1.0f, 0.0f, 1.0f);
    gl.Clear(GL_COLOR_BUFFER_BIT);
    gl.Scissor(0, 0, 1, 1);
    gl.ClearColor(1.0f, 0.0f, 0.0f, 1.0f);
    gl.Clear(GL_COLOR_BUFFER_BIT);
    gl.Disable(GL_SCISSOR_TEST);

    memset(px, 0xAB, n);
    assert_true(gl_context_read_rgba8(ctx, px, err, sizeof err));
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const uint8_t *want = y < h / 2 ? B : (x == 0 && y == h - 1) ? C : A;
            assert_pixel(px, w, x, y, want);
        }
    free(px);
    assert_int_equal(gl_context_poll_errors(ctx, "check_readback"), 0);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static void parse_version(const char *s, int *major, int *minor)
{
    *major = *minor = -1;
    /* "4.5 (Core Profile) Mesa 22.3.6" */
    if (sscanf(s, "%d.%d", major, minor) != 2)
        fail_msg("cannot parse the GL version string '%s'", s);
}

// >>loader

static void fake_function(void) {}

static void *fake_getproc_all(const char *name)
{
    (void)name;
    void (*f)(void) = fake_function;
    void *p;
    memcpy(&p, &f, sizeof p);
    return p;
}

static void *fake_getproc_no_drawbuffers(const char *name)
{
    return strcmp(name, "glDrawBuffers") == 0 ? NULL : fake_getproc_all(name);
}

static void test_loader(void **state)
{
    (void)state;
    char err[256] = "";
    assert_true(gl_load(fake_getproc_all, err, sizeof err));
    assert_all_functions_loaded();
    assert_int_equal(gl_func_count(), sizeof(struct gl_api) / sizeof(void (*)(void)));
    assert_true(gl_func_count() > 100);

    assert_false(gl_load(fake_getproc_no_drawbuffers, err, sizeof err));
    assert_string_equal(err, "GL: glDrawBuffers not found by the backend's GetProcAddress");
    /* A failed load leaves nothing half-loaded behind. */
    assert_null(gl.Clear);
    assert_null(gl.GetError);
    gl_unload();
}

// >>egl

static void test_create_destroy_many(void **state)
{
    (void)state;
    for (int i = 0; i < 8; i++) {
        int w = 16 + i, h = 9 + 2 * i;
        gl_context *ctx = create(GL_BACKEND_EGL, -1, true, w, h);
        assert_string_equal(gl_context_info(ctx)->backend, "egl-surfaceless");
        assert_int_not_equal(gl_context_framebuffer(ctx), 0);
        GLint fb = 0;
        gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb);
        assert_int_equal(fb, gl_context_framebuffer(ctx));
        gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &fb);
        assert_int_equal(fb, gl_context_framebuffer(ctx));
        GLint vp[4];
        gl.GetIntegerv(GL_VIEWPORT, vp);
        assert_int_equal(vp[2], w);
        assert_int_equal(vp[3], h);
        check_readback(ctx, w, h);
        gl_context_destroy(ctx);
        assert_null(gl.Clear);   /* the table goes with the context */
    }
    gl_context_destroy(NULL);
}

static void test_info(void **state)
{
    (void)state;
    gl_context *ctx = create(GL_BACKEND_EGL, -1, true, 0, 0);
    assert_all_functions_loaded();
    const gl_info *i = gl_context_info(ctx);
    int major, minor;
    parse_version(i->version, &major, &minor);
    assert_true(major > 4 || (major == 4 && minor >= 5));
    assert_non_null(strstr(i->version, "Core Profile"));
    assert_true(i->vendor[0] != '\0');
    assert_true(i->renderer[0] != '\0');
    assert_true(i->glsl_version[0] != '\0');
    assert_true(i->max_draw_buffers >= 8);
    assert_true(i->max_color_attachments >= 8);
    assert_true(i->max_uniform_block_size >= 16384);
    assert_true(i->max_texture_size >= 1024);
    assert_true(i->max_renderbuffer_size >= 1024);
    assert_true(i->max_viewport_dims[0] >= 1024 && i->max_viewport_dims[1] >= 1024);
    assert_true(i->timer_query);   /* core since GL 3.3 */
    assert_true(i->debug_context);
    assert_string_equal(i->device, "");
    assert_int_equal(gl_context_framebuffer(ctx), 0);

    /* No framebuffer at 0x0: nothing to read. */
    uint8_t px[4];
    char err[256] = "";
    assert_false(gl_context_read_rgba8(ctx, px, err, sizeof err));
    assert_non_null(strstr(err, "no off-screen framebuffer"));

    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    assert_non_null(f);
    gl_context_print_info(ctx, f);
    fclose(f);
    static const char *const keys[] = {
        "backend", "device", "vendor", "renderer", "version", "glsl", "max_draw_buffers",
        "max_color_attachments", "max_samples", "max_uniform_block_size", "max_texture_size",
        "max_renderbuffer_size", "max_viewport", "timer_query", "pipeline_statistics_query",
        "debug_context", NULL,
    };
    const char *line = text;
    for (size_t k = 0; keys[k]; k++) {
        size_t kl = strlen(keys[k]);
        if (strncmp(line, keys[k], kl) != 0 || strncmp(line + kl, ": ", 2) != 0)
            fail_msg("line %zu of the info is '%.40s', expected key '%s'", k + 1, line, keys[k]);
        line = strchr(line, '\n');
        assert_non_null(line);
        line++;
    }
    assert_string_equal(line, "");
    assert_non_null(strstr(text, "backend: egl-surfaceless\n"));
    assert_non_null(strstr(text, "device: none\n"));
    assert_non_null(strstr(text, "debug_context: yes\n"));
    assert_non_null(strstr(text, "timer_query: yes\n"));
    char want[300];
    snprintf(want, sizeof want, "\nmax_viewport: %dx%d\n", i->max_viewport_dims[0],
             i->max_viewport_dims[1]);
    assert_non_null(strstr(text, want));
    snprintf(want, sizeof want, "\npipeline_statistics_query: %s\n",
             i->pipeline_statistics ? "yes" : "no");
    assert_non_null(strstr(text, want));
    snprintf(want, sizeof want, "\nversion: %s\n", i->version);
    assert_non_null(strstr(text, want));
    free(text);
    gl_context_destroy(ctx);
}

static void test_debug_context_counts_error_once(void **state)
{
    (void)state;
    gl_context *ctx = create(GL_BACKEND_EGL, -1, true, 8, 8);
    assert_true(gl_context_info(ctx)->debug_context);
    assert_int_equal(gl_context_error_count(ctx), 0);

    capture c;
    capture_begin(&c);
    gl.Enable(0xFFFF);   /* GL_INVALID_ENUM */
    uint64_t after_call = gl_context_error_count(ctx);
    unsigned polled = gl_context_poll_errors(ctx, "test");
    uint64_t after_poll = gl_context_error_count(ctx);
    unsigned polled_again = gl_context_poll_errors(ctx, "test again");
    char *out = capture_end(&c);

    assert_int_equal(after_call, 1);   /* counted by the callback, synchronously */
    assert_int_equal(polled, 1);       /* the poll reports it ... */
    assert_int_equal(after_poll, 1);   /* ... without counting it twice */
    assert_int_equal(polled_again, 0);
    assert_int_equal(gl_context_error_count(ctx), 1);
    assert_true(strncmp(out, "GL error: API ", strlen("GL error: API ")) == 0);
    free(out);
    gl_context_destroy(ctx);
}

static void test_poll_finds_error_without_debug(void **state)
{
    (void)state;
    debug_env_unset();
    gl_context *ctx = create(GL_BACKEND_EGL, -1, false, 8, 8);
    debug_env_restore();
    assert_false(gl_context_info(ctx)->debug_context);

    capture c;
    capture_begin(&c);
    gl.Enable(0xFFFF);
    uint64_t before_poll = gl_context_error_count(ctx);
    unsigned polled = gl_context_poll_errors(ctx, "after glEnable(0xFFFF)");
    unsigned polled_again = gl_context_poll_errors(ctx, "later");
    char *out = capture_end(&c);

    assert_int_equal(before_poll, 0);   /* no callback: nobody saw it yet */
    assert_int_equal(polled, 1);
    assert_int_equal(polled_again, 0);
    assert_int_equal(gl_context_error_count(ctx), 1);
    assert_string_equal(out, "GL error: GL_INVALID_ENUM (0x0500) at after glEnable(0xFFFF)\n");
    free(out);
    gl_context_destroy(ctx);
}

static void test_debug_forced_by_environment(void **state)
{
    (void)state;
    const char *old = getenv("SHADESWEEP_GL_DEBUG");
    char *saved = old ? strdup(old) : NULL;
    setenv("SHADESWEEP_GL_DEBUG", "1", 1);
    gl_context *ctx = create(GL_BACKEND_EGL, -1, false, 0, 0);
    assert_true(gl_context_info(ctx)->debug_context);
    gl_context_destroy(ctx);
    setenv("SHADESWEEP_GL_DEBUG", "0", 1);
    ctx = create(GL_BACKEND_EGL, -1, false, 0, 0);
    assert_false(gl_context_info(ctx)->debug_context);
    gl_context_destroy(ctx);
    if (saved)
        setenv("SHADESWEEP_GL_DEBUG", saved, 1);
    else
        unsetenv("SHADESWEEP_GL_DEBUG");
    free(saved);
}

static void test_resolution_limits(void **state)
{
    (void)state;
    gl_context *ctx = create(GL_BACKEND_EGL, -1, true, 0, 0);
    int rb = gl_context_info(ctx)->max_renderbuffer_size;
    gl_context_destroy(ctx);
    assert_true(rb < 70000);

    char err[512], want[512];
    create_fails(GL_BACKEND_EGL, -1, 70000, 10, err, sizeof err);
    snprintf(want, sizeof want,
             "resolution 70000x10 exceeds this context's limit of %d (GL_MAX_RENDERBUFFER_SIZE)",
             rb);
    assert_string_equal(err, want);

    create_fails(GL_BACKEND_EGL, -1, 10, rb + 1, err, sizeof err);
    snprintf(want, sizeof want,
             "resolution 10x%d exceeds this context's limit of %d (GL_MAX_RENDERBUFFER_SIZE)",
             rb + 1, rb);
    assert_string_equal(err, want);

    create_fails(GL_BACKEND_EGL, -1, -4, 10, err, sizeof err);
    assert_string_equal(err, "resolution -4x10 is invalid (both positive, or 0x0 for no "
                             "framebuffer)");
    create_fails(GL_BACKEND_EGL, -1, 0, 10, err, sizeof err);
    assert_non_null(strstr(err, "resolution 0x10 is invalid"));

    /* The limit itself is fine, and a context works after the failures. */
    ctx = create(GL_BACKEND_EGL, -1, true, rb, 1);
    assert_int_not_equal(gl_context_framebuffer(ctx), 0);
    gl_context_destroy(ctx);
}

static void test_egl_devices(void **state)
{
    (void)state;
    char err[512] = "";
    int n = gl_egl_device_count(err, sizeof err);
    if (n < 0) {
        /* No device enumeration here: said clearly, and no device opens. */
        assert_non_null(strstr(err, "EGL"));
        char err2[512];
        create_fails(GL_BACKEND_EGL, 0, 8, 8, err2, sizeof err2);
        assert_string_equal(err2, err);
        return;
    }
    char want[128];
    /* A failed creation leaves the context that is current alone. */
    gl_context *live = create(GL_BACKEND_EGL, -1, true, 6, 4);
    create_fails(GL_BACKEND_EGL, 99, 8, 8, err, sizeof err);
    snprintf(want, sizeof want, "EGL device 99 requested, but %d found", n);
    assert_string_equal(err, want);
    check_readback(live, 6, 4);
    gl_context_destroy(live);
    if (n == 0)
        return;

    gl_context *ctx = create(GL_BACKEND_EGL, 0, true, 12, 10);
    const gl_info *i = gl_context_info(ctx);
    assert_string_equal(i->backend, "egl-device");
    assert_true(i->device[0] != '\0');
    int major, minor;
    parse_version(i->version, &major, &minor);
    assert_true(major > 4 || (major == 4 && minor >= 5));
    check_readback(ctx, 12, 10);
    gl_context_destroy(ctx);
}

// >>osmesa

static void test_osmesa(void **state)
{
    (void)state;
#if HAVE_OSMESA
    for (int round = 0; round < 3; round++) {
        gl_context *ctx = create(GL_BACKEND_OSMESA, -1, true, 11, 8);
        const gl_info *i = gl_context_info(ctx);
        assert_string_equal(i->backend, "osmesa");
        int major, minor;
        parse_version(i->version, &major, &minor);
        assert_true(major > 3 || (major == 3 && minor >= 3));
        assert_non_null(strstr(i->version, "Core Profile"));
        if (round == 0)
            print_message("OSMesa gives GL %s (%s)\n", i->version, i->renderer);
        assert_true(i->max_draw_buffers >= 8);
        assert_all_functions_loaded();
        check_readback(ctx, 11, 8);

        /* No debug flag on OSMesa, but debug output still counts errors. */
        assert_false(i->debug_context);
        capture c;
        capture_begin(&c);
        gl.Enable(0xFFFF);
        uint64_t counted = gl_context_error_count(ctx);
        unsigned polled = gl_context_poll_errors(ctx, "osmesa");
        free(capture_end(&c));
        assert_int_equal(counted, 1);
        assert_int_equal(polled, 1);
        assert_int_equal(gl_context_error_count(ctx), 1);
        gl_context_destroy(ctx);
    }
#else
    skip();
#endif
}

static void test_backends_alternate(void **state)
{
    (void)state;
#if HAVE_OSMESA
    gl_backend order[] = {GL_BACKEND_EGL, GL_BACKEND_OSMESA, GL_BACKEND_EGL, GL_BACKEND_OSMESA};
    for (size_t k = 0; k < sizeof order / sizeof order[0]; k++) {
        gl_context *ctx = create(order[k], -1, true, 5, 4);
        check_readback(ctx, 5, 4);
        gl_context_destroy(ctx);
    }
#else
    skip();
#endif
}

int main(void)
{
    GL_TEST_SKIP_WITHOUT_EGL();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_loader),
        cmocka_unit_test(test_create_destroy_many),
        cmocka_unit_test(test_info),
        cmocka_unit_test(test_debug_context_counts_error_once),
        cmocka_unit_test(test_poll_finds_error_without_debug),
        cmocka_unit_test(test_debug_forced_by_environment),
        cmocka_unit_test(test_resolution_limits),
        cmocka_unit_test(test_egl_devices),
        cmocka_unit_test(test_osmesa),
        cmocka_unit_test(test_backends_alternate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
