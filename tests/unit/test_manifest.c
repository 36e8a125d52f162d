/* Manifests (runner/manifest.c), their YAML layer (runner/manifest/yamldoc.c), diagnostics
 * (runner/manifest/diag.c) and hashing (runner/manifest/hash.c).
 *
 * Good manifests: every parsed value and every default. Bad manifests: the exact
 * output of diag_print, line by line, for each file under tests/data/bad. */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "renderers/renderer.h"
#include "runner/manifest/diag.h"
#include "runner/manifest/hash.h"
#include "runner/manifest/manifest.h"
#include "runner/manifest/params.h"
#include "runner/manifest/yamldoc.h"

static const char *data_dir(void)
{
    const char *d = getenv("TEST_DATA");
    if (!d)
        fail_msg("TEST_DATA is not set (meson test sets it to tests/data)");
    return d;
}

static void data_path(char *out, size_t len, const char *rel)
{
    snprintf(out, len, "%s/%s", data_dir(), rel);
}

/* diag_print's whole output as a string (free it). */
static char *print_diags(const diag_list *d)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    diag_print(d, f);
    fclose(f);
    return buf;
}

static experiment *load_good(const char *rel)
{
    char path[1024];
    data_path(path, sizeof path, rel);
    experiment *e = NULL;
    diag_list d = {0};
    bool ok = manifest_load(path, &e, &d);
    if (!ok) {
        char *s = print_diags(&d);
        print_error("%s", s);
        free(s);
    }
    assert_true(ok);
    assert_int_equal(d.n, 0);
    assert_non_null(e);
    diag_free(&d);
    return e;
}

/* An FNV-1a 64 written out here, independent of runner/manifest/hash.c. */
static uint64_t file_fnv(const char *path)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    uint64_t h = 14695981039346656037u;
    int c;
    while ((c = fgetc(f)) != EOF) {
        h ^= (unsigned char)c;
        h *= 1099511628211u;
    }
    fclose(f);
    return h;
}

/* >>hash */

static void test_fnv1a64_vectors(void **state)
{
    (void)state;
    /* the reference vectors of the FNV authors' test suite */
    static const struct {
        const char *in;
        uint64_t out;
    } cases[] = {
        {"", UINT64_C(0xcbf29ce484222325)},
        {"a", UINT64_C(0xaf63dc4c8601ec8c)},
        {"foobar", UINT64_C(0x85944171f73967e8)},
        {NULL, 0},
    };
    for (size_t i = 0; cases[i].in; i++)
        assert_int_equal(fnv1a64(cases[i].in, strlen(cases[i].in)), cases[i].out);
    assert_int_equal(fnv1a64_update(fnv1a64("foo", 3), "bar", 3), fnv1a64("foobar", 6));

    char hex[17];
    hash_hex(UINT64_C(0x85944171f73967e8), 16, hex);
    assert_string_equal(hex, "85944171f73967e8");
    hash_hex(UINT64_C(0x85944171f73967e8), 12, hex);
    assert_string_equal(hex, "85944171f739");
    hash_hex(UINT64_C(0x000000000000000f), 16, hex);
    assert_string_equal(hex, "000000000000000f");
    hash_hex(UINT64_C(0x0123456789abcdef), 40, hex);
    assert_string_equal(hex, "0123456789abcdef");
}

/* >>diag */

static void test_diag_print_format(void **state)
{
    (void)state;
    diag_list d = {0};
    diag_add(&d, "m.yaml", 3, 9, "trials", "expected an integer %d..%d, found '%s'", 1, 1000, "0");
    diag_add(&d, "m.yaml", 1, 1, "", "expected a mapping, found a sequence");
    diag_add(&d, "gone.yaml", 0, 0, "", "expected a readable file, found %s", "nothing there");
    assert_int_equal(d.n, 3);
    char *s = print_diags(&d);
    assert_string_equal(s, "m.yaml:3:9: trials: expected an integer 1..1000, found '0'\n"
                           "m.yaml:1:1: expected a mapping, found a sequence\n"
                           "gone.yaml: expected a readable file, found nothing there\n");
    free(s);
    diag_free(&d);
    assert_null(d.v);
    assert_int_equal(d.n, 0);
    diag_free(&d);   /* twice is harmless */
}

/* >>yamldoc */

static ydoc *load_text(const char *text, diag_list *d)
{
    ydoc *doc = NULL;
    bool ok = ydoc_load("t.yaml", text, strlen(text), &doc, d);
    assert_true(ok == (doc != NULL));
    return doc;
}

