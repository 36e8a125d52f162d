/* The GL layer the renderers share: embedded shaders (renderers/gl/shaders.h),
 * programs in #define variants (program.h), render targets and framebuffers
 * (target.h) and the counting state cache (state.h), on whatever headless GL this
 * machine has (llvmpipe in CI). Every test runs in a debug context and fails on any
 * GL error it did not expect. Exits 77 (skip) when no EGL display can be created. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/query.h"
#include "renderers/gl/shaders.h"
#include "renderers/gl/state.h"
#include "renderers/gl/target.h"
#include "tests/gl/gl_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// >>fixture

typedef struct fixture {
    gl_context *ctx;
    uint64_t expected_errors;   /* GL errors a test provokes on purpose */
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    char err[512] = "";
    gl_context_desc desc = {.backend = GL_BACKEND_EGL, .device = -1, .debug = true,
                            .width = 64, .height = 48};
    f->ctx = gl_context_create(&desc, err, sizeof err);
    if (!f->ctx) {
        fprintf(stderr, "gl_context_create failed: %s\n", err);
        free(f);
        return -1;
    }
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    gl_context_poll_errors(f->ctx, "test end");
    uint64_t errors = gl_context_error_count(f->ctx);
    uint64_t expected = f->expected_errors;
    gl_context_destroy(f->ctx);
    free(f);
    if (errors != expected) {
        fprintf(stderr, "%llu GL errors, expected %llu\n", (unsigned long long)errors,
                (unsigned long long)expected);
        return -1;
    }
    return 0;
}

// >>helpers

static void assert_contains(const char *haystack, const char *needle)
{
    if (!haystack)
        fail_msg("expected \"%s\" in a NULL string", needle);
    else if (!strstr(haystack, needle))
        fail_msg("expected \"%s\" in:\n%s", needle, haystack);
}

static void assert_no_gl_errors(fixture *f)
{
    gl_context_poll_errors(f->ctx, "test");
    assert_int_equal(gl_context_error_count(f->ctx), f->expected_errors);
}

/* The line (from 1) of the first occurrence of needle in an embedded source. */
static unsigned line_of(const char *source_name, const char *needle)
{
    const char *src = gl_shader_source(source_name);
    assert_non_null(src);
    const char *at = strstr(src, needle);
    assert_non_null(at);
    unsigned line = 1;
    for (const char *p = src; p < at; p++)
        line += *p == '\n';
    return line;
}

/* The driver's log names source string `string`, line `line`: "0:28(" in Mesa's
 * form, "0(28)" in NVIDIA's. */
static void assert_log_line(const char *log, unsigned string, unsigned line)
{
    char mesa[32], nvidia[32];
    snprintf(mesa, sizeof mesa, "%u:%u(", string, line);
    snprintf(nvidia, sizeof nvidia, "%u(%u)", string, line);
    if (!strstr(log, mesa) && !strstr(log, nvidia))
        fail_msg("expected source string %u line %u (\"%s\" or \"%s\") in:\n%s", string, line,
                 mesa, nvidia, log);
}

static GLuint get_program(gl_program_cache *pc, const gl_program_desc *d)
{
    char err[4096];
    GLuint prog = 0;
    gl_program_err e = gl_program_get(pc, d, &prog, err, sizeof err);
    if (e != GLP_OK)
        fail_msg("gl_program_get: %s", err);
    assert_int_not_equal(prog, 0);
    return prog;
}

static void make_target(gl_target *t, const char *name, gl_format fmt, int w, int h)
{
    char err[512];
    if (!gl_target_create(t, &(gl_target_desc){.name = name, .format = fmt, .width = w,
                                                .height = h},
                          err, sizeof err))
        fail_msg("gl_target_create(%s): %s", name, err);
}

static void make_framebuffer(gl_framebuffer *fb, const gl_framebuffer_desc *d)
{
    char err[1024];
    if (!gl_framebuffer_create(fb, d, err, sizeof err))
        fail_msg("gl_framebuffer_create: %s", err);
    assert_int_not_equal(fb->fbo, 0);
}

static void assert_category(const gls_counts *c, gls_category cat, uint64_t want)
{
    if (c->category[cat] != want)
        fail_msg("%s changes: %llu, expected %llu", gl_state_category_name(cat),
                 (unsigned long long)c->category[cat], (unsigned long long)want);
}

/* Every category of c against want[GLS_CAT_COUNT], and state_changes against their
 * sum over the counted categories. */
static void assert_counts(const gls_counts *c, const uint64_t want[GLS_CAT_COUNT],
                          uint64_t draws)
{
    uint64_t sum = 0;
    for (int k = 0; k < GLS_CAT_COUNT; k++) {
        assert_category(c, (gls_category)k, want[k]);
        if (k < GLS_CAT_STATE_CHANGES_END)
            sum += want[k];
    }
    assert_int_equal(c->state_changes, sum);
    assert_int_equal(c->draw_calls, draws);
}

static GLint get_int(GLenum pname)
{
    GLint v = -1;
    gl.GetIntegerv(pname, &v);
    return v;
}

// >>embedded sources

static void test_embedded_sources(void **state)
{
    (void)state;
    const char *src = gl_shader_source("test_color.frag");
    assert_non_null(src);
    assert_contains(src, "TEST_COMPILE_ERROR");
    assert_non_null(gl_shader_source("fullscreen.vert"));
    assert_non_null(gl_shader_source("test_common.inc"));
    assert_contains(gl_shader_source("fullscreen.vert"), "gl_VertexID");
    /* The source ends in a newline and nothing follows it. */
    assert_int_equal(src[strlen(src) - 1], '\n');

    assert_null(gl_shader_source("test_color"));
    assert_null(gl_shader_source("test_color.frag.glsl"));
    assert_null(gl_shader_source("shaders/test_color.frag"));
    assert_null(gl_shader_source("TEST_COLOR.FRAG"));
    assert_null(gl_shader_source(""));
    assert_null(gl_shader_source(NULL));

    size_t n = gl_shader_count();
    assert_true(n >= 4);
    for (size_t i = 0; i < n; i++) {
        assert_non_null(gl_shader_source(gl_shader_name(i)));
        if (i > 0)
            assert_true(strcmp(gl_shader_name(i - 1), gl_shader_name(i)) < 0);
    }
    assert_null(gl_shader_name(n));
}

// >>programs

static const char *program_fails(gl_program_cache *pc, const gl_program_desc *d,
                                 gl_program_err want);

