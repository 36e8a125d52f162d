/* The visibility renderer (renderers/visibility/visibility.c; Burns and Hunt 2013) on "shapes"
 * (textured, glossy, normal-mapped and emissive materials): its plan holds the R32UI
 * "visibility" target at 4 bytes a pixel; its passes make exactly one draw per visible
 * opaque object (the visibility pass), one cull dispatch with point lights and none
 * without, and one shading dispatch per run of the visible list whose materials bind
 * the same maps (counted here from the frontend's own list); its image agrees with
 * forward-spml within RMSE 1/255 (max 4/255), and at msaa 4 too (deferred's edge rule
 * on the rebuilt surfaces, edge pixels per distinct id); the shade pass's own counts
 * (covered samples as forward-plus's shading pass passes them, shadings, edge pixels);
 * seed 002's terms below deferred's for every G-buffer preset; and the id split
 * (visibility_split) takes the fewest triangle bits and refuses, naming the numbers,
 * what does not fit. Every frame runs in a debug context; any GL error fails the test. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/frame/frontend.h"
#include "renderers/gl/context.h"
#include "renderers/gl/loader.h"
#include "renderers/renderer.h"
#include "renderers/visibility/visibility.h"
#include "common/image_io.h"
#include "scenes/scene.h"
#include "tests/gl/gl_test.h"

enum { W = 100, H = 60 };   /* not multiples of 16: partial tiles */

static gl_context *ctx;

typedef struct shot {
    image img;
    frame_stats fs;
    pass_plan plan;
    uint64_t covered;   /* pixels with some sample nearer than the far plane */
    gbuffer_traffic traffic;
} shot;

static renderer_options options(void)
{
    const gl_info *gi = gl_context_info(ctx);
    renderer_options o = {
        .width = W, .height = H, .queries = true,
        .timer_query = gi->timer_query, .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size,
        .light_buffer = LIGHT_BUFFER_STORAGE,
    };
    return o;
}

static void render(const char *kind, const renderer_options *o, scene *s, shot *out)
{
    char err[512];
    memset(out, 0, sizeof *out);
    renderer *r = test_renderer_create(kind, o, err, sizeof err);
    if (!r || !renderer_prepare(r, s, err, sizeof err))
        fail_msg("%s: %s", kind, err);
    renderer_draw(r, s, &out->fs);
    gl.Finish();
    renderer_collect(r, &out->fs);
    renderer_describe(r, &out->plan);
    if (!renderer_coverage(r, &out->covered, err, sizeof err))
        fail_msg("%s: coverage: %s", kind, err);
    out->traffic = renderer_traffic(r, &out->fs);
    out->img = (image){.width = W, .height = H, .channels = 4, .type = IMAGE_U8,
                       .pixels = malloc((size_t)W * H * 4)};
    assert_true(gl_context_read_rgba8(ctx, out->img.pixels, err, sizeof err));
    renderer_destroy(r);
    gl_context_poll_errors(ctx, kind);
    assert_int_equal(gl_context_error_count(ctx), 0);
}

static scene *shapes(const scene_light *lights, uint32_t n)
{
    char err[256];
    light_params lp = {.placement = PLACEMENT_NONE, .radius = 1.0f};
    scene *s = scene_build("shapes", &lp, W, H, err, sizeof err);
    if (!s)
        fail_msg("shapes: %s", err);
    s->lights = calloc(n ? n : 1, sizeof *s->lights);
    memcpy(s->lights, lights, n * sizeof *s->lights);
    s->nlights_total = n;
    s->count = (light_count){.start = n, .max = n};
    scene_update(s, 0.0);
    sm_vec3 up = {0.0f, 1.0f, 0.0f};
    sm_vec3 eye = {0.0f, 12.0f, 28.0f}, target = {0.0f, 1.0f, 0.0f};
    sm_vec3_copy(eye, s->cam.eye);
    sm_vec3_copy(target, s->cam.target);
    sm_lookat(s->cam.eye, s->cam.target, up, s->view);
    sm_perspective(s->fovy, (float)W / (float)H, s->znear, s->zfar, s->proj);
    sm_mat4_mul(s->proj, s->view, s->viewproj);
    return s;
}

/* The visible opaque objects, and the runs of them whose materials bind the same maps
 * (what the shading pass makes one dispatch for), from the frontend as every renderer
 * builds it. */
