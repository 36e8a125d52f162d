/* Plans (runner/plan/sweep.c): expansion order, run ids, shards, --shard parsing,
 * `shadesweep list` output, duplicate points, sweeps of blocks. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "runner/manifest/diag.h"
#include "runner/manifest/manifest.h"

static void data_path(char *out, size_t len, const char *rel)
{
    const char *d = getenv("TEST_DATA");
    if (!d)
        fail_msg("TEST_DATA is not set (meson test sets it to tests/data)");
    snprintf(out, len, "%s/%s", d, rel);
}

static experiment *load(const char *rel)
{
    char path[1024];
    data_path(path, sizeof path, rel);
    experiment *e = NULL;
    diag_list d = {0};
    if (!manifest_load(path, &e, &d)) {
        diag_print(&d, stderr);
        fail_msg("%s does not load", rel);
    }
    diag_free(&d);
    return e;
}

/* Only "null" exists yet; plan_expand takes the names as validated, so a second
 * name stands for the renderers to come. */
static void set_renderers(experiment *e, const char *const *names)
{
    size_t n = 0;
    while (names[n])
        n++;
    free(e->renderers);
    e->renderers = calloc(n, sizeof *e->renderers);
    assert_non_null(e->renderers);
    for (size_t i = 0; i < n; i++)
        snprintf(e->renderers[i], sizeof e->renderers[i], "%s", names[i]);
    e->nrenderers = n;
}

static char *print_plan(const plan *p, unsigned shard)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    plan_print(p, shard, f);
    fclose(f);
    return buf;
}

static bool expand(const experiment *e, unsigned nshards, plan *p)
{
    diag_list d = {0};
    bool ok = plan_expand(e, nshards, p, &d);
    if (!ok)
        diag_print(&d, stderr);
    diag_free(&d);
    return ok;
}

/* FNV-1a 64 written out here, independent of runner/manifest/hash.c. */
static uint64_t fnv(const char *s)
{
    uint64_t h = 14695981039346656037u;
    for (; *s; s++) {
        h ^= (unsigned char)*s;
        h *= 1099511628211u;
    }
    return h;
}

/* good/sweep.yaml: resolution [800x600, 1024x768, 1600x1200] x lights.count [0, 100]
 * x renderers [null, deferred]: first axis slowest, renderers fastest. The ids are
 * recorded: a change to the canonical text or the hash changes them, and then
 * every results folder ever written changes name, so it must be deliberate. */
static void test_order_and_ids(void **state)
{
    (void)state;
    static const struct {
        const char *id, *renderer;
        int w, h;
        uint32_t lights;
    } want[] = {
        {"2483101a0380", "null", 800, 600, 0},
        {"b83a2809d8bc", "deferred", 800, 600, 0},
        {"d323c9a10be4", "null", 800, 600, 100},
        {"0e7607522d02", "deferred", 800, 600, 100},
        {"1f54dd1ce9fd", "null", 1024, 768, 0},
        {"b29a656e6fab", "deferred", 1024, 768, 0},
        {"f04d2a90f5c0", "null", 1024, 768, 100},
        {"546c536cf236", "deferred", 1024, 768, 100},
        {"642f87933697", "null", 1600, 1200, 0},
        {"de666e08c311", "deferred", 1600, 1200, 0},
        {"d7ab31709cf6", "null", 1600, 1200, 100},
        {"6b48b8eb2b60", "deferred", 1600, 1200, 100},
        {NULL, NULL, 0, 0, 0},
    };
    experiment *e = load("good/sweep.yaml");
    set_renderers(e, (const char *const[]){"null", "deferred", NULL});
    plan p;
    assert_true(expand(e, 1, &p));
    assert_ptr_equal(p.exp, e);
    assert_int_equal(p.nruns, 12);
    for (size_t k = 0; want[k].id; k++) {
        const run_spec *r = &p.runs[k];
        assert_int_equal(r->index, k);
        assert_int_equal(r->shard, 1);
        assert_string_equal(r->id, want[k].id);
        assert_string_equal(r->p.renderer, want[k].renderer);
        assert_int_equal(r->p.width, want[k].w);
        assert_int_equal(r->p.height, want[k].h);
        assert_false(r->p.lights.count.growth);
        assert_int_equal(r->p.lights.count.start, want[k].lights);
        assert_int_equal(r->p.lights.count.max, want[k].lights);
        /* what is not swept is the base */
        assert_string_equal(r->p.scene, "empty");
        assert_int_equal(r->p.duration.frames, 100);
        assert_int_equal(r->p.lights.placement, PLACEMENT_RANDOM);
    }

    /* the id is the first 12 hex digits of FNV-1a 64 over "key=value\n" in table order,
     * for the parameters not at their default (params.def) */
    const char *canonical = "scene=empty\nrenderer=null\nresolution=800x600\n"
                            "duration=frames:100\n";
    char id[17];
    snprintf(id, sizeof id, "%016llx", (unsigned long long)fnv(canonical));
    id[12] = '\0';
    assert_string_equal(p.runs[0].id, id);

    plan_free(&p);
    assert_null(p.runs);
    plan_free(&p);
    experiment_free(e);
}

