/* The parameter definition (runner/manifest/params.def): run ids pinned for every manifest
 * in experiments/ (this file is built twice, the second time with one more key,
 * SHADESWEEP_TEST_EXTRA_PARAM: a new key at its default must change no id),
 * folding of runs that differ only in keys their renderer does not read, sweeps of
 * keys no renderer reads, and the table's own consistency. */
#include <dirent.h>
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
#include "runner/manifest/manifest.h"
#include "runner/manifest/params.h"


/* The renderer options a run's parameters give (params.def's apply column). */
static renderer_options options_of(const run_params *p)
{
    renderer_options o = {0};
    params_to_renderer_options(p, &o);
    return o;
}

/* The renderers' defaults (renderer_options_default: the key tables' texts read by their
 * C types) are the runner's (the same texts validated and applied), and what the tests
 * mean by a zero member (renderer_options_complete) is the default. */
static void test_renderer_option_defaults(void **state)
{
    (void)state;
    run_params d;
    assert_true(params_defaults(&d));
    renderer_options fromdef = options_of(&d), completed = {0};
    renderer_options_complete(&completed);
    renderer_options tables = renderer_options_default();
#define KEY_ENUM(...)
#define PARAM_META(...)
#define PARAM(...)
#define KEY_OPTION(type, member, dims)                                                      \
    assert_memory_equal(&fromdef.member, &tables.member, sizeof fromdef.member);            \
    assert_memory_equal(&fromdef.member, &completed.member, sizeof fromdef.member);
#include "renderers/keys.def"
#undef KEY_ENUM
#undef PARAM_META
#undef PARAM
#undef KEY_OPTION
    assert_int_equal(fromdef.gbuffer, completed.gbuffer);
    assert_int_equal(fromdef.gbuffer_position, completed.gbuffer_position);
    assert_int_equal(fromdef.gbuffer_normal, completed.gbuffer_normal);
    assert_int_equal(fromdef.light_volumes, completed.light_volumes);
    assert_int_equal(fromdef.light_buffer, completed.light_buffer);
    assert_int_equal(fromdef.tile_size, completed.tile_size);
    assert_int_equal(fromdef.clustered_slices, completed.clustered_slices);
    assert_int_equal(fromdef.hdr, completed.hdr);
    assert_int_equal(fromdef.aa, completed.aa);
    assert_int_equal(fromdef.tile_size, 16);
    assert_int_equal(fromdef.clustered_slices, 24);
    assert_int_equal(fromdef.msaa, 1);
    assert_false(fromdef.no_illumination_sets);
    assert_true(fromdef.fog_color[0] == 0.5f && fromdef.fog_color[2] == 0.5f);
}

static experiment *load_text(const char *yaml, diag_list *d)
{
    experiment *e = NULL;
    manifest_load_mem("mem.yaml", yaml, strlen(yaml), &e, d);
    return e;
}

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    size_t got = fread(s, 1, (size_t)n, f);
    s[got] = '\0';
    fclose(f);
    return s;
}

/* tests/data/ids/NAME.txt holds the ids `shadesweep list experiments/NAME.yaml`
 * printed when ids stopped depending on defaults; they must never change. */