static void test_yamldoc_nodes(void **state)
{
    (void)state;
    diag_list d = {0};
    ydoc *doc = load_text("a: 3\n"
                          "b: \"3\"\n"
                          "c:\n"
                          "  - x\n"
                          "  - {k: 'v'}\n"
                          "d: &n [1, 2]\n"
                          "e: *n\n"
                          "f: !!str 5\n",
                          &d);
    assert_non_null(doc);
    assert_int_equal(d.n, 0);
    const ynode *r = doc->root;
    assert_int_equal(r->kind, YNODE_MAPPING);
    assert_int_equal(r->n, 6);
    assert_int_equal(r->line, 1);
    assert_int_equal(r->col, 1);

    const ynode *a = r->pairs[0].value, *b = r->pairs[1].value;
    assert_string_equal(r->pairs[0].key->text, "a");
    assert_string_equal(a->text, "3");
    assert_true(ynode_plain(a));
    assert_int_equal(a->line, 1);
    assert_int_equal(a->col, 4);
    assert_string_equal(b->text, "3");
    assert_int_equal(b->style, YSTYLE_DOUBLE_QUOTED);
    assert_false(ynode_plain(b));

    const ynode *c = r->pairs[2].value;
    assert_int_equal(c->kind, YNODE_SEQUENCE);
    assert_int_equal(c->n, 2);
    assert_int_equal(c->line, 4);
    assert_int_equal(c->col, 3);
    assert_int_equal(c->items[1]->kind, YNODE_MAPPING);
    assert_int_equal(c->items[1]->line, 5);
    assert_int_equal(c->items[1]->col, 5);
    assert_int_equal(c->items[1]->pairs[0].value->style, YSTYLE_SINGLE_QUOTED);

    /* an alias is the anchored node itself */
    assert_ptr_equal(r->pairs[3].value, r->pairs[4].value);
    assert_int_equal(r->pairs[4].value->expanded, 3);

    const ynode *f = r->pairs[5].value;
    assert_string_equal(f->tag, "tag:yaml.org,2002:str");
    assert_false(ynode_plain(f));
    ydoc_free(doc);
    ydoc_free(NULL);
}

static void test_yamldoc_errors(void **state)
{
    (void)state;
    static const struct {
        const char *text;
        const char *out;
    } cases[] = {
        {"", "t.yaml:1:1: expected a YAML document, found nothing\n"},
        {"# only a comment\n", "t.yaml:1:1: expected a YAML document, found nothing\n"},
        {"a: 1\n---\nb: 2\n", "t.yaml:2:1: expected one YAML document, found a second document\n"},
        {"a: &x [1, *x]\n",
         "t.yaml:1:11: expected an alias to a complete node, found a recursive alias '*x'\n"},
        {"a: *nowhere\n",
         "t.yaml:1:4: expected an alias to an earlier anchor, found an undefined alias '*nowhere'\n"},
        {"a: [1, 2\n",
         "t.yaml:2:1: expected valid YAML, found a syntax error: did not find expected ',' or ']' "
         "(while parsing a flow sequence at 1:4)\n"},
        {NULL, NULL},
    };
    for (size_t i = 0; cases[i].text; i++) {
        diag_list d = {0};
        ydoc *doc = load_text(cases[i].text, &d);
        assert_null(doc);
        char *s = print_diags(&d);
        assert_string_equal(s, cases[i].out);
        free(s);
        diag_free(&d);
    }
}

/* Each level aliases the previous one ten times: 10^k nodes at level k if expanded.
 * The load stops at the bound; the nodes it holds are the file's own. */
static void test_yamldoc_alias_bound(void **state)
{
    (void)state;
    char text[4096];
    size_t n = (size_t)snprintf(text, sizeof text, "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\n");
    for (int k = 1; k <= 20; k++) {
        n += (size_t)snprintf(text + n, sizeof text - n, "l%d: &l%d [", k, k);
        for (int j = 0; j < 10; j++)
            n += (size_t)snprintf(text + n, sizeof text - n, "%s*l%d", j ? ", " : "", k - 1);
        n += (size_t)snprintf(text + n, sizeof text - n, "]\n");
    }
    diag_list d = {0};
    ydoc *doc = load_text(text, &d);
    assert_null(doc);
    assert_int_equal(d.n, 1);
    assert_string_equal(d.v[0].msg, "expected at most 10000 nodes reached through aliases, "
                                    "found more at alias '*l2'");
    assert_int_equal(d.v[0].line, 4);
    diag_free(&d);

    /* the same shape within the bound loads, and the sizes add up */
    d = (diag_list){0};
    doc = load_text("a: &a [x, x]\nb: &b [*a, *a]\nc: [*b, *b]\n", &d);
    assert_non_null(doc);
    assert_int_equal(doc->root->pairs[2].value->expanded, 1 + 2 * (1 + 2 * 3));
    assert_int_equal(doc->alias_nodes, 2 * 3 + 2 * 7);
    ydoc_free(doc);
}

/* >>good manifests */

static void test_minimal_defaults(void **state)
{
    (void)state;
    experiment *e = load_good("good/minimal.yaml");
    char path[1024], hex[17];
    data_path(path, sizeof path, "good/minimal.yaml");
    assert_string_equal(e->path, path);
    assert_string_equal(e->name, "minimal");
    assert_string_equal(e->description, "");
    snprintf(hex, sizeof hex, "%016llx", (unsigned long long)file_fnv(path));
    assert_string_equal(e->hash, hex);
    assert_int_equal(e->nrenderers, 1);
    assert_string_equal(e->renderers[0], "null");
    assert_int_equal(e->naxes, 0);

    const run_params *p = &e->base;
    assert_string_equal(p->scene, "empty");
    assert_string_equal(p->renderer, "");
    assert_int_equal(p->width, 640);
    assert_int_equal(p->height, 360);
    assert_int_equal(p->trials, 1);
    assert_int_equal(p->warmup.kind, SPAN_FRAMES);
    assert_int_equal(p->warmup.frames, 0);
    assert_int_equal(p->duration.kind, SPAN_FRAMES);
    assert_int_equal(p->duration.frames, 10);
    assert_int_equal(p->clock, RUN_CLOCK_WALL);
    assert_true(p->step == 1.0 / 60);
    assert_int_equal(p->sync, RUN_SYNC_FINISH);
    /* no lights mapping: no lights */
    assert_int_equal(p->lights.placement, PLACEMENT_NONE);
    assert_int_equal(p->lights.seed, 1337);
    assert_int_equal(p->lights.rng, RNG_MSVC);
    assert_false(p->lights.count.growth);
    assert_int_equal(p->lights.count.start, 0);
    assert_int_equal(p->lights.count.max, 0);
    assert_true(p->lights.radius == 10.0f);
    assert_true(p->lights.color_max == 0.3f);
    assert_true(p->out_frames);
    assert_true(p->out_seconds);
    assert_int_equal(p->nscreenshots, 0);
    experiment_free(e);
    experiment_free(NULL);
}

