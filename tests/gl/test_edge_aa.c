/* aa: edge (renderers/frame/edge_aa.h; seed 001 19.5.2's edge-detect blur) in a debug
 * context (any GL error fails; 77 when no EGL display), on "shapes" without its maps (every
 * contrast left is an edge or a crease) under three point lights, in every renderer that
 * draws (the forward three, deferred, tiled-deferred, clustered forward and deferred):
 *   - aa: none has no "edge-aa" pass, its plan lists it as skipped with why; aa: edge has
 *     it: one draw, every pixel shaded once, exactly one draw more in the frame, the plan
 *     listing the pass and the "hdr.aa" target;
 *   - read_hdr gives the anti-aliased image (finite, >= 0), and the output is it clamped
 *     and rounded to 8 bits within 1;
 *   - against a supersampled reference (forward-spml at 4x the size, 4 x 4 blocks
 *     averaged), the RMSE over the edge pixels (16 samples spanning more than EDGE_SPAN)
 *     with aa: edge is at most MARGIN x the one with aa: none. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 64, H = 64, SS = 4, WS = W * SS, HS = H * SS };
#define EDGE_SPAN 0.1f   /* a reference pixel's samples span more: an edge pixel */
#define MARGIN 0.85      /* edge-pixel RMSE with aa: edge <= MARGIN x without */

static gl_context *ctx;   /* WS x HS: the 64 x 64 runs draw into its bottom-left corner */

static scene_light point(float x, float y, float z, float radius, float c)
{
    return (scene_light){.type = LIGHT_POINT, .position = {x, y, z}, .color = {c, c, c},
                         .direction = {0.0f, -1.0f, 0.0f}, .radius = radius,
                         .attenuation = ATTENUATION_LINEAR_RANGE};
}

/* "shapes" at w x h without maps or emission, three point lights, seen from the side
 * and above. */
static scene *build(int w, int h)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build("shapes", &lp, w, h, err, sizeof err);
    if (!s)
        fail_msg("scene shapes: %s", err);
    for (uint32_t m = 0; m < s->nmaterials; m++) {
        scene_material *mt = &s->materials[m];
        mt->diffuse_map = mt->gloss_map = mt->normal_map = mt->emissive_map = -1;
        mt->emissive[0] = mt->emissive[1] = mt->emissive[2] = 0.0f;
    }
    const scene_light l[] = {
        point(-6.0f, 4.0f, 2.0f, 14.0f, 0.9f),
        point(5.0f, 3.0f, -2.0f, 12.0f, 0.7f),
        point(0.0f, 6.0f, 6.0f, 16.0f, 0.6f),
    };
    uint32_t n = sizeof l / sizeof l[0];
    s->lights = calloc(n, sizeof *s->lights);
    assert_non_null(s->lights);
    memcpy(s->lights, l, sizeof l);
    s->nlights_total = n;
    s->count = (light_count){.start = n, .max = n};
    scene_update(s, 0.0);
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    s->cam.eye[0] = 0.0f, s->cam.eye[1] = 12.0f, s->cam.eye[2] = 28.0f;
    s->cam.target[0] = 0.0f, s->cam.target[1] = 1.0f, s->cam.target[2] = 0.0f;
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)w / (float)h, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
    return s;
}

typedef struct config {
    const char *kind;
    bool clustered_deferred;
} config;

static const config CONFIGS[] = {
    {"forward-spml", false}, {"forward-mpml", false},   {"forward-plus", false},
    {"deferred", false},     {"tiled-deferred", false}, {"clustered", false},
    {"clustered", true},     {"visibility", false},
};

typedef struct result {
    frame_stats fs;
    pass_plan plan;
    float *img;        /* clamp(read_hdr) RGB, w x h, row 0 at the bottom */
    uint8_t *out;      /* the output's w x h corner, row 0 at the bottom */
} result;

static float clamp01(float v)
{
    return v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
}

static result render(const config *c, aa_mode aa, const scene *s, int w, int h)
{
    char err[512] = "";
    const gl_info *i = gl_context_info(ctx);
    renderer_options o = {.width = w, .height = h, .queries = true,
                          .timer_query = i->timer_query,
                          .pipeline_statistics = i->pipeline_statistics,
                          .max_uniform_block_size = i->max_uniform_block_size,
                          .clustered_deferred = c->clustered_deferred, .aa = aa};
    gl.BindFramebuffer(GL_FRAMEBUFFER, gl_context_framebuffer(ctx));
    renderer *r = test_renderer_create(c->kind, &o, err, sizeof err);
    if (!r || !renderer_prepare(r, s, err, sizeof err))
        fail_msg("%s (aa %d): %s", c->kind, (int)aa, err);
    result res;
    memset(&res, 0, sizeof res);
    renderer_draw(r, s, &res.fs);
    gl.Finish();
    renderer_collect(r, &res.fs);
    assert_int_equal(gl_context_error_count(ctx), 0);
    renderer_describe(r, &res.plan);

    size_t n = (size_t)w * h;
    float *hdr = malloc(n * 4 * sizeof *hdr);
    res.img = malloc(n * 3 * sizeof *res.img);
    uint8_t *full = malloc((size_t)WS * HS * 4);
    res.out = malloc(n * 3);
    assert_true(hdr && res.img && full && res.out);
    size_t nonfinite = 1;
    assert_true(renderer_read_hdr(r, hdr, w, h, &nonfinite));
    assert_int_equal(nonfinite, 0);
    if (!gl_context_read_rgba8(ctx, full, err, sizeof err))
        fail_msg("read back: %s", err);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t p = (size_t)y * w + (size_t)x;
            const uint8_t *o8 = &full[((size_t)(HS - 1 - y) * WS + (size_t)x) * 4];   /* top-down */
            for (int k = 0; k < 3; k++) {
                float v = hdr[p * 4 + (size_t)k];
                if (!isfinite(v) || v < 0.0f)
                    fail_msg("%s (aa %d): hdr (%d, %d)[%d] = %g", c->kind, (int)aa, x, y, k,
                             (double)v);
                res.img[p * 3 + (size_t)k] = clamp01(v);
                res.out[p * 3 + (size_t)k] = o8[k];
                int want = (int)lroundf(clamp01(v) * 255.0f);
                if (abs((int)o8[k] - want) > 1)
                    fail_msg("%s (aa %d): pixel (%d, %d)[%d]: output %d, hdr %g", c->kind,
                             (int)aa, x, y, k, o8[k], (double)v);
            }
        }
    free(hdr);
    free(full);
    renderer_destroy(r);
    gl_context_poll_errors(ctx, c->kind);
    assert_int_equal(gl_context_error_count(ctx), 0);
    return res;
}