static void test_program_variants(void **state)
{
    fixture *f = *state;
    gl_program_cache *pc = gl_program_cache_create();
    assert_non_null(pc);
    assert_int_equal(gl_program_cache_count(pc), 0);

    GLuint plain = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                      .fragment = "test_color.frag"});
    GLuint a = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                  .fragment = "test_color.frag",
                                                  .defines = {"FRAGCOORD"}});
    GLuint b = get_program(pc, &(gl_program_desc){.name = "mrt",
                                                  .vertex = "fullscreen.vert",
                                                  .fragment = "test_color.frag",
                                                  .defines = {"OUTPUTS 2", "FRAGCOORD"}});
    assert_int_equal(gl_program_cache_count(pc), 3);
    assert_true(plain != a && a != b && plain != b);
    assert_string_equal(gl_program_cache_variant(pc, 0), "test_color");
    assert_string_equal(gl_program_cache_variant(pc, 1), "test_color+FRAGCOORD");
    assert_string_equal(gl_program_cache_variant(pc, 2), "mrt+FRAGCOORD+OUTPUTS=2");
    assert_int_equal(gl_program_cache_program(pc, 1), a);
    assert_null(gl_program_cache_variant(pc, 3));
    assert_int_equal(gl_program_cache_program(pc, 3), 0);

    /* The same variants again, defines reordered and spaced differently, under
     * another display name: nothing is compiled. */
    assert_int_equal(get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                        .fragment = "test_color.frag",
                                                        .defines = {" FRAGCOORD\t"}}),
                     a);
    assert_int_equal(get_program(pc, &(gl_program_desc){.name = "other",
                                                        .vertex = "fullscreen.vert",
                                                        .fragment = "test_color.frag",
                                                        .defines = {"FRAGCOORD", "OUTPUTS\t 2 "}}),
                     b);
    assert_int_equal(get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                        .fragment = "test_color.frag"}),
                     plain);
    assert_int_equal(gl_program_cache_count(pc), 3);
    assert_string_equal(gl_program_cache_variant(pc, 2), "mrt+FRAGCOORD+OUTPUTS=2");

    pass_plan plan = {.nprograms = 1};
    gl_program_cache_describe(pc, &plan);
    assert_int_equal(plan.nprograms, 4);
    assert_string_equal(plan.program[1], "test_color");
    assert_string_equal(plan.program[3], "mrt+FRAGCOORD+OUTPUTS=2");

    /* fullscreen.vert's v_uv, read as its header says. */
    get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                       .fragment = "test_color.frag",
                                       .defines = {"READ_UV"}});
    assert_int_equal(gl_program_cache_count(pc), 4);

    /* Another vertex source is another variant. */
    GLuint back = get_program(pc, &(gl_program_desc){.vertex = "test_back.vert",
                                                     .fragment = "test_color.frag",
                                                     .defines = {"FRAGCOORD"}});
    assert_true(back != a);
    assert_int_equal(gl_program_cache_count(pc), 5);

    GLint linked = 0;
    gl.GetProgramiv(b, GL_LINK_STATUS, &linked);
    assert_int_equal(linked, GL_TRUE);

    /* Common defines: in every program built from now on and in its identity (the same
     * desc is another program under them), not in its name; a desc that names one is
     * refused; malformed or repeated ones are refused and change nothing. */
    const char *common[] = {"OUTPUTS 2"};
    assert_true(gl_program_cache_set_common(pc, common, 1));
    GLuint ca = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                   .fragment = "test_color.frag",
                                                   .defines = {"FRAGCOORD"}});
    assert_true(ca != a && ca != b);
    assert_int_equal(gl_program_cache_count(pc), 6);
    assert_string_equal(gl_program_cache_variant(pc, 5), "test_color+FRAGCOORD");
    GLint outputs = 0;   /* OUTPUTS 2 made test_color.frag's o_color an array of 2 */
    const GLenum array_size = GL_ARRAY_SIZE;
    gl.GetProgramResourceiv(ca, GL_PROGRAM_OUTPUT, 0, 1, &array_size, 1, NULL, &outputs);
    assert_int_equal(outputs, 2);
    gl.GetProgramResourceiv(a, GL_PROGRAM_OUTPUT, 0, 1, &array_size, 1, NULL, &outputs);
    assert_int_equal(outputs, 1);
    const char *err = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                           .fragment = "test_color.frag",
                                                           .defines = {"OUTPUTS 3"}},
                                    GLP_ERR_DEFINE);
    assert_non_null(strstr(err, "OUTPUTS is one of the cache's common defines"));
    const char *bad[] = {"9X"}, *twice[] = {"A", "A 1"};
    assert_false(gl_program_cache_set_common(pc, bad, 1));
    assert_false(gl_program_cache_set_common(pc, twice, 2));
    assert_int_equal(get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                        .fragment = "test_color.frag",
                                                        .defines = {"FRAGCOORD"}}),
                     ca);
    assert_true(gl_program_cache_set_common(pc, NULL, 0));
    assert_int_equal(get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                        .fragment = "test_color.frag",
                                                        .defines = {"FRAGCOORD"}}),
                     a);
    gl_program_cache_destroy(pc);
    gl_program_cache_destroy(NULL);
    assert_no_gl_errors(f);
}

/* A build that must fail with error e; returns the message (static buffer). */
static const char *program_fails(gl_program_cache *pc, const gl_program_desc *d,
                                 gl_program_err want)
{
    static char err[8192];
    GLuint prog = 12345;
    gl_program_err e = gl_program_get(pc, d, &prog, err, sizeof err);
    if (e != want)
        fail_msg("gl_program_get gave %d (%s), expected %d; message: %s", (int)e,
                 gl_program_err_text(e), (int)want, err);
    assert_int_equal(prog, 0);
    assert_true(err[0] != '\0');
    return err;
}

