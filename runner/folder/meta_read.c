/* A run's meta.yaml read back (runner/folder/meta_read.h). */
#include "runner/folder/meta_read.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/fsutil.h"
#include "runner/manifest/diag.h"
#include "runner/manifest/yamldoc.h"

/* The value at key of mapping m, NULL when there is none. */
static const ynode *map_get(const ynode *m, const char *key)
{
    for (size_t i = 0; m && m->kind == YNODE_MAPPING && i < m->n; i++)
        if (m->pairs[i].key->kind == YNODE_SCALAR && strcmp(m->pairs[i].key->text, key) == 0)
            return m->pairs[i].value;
    return NULL;
}

/* A plain scalar that YAML's core schema reads as null (yamlout.c writes a missing
 * string so: a trial without a context has `renderer: null`). */
static bool yaml_null(const ynode *v)
{
    static const char *const nulls[] = {"~", "null", "Null", "NULL"};
    for (size_t i = 0; v->style == YSTYLE_PLAIN && i < sizeof nulls / sizeof *nulls; i++)
        if (strcmp(v->text, nulls[i]) == 0)
            return true;
    return false;
}

/* RUN_DIR/meta.yaml as a tree; NULL when it cannot be read or is not YAML */
static ydoc *meta_load(const char *run_dir)
{
    char path[4300];
    snprintf(path, sizeof path, "%s/meta.yaml", run_dir);
    size_t n;
    int e;
    char *text = fs_read_all(path, 64u << 20, &n, &e);
    diag_list d = {0};
    ydoc *doc = NULL;
    if (text && !ydoc_load(path, text, n, &doc, &d))
        doc = NULL;
    diag_free(&d);
    free(text);
    return doc;
}

bool meta_read_first_start(const char *run_dir, char *out, size_t len)
{
    out[0] = '\0';
    ydoc *doc = meta_load(run_dir);
    const ynode *t = doc ? map_get(doc->root, "trials") : NULL;
    for (size_t i = 0; t && t->kind == YNODE_SEQUENCE && i < t->n; i++) {
        const ynode *v = map_get(t->items[i], "started");
        if (v && v->kind == YNODE_SCALAR && !yaml_null(v) && v->len < len &&
            (!out[0] || strcmp(v->text, out) < 0))
            snprintf(out, len, "%s", v->text);
    }
    ydoc_free(doc);
    return out[0] != '\0';
}

bool meta_read_block(const char *run_dir, const char *block, const char *const *keys,
                     size_t nkeys, char *out, size_t len)
{
    for (size_t k = 0; k < nkeys; k++)
        out[k * len] = '\0';
    ydoc *doc = meta_load(run_dir);
    bool ok = doc != NULL;
    const ynode *b = ok ? map_get(doc->root, block) : NULL;
    for (size_t k = 0; k < nkeys; k++) {
        const ynode *v = map_get(b, keys[k]);
        if (v && v->kind == YNODE_SCALAR && !yaml_null(v))
            snprintf(out + k * len, len, "%s", v->text);
    }
    ydoc_free(doc);
    return ok;
}