static void test_full_values(void **state)
{
    (void)state;
    experiment *e = load_good("good/full.yaml");
    assert_string_equal(e->name, "full-2014-exp2");
    assert_string_equal(e->description, "Lights grow 10/s from 0 to 590 while the camera orbits.");
    assert_int_equal(e->nrenderers, 1);
    assert_string_equal(e->renderers[0], "null");
    const run_params *p = &e->base;
    assert_string_equal(p->scene, "empty");
    assert_int_equal(p->width, 1280);
    assert_int_equal(p->height, 720);
    assert_int_equal(p->trials, 3);
    assert_int_equal(p->warmup.kind, SPAN_SECONDS);
    assert_true(p->warmup.seconds == 2.5);
    assert_int_equal(p->duration.kind, SPAN_SECONDS);
    assert_true(p->duration.seconds == 60.0);
    assert_int_equal(p->clock, RUN_CLOCK_FIXED);
    assert_true(p->step == 0.1);
    assert_int_equal(p->sync, RUN_SYNC_FENCE);
    assert_int_equal(p->lights.placement, PLACEMENT_RANDOM);
    assert_int_equal(p->lights.seed, 4294967295u);
    assert_int_equal(p->lights.rng, RNG_PCG32);
    assert_true(p->lights.count.growth);
    assert_int_equal(p->lights.count.start, 0);
    assert_int_equal(p->lights.count.step, 10);
    assert_true(p->lights.count.every == 1.0);
    assert_int_equal(p->lights.count.max, 590);
    assert_true(p->lights.radius == 12.5f);
    assert_true(p->lights.color_max == 0.25f);
    assert_false(p->out_frames);
    assert_false(p->out_seconds);
    assert_int_equal(p->nscreenshots, 3);
    assert_true(p->screenshots[0] == 0.0);
    assert_true(p->screenshots[1] == 10.0);
    assert_true(p->screenshots[2] == 30.5);
    experiment_free(e);
}

static void test_aliases_and_quoted_keys(void **state)
{
    (void)state;
    experiment *e = load_good("good/aliases.yaml");
    const run_params *p = &e->base;
    assert_int_equal(p->warmup.kind, SPAN_FRAMES);
    assert_int_equal(p->warmup.frames, 5);
    assert_int_equal(p->duration.kind, SPAN_FRAMES);
    assert_int_equal(p->duration.frames, 5);
    assert_int_equal(p->trials, 2);
    /* a lights mapping, even without placement, means random placement */
    assert_int_equal(p->lights.placement, PLACEMENT_RANDOM);
    assert_int_equal(p->lights.count.max, 7);
    assert_int_equal(p->lights.seed, 7);
    assert_int_equal(p->nscreenshots, 2);
    assert_true(p->screenshots[1] == 1.5);
    experiment_free(e);
}