static void test_pinned_ids(void **state)
{
    (void)state;
    const char *root = getenv("SOURCE_ROOT"), *data = getenv("TEST_DATA");
    assert_non_null(root);
    assert_non_null(data);
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/experiments", root);
    DIR *dp = opendir(dir);
    assert_non_null(dp);
    size_t nmanifests = 0;
    struct dirent *de;
    while ((de = readdir(dp))) {
        size_t len = strlen(de->d_name);
        if (len < 6 || strcmp(de->d_name + len - 5, ".yaml") != 0)
            continue;
        char path[2048], pinned[2048];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        snprintf(pinned, sizeof pinned, "%s/ids/%.*s.txt", data, (int)(len - 5), de->d_name);
        char *want = read_all(pinned);
        if (!want)
            fail_msg("%s has no pinned ids (%s): pin them when the manifest is added", path,
                     pinned);
        experiment *e = NULL;
        diag_list d = {0};
        plan p;
        if (!manifest_load(path, &e, &d) || !plan_expand(e, 1, &p, &d)) {
            diag_print(&d, stderr);
            fail_msg("%s does not load", path);
        }
        size_t cap = p.nruns * 13 + 1, at = 0;
        char *got = malloc(cap);
        got[0] = '\0';
        for (size_t k = 0; k < p.nruns; k++)
            at += (size_t)snprintf(got + at, cap - at, "%s\n", p.runs[k].id);
        if (strcmp(got, want) != 0)
            fail_msg("%s: run ids differ from %s:\n%s", path, pinned, got);
        free(got);
        free(want);
        plan_free(&p);
        experiment_free(e);
        diag_free(&d);
        nmanifests++;
    }
    closedir(dp);
    assert_true(nmanifests >= 16);
}

/* The G-buffer study with forward baselines of issue 15: 3 renderers x 4 modes x
 * 2 presets = 24 points, of which the forward renderers' 16 are 2 runs. */
static void test_fold(void **state)
{
    (void)state;
    diag_list d = {0};
    experiment *e = load_text("shadesweep: 1\nname: fold\nscene: shapes\n"
                              "renderers: [deferred, forward-spml, forward-mpml]\n"
                              "duration: {frames: 2}\n"
                              "sweep:\n"
                              "  deferred.light_volumes: [stencil, fullscreen, volume, "
                              "stencil-two-pass]\n"
                              "  gbuffer: [curtis, fat]\n",
                              &d);
    assert_non_null(e);
    plan p;
    assert_true(plan_expand(e, 3, &p, &d));
    assert_int_equal(p.npoints, 24);
    assert_int_equal(p.nruns, 10);
    assert_int_equal(p.nfolded, 14);
    size_t deferred = 0, folded = 0;
    for (size_t k = 0; k < p.nruns; k++) {
        const run_spec *r = &p.runs[k];
        assert_int_equal(r->index, k);
        /* one sweep point (only renderer keys vary): whole points go to a shard */
        assert_int_equal(r->group, 0);
        assert_int_equal(r->shard, 1);
        for (size_t j = 0; j < k; j++)
            assert_string_not_equal(p.runs[j].id, r->id);
        if (strcmp(r->p.renderer, "deferred") == 0) {
            deferred++;
            assert_int_equal(r->folded, 0);
        } else {
            /* each forward renderer: one run standing for its 8 points */
            assert_int_equal(r->folded, 7);
            assert_int_equal(options_of(&r->p).gbuffer, GBUFFER_CURTIS);
            assert_int_equal(options_of(&r->p).light_volumes, LIGHT_VOLUMES_STENCIL);
        }
        folded += r->folded;
    }
    assert_int_equal(deferred, 8);
    assert_int_equal(folded, 14);
    for (size_t f = 0; f < p.nfolded; f++) {
        const plan_fold *pf = &p.folds[f];
        assert_string_equal(pf->p.renderer, p.runs[pf->into].p.renderer);
        assert_true(pf->point > p.runs[pf->into].point);
    }
    plan_free(&p);
    experiment_free(e);
    diag_free(&d);
}

/* The error reference does not inherit gbuffer.* (params.def: "default"), so a
 * null run with a reference folds over the G-buffer; the deferred runs do not. */
static void test_fold_with_reference(void **state)
{
    (void)state;
    diag_list d = {0};
    experiment *e = load_text("shadesweep: 1\nname: ref\nscene: shapes\n"
                              "renderers: [null, deferred]\nduration: {frames: 2}\n"
                              "error: {reference: {renderer: forward-spml}, at: [0]}\n"
                              "sweep:\n  gbuffer: [curtis, fat]\n",
                              &d);
    assert_non_null(e);
    plan p;
    assert_true(plan_expand(e, 1, &p, &d));
    assert_int_equal(p.npoints, 4);
    assert_int_equal(p.nruns, 3);
    assert_string_equal(p.runs[0].p.renderer, "null");
    assert_int_equal(p.runs[0].folded, 1);
    assert_int_equal(p.folds[0].point, 2);
    assert_int_equal(options_of(&p.folds[0].p).gbuffer, GBUFFER_FAT);
    plan_free(&p);
    experiment_free(e);
    diag_free(&d);
}

