/* The defaults of the table, each parsed and validated as any value (mf_parse_value),
 * schema 2's over them, and what is computed from the defaults: run_params_kv (a key
 * at its default leaves the id) and the error reference's parameters. */
#include "runner/manifest/params.h"

#include <stdlib.h>
#include <string.h>

#include "runner/manifest/manifest_parse.h"

/* What `shadesweep: 2` changes (issue 36): a file scene shown as a viewer shows it,
 * its lights sized by what they light. Every other default is schema 1's. */
static const struct {
    const char *path, *value;
} params_schema2[] = {
    {"lights.attenuation", "windowed"},
    {"lights.sizing", "range-from-intensity"},
    {"exposure.mode", "auto"},
    {"tonemap", "pbr-neutral"},
    {"environment.light", "scene"},
};

/* A key's schema-2 default, or NULL where it is schema 1's. */
const char *params_schema2_default(const char *path)
{
    for (size_t i = 0; i < sizeof params_schema2 / sizeof *params_schema2; i++)
        if (strcmp(params_schema2[i].path, path) == 0)
            return params_schema2[i].value;
    return NULL;
}

/* The canonical text of every parameter's default ("" for those without one). */
const char (*params_default_texts(void))[160]
{
    static char text[PARAMS_N][160];
    static bool done;
    if (!done) {
        run_params d;
        params_defaults(&d);
        for (size_t i = 0; i < NPARAMS; i++)
            if (params_table[i].size && params_table[i].def)
                param_format(&params_table[i], &d, text[i], sizeof text[i]);
        done = true;
    }
    return (const char (*)[160])text;
}

size_t run_params_kv(const run_params *p, param_kv *out, size_t max)
{
    const char (*defaults)[160] = params_default_texts();
    size_t k = 0;
    for (size_t i = 0; i < NPARAMS && k < max; i++) {
        const param *pd = &params_table[i];
        if (pd->size == 0)
            continue;
        out[k].key = param_column(pd);
        out[k].in_id = !(pd->flags & PF_NOT_IN_ID);
        param_format(pd, p, out[k].value, sizeof out[k].value);
        /* without a default (scene, renderer, duration, error.reference.renderer), only
         * the empty text: a reference renderer not named */
        out[k].is_default = pd->def ? strcmp(out[k].value, defaults[i]) == 0 : !out[k].value[0];
        k++;
    }
    return k;
}

void params_reference(const run_params *p, run_params *ref)
{
    run_params d;
    params_defaults(&d);
    *ref = *p;
    for (size_t i = 0; i < NPARAMS; i++) {
        const param *pd = &params_table[i];
        if (pd->size && pd->ref && strcmp(pd->ref, "default") == 0)
            memcpy((char *)ref + pd->off, (const char *)&d + pd->off, pd->size);
    }
    for (size_t i = 0; i < NPARAMS; i++) {
        const param *pd = &params_table[i];
        if (!pd->size || !pd->ref || strncmp(pd->ref, "sets:", 5) != 0)
            continue;
        const param *t = param_find(pd->ref + 5);
        if (t && t->size == pd->size)   /* tests/unit/test_params.c checks every one */
            memcpy((char *)ref + t->off, (const char *)p + pd->off, pd->size);
    }
    ref->error_renderer[0] = '\0';   /* the reference is compared with nothing */
    ref->nerror_at = 0;
}

/* The table's defaults go through the same validation as any value: a default
 * that fails its own parameter is a bug, caught by every load. */
bool params_apply_defaults(vctx *c, run_params *dst)
{
    bool ok = true;
    for (size_t i = 0; i < NPARAMS && ok; i++) {
        const param *pd = &params_table[i];
        if (!pd->def)
            continue;
        diag_list scratch = {0};
        ydoc *doc = NULL;
        vctx dc = {.file = "<default>", .d = &scratch, .e = c->e};
        ok = ydoc_load(dc.file, pd->def, strlen(pd->def), &doc, &scratch) &&
             mf_parse_value(&dc, pd, doc->root, pd->path, dst) && dc.nerr == 0;
        if (!ok)
            diag_add(c->d, c->file, 0, 0, "", "bug: the default of %s (%s) does not validate",
                     pd->path, pd->def);
        ydoc_free(doc);
        diag_free(&scratch);
    }
    return ok;
}

bool params_apply_schema_defaults(vctx *c, unsigned schema, run_params *dst)
{
    bool ok = true;
    for (size_t i = 0; schema == 2 && ok && i < sizeof params_schema2 / sizeof *params_schema2;
         i++) {
        const param *pd = param_find(params_schema2[i].path);
        diag_list scratch = {0};
        ydoc *doc = NULL;
        vctx dc = {.file = "<schema 2>", .d = &scratch, .e = c->e};
        const char *v = params_schema2[i].value;
        ok = pd && ydoc_load(dc.file, v, strlen(v), &doc, &scratch) &&
             mf_parse_value(&dc, pd, doc->root, pd->path, dst) && dc.nerr == 0;
        if (!ok)
            diag_add(c->d, c->file, 0, 0, "", "bug: schema 2's default of %s (%s) does not "
                     "validate", params_schema2[i].path, v);
        ydoc_free(doc);
        diag_free(&scratch);
    }
    return ok;
}

unsigned params_schema_of(const ynode *root)
{
    if (!root || root->kind != YNODE_MAPPING)
        return 1;
    for (size_t i = 0; i < root->n; i++) {
        const ynode *k = root->pairs[i].key, *v = root->pairs[i].value;
        if (k->kind == YNODE_SCALAR && strcmp(k->text, "shadesweep") == 0)
            return v->kind == YNODE_SCALAR && ynode_plain(v) && strcmp(v->text, "2") == 0 ? 2
                                                                                       : 1;
    }
    return 1;
}

bool params_defaults(run_params *out)
{
    static run_params d;
    static int state;   /* 0: not yet, 1: made, -1: a default does not validate (a bug) */
    if (state == 0) {
        diag_list scratch = {0};
        experiment e = {0};
        vctx c = {.file = "<default>", .d = &scratch, .e = &e};
        memset(&d, 0, sizeof d);
        state = params_apply_defaults(&c, &d) ? 1 : -1;
        free(e.renderers);
        free(e.description);
        diag_free(&scratch);
    }
    *out = d;
    return state == 1;
}