/* The canonical text of every parameter, in table order: what run ids hash. */
static void test_kv_canonical(void **state)
{
    (void)state;
    static const char *const minimal[][2] = {
        {"scene", "empty"},
        {"renderer", ""},
        {"resolution", "640x360"},
        {"trials", "1"},
        {"schedule", "interleaved"},
        {"measure.metric", "auto"},
        {"measure.rasterizer", "auto"},
        {"measure.precision", "0.03"},
        {"measure.budget", "600"},
        {"measure.seed", "1337"},
        {"warmup", "frames:0"},
        {"duration", "frames:10"},
        {"clock", "wall"},
        {"step", "0.016666666666666666"},
        {"sync", "finish"},
        {"timeout", "0"},
        {"draw_limit", "0"},
        {"gbuffer.preset", "curtis"},
        {"gbuffer.position", "preset"},
        {"gbuffer.normal", "preset"},
        {"deferred.light_volumes", "stencil"},
        {"deferred.separate_specular", "false"},
        {"deferred.sky_stencil", "false"},
        {"forward.illumination_sets", "true"},
        {"forward.directional_in_base", "false"},
        {"forward.light_buffer", "uniform"},
        {"tiles.size", "16"},
        {"tiles.depth_culling", "minmax"},
        {"tiles.prune", "bounds"},
        {"tiles.levels", "1"},
        {"tiles.coarse_size", "64"},
        {"tiles.max_lights_per_tile", "0"},
        {"clustered.slices", "24"},
        {"clustered.shading", "forward"},
        {"lights.culling", "exact"},
        {"lights.culling_error", "0.005"},
        {"deferred_lighting.light_buffer", "rgba16f"},
        {"deferred_lighting.lights", "volumes"},
        {"shadows", "auto"},
        {"hdr", "rgba16f"},
        {"msaa", "1"},
        {"fog.density", "0"},
        {"fog.colour", "0.5,0.5,0.5"},
        {"aa", "none"},
        {"zbin.bins", "1024"},
        {"zbin.shading", "forward"},
        {"translucency", "blend"},
        {"shading.model", "scene"},
        {"environment.light", "none"},
        {"environment.intensity", "1"},
        {"camera.radius", "scene"},
        {"camera.height", "scene"},
        {"camera.period", "scene"},
        {"camera.target", "scene"},
        {"camera.near", "scene"},
        {"camera.far", "scene"},
        {"camera.hold", "scene"},
        {"error.reference.renderer", ""},
        {"error.reference.gbuffer", "reference"},
        {"error.reference.light_volumes", "stencil"},
        {"error.reference.supersample", "1"},
        {"error.reference.msaa", "1"},
        {"error.at", ""},
        {"error.max_rmse", "0"},
        {"error.save_images", "false"},
        {"lights.placement", "none"},
        {"lights.seed", "1337"},
        {"lights.rng", "msvc"},
        {"lights.count", "0"},
        {"lights.radius", "10"},
        {"lights.overlap", "0"},
        {"lights.color_max", "0.3"},
        {"lights.attenuation", "inverse-square"},
        {"lights.sizing", "radius"},
        {"lights.cutoff", "0.005"},
        {"lights.quadratic.a", "1"},
        {"lights.quadratic.b", "0"},
        {"lights.quadratic.c", "1"},
        {"exposure.mode", "none"},
        {"exposure.ev100", "0"},
        {"exposure.key", "0.18"},
        {"tonemap", "none"},
        {"outputs.frames", "true"},
        {"outputs.seconds", "true"},
        {"outputs.scene_cache", "true"},
        {"outputs.screenshots", ""},
        {"allow_empty", "false"},
        {"debug.busy_us", "0"},
        {"debug.busy_renderer", ""},
        {"debug.stall_trial", "0"},
        {NULL, NULL},
    };
    static const char *const full[][2] = {
        {"scene", "empty"},
        {"renderer", ""},
        {"resolution", "1280x720"},
        {"trials", "3"},
        {"schedule", "interleaved"},
        {"measure.metric", "auto"},
        {"measure.rasterizer", "auto"},
        {"measure.precision", "0.03"},
        {"measure.budget", "600"},
        {"measure.seed", "1337"},
        {"warmup", "seconds:2.5"},
        {"duration", "seconds:60"},
        {"clock", "fixed"},
        {"step", "0.1"},
        {"sync", "fence"},
        {"timeout", "7200"},
        {"draw_limit", "0"},
        {"gbuffer.preset", "curtis"},
        {"gbuffer.position", "preset"},
        {"gbuffer.normal", "preset"},
        {"deferred.light_volumes", "stencil"},
        {"deferred.separate_specular", "false"},
        {"deferred.sky_stencil", "false"},
        {"forward.illumination_sets", "true"},
        {"forward.directional_in_base", "false"},
        {"forward.light_buffer", "uniform"},
        {"tiles.size", "16"},
        {"tiles.depth_culling", "minmax"},
        {"tiles.prune", "bounds"},
        {"tiles.levels", "1"},
        {"tiles.coarse_size", "64"},
        {"tiles.max_lights_per_tile", "0"},
        {"clustered.slices", "24"},
        {"clustered.shading", "forward"},
        {"lights.culling", "exact"},
        {"lights.culling_error", "0.005"},
        {"deferred_lighting.light_buffer", "rgba16f"},
        {"deferred_lighting.lights", "volumes"},
        {"shadows", "off"},
        {"hdr", "rgba16f"},
        {"msaa", "1"},
        {"fog.density", "0"},
        {"fog.colour", "0.5,0.5,0.5"},
        {"aa", "none"},
        {"zbin.bins", "1024"},
        {"zbin.shading", "forward"},
        {"translucency", "blend"},
        {"shading.model", "scene"},
        {"environment.light", "none"},
        {"environment.intensity", "1"},
        {"camera.radius", "40"},
        {"camera.height", "12.5"},
        {"camera.period", "30"},
        {"camera.target", "0,1.5,-2"},
        {"camera.near", "0.25"},
        {"camera.far", "500"},
        {"camera.hold", "0.5"},
        {"error.reference.renderer", ""},
        {"error.reference.gbuffer", "reference"},
        {"error.reference.light_volumes", "stencil"},
        {"error.reference.supersample", "1"},
        {"error.reference.msaa", "1"},
        {"error.at", ""},
        {"error.max_rmse", "0"},
        {"error.save_images", "false"},
        {"lights.placement", "random"},
        {"lights.seed", "4294967295"},
        {"lights.rng", "pcg32"},
        {"lights.count", "start:0,step:10,every:1,max:590"},
        {"lights.radius", "12.5"},
        {"lights.overlap", "1.5"},
        {"lights.color_max", "0.25"},
        {"lights.attenuation", "inverse-square"},
        {"lights.sizing", "radius"},
        {"lights.cutoff", "0.005"},
        {"lights.quadratic.a", "1"},
        {"lights.quadratic.b", "0"},
        {"lights.quadratic.c", "1"},
        {"exposure.mode", "none"},
        {"exposure.ev100", "0"},
        {"exposure.key", "0.18"},
        {"tonemap", "none"},
        {"outputs.frames", "false"},
        {"outputs.seconds", "false"},
        {"outputs.scene_cache", "true"},
        {"outputs.screenshots", "0,10,30.5"},
        {"allow_empty", "false"},
        {"debug.busy_us", "0"},
        {"debug.busy_renderer", ""},
        {"debug.stall_trial", "0"},
        {NULL, NULL},
    };
    static const struct {
        const char *file;
        const char *const (*kv)[2];
    } cases[] = {{"good/minimal.yaml", minimal}, {"good/full.yaml", full}, {NULL, NULL}};

    for (size_t c = 0; cases[c].file; c++) {
        experiment *e = load_good(cases[c].file);
        param_kv kv[PARAM_KV_MAX];
        size_t n = run_params_kv(&e->base, kv, PARAM_KV_MAX);
        size_t want = 0;
        while (cases[c].kv[want][0])
            want++;
        assert_int_equal(n, want);
        for (size_t i = 0; i < n; i++) {
            assert_string_equal(kv[i].key, cases[c].kv[i][0]);
            assert_string_equal(kv[i].value, cases[c].kv[i][1]);
            /* a timeout changes no result, so it is not part of the run id; nor the
             * debug keys (testing regression gates: a slowed run keeps its id), nor how
             * trials are scheduled and ranked (schedule, measure.*). Keys at their
             * default leave the id too (is_default), which test_params.c checks. Nor
             * whether a file scene is read from the cache (the same scene either way). */
            assert_int_equal(kv[i].in_id, strcmp(kv[i].key, "timeout") != 0 &&
                                              strcmp(kv[i].key, "schedule") != 0 &&
                                              strcmp(kv[i].key, "outputs.scene_cache") != 0 &&
                                              strncmp(kv[i].key, "measure.", 8) != 0 &&
                                              strncmp(kv[i].key, "debug.", 6) != 0);
        }
        /* away from its default, such a key is part of the id */
        run_params p = e->base;
        p.tile_size = TILE_SIZE_32;
        size_t m = run_params_kv(&p, kv, PARAM_KV_MAX);
        bool seen = false;
        for (size_t i = 0; i < m; i++)
            if (strcmp(kv[i].key, "tiles.size") == 0) {
                assert_string_equal(kv[i].value, "32");
                assert_true(kv[i].in_id);
                seen = true;
            }
        assert_true(seen);
        /* max bounds the pairs written */
        assert_int_equal(run_params_kv(&e->base, kv, 3), 3);
        assert_string_equal(kv[2].key, "resolution");
        experiment_free(e);
    }
}

