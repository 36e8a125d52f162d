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

bool meta_read_block(const char *run_dir, const char *block, const char *const *keys,
                     size_t nkeys, char *out, size_t len)
{
    for (size_t k = 0; k < nkeys; k++)
        out[k * len] = '\0';
    char path[4300];
    snprintf(path, sizeof path, "%s/meta.yaml", run_dir);
    size_t n;
    int e;
    char *text = fs_read_all(path, 64u << 20, &n, &e);
    diag_list d = {0};
    ydoc *doc = NULL;
    bool ok = text && ydoc_load(path, text, n, &doc, &d);
    const ynode *b = ok ? map_get(doc->root, block) : NULL;
    for (size_t k = 0; k < nkeys; k++) {
        const ynode *v = map_get(b, keys[k]);
        bool null = v && v->style == YSTYLE_PLAIN &&
                    (strcmp(v->text, "null") == 0 || strcmp(v->text, "~") == 0);
        if (v && v->kind == YNODE_SCALAR && !null)
            snprintf(out + k * len, len, "%s", v->text);
    }
    ydoc_free(doc);
    diag_free(&d);
    free(text);
    return ok;
}