/* Changing any one parameter of a run changes its id. */
static void test_ids_differ(void **state)
{
    (void)state;
    experiment *e = load("good/minimal.yaml");
    const run_params base = e->base;
    enum { NMUT = 27 };
    char ids[NMUT + 1][13];
    plan p;
    assert_true(expand(e, 1, &p));
    memcpy(ids[0], p.runs[0].id, 13);
    plan_free(&p);

    for (int m = 1; m <= NMUT; m++) {
        run_params *q = &e->base;
        *q = base;
        snprintf(e->renderers[0], sizeof e->renderers[0], "null");
        switch (m) {
        case 1: snprintf(q->scene, sizeof q->scene, "other"); break;
        case 2: snprintf(e->renderers[0], sizeof e->renderers[0], "other"); break;
        case 3: q->width = 641; break;
        case 4: q->height = 361; break;
        case 5: q->trials = 2; break;
        case 6: q->warmup.frames = 1; break;
        case 7: q->warmup = (span){.kind = SPAN_SECONDS, .seconds = 0}; break;
        case 8: q->duration.frames = 11; break;
        case 9: q->duration = (span){.kind = SPAN_SECONDS, .seconds = 10}; break;
        case 10: q->clock = RUN_CLOCK_FIXED; break;
        case 11: q->step = 0.5; break;
        case 12: q->sync = RUN_SYNC_FENCE; break;
        case 13: q->lights.placement = PLACEMENT_RANDOM; break;
        case 14: q->lights.seed = 1338; break;
        case 15: q->lights.rng = RNG_PCG32; break;
        case 16: q->lights.rng = RNG_MT19937; break;
        case 17: q->lights.count.start = q->lights.count.max = 1; break;
        case 18: q->lights.count = (light_count){.growth = true, .every = 1}; break;
        case 19: q->lights.count = (light_count){.growth = true, .step = 1, .every = 1}; break;
        case 20: q->lights.count = (light_count){.growth = true, .every = 2}; break;
        case 21: q->lights.count = (light_count){.growth = true, .every = 1, .max = 1}; break;
        case 22: q->lights.radius = 10.5f; break;
        case 23: q->lights.color_max = 0.31f; break;
        case 24: q->out_frames = false; break;
        case 25: q->out_seconds = false; break;
        case 26: q->nscreenshots = 1; break;
        case 27: q->nscreenshots = 1, q->screenshots[0] = 1; break;
        }
        assert_true(expand(e, 1, &p));
        memcpy(ids[m], p.runs[0].id, 13);
        plan_free(&p);
    }
    for (int a = 0; a <= NMUT; a++)
        for (int b = a + 1; b <= NMUT; b++)
            if (strcmp(ids[a], ids[b]) == 0)
                fail_msg("mutations %d and %d share id %s", a, b, ids[a]);
    experiment_free(e);
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The ids of plan_print's lines, sorted; *n of them. */
static char **printed_ids(const plan *p, unsigned shard, size_t *n)
{
    char *out = print_plan(p, shard);
    size_t cap = p->nruns + 1;
    char **ids = calloc(cap, sizeof *ids);
    assert_non_null(ids);
    *n = 0;
    for (char *line = out; *line;) {
        char *nl = strchr(line, '\n');
        assert_non_null(nl);
        assert_true(*n < cap);
        assert_true(nl - line > 14);
        assert_memory_equal(line + 12, "  ", 2);
        ids[*n] = strndup(line, 12);
        (*n)++;
        line = nl + 1;
    }
    free(out);
    qsort(ids, *n, sizeof *ids, cmp_str);
    return ids;
}

static void free_ids(char **ids, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(ids[i]);
    free(ids);
}

/* For N in 1..7, the N shards are disjoint, balanced and together the plan. */
static void test_shards_partition(void **state)
{
    (void)state;
    static const char *const files[] = {"good/sweep.yaml", "good/sweep_many.yaml", NULL};
    for (size_t f = 0; files[f]; f++) {
        experiment *e = load(files[f]);
        for (unsigned n = 1; n <= 7; n++) {
            plan p;
            assert_true(expand(e, n, &p));
            size_t nall;
            char **all = printed_ids(&p, 0, &nall);
            assert_int_equal(nall, p.nruns);
            for (size_t k = 1; k < nall; k++)
                assert_true(strcmp(all[k - 1], all[k]) < 0);   /* distinct */

            char **merged = calloc(nall, sizeof *merged);
            assert_non_null(merged);
            size_t nmerged = 0;
            for (unsigned i = 1; i <= n; i++) {
                size_t ns;
                char **ids = printed_ids(&p, i, &ns);
                size_t expect = p.nruns / n + (i <= p.nruns % n ? 1 : 0);
                assert_int_equal(ns, expect);
                for (size_t k = 0; k < ns; k++) {
                    assert_true(nmerged < nall);
                    merged[nmerged++] = ids[k];
                }
                free(ids);   /* the strings moved to merged */
            }
            for (size_t k = 0; k < p.nruns; k++)
                assert_int_equal(p.runs[k].shard, k % n + 1);
            /* union = plan, and no id twice (which pairwise disjoint means) */
            assert_int_equal(nmerged, nall);
            qsort(merged, nmerged, sizeof *merged, cmp_str);
            for (size_t k = 0; k < nall; k++)
                assert_string_equal(merged[k], all[k]);
            free_ids(merged, nmerged);
            free_ids(all, nall);
            plan_free(&p);
        }
        experiment_free(e);
    }
}

static void test_parse_shard(void **state)
{
    (void)state;
    static const struct {
        const char *in;
        unsigned i, n;   /* 0, 0: rejected */
    } cases[] = {
        {"1/1", 1, 1},
        {"3/4", 3, 4},
        {"4/4", 4, 4},
        {"1/100000", 1, 100000},
        {"100000/100000", 100000, 100000},
        {"07/10", 7, 10},
        {"0/4", 0, 0},
        {"5/4", 0, 0},
        {"1/0", 0, 0},
        {"0/0", 0, 0},
        {"1/100001", 0, 0},
        {"", 0, 0},
        {"/", 0, 0},
        {"1/", 0, 0},
        {"/4", 0, 0},
        {"1", 0, 0},
        {"1/4x", 0, 0},
        {" 1/4", 0, 0},
        {"1/ 4", 0, 0},
        {"1/4\n", 0, 0},
        {"-1/4", 0, 0},
        {"+1/4", 0, 0},
        {"1/+4", 0, 0},
        {"1/4/5", 0, 0},
        {"a/b", 0, 0},
        {"1.0/4", 0, 0},
        {"99999999999999999999/1", 0, 0},
        {"4294967297/4294967297", 0, 0},
        {NULL, 0, 0},
    };
    for (size_t k = 0; cases[k].in; k++) {
        unsigned i = 77, n = 77;
        char err[200] = "untouched";
        bool ok = parse_shard(cases[k].in, &i, &n, err, sizeof err);
        if (ok != (cases[k].i != 0))
            fail_msg("parse_shard(\"%s\") returned %d", cases[k].in, ok);
        if (ok) {
            assert_int_equal(i, cases[k].i);
            assert_int_equal(n, cases[k].n);
            assert_string_equal(err, "untouched");
        } else {
            assert_int_equal(i, 77);
            assert_int_equal(n, 77);
            assert_non_null(strstr(err, "--shard: expected I/N with 1 <= I <= N <= 100000, found '"));
        }
    }
    char err[200];
    unsigned i, n;
    assert_false(parse_shard("0/4", &i, &n, err, sizeof err));
    assert_string_equal(err, "--shard: expected I/N with 1 <= I <= N <= 100000, found '0/4'");
    assert_false(parse_shard("1/4\n'", &i, &n, err, sizeof err));
    assert_string_equal(err,
                        "--shard: expected I/N with 1 <= I <= N <= 100000, found '1/4\\x0a\\x27'");
    /* a small buffer truncates, a NULL one is allowed */
    assert_false(parse_shard("9/4", &i, &n, err, 10));
    assert_string_equal(err, "--shard: ");
    assert_false(parse_shard("9/4", &i, &n, NULL, 0));
}

static void test_plan_print(void **state)
{
    (void)state;
    experiment *e = load("good/sweep.yaml");
    plan p;
    assert_true(expand(e, 4, &p));
    char *all = print_plan(&p, 0);
    assert_string_equal(all,
                        "2483101a0380  renderer=null resolution=800x600 lights.count=0\n"
                        "d323c9a10be4  renderer=null resolution=800x600 lights.count=100\n"
                        "1f54dd1ce9fd  renderer=null resolution=1024x768 lights.count=0\n"
                        "f04d2a90f5c0  renderer=null resolution=1024x768 lights.count=100\n"
                        "642f87933697  renderer=null resolution=1600x1200 lights.count=0\n"
                        "d7ab31709cf6  renderer=null resolution=1600x1200 lights.count=100\n");
    free(all);
    char *two = print_plan(&p, 2);
    assert_string_equal(two, "d323c9a10be4  renderer=null resolution=800x600 lights.count=100\n"
                             "d7ab31709cf6  renderer=null resolution=1600x1200 lights.count=100\n");
    free(two);
    char *none = print_plan(&p, 5);
    assert_string_equal(none, "");
    free(none);
    plan_free(&p);
    experiment_free(e);

    /* without a sweep: the id and the renderer */
    e = load("good/minimal.yaml");
    assert_true(expand(e, 1, &p));
    char *one = print_plan(&p, 0);
    assert_string_equal(one, "ef47071b4194  renderer=null\n");
    free(one);
    plan_free(&p);
    experiment_free(e);
}

/* plan_expand fails on e with the one diagnostic "PATH:line" (line: "L:C: KEY: ...");
 * e is freed. */
static void expect_plan_error(experiment *e, const char *line)
{
    plan p;
    diag_list d = {0};
    assert_false(plan_expand(e, 1, &p, &d));
    assert_int_equal(p.nruns, 0);
    assert_null(p.runs);
    char *got = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&got, &len);
    assert_non_null(f);
    diag_print(&d, f);
    fclose(f);
    char want[1024];
    snprintf(want, sizeof want, "%s:%s\n", e->path, line);
    assert_string_equal(got, want);
    free(got);
    diag_free(&d);
    experiment_free(e);
}