/* Numbers print as the shortest text that reads back as the same value. */
static void test_kv_numbers(void **state)
{
    (void)state;
    experiment *e = load_good("good/minimal.yaml");
    run_params p = e->base;
    static const struct {
        double step;
        float radius;
        const char *step_text, *radius_text;
    } cases[] = {
        {0.1, 0.1f, "0.1", "0.1"},
        {1e9, 1e9f, "1e+09", "1e+09"},
        {604800, 604800.0f, "604800", "604800"},
        {1.0 / 3, 1.0f / 3, "0.3333333333333333", "0.33333334"},
        {2.5e-7, 2.5e-7f, "2.5e-07", "2.5e-07"},
        {0, 0, NULL, NULL},
    };
    for (size_t i = 0; cases[i].step_text; i++) {
        p.step = cases[i].step;
        p.lights.radius = cases[i].radius;
        param_kv kv[PARAM_KV_MAX];
        size_t n = run_params_kv(&p, kv, PARAM_KV_MAX);
        for (size_t k = 0; k < n; k++) {
            if (strcmp(kv[k].key, "step") == 0) {
                assert_string_equal(kv[k].value, cases[i].step_text);
                assert_true(strtod(kv[k].value, NULL) == cases[i].step);
            }
            if (strcmp(kv[k].key, "lights.radius") == 0) {
                assert_string_equal(kv[k].value, cases[i].radius_text);
                assert_true(strtof(kv[k].value, NULL) == cases[i].radius);
            }
        }
    }
    experiment_free(e);
}

/* >>bad manifests */

typedef struct bad_case {
    const char *file;           /* under tests/data/bad */
    const char *lines[16];      /* each printed as "<path>:<line>\n", NULL-terminated */
} bad_case;