static void drop(result *r)
{
    free(r->img);
    free(r->out);
}

static void test_edge_aa(void **state)
{
    (void)state;
    scene *s = build(W, H), *ss = build(WS, HS);
    /* the supersampled reference, one for all: the renderers' images agree within 1/255
     * (tests/gl/test_agreement.c) */
    result ref = render(&CONFIGS[0], AA_NONE, ss, WS, HS);
    for (size_t ci = 0; ci < sizeof CONFIGS / sizeof CONFIGS[0]; ci++) {
        const config *c = &CONFIGS[ci];
        const char *name = c->clustered_deferred ? "clustered (deferred)" : c->kind;
        result none = render(c, AA_NONE, s, W, H);
        result edge = render(c, AA_EDGE, s, W, H);

        /* the passes and the plan */
        assert_null(find_pass(&none.fs, "edge-aa"));
        const pass_plan_entry *e = plan_pass(&none.plan, "edge-aa");
        assert_non_null(e);
        assert_false(e->run);
        assert_string_equal(e->reason, "skipped, aa: none");
        const pass_stats *p = find_pass(&edge.fs, "edge-aa");
        assert_non_null(p);
        assert_int_equal(p->draw_calls, 1);
        if (!isnan(p->samples))
            assert_true(p->samples == (double)W * H);
        assert_int_equal(total_draws(&edge.fs), total_draws(&none.fs) + 1);
        assert_string_equal(edge.fs.pass[edge.fs.npasses - 1].name, "resolve");
        assert_string_equal(edge.fs.pass[edge.fs.npasses - 2].name, "edge-aa");
        e = plan_pass(&edge.plan, "edge-aa");
        assert_non_null(e);
        assert_true(e->run);
        bool target = false;
        for (size_t t = 0; t < edge.plan.ntargets; t++)
            target |= strcmp(edge.plan.target[t].name, "hdr.aa") == 0;
        assert_true(target);

        /* the error over the reference's edge pixels */
        double se_none = 0, se_edge = 0, all_none = 0, all_edge = 0;
        size_t nedge = 0, changed = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                size_t q = ((size_t)y * W + (size_t)x) * 3;
                bool is_edge = false;
                double dn[3], de[3];
                for (int k = 0; k < 3; k++) {
                    float lo = 1.0f, hi = 0.0f, sum = 0.0f;
                    for (int j = 0; j < SS; j++)
                        for (int i = 0; i < SS; i++) {
                            float v = ref.img[((size_t)(y * SS + j) * WS +
                                               (size_t)(x * SS + i)) * 3 + (size_t)k];
                            sum += v;
                            lo = v < lo ? v : lo;
                            hi = v > hi ? v : hi;
                        }
                    is_edge |= hi - lo > EDGE_SPAN;
                    dn[k] = none.img[q + (size_t)k] - sum / (SS * SS);
                    de[k] = edge.img[q + (size_t)k] - sum / (SS * SS);
                    all_none += dn[k] * dn[k];
                    all_edge += de[k] * de[k];
                    changed += none.out[q + (size_t)k] != edge.out[q + (size_t)k];
                }
                if (!is_edge)
                    continue;
                nedge++;
                for (int k = 0; k < 3; k++) {
                    se_none += dn[k] * dn[k];
                    se_edge += de[k] * de[k];
                }
            }
        assert_true(nedge > (size_t)W * H / 20);   /* the scene has edges to measure */
        double rn = sqrt(se_none / (3.0 * (double)nedge));
        double re = sqrt(se_edge / (3.0 * (double)nedge));
        print_message("%-20s edge pixels %zu of %d; edge RMSE none %.5f, edge-aa %.5f "
                      "(x %.3f); whole image %.5f, %.5f; %zu values changed\n",
                      name, nedge, W * H, rn, re, re / rn,
                      sqrt(all_none / (3.0 * W * H)), sqrt(all_edge / (3.0 * W * H)), changed);
        assert_true(re <= MARGIN * rn);
        drop(&none);
        drop(&edge);
    }
    drop(&ref);
    scene_destroy(s);
    scene_destroy(ss);
}

int main(void)
{
    GL_TEST_SKIP_WITHOUT_EGL();
    ctx = gl_test_context(WS, HS);
    if (!ctx)
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_edge_aa),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    gl_context_destroy(ctx);
    return rc;
}