static void visible_runs(const scene *s, uint32_t *nvisible, uint32_t *nruns)
{
    char err[256];
    frontend fe = {0};
    fe.no_illumination = true;
    if (!frontend_init(&fe, s, err, sizeof err))
        fail_msg("frontend: %s", err);
    frontend_build(&fe, s);
    *nvisible = fe.nvisible;
    *nruns = 0;
    int last[4] = {-2, -2, -2, -2};
    for (uint32_t k = 0; k < fe.nvisible; k++) {
        const scene_material *m = &s->materials[s->objects[fe.visible[k]].material];
        int map[4] = {m->diffuse_map, m->gloss_map, m->normal_map, m->emissive_map};
        if (k == 0 || memcmp(map, last, sizeof map) != 0)
            (*nruns)++;
        memcpy(last, map, sizeof map);
    }
    frontend_free(&fe);
}

static scene_light point(float x, float y, float z, float radius)
{
    scene_light l = {.type = LIGHT_POINT, .position = {x, y, z}, .color = {0.6f, 0.5f, 0.4f},
                     .radius = radius, .attenuation = ATTENUATION_LINEAR_RANGE};
    return l;
}

/* Sixteen point lights: the target, the exact draws and dispatches, the image. */
static void test_counts_and_target(void **state)
{
    (void)state;
    scene_light l[16];
    for (int i = 0; i < 16; i++)
        l[i] = point((float)(i % 4) * 8.0f - 12.0f, 3.0f, (float)(i / 4) * 8.0f - 12.0f, 7.0f);
    scene *s = shapes(l, 16);
    uint32_t v = 0, runs = 0;
    visible_runs(s, &v, &runs);
    print_message("%u visible objects in %u runs of equal maps\n", v, runs);
    assert_true(v > 0 && runs > 1);   /* shapes' materials bind different maps */
    renderer_options o = options();
    shot ref, vis;
    render("forward-spml", &o, s, &ref);
    render("visibility", &o, s, &vis);
    shot plus;
    render("forward-plus", &o, s, &plus);

    /* passes: visibility, cull, shade, [sky], resolve */
    const frame_stats *fs = &vis.fs;
    assert_int_equal(fs->npasses, s->sky ? 5 : 4);
    assert_string_equal(fs->pass[0].name, "visibility");
    assert_string_equal(fs->pass[1].name, "cull");
    assert_string_equal(fs->pass[2].name, "shade");
    assert_int_equal(fs->pass[0].draw_calls, v);
    assert_int_equal(fs->pass[0].dispatches, 0);
    assert_int_equal(fs->pass[1].draw_calls, 0);
    assert_int_equal(fs->pass[1].dispatches, 1);
    assert_int_equal(fs->pass[2].draw_calls, 0);
    assert_int_equal(fs->pass[2].dispatches, runs);
    assert_int_equal(fs->total.draw_calls, v + (s->sky ? 1u : 0u) + 1u);
    assert_int_equal(fs->total.dispatches, 1u + runs);
    assert_int_equal(fs->grid_cells, ((W + 15) / 16) * ((H + 15) / 16));
    assert_int_equal(fs->overflow[0], '\0');
    /* the shade pass counts its own work: one shading per covered pixel, the samples
     * forward-plus's depth-EQUAL shading pass passes (the same visible surfaces) */
    const pass_stats *sh = &fs->pass[2], *fp = find_pass(&plus.fs, "shade");
    print_message("covered %llu pixels; shade: %.0f samples, %.0f shaded; forward-plus %.0f\n",
                  (unsigned long long)vis.covered, sh->samples, sh->samples_shaded,
                  fp->samples);
    assert_true(vis.covered > 0 && vis.covered < (uint64_t)W * H);
    assert_true(sh->samples == (double)vis.covered);
    assert_true(sh->samples_shaded == sh->samples);
    assert_true(sh->samples == fp->samples);
    assert_true(isnan(fs->edge_fraction));
    image_free(&plus.img);

    /* the plan: the id target, 4 bytes a sample, among the target bytes */
    bool found = false;
    uint64_t sum = 0;
    for (size_t t = 0; t < vis.plan.ntargets; t++) {
        sum += vis.plan.target[t].bytes;
        if (strcmp(vis.plan.target[t].name, "visibility") == 0) {
            assert_string_equal(vis.plan.target[t].format, "r32ui");
            assert_int_equal(vis.plan.target[t].width, W);
            assert_int_equal(vis.plan.target[t].height, H);
            assert_int_equal(vis.plan.target[t].bytes, (uint64_t)W * H * 4);
            found = true;
        }
    }
    assert_true(found);
    assert_int_equal(vis.plan.target_bytes, sum);
    assert_int_equal(vis.plan.gbuffer_bytes, (uint64_t)W * H * 4);   /* the ids */
    const pass_plan_entry *e = plan_pass(&vis.plan, "visibility");
    assert_non_null(e);
    assert_true(e->run);
    assert_non_null(plan_pass(&vis.plan, "cull"));
    assert_true(plan_pass(&vis.plan, "cull")->run);

    gl_test_expect_agree("visibility vs forward-spml", &vis.img, &ref.img, 1.0 / 255.0,
                         4.0 / 255.0, false);
    image_free(&ref.img);
    image_free(&vis.img);
    scene_destroy(s);
}