static const bad_case bad_cases[] = {
    {"unknown_top_key.yaml",
     {"1:1: duration: expected {seconds: S} or {frames: N}, found nothing",
      "5:1: durtion: expected one of shadesweep, name, description, scene, renderers, "
      "resolution, trials, schedule, measure, warmup, duration, clock, step, sync, timeout, draw_limit, gbuffer, deferred, forward, tiles, clustered, deferred_lighting, shadows, hdr, msaa, fog, aa, zbin, translucency, shading, environment, camera, error, lights, exposure, tonemap, outputs, allow_empty, debug, sweep, "
      "found 'durtion'"}},
    {"unknown_nested_key.yaml",
     {"8:3: lights.cnt: expected one of culling, culling_error, placement, seed, rng, count, "
      "radius, overlap, color_max, "
      "attenuation, sizing, cutoff, quadratic, found 'cnt'"}},
    {"duplicate_key.yaml",
     {"7:1: trials: expected a key used once, found a second 'trials' (first at 5:1)"}},
    {"string_for_integer.yaml", {"6:9: trials: expected an integer 1..1000, or auto, found 'many'"}},
    {"sequence_for_mapping.yaml",
     {"5:11: duration: expected {seconds: S} or {frames: N}, found a sequence"}},
    {"quoted_integer.yaml", {"6:9: trials: expected an integer 1..1000, or auto, found a string '3'"}},
    {"nan.yaml", {"7:7: step: expected a finite number, found '.nan'"}},
    {"inf.yaml",
     {"7:11: lights.radius: expected a finite number, found '.inf'",
      "8:14: lights.color_max: expected a finite number, found '-.Inf'"}},
    {"overflow.yaml", {"5:21: duration.seconds: expected a finite number, found '1e999'"}},
    {"negative_trials.yaml", {"6:9: trials: expected an integer 1..1000, or auto, found '-1'"}},
    {"zero_trials.yaml", {"6:9: trials: expected an integer 1..1000, or auto, found '0'"}},
    {"error_supersample_zero.yaml",
     {"8:52: error.reference.supersample: expected an integer 1..4, found '0'"}},
    {"error_supersample_five.yaml",
     {"8:52: error.reference.supersample: expected an integer 1..4, found '5'"}},
    {"negative_light_count.yaml",
     {"7:10: lights.count: expected an integer 0..1000000, all, or {start, step, every, max}, "
      "found '-5'"}},
    {"resolution_zero.yaml",
     {"6:13: resolution: expected WxH with each side 1..32768, found '0x0'"}},
    {"resolution_huge.yaml",
     {"6:13: resolution: expected WxH with each side 1..32768, found '100000x100000'"}},
    {"resolution_malformed.yaml",
     {"6:13: resolution: expected WxH with each side 1..32768, found '640 x 480'"}},
    {"unknown_scene.yaml", {"3:8: scene: expected one of {SCENES}or {file: PATH, scale, up, camera}, found 'castle'"}},
    {"unknown_renderer.yaml",
     {"4:19: renderers[1]: expected one of {RENDERERS}found 'raytrace'",
      "4:29: renderers[2]: expected a renderer listed once, found a second 'null' (first at 4:13)"}},
    {"empty_renderers.yaml",
     {"4:12: renderers: expected a non-empty sequence of renderer names, found an empty sequence"}},
    {"empty_file.yaml", {"1:1: expected a YAML document, found nothing"}},
    {"empty_document.yaml", {"2:1: expected a YAML document, found an empty document"}},
    {"binary.yaml", {"1:1: expected UTF-8 text, found invalid leading UTF-8 octet (#x89)"}},
    {"control_char.yaml", {"2:7: expected UTF-8 text, found control characters are not allowed (#x01)"}},
    {"bad_utf8.yaml", {"2:12: expected UTF-8 text, found invalid leading UTF-8 octet (#xFF)"}},
    {"unclosed_bracket.yaml",
     {"5:9: expected valid YAML, found a syntax error: did not find expected ',' or ']' "
      "(while parsing a flow sequence at 4:12)"}},
    {"tab_indent.yaml",
     {"6:1: expected valid YAML, found a syntax error: found character that cannot start any "
      "token (while scanning for the next token at 6:1)"}},
    {"billion_laughs.yaml",
     {"9:36: expected at most 10000 nodes reached through aliases, found more at alias '*c'"}},
    {"recursive_alias.yaml",
     {"6:11: expected an alias to a complete node, found a recursive alias '*r'"}},
    {"undefined_alias.yaml",
     {"5:11: expected an alias to an earlier anchor, found an undefined alias '*frames'"}},
    {"deep_nesting.yaml", {"2:262: expected nesting at most 256 deep, found deeper"}},
    {"two_documents.yaml", {"6:1: expected one YAML document, found a second document"}},
    {"camera_bad.yaml",
     {"7:11: camera.target: expected [x, y, z] (finite numbers) or scene, found a sequence",
      "8:9: camera.hold: expected a number >= 0 and <= 1, or scene, found '1.5'",
      "9:9: camera.near: expected a number > 0 and <= 1e+09, or scene, found '0'",
      "10:8: camera.far: expected a number > 0 and <= 1e+09, or scene, found 'scenery'",
      "11:10: shadows: expected one of auto, off, found 'maybe'"}},
    {"camera_target_not_number.yaml",
     {"6:22: camera.target[1]: expected a finite number, found '.inf'",
      "8:20: sweep.camera.hold[1]: expected a number >= 0 and <= 1, or scene, found '-1'"}},
    {"count_all_random.yaml",
     {"8:10: lights.count: expected a number of lights (all is for lights.placement scene "
      "only), found all",
      "10:3: sweep.lights.placement: expected lights.placement either set or swept, found "
      "both (set at 7:3)"}},
    {"count_all_swept.yaml",
     {"9:21: sweep.lights.count[1]: expected a number of lights (all is for lights.placement "
      "scene only), found all"}},
    {"placement_none_swept_count.yaml",
     {"8:21: sweep.lights.count[1]: expected 0 lights with lights.placement none, found 5 lights",
      "8:24: sweep.lights.count[2]: expected 0 lights with lights.placement none, found up to 9 "
      "lights"}},
    {"not_mapping.yaml", {"1:1: expected a mapping, found a sequence"}},
    {"scene_file_missing.yaml",
     {"5:15: scene.file: expected a scene file that loads, found "
      "/nonexistent-shadesweep-test/scene.glb: cannot open: No such file or directory"}},
    {"missing_required.yaml", {"1:1: scene: expected one of {SCENES}or {file: PATH, scale, up, camera}, found nothing"}},
    {"missing_all.yaml",
     {"1:1: shadesweep: expected 1 or 2, found nothing",
      "1:1: name: expected a name of 1..63 characters from a-z, 0-9 and -, found nothing",
      "1:1: scene: expected one of {SCENES}or {file: PATH, scale, up, camera}, found nothing",
      "1:1: renderers: expected a non-empty sequence of renderer names, found nothing",
      "1:1: duration: expected {seconds: S} or {frames: N}, found nothing"}},
    {"bad_name.yaml",
     {"2:7: name: expected a name of 1..63 characters from a-z, 0-9 and -, found 'My_Experiment'"}},
    {"schema_3.yaml", {"1:13: shadesweep: expected 1 or 2, found '3'"}},
    {"duration_both.yaml",
     {"5:11: duration: expected {seconds: S} or {frames: N}, found both seconds and frames"}},
    {"warmup_nothing.yaml",
     {"6:8: warmup: expected {seconds: S} or {frames: N}, found nothing"}},
    {"bool_yes.yaml",
     {"7:11: outputs.frames: expected true or false, found 'yes'",
      "8:12: outputs.seconds: expected true or false, found a string 'true'"}},
    {"tagged.yaml",
     {"5:20: duration.frames: expected an integer 1..100000000, found '10' tagged !!int",
      "6:9: trials: expected an integer 1..1000, or auto, found '3' tagged !custom"}},
    {"placement_none_count.yaml",
     {"8:10: lights.count: expected 0 lights with lights.placement none, found 5 lights"}},
    {"growth_bad.yaml",
     {"7:10: lights.count.every: expected a number > 0 and <= 604800, found nothing",
      "7:36: lights.count.max: expected an integer 10..1000000 (at least start), found '5'",
      "7:39: lights.count.by: expected one of start, step, every, max, found 'by'"}},
    {"screenshots_many.yaml",
     {"7:16: outputs.screenshots: expected a sequence of at most 16 times in seconds, "
      "found 17 times"}},
    {"sweep_unknown_path.yaml",
     {"7:3: sweep.lights.cnt: expected a sweepable parameter (one of scene, resolution, "
      "trials, warmup, duration, clock, step, sync, timeout, draw_limit, gbuffer.preset, gbuffer.position, "
      "gbuffer.normal, deferred.light_volumes, deferred.separate_specular, "
       "deferred.sky_stencil, "
       "forward.illumination_sets, forward.directional_in_base, forward.light_buffer, tiles.size, "
      "tiles.depth_culling, tiles.prune, tiles.levels, tiles.coarse_size, "
      "tiles.max_lights_per_tile, clustered.slices, clustered.shading, lights.culling, "
      "lights.culling_error, deferred_lighting.light_buffer, deferred_lighting.lights, shadows, hdr, msaa, "
      "fog.density, "
      "fog.colour, aa, zbin.bins, zbin.shading, translucency, shading.model, environment.light, environment.intensity, camera.radius, "
      "camera.height, camera.period, "
      "camera.target, camera.near, camera.far, camera.hold, lights.placement, lights.seed, "
      "lights.rng, lights.count, lights.radius, lights.overlap, lights.color_max, lights.attenuation, lights.sizing, "
      "lights.cutoff, lights.quadratic.a, lights.quadratic.b, lights.quadratic.c, "
      "exposure.mode, exposure.ev100, exposure.key, tonemap), found 'lights.cnt'"}},
    {"sweep_empty_list.yaml",
     {"7:11: sweep.trials: expected a non-empty sequence of values, found an empty sequence"}},
    {"sweep_wrong_type.yaml",
     {"8:22: sweep.lights.count[1]: expected an integer 0..1000000, all, or {start, step, every, max}, "
      "found 'ten'",
      "8:66: sweep.lights.count[3].max: expected an integer 5..1000000 (at least start), "
      "found '2'"}},
    {"set_and_swept.yaml",
     {"8:3: sweep.trials: expected trials either set or swept, found both (set at 6:1)",
      "9:3: sweep.trials: expected a key used once, found a second 'trials' (first at 8:3)"}},
    {"several_errors.yaml",
     {"1:1: duration: expected {seconds: S} or {frames: N}, found nothing",
      "3:8: scene: expected one of {SCENES}or {file: PATH, scale, up, camera}, found 'castle'",
      "5:13: resolution: expected WxH with each side 1..32768, found '640x'",
      "6:9: trials: expected an integer 1..1000, or auto, found '0'",
      "7:1: durtion: expected one of {TOPKEYS}found 'durtion'",
      "8:19: warmup.seconds: expected a number >= 0 and <= 3600, found '-1'",
      "10:9: lights.seed: expected an integer 0..4294967295, found '-1'",
      "11:8: lights.rng: expected one of msvc, pcg32, mt19937, found 'rand'",
      "12:37: lights.count.every: expected a number > 0 and <= 604800, found '0'",
      "12:45: lights.count.max: expected an integer 5..1000000 (at least start), found '4'",
      "14:11: outputs.frames: expected true or false, found 'yes'",
      "15:21: outputs.screenshots[1]: expected a finite number, found '.nan'",
      "17:18: sweep.sync[1]: expected one of finish, fence, found 'flush'"}},
    /* a sweep of blocks: each item a non-empty mapping of today's sweep; a required key
     * swept in one block only is missing from the others */
    {"blocks_errors.yaml",
     {"1:1: scene: expected one of {SCENES}or {file: PATH, scale, up, camera}, found nothing",
      "6:5: sweep[0]: expected a block (a mapping from parameters to sequences of values), "
      "found '5'",
      "7:5: sweep[1]: expected a block with at least one parameter, found an empty mapping",
      "8:22: sweep[2].bogus: expected a sweepable parameter (one of {SWEEPABLE}), found 'bogus'",
      "9:18: sweep[3].trials[1]: expected an integer 1..1000, or auto, found '0.5'",
      "9:24: sweep[3].trials: expected a key used once, found a second 'trials' (first at 9:6)",
      "10:20: sweep[4].lights.count: expected a non-empty sequence of values, found an empty "
      "sequence"}},
    /* lights per block: placement none meets the count in place in blocks 1 and 2
     * (reported once) and block 0's own counts; block 3 (placement random) any count */
    {"blocks_lights.yaml",
     {"6:17: lights.count: expected 0 lights with lights.placement none, found 16 lights",
      "8:50: sweep[0].lights.count[1]: expected 0 lights with lights.placement none, found 4 "
      "lights"}},
    {"blocks_empty.yaml",
     {"6:8: sweep: expected a non-empty sequence of blocks (mappings from parameters to "
      "sequences of values), found an empty sequence"}},
    {NULL, {NULL}},
};

