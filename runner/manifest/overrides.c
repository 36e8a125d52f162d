/* --set and --renderer (manifest.h's manifest_overrides). Each --set's value is loaded
 * as a YAML document of its own and grafted onto the manifest's tree before the manifest is read, so it
 * meets exactly the checks, messages and canonical values of a value written in the
 * file. The nodes of the k-th --set carry line -k: overrides_where turns that into
 * "MANIFEST: --set KEY=VALUE" for a diag.
 *
 * >>command line   the checks before any manifest is read
 * >>graft          the tree surgery: a key set in place or as an axis, and removed
 *                  from the other place
 * >>load           what manifest_load calls */
#include "runner/manifest/manifest_parse.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/renderer.h"
#include "runner/manifest/hash.h"

#define KEY_MAX 200

/* >>command line */

/* KEY of KEY=VALUE: dotted names without an empty one; after "sweep." the rest is one
 * key of the sweep (itself dotted). */
static bool key_ok(const char *key, size_t len)
{
    if (len == 0 || len > KEY_MAX)
        return false;
    if (len > 6 && strncmp(key, "sweep.", 6) == 0)
        return true;
    bool empty = true;   /* the current name so far */
    for (size_t i = 0; i < len; i++) {
        if (key[i] == '.' && empty)
            return false;
        empty = key[i] == '.';
    }
    return !empty;
}

bool override_check_set(const char *arg, char *err, size_t errlen)
{
    const char *eq = strchr(arg, '=');
    if (eq && key_ok(arg, (size_t)(eq - arg)))
        return true;
    snprintf(err, errlen, "--set: expected KEY=VALUE (KEY a manifest key such as "
             "lights.count, or sweep.KEY), found '%.200s'", arg);
    return false;
}

/* Does the comma-separated list name `name`? */
static bool names(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *s = list;; s++) {
        size_t k = strcspn(s, ",");
        if (k == n && strncmp(s, name, n) == 0)
            return true;
        s += k;
        if (!*s)
            return false;
    }
}

bool override_check_renderers(const char *list, char *err, size_t errlen)
{
    for (const char *s = list;; s++) {
        size_t k = strcspn(s, ",");
        char name[32];
        snprintf(name, sizeof name, "%.*s", (int)(k < sizeof name ? k : sizeof name - 1), s);
        if (k == 0 || k >= sizeof name || !renderer_kind_find(name)) {
            char all[512];
            sbuf b = {all, sizeof all, 0};
            mf_list_renderers(&b);
            snprintf(err, errlen, "--renderer: expected renderer names separated by commas "
                     "(each %s), found '%.*s'", all, (int)(k < 100 ? k : 100), s);
            return false;
        }
        s += k;
        if (!*s)
            return true;
    }
}

/* >>graft */

typedef struct graft {
    ydoc *doc;
    ynode *root;               /* the manifest's root mapping, this code's own copy */
    int line;                  /* of the --set at hand: -k */
    bool oom;
} graft;

#define NONE ((size_t)-1)

/* The index of the first pair of map whose key is `name`; NONE if none is. */
static size_t find_key(const ynode *map, const char *name, size_t len)
{
    for (size_t i = 0; i < map->n; i++) {
        const ynode *k = map->pairs[i].key;
        if (k->kind == YNODE_SCALAR && k->len == len && memcmp(k->text, name, len) == 0)
            return i;
    }
    return NONE;
}

/* The mapping at *slot, copied (the tree may share it through an alias) and put
 * there: this code's to change. NULL when it is not a mapping (or no memory). */
static ynode *own(graft *g, const ynode **slot)
{
    const ynode *m = *slot;
    if (m->kind != YNODE_MAPPING)
        return NULL;
    ynode *n = ydoc_node(g->doc, YNODE_MAPPING, m->line, m->col);
    if (n && m->tag)
        n->tag = strdup(m->tag);
    if (n && m->n)
        n->pairs = malloc(m->n * sizeof *n->pairs);
    if (!n || (m->tag && !n->tag) || (m->n && !n->pairs)) {
        g->oom = true;
        return NULL;
    }
    if (m->n)
        memcpy(n->pairs, m->pairs, m->n * sizeof *n->pairs);
    n->n = m->n;
    *slot = n;
    return n;
}