static void test_duplicate_points(void **state)
{
    (void)state;
    static const struct {
        const char *file, *line;
    } cases[] = {
        {"sweep/duplicate_value.yaml",
         "8:18: sweep.trials[2]: expected a distinct sweep point, found run 2 the same as run 0 "
         "(id ef47071b4194)"},
        /* 0.50 repeats 0.5 at both resolutions: reported once, at its first pair */
        {"sweep/duplicate_canonical.yaml",
         "10:24: sweep.lights.radius[1]: expected a distinct sweep point, found run 1 the same "
         "as run 0 (id fbe0f6967819)"},
        {NULL, NULL},
    };
    for (size_t k = 0; cases[k].file; k++)
        expect_plan_error(load(cases[k].file), cases[k].line);
}

static experiment *load_text(const char *yaml)
{
    experiment *e = NULL;
    diag_list d = {0};
    if (!manifest_load_mem("mem.yaml", yaml, strlen(yaml), &e, &d)) {
        diag_print(&d, stderr);
        fail_msg("the manifest does not load");
    }
    diag_free(&d);
    return e;
}

static const char PAPER[] =
    "shadesweep: 1\n"
    "name: paper\n"
    "scene: shapes\n"
    "renderers: [null]\n"
    "trials: 3\n"
    "warmup: {seconds: 2}\n"
    "duration: {seconds: 60}\n"
    "outputs: {screenshots: [0.5, 30, 45]}\n"
    "sweep:\n"
    "  resolution: [800x600, 2560x1440]\n"
    "  lights.radius: [5, 10]\n";