/* A line of bad_cases with its lists made from the tables they come from: {SCENES}
 * the scene catalog, {RENDERERS} the renderer registry, {TOPKEYS} the manifest's
 * top-level keys (params.def's), each name followed by ", "; {SWEEPABLE} the
 * sweepable keys, separated by ", ". */
static void expand_lists(FILE *w, const char *line)
{
    for (const char *s = line; *s;) {
        if (strncmp(s, "{SCENES}", 8) == 0) {
            for (size_t i = 0; i < scene_catalog_count(); i++)
                fprintf(w, "%s, ", scene_catalog_at(i)->name);
            s += 8;
        } else if (strncmp(s, "{RENDERERS}", 11) == 0) {
            for (size_t i = 0; i < renderer_kind_count(); i++)
                fprintf(w, "%s, ", renderer_kind_at(i)->name);
            s += 11;
        } else if (strncmp(s, "{TOPKEYS}", 9) == 0) {
            for (size_t i = 0; i < NPARAMS; i++)
                if (!strchr(params_table[i].path, '.'))
                    fprintf(w, "%s, ", params_table[i].path);
            s += 9;
        } else if (strncmp(s, "{SWEEPABLE}", 11) == 0) {
            const char *sep = "";
            for (size_t i = 0; i < NPARAMS; i++)
                if (params_table[i].flags & PF_SWEEP) {
                    fprintf(w, "%s%s", sep, params_table[i].path);
                    sep = ", ";
                }
            s += 11;
        } else {
            fputc(*s++, w);
        }
    }
}