static void test_program_errors(void **state)
{
    fixture *f = *state;
    gl_program_cache *pc = gl_program_cache_create();
    assert_non_null(pc);

    /* A compile error in the file itself: source string 0, the file's own line. */
    uint64_t before = gl_context_error_count(f->ctx);
    const char *m = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                         .fragment = "test_color.frag",
                                                         .defines = {"TEST_COMPILE_ERROR",
                                                                     "FRAGCOORD"}},
                                  GLP_ERR_COMPILE);
    assert_contains(m, "program test_color+FRAGCOORD+TEST_COMPILE_ERROR (vertex fullscreen.vert, "
                       "fragment test_color.frag, defines FRAGCOORD, TEST_COMPILE_ERROR)");
    assert_contains(m, "the fragment shader does not compile");
    assert_contains(m, "source strings: 0 test_color.frag, 1 test_common.inc");
    assert_contains(m, "this_is_not_declared");   /* the driver's log */
    assert_log_line(m, 0, line_of("test_color.frag", "this_is_not_declared"));
    /* Mesa reports a failed compile through KHR_debug too: a debug context counts it. */
    uint64_t per_failure = gl_context_error_count(f->ctx) - before;
    assert_true(per_failure <= 1);
    f->expected_errors += per_failure;

    /* Before any #include: the lines after the defines count from 1. */
    m = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                             .fragment = "test_color.frag",
                                             .defines = {"TEST_EARLY_ERROR", "A", "B 2"}},
                      GLP_ERR_COMPILE);
    assert_log_line(m, 0, line_of("test_color.frag", "this_line_comes_before_any_include"));
    f->expected_errors += per_failure;

    /* A compile error in an included file: its source string number and its line. */
    m = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                             .fragment = "test_color.frag",
                                             .defines = {"TEST_INCLUDE_ERROR"}},
                      GLP_ERR_COMPILE);
    assert_log_line(m, 1, line_of("test_common.inc", "this_include_line_is_not_glsl"));
    assert_contains(m, "source strings: 0 test_color.frag, 1 test_common.inc");
    f->expected_errors += per_failure;

    /* A link error: the fragment shader reads what no vertex shader writes. */
    before = gl_context_error_count(f->ctx);
    m = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                             .fragment = "test_color.frag",
                                             .defines = {"TEST_LINK_ERROR"}},
                      GLP_ERR_LINK);
    assert_contains(m, "program test_color+TEST_LINK_ERROR (vertex fullscreen.vert, fragment "
                       "test_color.frag, defines TEST_LINK_ERROR): the program does not link:\n");
    assert_contains(m, "v_not_written_by_any_vertex_shader");
    uint64_t link_errors = gl_context_error_count(f->ctx) - before;
    assert_true(link_errors <= 1);
    f->expected_errors += link_errors;

    /* Refused before any GL call. */
    before = gl_context_error_count(f->ctx);
    m = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                             .fragment = "no_such.frag"},
                      GLP_ERR_SOURCE);
    assert_contains(m, "no embedded shader is called \"no_such.frag\"");
    m = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert"}, GLP_ERR_DESC);
    m = program_fails(pc, &(gl_program_desc){0}, GLP_ERR_DESC);
    m = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                             .fragment = "test_color.frag",
                                             .compute = "test_color.frag"},
                      GLP_ERR_DESC);
    m = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                             .fragment = "test_color.frag",
                                             .defines = {"1ABC"}},
                      GLP_ERR_DEFINE);
    assert_contains(m, "define \"1ABC\" does not start with a GLSL identifier");
    m = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                             .fragment = "test_color.frag",
                                             .defines = {"A 1\nvoid"}},
                      GLP_ERR_DEFINE);
    m = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                             .fragment = "test_color.frag",
                                             .defines = {"A-B"}},
                      GLP_ERR_DEFINE);
    m = program_fails(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                             .fragment = "test_color.frag",
                                             .defines = {"OUTPUTS 1", "FRAGCOORD", "OUTPUTS 2"}},
                      GLP_ERR_DEFINE);
    assert_contains(m, "OUTPUTS is defined twice");
    assert_int_equal(gl_context_error_count(f->ctx), before);

    /* Nothing failed was cached; a good variant still builds. */
    assert_int_equal(gl_program_cache_count(pc), 0);
    get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                       .fragment = "test_color.frag"});
    assert_int_equal(gl_program_cache_count(pc), 1);
    assert_string_equal(gl_program_err_text(GLP_ERR_LINK), "the program does not link");
    gl_program_cache_destroy(pc);
    assert_no_gl_errors(f);
}

// >>targets

static const struct {
    const char *name;
    gl_format format;
    unsigned bpp;
    GLenum internal_format;
    bool depth;
} format_cases[] = {
    {"rgba8", GLT_FORMAT_RGBA8, 4, GL_RGBA8, false},
    {"rgb10a2", GLT_FORMAT_RGB10A2, 4, GL_RGB10_A2, false},
    {"rg8", GLT_FORMAT_RG8, 2, GL_RG8, false},
    {"rgba16f", GLT_FORMAT_RGBA16F, 8, GL_RGBA16F, false},
    {"rg16f", GLT_FORMAT_RG16F, 4, GL_RG16F, false},
    {"r16f", GLT_FORMAT_R16F, 2, GL_R16F, false},
    {"rgba32f", GLT_FORMAT_RGBA32F, 16, GL_RGBA32F, false},
    {"r32f", GLT_FORMAT_R32F, 4, GL_R32F, false},
    {"r32ui", GLT_FORMAT_R32UI, 4, GL_R32UI, false},
    {"depth24-stencil8", GLT_FORMAT_DEPTH24_STENCIL8, 4, GL_DEPTH24_STENCIL8, true},
    {"depth32f-stencil8", GLT_FORMAT_DEPTH32F_STENCIL8, 8, GL_DEPTH32F_STENCIL8, true},
    {NULL, GLT_FORMAT_NONE, 0, 0, false},
};

static void test_formats_complete(void **state)
{
    fixture *f = *state;
    const int w = 37, h = 23;
    size_t n = 0;
    for (size_t i = 0; format_cases[i].name; i++, n++) {
        const char *name = format_cases[i].name;
        gl_format fmt = gl_format_find(name);
        assert_int_equal(fmt, format_cases[i].format);
        const gl_format_info *fi = gl_format_get(fmt);
        assert_non_null(fi);
        assert_string_equal(fi->name, name);
        assert_string_equal(gl_format_name(fmt), name);
        assert_int_equal(fi->bytes_per_pixel, format_cases[i].bpp);
        assert_int_equal(fi->internal_format, format_cases[i].internal_format);
        assert_int_equal(fi->depth, format_cases[i].depth);
        assert_int_equal(fi->color, !format_cases[i].depth);

        gl_target t;
        make_target(&t, name, fmt, w, h);
        assert_int_equal(t.bytes, (uint64_t)w * h * format_cases[i].bpp);
        assert_int_equal(gl_format_bytes(fmt, w, h), t.bytes);
        GLint v = 0;
        gl.GetTextureLevelParameteriv(t.texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &v);
        assert_int_equal(v, (GLint)format_cases[i].internal_format);
        gl.GetTextureLevelParameteriv(t.texture, 0, GL_TEXTURE_WIDTH, &v);
        assert_int_equal(v, w);
        gl.GetTextureLevelParameteriv(t.texture, 0, GL_TEXTURE_HEIGHT, &v);
        assert_int_equal(v, h);

        target_plan_entry e;
        gl_target_describe(&t, &e);
        assert_string_equal(e.name, name);
        assert_string_equal(e.format, name);
        assert_int_equal(e.width, w);
        assert_int_equal(e.height, h);
        assert_int_equal(e.bytes, t.bytes);

        gl_target ds = {0};
        gl_framebuffer fb;
        if (format_cases[i].depth) {
            make_framebuffer(&fb, &(gl_framebuffer_desc){.name = name, .depth_stencil = &t});
            assert_int_equal(fb.ncolor, 0);
        } else {
            make_target(&ds, "depth", GLT_FORMAT_DEPTH24_STENCIL8, w, h);
            make_framebuffer(&fb, &(gl_framebuffer_desc){.name = name, .color = {&t},
                                                         .depth_stencil = &ds});
            assert_int_equal(fb.ncolor, 1);
        }
        assert_int_equal(gl.CheckNamedFramebufferStatus(fb.fbo, GL_DRAW_FRAMEBUFFER),
                         GL_FRAMEBUFFER_COMPLETE);
        assert_int_equal(fb.width, w);
        assert_int_equal(fb.height, h);
        gl_framebuffer_destroy(&fb);
        gl_framebuffer_destroy(&fb);   /* twice is harmless */
        gl_target_destroy(&ds);
        gl_target_destroy(&t);
        gl_target_destroy(&t);
    }
    assert_int_equal(n, GLT_FORMAT_COUNT - 1);

    assert_int_equal(gl_format_find("RGBA8"), GLT_FORMAT_NONE);
    assert_int_equal(gl_format_find("rgba"), GLT_FORMAT_NONE);
    assert_int_equal(gl_format_find("d24s8"), GLT_FORMAT_NONE);
    assert_int_equal(gl_format_find(NULL), GLT_FORMAT_NONE);
    assert_null(gl_format_get(GLT_FORMAT_NONE));
    assert_null(gl_format_get(GLT_FORMAT_COUNT));
    assert_string_equal(gl_format_name(GLT_FORMAT_NONE), "none");
    assert_int_equal(gl_format_bytes(GLT_FORMAT_RGBA32F, 1280, 720), 1280ull * 720 * 16);
    assert_int_equal(gl_format_bytes(GLT_FORMAT_RGBA32F, 0, 720), 0);
    assert_no_gl_errors(f);
}