/* shadesweep: 2 (issue 36): its defaults (windowed falloff, ranges from intensity, auto
 * exposure, PBR Neutral, the environment) are schema 1's keys written out, so a schema-2 run has the id of
 * the schema-1 manifest that spells them; a key the manifest sets wins over them; a
 * schema-1 manifest keeps schema 1's defaults and its ids. */
static void test_schema2_defaults(void **state)
{
    (void)state;
    static const char body[] =
        "name: s\nscene: shapes\nrenderers: [null]\nduration: {frames: 2}\n"
        "lights: {count: 4}\n";
    char two[512], one[512], spelt[512], own[512];
    snprintf(two, sizeof two, "shadesweep: 2\n%s", body);
    snprintf(one, sizeof one, "shadesweep: 1\n%s", body);
    snprintf(spelt, sizeof spelt,
             "shadesweep: 1\n%sexposure: {mode: auto}\ntonemap: pbr-neutral\n"
             "environment: {light: scene}\n"
             "sweep: {lights.attenuation: [windowed], lights.sizing: [range-from-intensity]}\n",
             body);
    snprintf(own, sizeof own, "shadesweep: 2\n%stonemap: none\n", body);
    experiment *e2 = load_text(two), *e1 = load_text(one), *es = load_text(spelt),
               *eo = load_text(own);
    assert_int_equal(e2->schema, 2);
    assert_int_equal(e1->schema, 1);
    assert_int_equal(e2->base.lights.attenuation, ATTENUATION_WINDOWED);
    assert_int_equal(e2->base.lights.sizing, LIGHT_SIZING_RANGE_FROM_INTENSITY);
    assert_int_equal(e2->base.exposure_mode, EXPOSURE_AUTO);
    assert_int_equal(e2->base.tonemap, TONEMAP_PBR_NEUTRAL);
    assert_int_equal(e2->base.environment, RUN_ENVIRONMENT_SCENE);
    assert_int_equal(e1->base.environment, RUN_ENVIRONMENT_NONE);
    assert_int_equal(e1->base.lights.attenuation, ATTENUATION_INVERSE_SQUARE);
    assert_int_equal(e1->base.lights.sizing, LIGHT_SIZING_RADIUS);
    assert_int_equal(e1->base.exposure_mode, EXPOSURE_NONE);
    assert_int_equal(e1->base.tonemap, TONEMAP_NONE);
    assert_int_equal(eo->base.tonemap, TONEMAP_NONE);
    assert_int_equal(eo->base.exposure_mode, EXPOSURE_AUTO);
    plan p2, p1, ps;
    assert_true(expand(e2, 1, &p2));
    assert_true(expand(e1, 1, &p1));
    assert_true(expand(es, 1, &ps));
    assert_int_equal(p2.nruns, 1);
    assert_int_equal(ps.nruns, 1);
    assert_string_equal(p2.runs[0].id, ps.runs[0].id);
    assert_string_not_equal(p2.runs[0].id, p1.runs[0].id);
    plan_free(&p2);
    plan_free(&p1);
    plan_free(&ps);
    experiment_free(e2);
    experiment_free(e1);
    experiment_free(es);
    experiment_free(eo);
}