/* A new key name[0..len) of map (owned), at the --set's line, with value v. */
static bool add_pair(graft *g, ynode *map, const char *name, size_t len, int line,
                     const ynode *v)
{
    ynode *k = ydoc_node(g->doc, YNODE_SCALAR, line, 0);
    ypair *p = k ? realloc(map->pairs, (map->n + 1) * sizeof *p) : NULL;
    if (p)
        map->pairs = p;
    if (!p || !(k->text = strndup(name, len))) {
        g->oom = true;
        return false;
    }
    k->len = len;
    map->pairs[map->n++] = (ypair){k, v};
    return true;
}

static void remove_pair(ynode *map, size_t i)
{
    memmove(map->pairs + i, map->pairs + i + 1, (map->n - i - 1) * sizeof *map->pairs);
    map->n--;
}

/* The group at path[0..len) when a plain scalar sets one of its members
 * (`gbuffer: fat` is gbuffer.preset); NULL otherwise. */
static const param *shorthand_group(const char *path, size_t len)
{
    char p[KEY_MAX + 1];
    snprintf(p, sizeof p, "%.*s", (int)len, path);
    const param *pd = param_find(p);
    return pd && pd->type == PT_GROUP && pd->shorthand ? pd : NULL;
}

/* A sweep key's parameter path: `gbuffer` sweeps gbuffer.preset. */
static const char *canonical(const char *key)
{
    const param *pd = param_find(key);
    if (pd && pd->type == PT_GROUP && pd->shorthand)
        pd = param_find(pd->shorthand);
    return pd ? pd->path : key;
}

/* The mapping that holds path's last name, made where absent and, for a group set by
 * its shorthand scalar (`gbuffer: fat`), made {preset: fat}. NULL where something on
 * the way is not a mapping: the manifest's own message says so, as it would without
 * the --set. */
static ynode *parent_of(graft *g, const char *path, const char **leaf)
{
    ynode *map = g->root;
    for (const char *s = path;; s++) {
        size_t n = strcspn(s, ".");
        if (!s[n]) {
            *leaf = s;
            return map;
        }
        size_t i = find_key(map, s, n);
        if (i == NONE) {
            ynode *m = ydoc_node(g->doc, YNODE_MAPPING, g->line, 0);
            g->oom |= !m;
            if (!m || !add_pair(g, map, s, n, g->line, m))
                return NULL;
            map = m;
        } else if (map->pairs[i].value->kind == YNODE_MAPPING) {
            if (!(map = own(g, &map->pairs[i].value)))
                return NULL;
        } else {
            const param *pd = shorthand_group(path, (size_t)(s + n - path));
            const ynode *v = map->pairs[i].value;
            if (!pd || v->kind != YNODE_SCALAR)
                return NULL;
            ynode *m = ydoc_node(g->doc, YNODE_MAPPING, v->line, v->col);
            const char *member = path_leaf(pd->shorthand);
            g->oom |= !m;
            if (!m || !add_pair(g, m, member, strlen(member), v->line, v))
                return NULL;
            map->pairs[i].value = m;
            map = m;
        }
        s += n;
    }
}

/* Sets path to v in place. */
static void set_path(graft *g, const char *path, const ynode *v)
{
    const char *leaf;
    ynode *map = parent_of(g, path, &leaf);
    if (!map)
        return;
    size_t i = find_key(map, leaf, strlen(leaf));
    if (i != NONE)
        map->pairs[i].value = v;
    else
        add_pair(g, map, leaf, strlen(leaf), g->line, v);
}

/* Removes a sweepable parameter's value in place: its key, or the key of the group
 * whose shorthand scalar sets it (`gbuffer: fat` for gbuffer.preset). Anything else
 * (a group, an unknown key) stays, for the sweep's own message. */
static void unset_path(graft *g, const char *path)
{
    const param *pd = param_find(path);
    if (!pd || !(pd->flags & PF_SWEEP))
        return;
    ynode *map = g->root;
    for (const char *s = path; map; s++) {
        size_t n = strcspn(s, "."), i = find_key(map, s, n);
        if (i == NONE)
            return;
        const param *grp = shorthand_group(path, (size_t)(s + n - path));
        if (!s[n] || (grp && map->pairs[i].value->kind == YNODE_SCALAR &&
                      strcmp(grp->shorthand, path) == 0)) {
            remove_pair(map, i);
            return;
        }
        map = own(g, &map->pairs[i].value);
        s += n;
    }
}

/* The sweep mapping (owned), made when absent and `create`; NULL when absent or not a
 * mapping (the manifest's message then). */