static void test_sweep_key_nobody_reads(void **state)
{
    (void)state;
    diag_list d = {0};
    experiment *e = load_text("shadesweep: 1\nname: unread\nscene: shapes\n"
                              "renderers: [forward-spml, forward-mpml]\n"
                              "duration: {frames: 2}\n"
                              "sweep:\n  gbuffer.preset: [curtis, fat]\n",
                              &d);
    assert_non_null(e);
    plan p;
    assert_false(plan_expand(e, 1, &p, &d));
    char *got = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&got, &len);
    diag_print(&d, f);
    fclose(f);
    assert_string_equal(got, "mem.yaml:7:20: sweep.gbuffer.preset: expected a key one of the "
                             "renderers reads (gbuffer.preset is read by deferred clustered tiled-deferred zbin), "
                             "found none "
                             "of forward-spml, forward-mpml\n");
    free(got);
    experiment_free(e);
    diag_free(&d);
}

/* Every renderer a key names exists, every "sets:" names a key of the same size,
 * every run parameter says what the reference does with it. */
static void test_table(void **state)
{
    (void)state;
    run_params d;
    assert_true(params_defaults(&d));
    size_t nrun = 0;
    for (size_t i = 0; i < NPARAMS; i++) {
        const param *pd = &params_table[i];
        if (!pd->size)
            continue;
        nrun++;
        assert_non_null(pd->ref);
        /* a key no renderer reads, nor every run, would be swept for nothing */
        char readers[256];
        param_readers_text(pd, readers, sizeof readers);
        if (!readers[0])
            fail_msg("%s: read by no renderer (declare it in a renderer_impl.reads)", pd->path);
        if (strncmp(pd->ref, "sets:", 5) == 0) {
            const param *t = param_find(pd->ref + 5);
            if (!t || t->size != pd->size)
                fail_msg("%s: sets %s, which is no parameter of its size", pd->path, pd->ref + 5);
        } else if (strcmp(pd->ref, "inherit") != 0 && strcmp(pd->ref, "default") != 0) {
            fail_msg("%s: ref '%s'", pd->path, pd->ref);
        }
    }
    assert_int_equal(nrun, PARAM_KV_MAX);
    /* every key or group a renderer says it reads is one of the table's: a misspelt one
     * would be read by nobody */
    for (size_t k = 0; k < renderer_kind_count(); k++) {
        const renderer_impl *r = renderer_kind_at(k);
        char words[512];
        snprintf(words, sizeof words, "%s", r->reads ? r->reads : "");
        for (char *t = strtok(words, " "); t; t = strtok(NULL, " ")) {
            const param *pd = param_find(t);
            if (!pd || param_every_run_reads(pd))
                fail_msg("%s reads '%s', which is no key only some renderers read", r->name, t);
        }
    }
#ifdef SHADESWEEP_TEST_EXTRA_PARAM
    assert_non_null(param_find("deferred.test_extra"));   /* this build has one more key */
    assert_int_equal(d.test_extra, 7);
#else
    assert_null(param_find("deferred.test_extra"));
#endif
}

/* `params` in one format, as text (freed by the caller). */
static char *params_text(params_format fmt)
{
    char *got = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&got, &len);
    params_print(f, fmt);
    fclose(f);
    return got;
}

/* A key declared only in a renderer's table (renderers/deferred/deferred_keys.def's
 * deferred.test_extra, in the build with SHADESWEEP_TEST_EXTRA_PARAM) reaches the
 * validation, `params`, its markdown (docs/manifest.md) and its bash completion, and
 * is read by the renderer that reads its group; the plain build has none of it. The
 * ids of every manifest at its default: test_pinned_ids, in this same build. */