/* One directional light: no cull pass (the plan says why), the same shading runs. */
static void test_no_cull_without_local_lights(void **state)
{
    (void)state;
    scene_light d = {.type = LIGHT_DIRECTIONAL, .direction = {-0.4f, -1.0f, -0.3f},
                     .color = {0.8f, 0.8f, 0.7f}};
    sm_vec3_normalize(d.direction);
    scene *s = shapes(&d, 1);
    uint32_t v = 0, runs = 0;
    visible_runs(s, &v, &runs);
    renderer_options o = options();
    shot ref, vis;
    render("forward-spml", &o, s, &ref);
    render("visibility", &o, s, &vis);
    assert_null(find_pass(&vis.fs, "cull"));
    assert_int_equal(vis.fs.total.dispatches, runs);
    assert_int_equal(find_pass(&vis.fs, "visibility")->draw_calls, v);
    const pass_plan_entry *e = plan_pass(&vis.plan, "cull");
    assert_non_null(e);
    assert_false(e->run);
    assert_string_equal(e->reason, "skipped, the scene has no point or spot light");
    gl_test_expect_agree("visibility vs forward-spml, directional", &vis.img, &ref.img,
                         1.0 / 255.0, 4.0 / 255.0, false);
    image_free(&ref.img);
    image_free(&vis.img);
    scene_destroy(s);
}

/* msaa 4: the multisampled ids, deferred's edge rule on the surfaces they hold, each
 * distinct id of an edge pixel shaded once at its centre (as forward-spml shades each
 * triangle covering a sample), any other pixel once: within RMSE 1/255 of
 * forward-spml at msaa 4, fewer than 1 % of the pixels off by more than 1/255 (the
 * tolerance of gl-agreement's msaa cases); the same draws and dispatches plus the
 * msaa-resolve pass, and the target's samples in the plan's bytes. */
static void test_msaa4(void **state)
{
    (void)state;
    scene_light l[16];
    for (int i = 0; i < 16; i++)
        l[i] = point((float)(i % 4) * 8.0f - 12.0f, 3.0f, (float)(i / 4) * 8.0f - 12.0f, 7.0f);
    scene *s = shapes(l, 16);
    uint32_t v = 0, runs = 0;
    visible_runs(s, &v, &runs);
    renderer_options o = options();
    o.msaa = 4;
    shot ref, vis;
    render("forward-spml", &o, s, &ref);
    render("visibility", &o, s, &vis);
    shot plus;
    render("forward-plus", &o, s, &plus);
    assert_int_equal(vis.fs.msaa, 4);
    /* its counts: the covered samples as forward-plus's shading pass passes them; a
     * shading per covered pixel, and per extra id of an edge pixel (at most 3 more) */
    const pass_stats *sh = find_pass(&vis.fs, "shade");
    double edges = vis.fs.edge_fraction * W * H;
    print_message("msaa 4: covered %llu pixels, %.0f edge pixels; shade: %.0f samples, %.0f "
                  "shaded; forward-plus %.0f samples\n", (unsigned long long)vis.covered,
                  edges, sh->samples, sh->samples_shaded, find_pass(&plus.fs, "shade")->samples);
    assert_true(sh->samples == find_pass(&plus.fs, "shade")->samples);
    assert_true(sh->samples > (double)vis.covered && sh->samples <= 4.0 * (double)vis.covered);
    assert_true(vis.fs.edge_fraction > 0.0 && vis.fs.edge_fraction < 0.5);
    assert_true(sh->samples_shaded > (double)vis.covered);
    assert_true(sh->samples_shaded <= (double)vis.covered + 3.0 * edges);
    image_free(&plus.img);
    assert_int_equal(find_pass(&vis.fs, "visibility")->draw_calls, v);
    assert_int_equal(find_pass(&vis.fs, "shade")->dispatches, runs);
    assert_non_null(find_pass(&vis.fs, "msaa-resolve"));
    assert_int_equal(vis.fs.total.dispatches, 1u + runs);
    bool found = false;
    for (size_t t = 0; t < vis.plan.ntargets; t++)
        if (strcmp(vis.plan.target[t].name, "visibility") == 0) {
            assert_int_equal(vis.plan.target[t].bytes, (uint64_t)W * H * 4 * 4);
            found = true;
        }
    assert_true(found);
    image_error e;
    char err[256];
    assert_true(image_compare(&vis.img, &ref.img, &e, err, sizeof err));
    print_message("msaa 4: visibility vs forward-spml: rmse %.3f/255, max %.1f/255, %.4f of "
                  "pixels off by > 1/255\n", e.rmse * 255, e.max_abs * 255, e.frac_over_1_255);
    assert_true(e.rmse < 1.0 / 255.0);
    assert_true(e.frac_over_1_255 < 0.01);
    assert_int_equal(e.nonfinite, 0);
    image_free(&ref.img);
    image_free(&vis.img);
    scene_destroy(s);
}