static ynode *sweep_of(graft *g, bool create)
{
    size_t i = find_key(g->root, "sweep", 5);
    if (i != NONE)
        return own(g, &g->root->pairs[i].value);
    ynode *m = create ? ydoc_node(g->doc, YNODE_MAPPING, g->line, 0) : NULL;
    g->oom |= create && !m;
    return m && add_pair(g, g->root, "sweep", 5, g->line, m) ? m : NULL;
}

/* The axes of sw that sweep `path` (or, with `under`, a key under it) removed; with v,
 * the first of them keeps its place and takes v. True when one took v. */
static bool unsweep(ynode *sw, const char *path, bool under, const ynode *v)
{
    size_t len = strlen(path), first = NONE;
    for (size_t j = 0; j < sw->n; j++) {
        const ynode *k = sw->pairs[j].key;
        const char *c = k->kind == YNODE_SCALAR ? canonical(k->text) : "";
        if (strcmp(c, path) != 0 && !(under && strncmp(c, path, len) == 0 && c[len] == '.'))
            continue;
        if (v && first == NONE) {
            first = j;
            sw->pairs[j].value = v;
        } else {
            remove_pair(sw, j--);
        }
    }
    return first != NONE;
}

/* Is the manifest's sweep a list of blocks? */
static bool sweep_is_blocks(const graft *g)
{
    size_t i = find_key(g->root, "sweep", 5);
    return i != NONE && g->root->pairs[i].value->kind == YNODE_SEQUENCE;
}

/* `--set KEY=V` on a sweep of blocks: KEY (and the keys under it) leaves every block;
 * a block left with no key is the base point once (as --smoke leaves it): an empty
 * mapping at the --set's line and column -1, which the parser takes for that. */
static void unsweep_blocks(graft *g, const char *path)
{
    size_t i = find_key(g->root, "sweep", 5);
    const ynode *seq = g->root->pairs[i].value;
    ynode *n = ydoc_node(g->doc, YNODE_SEQUENCE, seq->line, seq->col);
    if (n && seq->n)
        n->items = malloc(seq->n * sizeof *n->items);
    if (!n || (seq->n && !n->items)) {
        g->oom = true;
        return;
    }
    for (size_t j = 0; j < seq->n; j++) {
        const ynode *b = seq->items[j];
        if (b->kind == YNODE_MAPPING) {
            size_t had = b->n;
            ynode *own_b = own(g, &b);
            if (!own_b)
                return;
            unsweep(own_b, path, true, NULL);
            if (had && !own_b->n) {
                own_b->line = g->line;
                own_b->col = -1;   /* not a YAML node's column: emptied, not written {} */
            }
        }
        n->items[n->n++] = b;
    }
    g->root->pairs[i].value = n;
}

/* Where a diag about a node at *line, *col goes: `file`, or for a node of the k-th
 * --set (line -k) "FILE: --set KEY=VALUE" in buf, with no line or column. */
static const char *where_of(const experiment *e, const char *file, int *line, int *col,
                            char *buf, size_t len)
{
    if (*line >= 0 || !e || (size_t)-*line > e->nsets)
        return file;
    snprintf(buf, len, "%s: --set %s", file, e->sets[-*line - 1]);
    *line = *col = 0;
    return buf;
}

/* The value of the k-th --set as nodes of doc at line -(k + 1); NULL after its diags. */
static const ynode *load_value(vctx *c, ydoc *doc, size_t k, bool *oom)
{
    const char *arg = c->e->sets[k], *text = strchr(arg, '=') + 1;
    int line = -(int)(k + 1), col = 0;
    if (!*text) {   /* `KEY=`: as `key:` with nothing after it */
        ynode *n = ydoc_node(doc, YNODE_SCALAR, line, 0);
        *oom = !n || !(n->text = strdup(""));
        return *oom ? NULL : n;
    }
    char where[1200];
    const char *file = where_of(c->e, c->file, &line, &col, where, sizeof where);
    size_t from = c->d->n;
    ydoc *vd = NULL;
    if (!ydoc_load(file, text, strlen(text), &vd, c->d)) {
        for (size_t i = from; i < c->d->n; i++)
            c->d->v[i].line = c->d->v[i].col = 0;   /* in the value, not the manifest */
        c->nerr++;
        return NULL;
    }
    const ynode *root = vd->root;
    for (size_t i = 0; i < vd->nall; i++) {
        vd->all[i]->line = -(int)(k + 1);
        vd->all[i]->col = 0;
    }
    if (!ydoc_take(doc, vd)) {
        ydoc_free(vd);
        *oom = true;
        return NULL;
    }
    return root;
}

/* >>load */

