/* A run's meta.yaml, and a device.yaml, read back (runner/folder/meta_read.h). */
#include "runner/folder/meta_read.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/fsutil.h"
#include "results/device_profile.h"
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

/* The YAML document at path, NULL when unreadable or not YAML (*err says which). */
static ydoc *load(const char *path, char *err, size_t errlen)
{
    size_t n;
    int e;
    char *text = fs_read_all(path, 64u << 20, &n, &e);
    diag_list d = {0};
    ydoc *doc = NULL;
    if (!text)
        fs_error_message(err, errlen, path, e);
    else if (!ydoc_load(path, text, n, &doc, &d))
        snprintf(err, errlen, "%s: not YAML", path);
    diag_free(&d);
    free(text);
    return doc;
}

bool meta_read_first_start(const char *run_dir, char *out, size_t len)
{
    out[0] = '\0';
    char path[4300], err[4400];
    snprintf(path, sizeof path, "%s/meta.yaml", run_dir);
    ydoc *doc = load(path, err, sizeof err);
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
    char path[4300], err[4400];
    snprintf(path, sizeof path, "%s/meta.yaml", run_dir);
    ydoc *doc = load(path, err, sizeof err);
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

/* The scalar text at key of m, "" when there is none (or null). */
static const char *text_at(const ynode *m, const char *key)
{
    const ynode *v = map_get(m, key);
    return v && v->kind == YNODE_SCALAR && !yaml_null(v) ? v->text : "";
}

bool meta_read_profile(const char *path, device_profile *p, char *err, size_t errlen)
{
    static const char *const units[] = {"Gsamples/s", "GB/s", "Gflop/s", "us", "ns"};
    memset(p, 0, sizeof *p);
    ydoc *doc = load(path, err, errlen);
    if (!doc)
        return false;
    const ynode *r = doc->root;
    device_profile_set_gl(p, (const char *const[6]){text_at(r, "vendor"), text_at(r, "renderer"),
                                                    text_at(r, "version"), text_at(r, "glsl"),
                                                    text_at(r, "backend"), text_at(r, "device")});
    snprintf(p->date, sizeof p->date, "%s", text_at(r, "date"));
    snprintf(p->host, sizeof p->host, "%s", text_at(r, "host"));
    p->quick = strcmp(text_at(r, "quick"), "true") == 0;
    const ynode *f = map_get(r, "figures");
    for (size_t i = 0; f && f->kind == YNODE_MAPPING && i < f->n; i++) {
        const ynode *v = f->pairs[i].value;
        if (f->pairs[i].key->kind != YNODE_SCALAR || v->kind != YNODE_MAPPING ||
            p->nfigures == DEVICE_PROFILE_MAX_FIGURES)
            continue;
        device_figure *g = &p->figure[p->nfigures++];
        snprintf(g->name, sizeof g->name, "%s", f->pairs[i].key->text);
        g->median = strtod(text_at(v, "median"), NULL);
        g->spread = strtod(text_at(v, "spread"), NULL);
        g->repeats = (unsigned)strtoul(text_at(v, "repeats"), NULL, 10);
        g->unit = "";
        for (size_t u = 0; u < sizeof units / sizeof *units; u++)
            if (strcmp(text_at(v, "unit"), units[u]) == 0)
                g->unit = units[u];
    }
    ydoc_free(doc);
    if (!p->nfigures)
        snprintf(err, errlen, "%s: no figures (not a device profile)", path);
    return p->nfigures > 0;
}