/* Seed 002's G-buffer terms at msaa 4: the visibility target's bytes a frame (4 a sample,
 * written by the id pass, read by each shading dispatch) below deferred's G-buffer
 * bytes for every preset (issue 26's question: where the thin target pays), on the same
 * frame; at msaa 1 too. */
static void test_traffic_below_deferred(void **state)
{
    (void)state;
    scene_light l[16];
    for (int i = 0; i < 16; i++)
        l[i] = point((float)(i % 4) * 8.0f - 12.0f, 3.0f, (float)(i / 4) * 8.0f - 12.0f, 7.0f);
    scene *s = shapes(l, 16);
    static const int msaa[] = {4, 1};
    for (size_t m = 0; m < sizeof msaa / sizeof msaa[0]; m++) {
        renderer_options o = options();
        o.msaa = msaa[m];
        shot vis;
        render("visibility", &o, s, &vis);
        double vb = vis.traffic.write_bytes + vis.traffic.read_bytes;
        const pass_stats *id = find_pass(&vis.fs, "visibility");
        assert_true(vis.traffic.write_bytes == 4.0 * id->samples);
        assert_true(vis.traffic.read_bytes ==
                    4.0 * W * H * msaa[m] * (double)find_pass(&vis.fs, "shade")->dispatches);
        image_free(&vis.img);
        for (gbuffer_preset p = GBUFFER_CURTIS; p <= GBUFFER_REFERENCE; p++) {
            o.gbuffer = p;
            shot def;
            render("deferred", &o, s, &def);
            double db = def.traffic.write_bytes + def.traffic.read_bytes;
            print_message("msaa %d, preset %d: visibility %.0f bytes (%.0f + %.0f), deferred "
                          "%.0f (%.0f + %.0f)\n", msaa[m], (int)p, vb,
                          vis.traffic.write_bytes, vis.traffic.read_bytes, db,
                          def.traffic.write_bytes, def.traffic.read_bytes);
            assert_true(isfinite(vb) && isfinite(db));
            assert_true(vb < db);
            image_free(&def.img);
        }
    }
    scene_destroy(s);
}

/* The split: the fewest triangle bits, the rest for draws, the all-ones id kept for
 * "no surface"; what does not fit refused with the numbers. */
static void test_split(void **state)
{
    (void)state;
    char err[256] = "";
    unsigned bits = 0;
    assert_true(visibility_split("visibility", 1, 0, &bits, err, sizeof err));
    assert_int_equal(bits, 1);
    assert_true(visibility_split("visibility", 1, 2, &bits, err, sizeof err));
    assert_int_equal(bits, 1);   /* triangles 0 and 1 */
    assert_true(visibility_split("visibility", 1, 3, &bits, err, sizeof err));
    assert_int_equal(bits, 2);
    /* 2^20 triangles: 20 bits, 12 for draws: 4095 draws (4096 would make draw 4095 with
     * triangle 2^20 - 1 the empty id) */
    assert_true(visibility_split("visibility", 4095, 1u << 20, &bits, err, sizeof err));
    assert_int_equal(bits, 20);
    assert_int_equal(visibility_pack(4094, (1u << 20) - 1, 20), 0xffefffffu);
    assert_false(visibility_split("visibility", 4096, 1u << 20, &bits, err, sizeof err));
    assert_string_equal(err, "visibility: 4096 opaque objects do not fit the 32-bit "
                             "visibility id: its largest mesh's 1048576 triangles take 20 "
                             "bits, which leaves 12 bits, 4095 draws");
    assert_true(visibility_split("visibility", 1, 1u << 31, &bits, err, sizeof err));
    assert_int_equal(bits, 31);
    assert_false(visibility_split("visibility", 1, (1u << 31) + 1u, &bits, err, sizeof err));
    assert_string_equal(err, "visibility: a mesh has 2147483649 triangles: the 32-bit "
                             "visibility id needs at least 1 bit for the draw, so at most "
                             "2^31 triangles a mesh");
}

GL_TEST_MAIN(ctx, W, H,
             cmocka_unit_test(test_split),
             cmocka_unit_test(test_counts_and_target),
             cmocka_unit_test(test_no_cull_without_local_lights),
             cmocka_unit_test(test_msaa4),
             cmocka_unit_test(test_traffic_below_deferred))