static void test_target_errors(void **state)
{
    fixture *f = *state;
    char err[1024];
    gl_target t;
    assert_false(gl_target_create(&t, &(gl_target_desc){.name = "x", .width = 4, .height = 4},
                                  err, sizeof err));
    assert_string_equal(err, "target x: no pixel format given");
    assert_int_equal(t.texture, 0);
    assert_false(gl_target_create(&t, &(gl_target_desc){.name = "big",
                                                        .format = GLT_FORMAT_RG8,
                                                        .width = 1 << 20, .height = 4},
                                  err, sizeof err));
    assert_contains(err, "target big (rg8): size 1048576x4 is not within 1x1 ..");
    assert_false(gl_target_create(&t, &(gl_target_desc){.format = GLT_FORMAT_RG8}, err,
                                  sizeof err));
    assert_contains(err, "target target (rg8): size 0x0");

    gl_target color, depth, small;
    make_target(&color, "albedo", GLT_FORMAT_RGBA16F, 16, 8);
    make_target(&depth, "depth", GLT_FORMAT_DEPTH32F_STENCIL8, 16, 8);
    make_target(&small, "small", GLT_FORMAT_R32F, 8, 8);
    gl_framebuffer fb;
    assert_false(gl_framebuffer_create(&fb, &(gl_framebuffer_desc){.name = "g",
                                                                   .color = {&depth}},
                                       err, sizeof err));
    assert_string_equal(err, "framebuffer g: colour 0 has the depth format depth32f-stencil8 "
                             "(colour 0 depth depth32f-stencil8 16x8)");
    assert_int_equal(fb.fbo, 0);
    assert_false(gl_framebuffer_create(&fb, &(gl_framebuffer_desc){.name = "g",
                                                                   .color = {&color},
                                                                   .depth_stencil = &color},
                                       err, sizeof err));
    assert_string_equal(err, "framebuffer g: the depth-stencil attachment has the colour format "
                             "rgba16f (colour 0 albedo rgba16f 16x8, depth-stencil albedo "
                             "rgba16f 16x8)");
    assert_false(gl_framebuffer_create(&fb, &(gl_framebuffer_desc){.name = "g",
                                                                   .color = {&color, &small},
                                                                   .depth_stencil = &depth},
                                       err, sizeof err));
    assert_string_equal(err, "framebuffer g: attachments differ in size (colour 0 albedo rgba16f "
                             "16x8, colour 1 small r32f 8x8, depth-stencil depth "
                             "depth32f-stencil8 16x8)");
    assert_false(gl_framebuffer_create(&fb, &(gl_framebuffer_desc){.name = "g"}, err,
                                       sizeof err));
    assert_string_equal(err, "framebuffer g: no attachments");
    gl_target none = {0};
    assert_false(gl_framebuffer_create(&fb, &(gl_framebuffer_desc){.color = {&color, &none}},
                                       err, sizeof err));
    assert_contains(err, "framebuffer framebuffer: colour 1 is a target that was not created");
    assert_false(gl_framebuffer_create(&fb, &(gl_framebuffer_desc){.color = {&color, NULL,
                                                                             &small}},
                                       err, sizeof err));
    assert_contains(err, "colour target 2 follows an empty slot 1");
    gl_target_destroy(&color);
    gl_target_destroy(&depth);
    gl_target_destroy(&small);
    assert_no_gl_errors(f);
}

/* Eight colour targets, every colour format once (rgba8 twice), and a
 * depth32f-stencil8: complete, and one draw writes all eight. */
static void test_mrt_eight(void **state)
{
    fixture *f = *state;
    const int w = 8, h = 4;
    static const gl_format fmts[GLT_MAX_COLOR] = {
        GLT_FORMAT_RGBA8, GLT_FORMAT_RGB10A2, GLT_FORMAT_RG8,     GLT_FORMAT_RGBA16F,
        GLT_FORMAT_RG16F, GLT_FORMAT_R16F,    GLT_FORMAT_RGBA32F, GLT_FORMAT_R32F,
    };
    gl_target t[GLT_MAX_COLOR], ds;
    gl_framebuffer_desc d = {.name = "mrt", .depth_stencil = &ds};
    uint64_t bytes = 0;
    for (int i = 0; i < GLT_MAX_COLOR; i++) {
        char name[16];
        snprintf(name, sizeof name, "c%d", i);
        make_target(&t[i], name, fmts[i], w, h);
        d.color[i] = &t[i];
        bytes += t[i].bytes;
    }
    assert_int_equal(bytes, (uint64_t)w * h * (4 + 4 + 2 + 8 + 4 + 2 + 16 + 4));
    make_target(&ds, "depth", GLT_FORMAT_DEPTH32F_STENCIL8, w, h);
    gl_framebuffer fb;
    make_framebuffer(&fb, &d);
    assert_int_equal(fb.ncolor, 8);
    assert_int_equal(gl.CheckNamedFramebufferStatus(fb.fbo, GL_DRAW_FRAMEBUFFER),
                     GL_FRAMEBUFFER_COMPLETE);

    gl_program_cache *pc = gl_program_cache_create();
    GLuint prog = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                     .fragment = "test_color.frag",
                                                     .defines = {"OUTPUTS 8"}});
    gl_state *s = gl_state_create();
    assert_non_null(s);
    gl_state_begin_pass(s, "mrt");
    gl_state_framebuffer(s, fb.fbo);
    gl_state_viewport(s, 0, 0, w, h);
    gl_state_clear(s, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, NULL,
                   1.0, 0);
    gl_state_program(s, prog);
    gl.Uniform4f(0, 1.0f, 0.0f, 1.0f, 1.0f);
    gl_state_blend(s, NULL);
    gl_state_depth(s, NULL);
    gl_state_stencil(s, NULL);
    gl_state_cull(s, GLS_CULL_NONE);
    gl_state_vertex_array(s, 0);
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);
    pass_stats ps;
    gl_state_end_pass(s, &ps);
    assert_int_equal(ps.draw_calls, 1);

    static const float want[4] = {1, 0, 1, 1};
    for (int i = 0; i < GLT_MAX_COLOR; i++) {
        float px[8 * 4 * 4];
        gl.GetTextureImage(t[i].texture, 0, GL_RGBA, GL_FLOAT, (GLsizei)sizeof px, px);
        int channels = fmts[i] == GLT_FORMAT_RG8 || fmts[i] == GLT_FORMAT_RG16F ? 2
                       : fmts[i] == GLT_FORMAT_R16F || fmts[i] == GLT_FORMAT_R32F ? 1
                                                                                   : 4;
        for (int p = 0; p < w * h; p++)
            for (int c = 0; c < channels; c++)
                if (px[p * 4 + c] != want[c])
                    fail_msg("attachment %d (%s) pixel %d channel %d: %g, expected %g", i,
                             gl_format_name(fmts[i]), p, c, (double)px[p * 4 + c],
                             (double)want[c]);
    }
    gl_state_destroy(s);
    gl_program_cache_destroy(pc);
    gl_framebuffer_destroy(&fb);
    for (int i = 0; i < GLT_MAX_COLOR; i++)
        gl_target_destroy(&t[i]);
    gl_target_destroy(&ds);
    assert_no_gl_errors(f);
}