/* run --scale S: every resolution (base and swept) times S, rounded, at least 1; the
 * hash changes with S; bad scales, collisions and overflow are refused with a message. */
static void test_scale_resolution(void **state)
{
    (void)state;
    experiment *e = load_text(PAPER);
    char hash[17], err[256];
    memcpy(hash, e->hash, sizeof hash);
    assert_true(experiment_scale_resolution(e, 0.25, err, sizeof err));
    assert_true(e->scale == 0.25);
    assert_string_not_equal(e->hash, hash);
    plan p;
    diag_list d = {0};
    assert_true(plan_expand(e, 1, &p, &d));
    assert_int_equal(p.nruns, 4);   /* resolution slowest, then radius */
    static const int want[4][2] = {{200, 150}, {200, 150}, {640, 360}, {640, 360}};
    for (size_t i = 0; i < 4; i++) {
        assert_int_equal(p.runs[i].p.width, want[i][0]);
        assert_int_equal(p.runs[i].p.height, want[i][1]);
        assert_int_equal(p.runs[i].p.trials, 3);   /* nothing else changes */
    }
    /* the ids follow the scaled parameters: a run of the scaled plan is not one of the
     * full plan's */
    experiment *full = load_text(PAPER);
    plan q;
    assert_true(plan_expand(full, 1, &q, &d));
    for (size_t i = 0; i < 4; i++)
        for (size_t j = 0; j < 4; j++)
            assert_string_not_equal(p.runs[i].id, q.runs[j].id);
    plan_free(&q);
    plan_free(&p);
    experiment_free(full);
    experiment_free(e);

    static const struct {
        double scale;
        const char *msg;
    } bad[] = {
        {0.0, "--scale: expected a number > 0 and <= 16, found 0"},
        {17.0, "--scale: expected a number > 0 and <= 16, found 17"},
        {0.0001, "--scale 0.0001: swept resolutions 1 and 2 both become 1x1"},
        {16.0, "--scale 16: a resolution would exceed 32768x32768"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        e = load_text(PAPER);
        memcpy(hash, e->hash, sizeof hash);
        err[0] = 0;
        assert_false(experiment_scale_resolution(e, bad[k].scale, err, sizeof err));
        assert_string_equal(err, bad[k].msg);
        experiment_free(e);
    }
    diag_free(&d);
}

/* run --smoke: 160x120, one trial, no warm-up, at most 2 s; the resolution sweep
 * collapses, other axes stay; screenshot times past the end move to its middle (once);
 * the name and the hash change. */
static void test_make_smoke(void **state)
{
    (void)state;
    experiment *e = load_text(PAPER);
    char hash[17];
    memcpy(hash, e->hash, sizeof hash);
    experiment_make_smoke(e);
    assert_true(e->smoke);
    assert_string_equal(e->name, "paper-smoke");
    assert_string_not_equal(e->hash, hash);
    plan p;
    diag_list d = {0};
    assert_true(plan_expand(e, 1, &p, &d));
    assert_int_equal(p.nruns, 2);   /* lights.radius 5 and 10 */
    for (size_t i = 0; i < 2; i++) {
        const run_params *r = &p.runs[i].p;
        assert_int_equal(r->width, 160);
        assert_int_equal(r->height, 120);
        assert_int_equal(r->trials, 1);
        assert_int_equal(r->warmup.kind, SPAN_FRAMES);
        assert_int_equal(r->warmup.frames, 0);
        assert_int_equal(r->duration.kind, SPAN_SECONDS);
        assert_true(r->duration.seconds == 2.0);
        assert_int_equal(r->nscreenshots, 2);   /* 0.5 kept; 30 and 45 both become 1 */
        assert_true(r->screenshots[0] == 0.5);
        assert_true(r->screenshots[1] == 1.0);
    }
    assert_true(p.runs[0].p.lights.radius == 5.0f);
    assert_true(p.runs[1].p.lights.radius == 10.0f);
    plan_free(&p);
    experiment_free(e);

    /* smaller than 160x120 stays as it is; a frame count is capped at 120 */
    e = load_text("shadesweep: 1\nname: tiny\nscene: shapes\nrenderers: [null]\n"
                  "resolution: 64x48\nduration: {frames: 500}\n");
    experiment_make_smoke(e);
    assert_true(plan_expand(e, 1, &p, &d));
    assert_int_equal(p.runs[0].p.width, 64);
    assert_int_equal(p.runs[0].p.height, 48);
    assert_int_equal(p.runs[0].p.duration.kind, SPAN_FRAMES);
    assert_int_equal(p.runs[0].p.duration.frames, 120);
    plan_free(&p);
    experiment_free(e);
    diag_free(&d);
}

/* >>blocks: `sweep:` as a list of blocks */

static const char BLOCKS[] =
    "shadesweep: 1\n"
    "name: blocks\n"
    "scene: shapes\n"
    "renderers: [deferred, forward-plus]\n"
    "duration: {frames: 10}\n"
    "lights: {count: 16}\n"
    "sweep:\n"
    "  - {scene: [shapes, canyon], lights.count: [16, 64]}\n"
    "  - {tiles.size: [16, 32]}\n";

/* The plan of the manifest BLOCKS with its sweep replaced by `sweep` (a mapping). */
static experiment *load_with_sweep(const char *sweep)
{
    char text[1024];
    snprintf(text, sizeof text, "%.*s%s", (int)(strstr(BLOCKS, "\nsweep:") + 1 - BLOCKS), BLOCKS,
             sweep);
    return load_text(text);
}

/* Each block's product in turn (first key slowest, renderers fastest); a key a block
 * does not sweep takes the value in place (lights.count 16, which block 0 sweeps too);
 * a run an earlier block made is folded into it; each run has the id of the same run
 * in the mapping form. */
static void test_blocks_order(void **state)
{
    (void)state;
    experiment *e = load_text(BLOCKS);
    assert_int_equal(e->nblocks, 2);
    assert_int_equal(e->naxes, 3);
    assert_int_equal(e->block_first[1], 2);
    plan p;
    assert_true(expand(e, 1, &p));
    assert_int_equal(p.npoints, 12);   /* 2 x 2 x 2 renderers + 2 x 2 renderers */
    assert_int_equal(p.nruns, 9);
    assert_int_equal(p.nfolded, 3);
    char *all = print_plan(&p, 0);
    assert_string_equal(all,
        "7b048d9a2785  renderer=deferred scene=shapes lights.count=16 tiles.size=16\n"
        "c6bf97306b78  renderer=forward-plus scene=shapes lights.count=16 tiles.size=16\n"
        "3f50149a05f7  renderer=deferred scene=shapes lights.count=64 tiles.size=16\n"
        "9b770c3052f6  renderer=forward-plus scene=shapes lights.count=64 tiles.size=16\n"
        "e039ebbe6782  renderer=deferred scene=canyon lights.count=16 tiles.size=16\n"
        "1783ef1b0a79  renderer=forward-plus scene=canyon lights.count=16 tiles.size=16\n"
        "0b900ebe8010  renderer=deferred scene=canyon lights.count=64 tiles.size=16\n"
        "0e82081b0546  renderer=forward-plus scene=canyon lights.count=64 tiles.size=16\n"
        "bfdb49ba3293  renderer=forward-plus scene=shapes lights.count=16 tiles.size=32\n"
        "# 3 of 12 grid points folded into a run that measures the same (they differ only "
        "in keys their renderer does not read):\n"
        "#   renderer=deferred scene=shapes lights.count=16 tiles.size=16 -> 7b048d9a2785\n"
        "#   renderer=forward-plus scene=shapes lights.count=16 tiles.size=16 -> c6bf97306b78\n"
        "#   renderer=deferred scene=shapes lights.count=16 tiles.size=32 -> 7b048d9a2785\n");
    free(all);
    assert_int_equal(p.folds[0].point, 8);
    assert_int_equal(p.folds[0].into, 0);
    assert_int_equal(p.folds[2].point, 10);
    assert_int_equal(p.runs[8].point, 11);
    assert_int_equal(p.runs[8].p.lights.count.max, 16);
    assert_int_equal(p.runs[8].p.tile_size, 2);   /* 8, 16, 32 */

    /* the same runs as the mapping form makes them: block 0 and block 1 each */
    experiment *m0 = load_text("shadesweep: 1\nname: blocks\n"
                               "renderers: [deferred, forward-plus]\n"
                               "duration: {frames: 10}\nlights: {}\nsweep:\n"
                               "  scene: [shapes, canyon]\n  lights.count: [16, 64]\n");
    experiment *m1 = load_with_sweep("sweep:\n  tiles.size: [16, 32]\n");
    plan p0, p1;
    assert_true(expand(m0, 1, &p0));
    assert_true(expand(m1, 1, &p1));
    assert_int_equal(p0.nruns, 8);
    for (size_t k = 0; k < 8; k++)
        assert_string_equal(p.runs[k].id, p0.runs[k].id);
    assert_int_equal(p1.nruns, 3);
    assert_string_equal(p.runs[8].id, p1.runs[2].id);
    /* sweep points: block 1's tiles.size 32 is ranked with block 0's shapes/16 */
    assert_int_equal(p.ngroups, 4);
    assert_int_equal(p.runs[8].group, p.runs[0].group);
    plan_free(&p0);
    plan_free(&p1);
    experiment_free(m0);
    experiment_free(m1);
    plan_free(&p);
    experiment_free(e);
}

/* Errors of the plan: a value repeated in one block's axis, a key none of the
 * renderers reads, more than 100000 runs over all the blocks; a block that only
 * repeats an earlier one is no error. */
static void test_blocks_plan_errors(void **state)
{
    (void)state;
    static const struct {
        const char *sweep, *line;
    } cases[] = {
        {"sweep:\n  - {lights.count: [16, 64]}\n  - {lights.count: [64, 16, 64]}\n",
         "9:29: sweep[1].lights.count[2]: expected a distinct sweep point, found run 8 the "
         "same as run 4 (id 3f50149a05f7)"},
        {"sweep:\n  - {lights.count: [16, 64]}\n  - {forward.illumination_sets: [true]}\n",
         "9:34: sweep[1].forward.illumination_sets: expected a key one of the renderers reads "
         "(forward.illumination_sets is read by forward-mpml), found none of deferred, "
         "forward-plus"},
        {NULL, NULL},
    };
    for (size_t k = 0; cases[k].sweep; k++)
        expect_plan_error(load_with_sweep(cases[k].sweep), cases[k].line);

    /* two identical blocks: the second folds into the first */
    experiment *e = load_with_sweep("sweep:\n  - {lights.count: [16, 64]}\n"
                                    "  - {lights.count: [16, 64]}\n");
    plan p;
    assert_true(expand(e, 1, &p));
    assert_int_equal(p.npoints, 8);
    assert_int_equal(p.nruns, 4);
    assert_int_equal(p.nfolded, 4);
    plan_free(&p);
    experiment_free(e);

    /* 2 blocks of 60000 runs each: 300 seeds x 100 radii x 2 renderers */
    size_t cap = 64 * 1024, n = 0;
    char *sw = malloc(cap);
    assert_non_null(sw);
    n += (size_t)snprintf(sw + n, cap - n, "sweep:\n");
    for (int b = 0; b < 2; b++) {
        n += (size_t)snprintf(sw + n, cap - n, "  - lights.seed: [%d", 1000 * b);
        for (int i = 1; i < 300; i++)
            n += (size_t)snprintf(sw + n, cap - n, ", %d", 1000 * b + i);
        n += (size_t)snprintf(sw + n, cap - n, "]\n    lights.radius: [1");
        for (int i = 2; i <= 100; i++)
            n += (size_t)snprintf(sw + n, cap - n, ", %d", i);
        n += (size_t)snprintf(sw + n, cap - n, "]\n");
    }
    char *text = malloc(cap + 512);
    assert_non_null(text);
    snprintf(text, cap + 512, "%.*s%s", (int)(strstr(BLOCKS, "\nsweep:") + 1 - BLOCKS), BLOCKS, sw);
    e = load_text(text);
    diag_list d = {0};
    assert_false(plan_expand(e, 1, &p, &d));
    assert_int_equal(d.n, 1);
    assert_string_equal(d.v[0].msg, "expected at most 100000 runs, found 120000");
    diag_free(&d);
    experiment_free(e);
    free(text);
    free(sw);
}

/* --smoke drops its axes in every block; a block left with none is the base point
 * once (here folded into block 0's run at the same values). */
static void test_blocks_smoke(void **state)
{
    (void)state;
    experiment *e = load_with_sweep("sweep:\n"
                                    "  - {resolution: [320x240, 640x480], lights.count: [16, 64]}\n"
                                    "  - {resolution: [320x240]}\n"
                                    "  - {trials: [1, 2], tiles.size: [8, 32]}\n");
    assert_int_equal(e->naxes, 5);
    plan p;
    assert_true(expand(e, 1, &p));
    assert_int_equal(p.npoints, 8 + 2 + 8);
    plan_free(&p);
    experiment_make_smoke(e);
    assert_int_equal(e->naxes, 2);
    assert_int_equal(e->nblocks, 3);
    assert_int_equal(e->block_first[0], 0);
    assert_int_equal(e->block_first[1], 1);
    assert_int_equal(e->block_first[2], 1);
    assert_int_equal(e->block_first[3], 2);
    assert_true(expand(e, 1, &p));
    assert_int_equal(p.npoints, 4 + 2 + 4);
    assert_int_equal(p.nruns, 6);   /* block 1 is block 0's count 16; deferred reads no tiles */
    for (size_t k = 0; k < p.nruns; k++) {
        assert_int_equal(p.runs[k].p.width, 160);
        assert_int_equal(p.runs[k].p.trials, 1);
    }
    plan_free(&p);
    experiment_free(e);
}

static void test_zero_shards(void **state)
{
    (void)state;
    experiment *e = load("good/minimal.yaml");
    plan p;
    diag_list d = {0};
    assert_false(plan_expand(e, 0, &p, &d));
    assert_int_equal(d.n, 1);
    assert_string_equal(d.v[0].msg, "expected at least 1 shard, found 0");
    assert_int_equal(p.nruns, 0);
    diag_free(&d);
    experiment_free(e);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_order_and_ids),
        cmocka_unit_test(test_ids_differ),
        cmocka_unit_test(test_shards_partition),
        cmocka_unit_test(test_parse_shard),
        cmocka_unit_test(test_plan_print),
        cmocka_unit_test(test_duplicate_points),
        cmocka_unit_test(test_zero_shards),
        cmocka_unit_test(test_scale_resolution),
        cmocka_unit_test(test_schema2_defaults),
        cmocka_unit_test(test_make_smoke),
        cmocka_unit_test(test_blocks_order),
        cmocka_unit_test(test_blocks_plan_errors),
        cmocka_unit_test(test_blocks_smoke),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