static void test_extra_key(void **state)
{
    (void)state;
    diag_list d = {0};
    experiment *e = load_text("shadesweep: 1\nname: extra\nscene: shapes\n"
                              "renderers: [deferred]\nduration: {frames: 2}\n"
                              "deferred: {test_extra: 101}\n",
                              &d);
    char *got = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&got, &len);
    diag_print(&d, f);
    fclose(f);
    char *md = params_text(PARAMS_MARKDOWN), *bash = params_text(PARAMS_BASH),
         *text = params_text(PARAMS_TEXT);
#ifdef SHADESWEEP_TEST_EXTRA_PARAM
    assert_null(e);
    assert_string_equal(got, "mem.yaml:6:24: deferred.test_extra: expected an integer 0..100, "
                             "found '101'\n");
    assert_non_null(strstr(md, "| `deferred.test_extra` | integer | 7 | an integer 0..100 | yes "
                               "| deferred | inherit | a key that only the id test knows |\n"));
    assert_non_null(strstr(bash, " deferred.sky_stencil deferred.test_extra forward "));
    assert_non_null(strstr(bash, " deferred.sky_stencil deferred.test_extra "
                                 "forward.illumination_sets "));   /* sweepable */
    assert_non_null(strstr(text, "deferred.test_extra  (integer, sweepable)\n"
                                 "    default:   7\n"));
    assert_true(param_read_by(param_find("deferred.test_extra"), "deferred"));
    assert_false(param_read_by(param_find("deferred.test_extra"), "forward-spml"));
#else
    assert_null(e);   /* an unknown key */
    assert_non_null(strstr(got, "deferred.test_extra"));
    assert_null(strstr(md, "test_extra"));
    assert_null(strstr(bash, "test_extra"));
    assert_null(strstr(text, "test_extra"));
#endif
    free(got);
    free(md);
    free(bash);
    free(text);
    experiment_free(e);
    diag_free(&d);
}

/* The reference renders with error.reference.*, the run's inherited keys, and the
 * defaults of the rest. */
static void test_reference_params(void **state)
{
    (void)state;
    diag_list d = {0};
    experiment *e = load_text("shadesweep: 1\nname: ref\nscene: shapes\n"
                              "renderers: [deferred]\nduration: {frames: 2}\nresolution: 64x32\n"
                              "shadows: off\ngbuffer: {preset: fat, position: depth}\n"
                              "deferred: {light_volumes: volume, separate_specular: true}\n"
                              "error: {reference: {renderer: forward-spml, "
                              "light_volumes: fullscreen}, at: [0]}\n",
                              &d);
    assert_non_null(e);
    run_params r;
    params_reference(&e->base, &r);
    assert_string_equal(r.renderer, "forward-spml");
    assert_int_equal(r.width, 64);
    assert_int_equal(r.shadows, 1);
    assert_int_equal(options_of(&r).gbuffer, GBUFFER_REFERENCE);
    assert_int_equal(options_of(&r).gbuffer_position, GBUFFER_POSITION_PRESET);
    assert_int_equal(options_of(&r).light_volumes, LIGHT_VOLUMES_FULLSCREEN);
    assert_false(r.separate_specular);
    assert_string_equal(r.error_renderer, "");
    renderer_options o = {0};
    params_to_renderer_options(&r, &o);
    assert_int_equal(o.width, 64);
    assert_int_equal(o.height, 32);
    assert_true(o.no_shadows);
    assert_int_equal(o.gbuffer, GBUFFER_REFERENCE);
    experiment_free(e);
    diag_free(&d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pinned_ids),
        cmocka_unit_test(test_renderer_option_defaults),
        cmocka_unit_test(test_fold),
        cmocka_unit_test(test_fold_with_reference),
        cmocka_unit_test(test_sweep_key_nobody_reads),
        cmocka_unit_test(test_table),
        cmocka_unit_test(test_extra_key),
        cmocka_unit_test(test_reference_params),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