// >>state cache

static void test_state_counts(void **state)
{
    fixture *f = *state;
    gl_program_cache *pc = gl_program_cache_create();
    GLuint p1 = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                   .fragment = "test_color.frag"});
    GLuint p2 = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                   .fragment = "test_color.frag",
                                                   .defines = {"FRAGCOORD"}});
    gl_target t1, t2, ds;
    make_target(&t1, "t1", GLT_FORMAT_RGBA8, 4, 4);
    make_target(&t2, "t2", GLT_FORMAT_R32F, 4, 4);
    make_target(&ds, "ds", GLT_FORMAT_DEPTH24_STENCIL8, 4, 4);
    gl_framebuffer fb;   /* with stencil bits: GL_STENCIL_REF reads back clamped to them */
    make_framebuffer(&fb, &(gl_framebuffer_desc){.color = {&t1}, .depth_stencil = &ds});

    gl_state *s = gl_state_create();
    assert_non_null(s);
    assert_false(gl_state_force(s));
    gl_state_begin_pass(s, "counts");
    uint64_t want[GLS_CAT_COUNT] = {0};

    /* Everything starts unknown: the first set of each part counts. */
    gl_state_program(s, p1);                                  /* +1 */
    gl_state_program(s, p1);
    gl_state_program(s, p2);                                  /* +1 */
    gl_state_program(s, p2);
    gl_state_program(s, p1);                                  /* +1 */
    want[GLS_CAT_PROGRAM] = 3;
    assert_int_equal(get_int(GL_CURRENT_PROGRAM), (GLint)p1);

    gl_state_texture(s, 0, t1.texture);                       /* +1 */
    gl_state_texture(s, 0, t1.texture);
    gl_state_texture(s, 3, t1.texture);                       /* +1: another unit */
    gl_state_texture(s, 0, t2.texture);                       /* +1 */
    gl_state_texture(s, 3, t1.texture);
    gl_state_texture(s, 16, t1.texture);                      /* out of range: ignored */
    want[GLS_CAT_TEXTURE] = 3;
    gl.ActiveTexture(GL_TEXTURE3);
    assert_int_equal(get_int(GL_TEXTURE_BINDING_2D), (GLint)t1.texture);
    gl.ActiveTexture(GL_TEXTURE0);
    assert_int_equal(get_int(GL_TEXTURE_BINDING_2D), (GLint)t2.texture);

    gl_state_framebuffer(s, fb.fbo);                          /* +1 */
    gl_state_framebuffer(s, fb.fbo);
    want[GLS_CAT_FRAMEBUFFER] = 1;
    assert_int_equal(get_int(GL_DRAW_FRAMEBUFFER_BINDING), (GLint)fb.fbo);

    const gls_blend add = {.enabled = true, .src = GLS_BLEND_ONE, .dst = GLS_BLEND_ONE};
    const gls_blend add_spelled_out = {.enabled = true, .src = GLS_BLEND_ONE,
                                       .dst = GLS_BLEND_ONE, .op = GLS_BLEND_OP_ADD,
                                       .src_alpha = GLS_BLEND_ONE, .dst_alpha = GLS_BLEND_ONE,
                                       .op_alpha = GLS_BLEND_OP_ADD};
    const gls_blend alpha = {.enabled = true, .src = GLS_BLEND_SRC_ALPHA,
                             .dst = GLS_BLEND_ONE_MINUS_SRC_ALPHA,
                             .dst_alpha = GLS_BLEND_ZERO};
    gl_state_blend(s, NULL);                                  /* +1 (unknown) */
    gl_state_blend(s, &(gls_blend){0});
    gl_state_blend(s, &(gls_blend){.src = GLS_BLEND_DST_COLOR});   /* off: factors ignored */
    gl_state_blend(s, &add);                                  /* +1 */
    gl_state_blend(s, &add);
    gl_state_blend(s, &add_spelled_out);                      /* the same values */
    gl_state_blend(s, &alpha);                                /* +1 */
    gl_state_blend(s, NULL);                                  /* +1 */
    gl_state_blend(s, &alpha);                                /* +1: only glEnable */
    gl_state_color_mask(s, GLS_COLOR_MASK_RGBA);              /* +1 (unknown) */
    gl_state_color_mask(s, GLS_COLOR_MASK_RGBA);
    gl_state_color_mask(s, GLS_COLOR_MASK_NONE);              /* +1 */
    gl_state_color_mask(s, GLS_COLOR_MASK_R | GLS_COLOR_MASK_A);   /* +1 */
    want[GLS_CAT_BLEND] = 8;
    assert_true(gl.IsEnabled(GL_BLEND));
    assert_int_equal(get_int(GL_BLEND_SRC_RGB), GL_SRC_ALPHA);
    assert_int_equal(get_int(GL_BLEND_DST_RGB), GL_ONE_MINUS_SRC_ALPHA);
    assert_int_equal(get_int(GL_BLEND_SRC_ALPHA), GL_SRC_ALPHA);
    assert_int_equal(get_int(GL_BLEND_DST_ALPHA), GL_ZERO);
    assert_int_equal(get_int(GL_BLEND_EQUATION_ALPHA), GL_FUNC_ADD);
    GLint cm[4] = {0};
    gl.GetIntegerv(GL_COLOR_WRITEMASK, cm);
    assert_true(cm[0] && !cm[1] && !cm[2] && cm[3]);

    gl_state_depth(s, NULL);                                  /* +1 */
    gl_state_depth(s, &(gls_depth){.compare = GLS_COMPARE_ALWAYS});   /* the same: off */
    gl_state_depth(s, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});   /* +1 */
    gl_state_depth(s, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});
    gl_state_depth(s, &(gls_depth){.compare = GLS_COMPARE_LEQUAL});   /* +1 */
    gl_state_depth(s, &(gls_depth){.write = true});           /* +1: ALWAYS, writing */
    want[GLS_CAT_DEPTH] = 4;
    assert_true(gl.IsEnabled(GL_DEPTH_TEST));
    assert_int_equal(get_int(GL_DEPTH_FUNC), GL_ALWAYS);
    assert_int_equal(get_int(GL_DEPTH_WRITEMASK), GL_TRUE);

    const gls_stencil mark = {.enabled = true, .two_sided = true,
                              .front = {.depth_fail = GLS_STENCIL_OP_DECR_WRAP},
                              .back = {.depth_fail = GLS_STENCIL_OP_INCR_WRAP}};
    gl_state_stencil(s, &mark);                               /* +1 */
    gl_state_stencil(s, &mark);
    gl_state_stencil(s, NULL);                                /* +1 */
    gl_state_stencil(s, NULL);
    gl_state_stencil(s, &(gls_stencil){.enabled = true, .ref = 1,
                                       .front = {.compare = GLS_COMPARE_EQUAL}});   /* +1 */
    want[GLS_CAT_STENCIL] = 3;
    assert_true(gl.IsEnabled(GL_STENCIL_TEST));
    assert_int_equal(get_int(GL_STENCIL_FUNC), GL_EQUAL);
    assert_int_equal(get_int(GL_STENCIL_BACK_FUNC), GL_EQUAL);   /* one-sided: both faces */
    assert_int_equal(get_int(GL_STENCIL_REF), 1);
    assert_int_equal(get_int(GL_STENCIL_BACK_PASS_DEPTH_FAIL), GL_KEEP);
    assert_int_equal(get_int(GL_STENCIL_VALUE_MASK), 0xff);
    assert_int_equal(get_int(GL_STENCIL_WRITEMASK), 0xff);

    gl_state_cull(s, GLS_CULL_BACK);                          /* +1 */
    gl_state_cull(s, GLS_CULL_BACK);
    gl_state_cull(s, GLS_CULL_FRONT);                         /* +1 */
    gl_state_cull(s, GLS_CULL_NONE);                          /* +1 */
    gl_state_cull(s, GLS_CULL_NONE);
    want[GLS_CAT_CULL] = 3;
    assert_false(gl.IsEnabled(GL_CULL_FACE));
    assert_int_equal(get_int(GL_CULL_FACE_MODE), GL_FRONT);

    gl_state_viewport(s, 0, 0, 4, 4);                         /* +1, not a state change */
    gl_state_viewport(s, 0, 0, 4, 4);
    gl_state_vertex_array(s, 0);                              /* +1, not a state change */
    gl_state_vertex_array(s, 0);
    want[GLS_CAT_VIEWPORT] = 1;
    want[GLS_CAT_VERTEX_ARRAY] = 1;

    assert_counts(gl_state_pass_counts(s), want, 0);
    pass_stats ps = {.gpu_us = 7.0, .fragments = 5.0};
    gl_state_end_pass(s, &ps);
    assert_string_equal(ps.name, "counts");
    assert_int_equal(ps.state_changes, 3 + 3 + 1 + 8 + 4 + 3 + 3);
    assert_int_equal(ps.draw_calls, 0);
    assert_true(ps.gpu_us == 7.0 && ps.fragments == 5.0);   /* left alone */
    assert_true(ps.cpu_us >= 0.0);
    assert_counts(gl_state_total_counts(s), want, 0);

    /* The next pass starts at zero, and what is known stays known. */
    gl_state_begin_pass(s, "again");
    gl_state_program(s, p1);
    gl_state_blend(s, &alpha);
    gl_state_cull(s, GLS_CULL_NONE);
    gl_state_end_pass(s, &ps);
    assert_int_equal(ps.state_changes, 0);

    /* Invalidated, the same values count again. */
    gl_state_invalidate(s);
    gl_state_begin_pass(s, "invalidated");
    gl_state_program(s, p1);
    gl_state_program(s, p1);
    gl_state_texture(s, 0, t2.texture);
    gl_state_texture(s, 3, t1.texture);
    gl_state_blend(s, &alpha);
    gl_state_blend(s, &alpha);
    gl_state_cull(s, GLS_CULL_NONE);
    gl_state_viewport(s, 0, 0, 4, 4);
    gl_state_end_pass(s, &ps);
    uint64_t w2[GLS_CAT_COUNT] = {[GLS_CAT_PROGRAM] = 1, [GLS_CAT_TEXTURE] = 2,
                                  [GLS_CAT_BLEND] = 1, [GLS_CAT_CULL] = 1,
                                  [GLS_CAT_VIEWPORT] = 1};
    assert_counts(gl_state_pass_counts(s), w2, 0);

    /* Outside a pass: in the totals only. */
    const gls_counts *total = gl_state_total_counts(s);
    uint64_t before = total->state_changes;
    gl_state_program(s, p2);
    assert_int_equal(total->state_changes, before + 1);
    assert_int_equal(gl_state_pass_counts(s)->state_changes, 5);

    gl_state_destroy(s);
    gl_state_destroy(NULL);
    gl_framebuffer_destroy(&fb);
    gl_target_destroy(&t1);
    gl_target_destroy(&t2);
    gl_target_destroy(&ds);
    gl_program_cache_destroy(pc);
    assert_no_gl_errors(f);
}