bool overrides_keep(vctx *c, const manifest_overrides *ov)
{
    experiment *e = c->e;
    if (!ov || (!ov->nsets && !ov->renderers))
        return true;
    uint64_t h = fnv1a64(e->hash, strlen(e->hash));
    bool ok = !ov->nsets || (e->sets = calloc(ov->nsets, sizeof *e->sets));
    for (size_t i = 0; ok && i < ov->nsets; i++) {
        ok = (e->sets[i] = strdup(ov->sets[i])) != NULL;
        e->nsets += ok;
        h = fnv1a64_update(h, "+set=", 5);
        h = fnv1a64_update(h, ov->sets[i], strlen(ov->sets[i]) + 1);
    }
    if (ok && ov->renderers) {
        ok = (e->renderer_filter = strdup(ov->renderers)) != NULL;
        h = fnv1a64_update(h, "+renderer=", 10);
        h = fnv1a64_update(h, ov->renderers, strlen(ov->renderers) + 1);
    }
    hash_hex(h, 16, e->hash);
    if (!ok)
        diag_add(c->d, c->file, 0, 0, "", "expected to load the manifest, found no memory left");
    return ok;
}

bool overrides_apply(vctx *c, ydoc *doc)
{
    if (!c->e->nsets)
        return true;
    graft g = {.doc = doc};
    size_t nerr = c->nerr;
    g.root = own(&g, &doc->root);
    for (size_t k = 0; g.root && k < c->e->nsets && !g.oom; k++) {
        const ynode *v = load_value(c, doc, k, &g.oom);
        if (!v)
            continue;
        const char *arg = c->e->sets[k];
        char key[KEY_MAX + 1];
        snprintf(key, sizeof key, "%.*s", (int)strcspn(arg, "="), arg);
        g.line = -(int)(k + 1);
        bool blocks = sweep_is_blocks(&g);
        if (strncmp(key, "sweep.", 6) == 0 && blocks) {
            overrides_diag(c->d, c->e, c->file, g.line, 0, "sweep", "expected "
                           "--set 'sweep=[...]' (the whole list of blocks) on a sweep of "
                           "blocks, found --set %s", key);
            c->nerr++;
        } else if (strncmp(key, "sweep.", 6) == 0) {
            const char *path = canonical(key + 6);
            unset_path(&g, path);
            ynode *sw = sweep_of(&g, true);
            if (sw && !unsweep(sw, path, false, v))
                add_pair(&g, sw, key + 6, strlen(key + 6), g.line, v);
        } else if (strcmp(key, "sweep") == 0) {
            set_path(&g, key, v);   /* blocks: a key set in place is their base */
            for (size_t i = 0; v->kind == YNODE_MAPPING && i < v->n; i++)
                if (v->pairs[i].key->kind == YNODE_SCALAR)
                    unset_path(&g, canonical(v->pairs[i].key->text));
        } else if (blocks) {
            set_path(&g, key, v);
            unsweep_blocks(&g, key);
        } else {
            set_path(&g, key, v);
            ynode *sw = sweep_of(&g, false);
            if (sw)
                unsweep(sw, key, true, NULL);
        }
    }
    if (g.oom || !g.root)
        diag_add(c->d, c->file, 0, 0, "", "expected to load the manifest, found no memory left");
    return !g.oom && g.root && c->nerr == nerr;
}

void overrides_filter(vctx *c)
{
    experiment *e = c->e;
    if (!e->renderer_filter)
        return;
    size_t kept = 0;
    for (size_t i = 0; i < e->nrenderers; i++)
        if (names(e->renderer_filter, e->renderers[i]))
            memmove(e->renderers[kept++], e->renderers[i], sizeof e->renderers[i]);
    if (kept) {
        e->nrenderers = kept;
        return;
    }
    char where[1200], list[1024];
    sbuf b = {list, sizeof list, 0};
    list[0] = '\0';
    for (size_t i = 0; i < e->nrenderers; i++)
        mf_sb_add(&b, "%s%s", i ? ", " : "", e->renderers[i]);
    snprintf(where, sizeof where, "%s: --renderer %s", c->file, e->renderer_filter);
    diag_add(c->d, where, 0, 0, "renderers", "expected one or more of the manifest's "
             "renderers (%s), found none of them", list);
    c->nerr++;
}

void overrides_diag(diag_list *d, const experiment *e, const char *file, int line, int col,
                    const char *key, const char *fmt, ...)
{
    char msg[2048], where[1200];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    diag_add(d, where_of(e, file, &line, &col, where, sizeof where), line, col, key, "%s", msg);
}
