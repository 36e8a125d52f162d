/* libFuzzer target for the manifest parser (runner/manifest/). Each input is a
 * manifest's bytes, loaded with manifest_load_mem; when valid, the plan is expanded (3
 * shards), every run's parameters formatted (run_params_kv) and `list` output made, then
 * all freed. A crash, a sanitizer report or a leak is a finding, and so is a broken
 * contract, which aborts:
 *   - a failed load reports at least one diagnostic, a successful one none;
 *   - every diagnostic is one line "expected ..., found ..." at a line:col >= 0;
 *   - the same bytes loaded twice give the same hash and run ids (a value depending on
 *     uninitialised memory would show here);
 *   - run ids are 12 lowercase hex digits, shards in 1..3, indexes in order.
 * Built with clang -fsanitize=fuzzer (scripts/fuzz.sh); with replay.c as main() it runs
 * the seed corpus and tests/data/bad/ as a unit test under any compiler. */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "runner/manifest/diag.h"
#include "runner/manifest/manifest.h"

#define FUZZ_SHARDS 3u

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void contract(bool ok, const char *what, const char *detail)
{
    if (ok)
        return;
    fprintf(stderr, "fuzz_manifest: contract broken: %s%s%s\n", what, detail ? ": " : "",
            detail ? detail : "");
    abort();
}

static FILE *devnull(void)
{
    static FILE *f;
    if (!f)
        f = fopen("/dev/null", "w");
    return f;
}

static void check_diags(const diag_list *d)
{
    for (size_t i = 0; i < d->n; i++) {
        const diag *g = &d->v[i];
        contract(g->msg && g->key && g->file, "a diagnostic with a NULL field", NULL);
        contract(g->line >= 0 && g->col >= 0, "a negative line or column", g->msg);
        contract(strncmp(g->msg, "expected ", 9) == 0 || strncmp(g->msg, "bug: ", 5) == 0,
                 "a message not starting with 'expected '", g->msg);
        contract(strstr(g->msg, "found") != NULL, "a message without 'found'", g->msg);
        contract(!strchr(g->msg, '\n') && !strchr(g->msg, '\r'), "a message of several lines",
                 g->msg);
        contract(!strchr(g->key, '\n') && !strchr(g->key, '\r'), "a key of several lines",
                 g->key);
    }
    if (devnull())
        diag_print(d, devnull());
}

static bool is_id(const char *id)
{
    if (strlen(id) != 12)
        return false;
    for (const char *c = id; *c; c++)
        if (!((*c >= '0' && *c <= '9') || (*c >= 'a' && *c <= 'f')))
            return false;
    return true;
}

/* Expands e; returns the plan (nruns 0 when the plan is invalid). */
static plan expand(const experiment *e)
{
    plan p;
    diag_list d = {0};
    bool ok = plan_expand(e, FUZZ_SHARDS, &p, &d);
    contract(ok == (d.n == 0), "plan_expand's result disagrees with its diagnostics", NULL);
    check_diags(&d);
    diag_free(&d);
    if (!ok) {
        contract(p.nruns == 0 && p.runs == NULL, "a failed plan with runs", NULL);
        return p;
    }
    contract(p.nruns >= 1 && p.runs != NULL, "a valid plan without runs", NULL);
    for (size_t k = 0; k < p.nruns; k++) {
        const run_spec *r = &p.runs[k];
        contract(r->index == k, "run index out of order", r->id);
        contract(is_id(r->id), "a run id that is not 12 hex digits", r->id);
        contract(r->shard >= 1 && r->shard <= FUZZ_SHARDS, "a shard out of range", r->id);
        param_kv kv[PARAM_KV_MAX];
        size_t n = run_params_kv(&r->p, kv, PARAM_KV_MAX);
        contract(n > 0 && n <= PARAM_KV_MAX, "run_params_kv returned no pairs", NULL);
        for (size_t i = 0; i < n; i++) {
            contract(kv[i].key && kv[i].key[0], "an empty parameter name", NULL);
            contract(memchr(kv[i].value, '\0', sizeof kv[i].value) != NULL,
                     "a value not NUL-terminated", kv[i].key);
            contract(!strchr(kv[i].value, '\n'), "a value of several lines", kv[i].key);
        }
    }
    if (devnull())
        plan_print(&p, 0, devnull());
    return p;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    experiment *e = NULL, *e2 = NULL;
    diag_list d = {0};
    bool ok = manifest_load_mem("fuzz.yaml", (const char *)data, size, &e, &d);
    contract(ok == (e != NULL), "manifest_load_mem's result disagrees with *out", NULL);
    contract(ok ? d.n == 0 : d.n > 0, ok ? "a valid manifest with diagnostics"
                                         : "an invalid manifest without a diagnostic", NULL);
    check_diags(&d);
    diag_free(&d);
    if (!ok)
        return 0;

    contract(strcmp(e->path, "fuzz.yaml") == 0, "experiment.path is not the name given", e->path);
    contract(e->name[0] != '\0' && e->nrenderers >= 1, "a valid manifest without name or renderer",
             NULL);
    plan p = expand(e);

    /* The same bytes again: the same experiment, the same runs. */
    diag_list d2 = {0};
    bool ok2 = manifest_load_mem("fuzz.yaml", (const char *)data, size, &e2, &d2);
    diag_free(&d2);
    contract(ok2, "the same bytes loaded once and failed the second time", NULL);
    contract(strcmp(e->hash, e2->hash) == 0, "two hashes of the same bytes", NULL);
    plan p2 = expand(e2);
    contract(p.nruns == p2.nruns, "two plans of different length from the same bytes", NULL);
    for (size_t k = 0; k < p.nruns; k++)
        contract(strcmp(p.runs[k].id, p2.runs[k].id) == 0, "two ids for the same run",
                 p.runs[k].id);

    plan_free(&p2);
    experiment_free(e2);
    plan_free(&p);
    experiment_free(e);
    return 0;
}