static void test_state_force(void **state)
{
    fixture *f = *state;
    gl_target t;
    make_target(&t, "t", GLT_FORMAT_RGBA8, 4, 4);
    gl_state *s = gl_state_create();
    gl_state_set_force(s, true);
    assert_true(gl_state_force(s));
    gl_state_begin_pass(s, "forced");
    const gls_blend add = {.enabled = true, .src = GLS_BLEND_ONE, .dst = GLS_BLEND_ONE};
    const gls_stencil st = {.enabled = true, .front = {.compare = GLS_COMPARE_LESS}};
    for (int i = 0; i < 3; i++) {
        gl_state_program(s, 0);
        gl_state_texture(s, 1, t.texture);
        gl_state_framebuffer(s, gl_context_framebuffer(f->ctx));
        gl_state_blend(s, &add);
        gl_state_blend(s, NULL);
        gl_state_color_mask(s, GLS_COLOR_MASK_RGBA);
        gl_state_depth(s, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});
        gl_state_stencil(s, &st);
        gl_state_cull(s, GLS_CULL_BACK);
        gl_state_viewport(s, 0, 0, 64, 48);
        gl_state_vertex_array(s, 0);
    }
    uint64_t want[GLS_CAT_COUNT] = {
        [GLS_CAT_PROGRAM] = 3, [GLS_CAT_TEXTURE] = 3, [GLS_CAT_FRAMEBUFFER] = 3,
        [GLS_CAT_BLEND] = 9,   [GLS_CAT_DEPTH] = 3,   [GLS_CAT_STENCIL] = 3,
        [GLS_CAT_CULL] = 3,    [GLS_CAT_VIEWPORT] = 3, [GLS_CAT_VERTEX_ARRAY] = 3,
    };
    assert_counts(gl_state_pass_counts(s), want, 0);
    gl_state_end_pass(s, NULL);

    /* Force off again: only real changes count. */
    gl_state_set_force(s, false);
    gl_state_begin_pass(s, "unforced");
    gl_state_program(s, 0);
    gl_state_blend(s, NULL);
    gl_state_stencil(s, &st);
    gl_state_end_pass(s, NULL);
    assert_int_equal(gl_state_pass_counts(s)->state_changes, 0);
    gl_state_destroy(s);
    gl_target_destroy(&t);
    assert_no_gl_errors(f);
}