static void test_bad_manifests(void **state)
{
    (void)state;
    size_t ncases = 0;
    for (const bad_case *c = bad_cases; c->file; c++, ncases++) {
        char path[1024], rel[256];
        snprintf(rel, sizeof rel, "bad/%s", c->file);
        data_path(path, sizeof path, rel);

        char *want = NULL;
        size_t wlen = 0;
        FILE *w = open_memstream(&want, &wlen);
        assert_non_null(w);
        for (size_t i = 0; c->lines[i]; i++) {
            fprintf(w, "%s:", path);
            expand_lists(w, c->lines[i]);
            fputc('\n', w);
        }
        fclose(w);

        static experiment stale;
        experiment *e = &stale;   /* manifest_load must reset it to NULL */
        diag_list d = {0};
        bool ok = manifest_load(path, &e, &d);
        char *got = print_diags(&d);
        if (strcmp(got, want) != 0)
            print_error("%s: got\n%swanted\n%s", c->file, got, want);
        assert_false(ok);
        assert_null(e);
        assert_string_equal(got, want);
        free(got);
        free(want);
        diag_free(&d);
    }
    assert_true(ncases >= 24);
}

/* diags already in the list are kept, in place, ahead of the new ones */
static void test_diags_append(void **state)
{
    (void)state;
    diag_list d = {0};
    diag_add(&d, "earlier", 99, 1, "x", "expected a, found b");
    char path[1024];
    data_path(path, sizeof path, "bad/zero_trials.yaml");
    experiment *e = NULL;
    assert_false(manifest_load(path, &e, &d));
    assert_int_equal(d.n, 2);
    assert_string_equal(d.v[0].file, "earlier");
    assert_string_equal(d.v[1].key, "trials");
    assert_int_equal(d.v[1].line, 6);
    diag_free(&d);
}

static void test_missing_file(void **state)
{
    (void)state;
    char path[1024];
    data_path(path, sizeof path, "bad/no-such-file.yaml");
    experiment *e = NULL;
    diag_list d = {0};
    assert_false(manifest_load(path, &e, &d));
    assert_null(e);
    char *got = print_diags(&d);
    char want[1200];
    snprintf(want, sizeof want, "%s: expected a readable file, found No such file or directory\n",
             path);
    assert_string_equal(got, want);
    free(got);
    diag_free(&d);

    /* a directory is not a manifest either, and is called one (it read as
     * "Input/output error") */
    data_path(path, sizeof path, "bad");
    assert_false(manifest_load(path, &e, &d));
    assert_int_equal(d.n, 1);
    assert_int_equal(d.v[0].line, 0);
    assert_string_equal(d.v[0].msg, "expected a manifest file, found a directory, not a regular "
                                    "file");
    diag_free(&d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fnv1a64_vectors),
        cmocka_unit_test(test_diag_print_format),
        cmocka_unit_test(test_yamldoc_nodes),
        cmocka_unit_test(test_yamldoc_errors),
        cmocka_unit_test(test_yamldoc_alias_bound),
        cmocka_unit_test(test_minimal_defaults),
        cmocka_unit_test(test_full_values),
        cmocka_unit_test(test_aliases_and_quoted_keys),
        cmocka_unit_test(test_kv_canonical),
        cmocka_unit_test(test_kv_numbers),
        cmocka_unit_test(test_bad_manifests),
        cmocka_unit_test(test_diags_append),
        cmocka_unit_test(test_missing_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