static void test_draws_per_pass(void **state)
{
    fixture *f = *state;
    gl_program_cache *pc = gl_program_cache_create();
    GLuint prog = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                     .fragment = "test_color.frag"});
    gl_state *s = gl_state_create();
    gl_state_framebuffer(s, gl_context_framebuffer(f->ctx));   /* outside any pass */
    gl_state_viewport(s, 0, 0, 64, 48);
    gl_state_program(s, prog);
    gl_state_vertex_array(s, 0);
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);
    assert_int_equal(gl_state_total_counts(s)->draw_calls, 1);

    frame_stats fs = {.npasses = 2};
    gl_state_begin_pass(s, "three");
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);
    gl_state_draw_arrays_instanced(s, GL_TRIANGLES, 0, 3, 4);   /* one draw call */
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);
    assert_int_equal(gl_state_pass_counts(s)->draw_calls, 3);
    gl_state_end_pass(s, &fs.pass[0]);
    gl_state_begin_pass(s, "one");
    assert_int_equal(gl_state_pass_counts(s)->draw_calls, 0);
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);
    gl_state_end_pass(s, &fs.pass[1]);
    assert_string_equal(fs.pass[0].name, "three");
    assert_int_equal(fs.pass[0].draw_calls, 3);
    assert_int_equal(fs.pass[0].state_changes, 0);
    assert_string_equal(fs.pass[1].name, "one");
    assert_int_equal(fs.pass[1].draw_calls, 1);
    assert_int_equal(gl_state_total_counts(s)->draw_calls, 5);
    gl_state_destroy(s);
    gl_program_cache_destroy(pc);
    assert_no_gl_errors(f);
}

// >>drawing

/* Reads an RGBA8 target and checks that every pixel holds its own coordinates
 * (x, y from the bottom left), blue 153 and alpha 255. */
static void assert_fragcoord_image(const gl_target *t)
{
    size_t n = (size_t)t->width * (size_t)t->height * 4;
    uint8_t *px = malloc(n);
    assert_non_null(px);
    gl.GetTextureImage(t->texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, (GLsizei)n, px);
    for (int y = 0; y < t->height; y++)
        for (int x = 0; x < t->width; x++) {
            const uint8_t *p = px + ((size_t)y * (size_t)t->width + (size_t)x) * 4;
            if (p[0] != x || p[1] != y || p[2] != 153 || p[3] != 255) {
                uint8_t got[4] = {p[0], p[1], p[2], p[3]};
                free(px);
                fail_msg("pixel (%d,%d) from the bottom is %u,%u,%u,%u, expected %d,%d,153,255",
                         x, y, got[0], got[1], got[2], got[3], x, y);
            }
        }
    free(px);
}

/* The full-screen triangle through the cache into a 64x48 RGBA8 target, in both
 * forms of fullscreen.vert: every pixel gets its own coordinates, exactly once;
 * unclipped, exactly 64*48 fragment shader invocations. */
static void test_fullscreen_triangle(void **state)
{
    fixture *f = *state;
    const int w = 64, h = 48;
    const gl_info *info = gl_context_info(f->ctx);
    gl_program_cache *pc = gl_program_cache_create();
    GLuint unclipped = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                          .fragment = "test_color.frag",
                                                          .defines = {"FRAGCOORD",
                                                                      "FULLSCREEN_UNCLIPPED"}});
    GLuint clipped = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                        .fragment = "test_color.frag",
                                                        .defines = {"FRAGCOORD"}});
    gl_target color;
    make_target(&color, "color", GLT_FORMAT_RGBA8, w, h);
    gl_framebuffer fb;
    make_framebuffer(&fb, &(gl_framebuffer_desc){.name = "out", .color = {&color}});
    gl_pass_queries *q = gl_pass_queries_create(2, false, info->pipeline_statistics);
    assert_non_null(q);
    gl_state *s = gl_state_create();
    assert_true(gl_state_fullscreen_unclipped_fits(s, w, h));
    frame_stats fs = {.npasses = 2};

    gl_state_begin_pass(s, "fullscreen");
    gl_pass_queries_begin(q, 0);
    gl_state_framebuffer(s, fb.fbo);
    gl_state_clear(s, GL_COLOR_BUFFER_BIT, (const float[4]){1, 1, 1, 0}, 1.0, 0);
    gl_state_program(s, unclipped);
    gl.Uniform4f(0, 0.0f, 0.0f, 153.0f / 255.0f, 1.0f);
    gl_state_blend(s, NULL);
    gl_state_depth(s, NULL);
    gl_state_stencil(s, NULL);
    gl_state_cull(s, GLS_CULL_BACK);
    assert_true(gl_state_draw_fullscreen(s, w, h, true));
    gl_pass_queries_end(q);
    gl_state_end_pass(s, &fs.pass[0]);
    uint64_t want[GLS_CAT_COUNT] = {
        [GLS_CAT_PROGRAM] = 1, [GLS_CAT_FRAMEBUFFER] = 1, [GLS_CAT_BLEND] = 2,
        [GLS_CAT_DEPTH] = 1,   [GLS_CAT_STENCIL] = 1,     [GLS_CAT_CULL] = 1,
        [GLS_CAT_VIEWPORT] = 1, [GLS_CAT_VERTEX_ARRAY] = 1,
    };
    assert_counts(gl_state_pass_counts(s), want, 1);
    GLint vp[4];
    gl.GetIntegerv(GL_VIEWPORT, vp);
    assert_true(vp[0] == 0 && vp[1] == 0 && vp[2] == 2 * w && vp[3] == 2 * h);
    assert_fragcoord_image(&color);

    gl_state_begin_pass(s, "fullscreen-clipped");
    gl_pass_queries_begin(q, 1);
    gl_state_clear(s, GL_COLOR_BUFFER_BIT, (const float[4]){1, 1, 1, 0}, 1.0, 0);
    gl_state_program(s, clipped);
    gl.Uniform4f(0, 0.0f, 0.0f, 153.0f / 255.0f, 1.0f);
    assert_true(gl_state_draw_fullscreen(s, w, h, false));
    /* samples: a paused stretch is not counted, resuming counts again */
    gl_pass_queries_pause(q);
    assert_true(gl_state_draw_fullscreen(s, w, h, false));
    gl_pass_queries_resume(q);
    assert_true(gl_state_draw_fullscreen(s, w, h, false));
    gl_pass_queries_end(q);
    gl_state_end_pass(s, &fs.pass[1]);
    uint64_t want2[GLS_CAT_COUNT] = {[GLS_CAT_PROGRAM] = 1, [GLS_CAT_VIEWPORT] = 1};
    assert_counts(gl_state_pass_counts(s), want2, 3);
    assert_fragcoord_image(&color);

    gl.Finish();
    gl_pass_queries_collect(q, &fs);
    assert_string_equal(fs.pass[0].name, "fullscreen");
    assert_int_equal(fs.pass[0].draw_calls, 1);
    /* GL_SAMPLES_PASSED on every driver: exactly the pixels, 2 of 3 draws in pass 1 */
    assert_true(fs.pass[0].samples == (double)(w * h));
    assert_true(fs.pass[1].samples == (double)(2 * w * h));
    if (info->pipeline_statistics) {
        if (fs.pass[0].fragments != (double)(w * h) || fs.pass[0].primitives != 1.0)
            fail_msg("%g fragments and %g primitives, expected %d and 1", fs.pass[0].fragments,
                     fs.pass[0].primitives, w * h);
        /* Clipped, an implementation may shade more (llvmpipe: see fullscreen.vert). */
        assert_true(fs.pass[1].fragments >= (double)(3 * w * h));   /* three draws */
        assert_true(fs.pass[1].primitives == 3.0);
    } else {
        fprintf(stderr, "note: no pipeline statistics queries here; fragments not checked\n");
    }

    /* Force on: every set counts, and the image is the same. */
    gl_state_set_force(s, true);
    gl_state_begin_pass(s, "fullscreen-forced");
    gl_state_framebuffer(s, fb.fbo);
    gl_state_clear(s, GL_COLOR_BUFFER_BIT, NULL, 1.0, 0);
    gl_state_program(s, unclipped);
    gl_state_blend(s, NULL);
    gl_state_depth(s, NULL);
    gl_state_stencil(s, NULL);
    gl_state_cull(s, GLS_CULL_BACK);
    gl_state_draw_fullscreen(s, w, h, true);
    gl_state_end_pass(s, NULL);
    assert_counts(gl_state_pass_counts(s), want, 1);
    assert_fragcoord_image(&color);

    gl_state_destroy(s);
    gl_pass_queries_destroy(q);
    gl_framebuffer_destroy(&fb);
    gl_target_destroy(&color);
    gl_program_cache_destroy(pc);
    assert_no_gl_errors(f);
}

/* Two-sided stencil: one pass marks with front faces incrementing and back faces
 * decrementing (seed 003's one-pass light volume marking), the next draws where
 * the stencil is exactly 1. */
static void test_two_sided_stencil(void **state)
{
    fixture *f = *state;
    const int w = 16, h = 8;
    gl_program_cache *pc = gl_program_cache_create();
    GLuint front = get_program(pc, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                      .fragment = "test_color.frag"});
    GLuint back = get_program(pc, &(gl_program_desc){.vertex = "test_back.vert",
                                                     .fragment = "test_color.frag"});
    gl_target color, ds;
    make_target(&color, "color", GLT_FORMAT_RGBA8, w, h);
    make_target(&ds, "ds", GLT_FORMAT_DEPTH24_STENCIL8, w, h);
    gl_framebuffer fb;
    make_framebuffer(&fb, &(gl_framebuffer_desc){.color = {&color}, .depth_stencil = &ds});

    gl_state *s = gl_state_create();
    gl_state_begin_pass(s, "mark");
    gl_state_framebuffer(s, fb.fbo);
    gl_state_viewport(s, 0, 0, w, h);
    gl_state_clear(s, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, NULL,
                   1.0, 0);
    gl_state_vertex_array(s, 0);
    gl_state_cull(s, GLS_CULL_NONE);
    gl_state_depth(s, NULL);
    gl_state_color_mask(s, GLS_COLOR_MASK_NONE);
    gl_state_stencil(s, &(gls_stencil){.enabled = true, .two_sided = true,
                                       .front = {.pass = GLS_STENCIL_OP_INCR_WRAP},
                                       .back = {.pass = GLS_STENCIL_OP_DECR_WRAP}});
    gl_state_program(s, front);
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);   /* +1 */
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);   /* +1 */
    gl_state_program(s, back);
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);   /* -1: stencil 1 everywhere */
    gl_state_end_pass(s, NULL);
    assert_int_equal(gl_state_pass_counts(s)->draw_calls, 3);

    gl_state_begin_pass(s, "shade");
    gl_state_color_mask(s, GLS_COLOR_MASK_RGBA);
    gl_state_stencil(s, &(gls_stencil){.enabled = true, .ref = 1,
                                       .front = {.compare = GLS_COMPARE_EQUAL}});
    gl_state_program(s, front);
    gl.Uniform4f(0, 51.0f / 255.0f, 102.0f / 255.0f, 153.0f / 255.0f, 1.0f);
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);
    /* ref 2 matches nothing: nothing drawn over. */
    gl.Uniform4f(0, 1.0f, 0.0f, 0.0f, 1.0f);
    gl_state_stencil(s, &(gls_stencil){.enabled = true, .ref = 2,
                                       .front = {.compare = GLS_COMPARE_EQUAL}});
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);
    gl_state_end_pass(s, NULL);
    uint64_t want[GLS_CAT_COUNT] = {[GLS_CAT_PROGRAM] = 1, [GLS_CAT_BLEND] = 1,
                                    [GLS_CAT_STENCIL] = 2};
    assert_counts(gl_state_pass_counts(s), want, 2);

    uint8_t px[16 * 8 * 4];
    gl.GetTextureImage(color.texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, (GLsizei)sizeof px, px);
    for (int i = 0; i < w * h; i++)
        if (px[i * 4] != 51 || px[i * 4 + 1] != 102 || px[i * 4 + 2] != 153 || px[i * 4 + 3] != 255)
            fail_msg("pixel %d is %u,%u,%u,%u, expected 51,102,153,255", i, px[i * 4],
                     px[i * 4 + 1], px[i * 4 + 2], px[i * 4 + 3]);

    /* Culling back faces: the mirrored triangle draws nothing. */
    gl_state_begin_pass(s, "cull");
    gl_state_stencil(s, NULL);
    gl_state_cull(s, GLS_CULL_BACK);
    gl_state_program(s, back);
    gl_state_draw_arrays(s, GL_TRIANGLES, 0, 3);
    gl_state_end_pass(s, NULL);
    gl.GetTextureImage(color.texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, (GLsizei)sizeof px, px);
    assert_true(px[0] == 51 && px[1] == 102);

    gl_state_destroy(s);
    gl_framebuffer_destroy(&fb);
    gl_target_destroy(&color);
    gl_target_destroy(&ds);
    gl_program_cache_destroy(pc);
    assert_no_gl_errors(f);
}

int main(void)
{
    GL_TEST_SKIP_WITHOUT_EGL();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_embedded_sources, setup, teardown),
        cmocka_unit_test_setup_teardown(test_program_variants, setup, teardown),
        cmocka_unit_test_setup_teardown(test_program_errors, setup, teardown),
        cmocka_unit_test_setup_teardown(test_formats_complete, setup, teardown),
        cmocka_unit_test_setup_teardown(test_target_errors, setup, teardown),
        cmocka_unit_test_setup_teardown(test_mrt_eight, setup, teardown),
        cmocka_unit_test_setup_teardown(test_state_counts, setup, teardown),
        cmocka_unit_test_setup_teardown(test_state_force, setup, teardown),
        cmocka_unit_test_setup_teardown(test_draws_per_pass, setup, teardown),
        cmocka_unit_test_setup_teardown(test_fullscreen_triangle, setup, teardown),
        cmocka_unit_test_setup_teardown(test_two_sided_stencil, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
