/* A YAML document as a node tree, from libyaml events (yamldoc.h).
 *
 * >>nodes    allocation; every node is owned by ydoc.all
 * >>anchors  name -> completed node, an open-addressing hash table
 * >>errors   libyaml's problems as diags
 * >>load     the event loop */
#include "runner/manifest/yamldoc.h"

#include <stdlib.h>
#include <string.h>
#include <yaml.h>

#include "common/grow.h"
#include "runner/manifest/hash.h"

/* >>nodes */

static ynode *node_new(ydoc *doc, ynode_kind kind, yaml_mark_t mark, const yaml_char_t *tag)
{
    if (!GROW(doc->all, doc->capall, doc->nall + 1, 64))
        return NULL;
    ynode *n = calloc(1, sizeof *n);
    if (!n)
        return NULL;
    if (tag) {
        n->tag = strdup((const char *)tag);
        if (!n->tag) {
            free(n);
            return NULL;
        }
    }
    n->kind = kind;
    n->line = (int)mark.line + 1;
    n->col = (int)mark.column + 1;
    n->expanded = 1;
    doc->all[doc->nall++] = n;
    return n;
}

static void node_free(ynode *n)
{
    free(n->tag);
    free(n->text);
    free(n->items);
    free(n->pairs);
    free(n);
}

void ydoc_free(ydoc *doc)
{
    if (!doc)
        return;
    for (size_t i = 0; i < doc->nall; i++)
        node_free(doc->all[i]);
    free(doc->all);
    free(doc);
}

ynode *ydoc_node(ydoc *doc, ynode_kind kind, int line, int col)
{
    ynode *n = node_new(doc, kind, (yaml_mark_t){0}, NULL);
    if (n) {
        n->line = line;
        n->col = col;
    }
    return n;
}

bool ydoc_take(ydoc *doc, ydoc *from)
{
    if (doc->capall - doc->nall < from->nall) {
        size_t cap = doc->nall + from->nall;
        ynode **all = realloc(doc->all, cap * sizeof *all);
        if (!all)
            return false;
        doc->all = all;
        doc->capall = cap;
    }
    memcpy(doc->all + doc->nall, from->all, from->nall * sizeof *from->all);
    doc->nall += from->nall;
    free(from->all);
    free(from);
    return true;
}

bool ynode_plain(const ynode *n)
{
    return n && n->kind == YNODE_SCALAR && n->style == YSTYLE_PLAIN && !n->tag;
}

bool ynode_empty(const ynode *n)
{
    return ynode_plain(n) && n->len == 0;
}

/* Saturating: a subtree's expanded size only matters up to the alias bound. */
static uint64_t add_sat(uint64_t a, uint64_t b)
{
    return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

/* >>anchors */

typedef struct anchor {
    char *name;
    const ynode *node;
} anchor;

typedef struct anchor_table {
    anchor *slot;              /* name NULL: empty */
    size_t cap, n;             /* cap a power of two, n <= cap / 2 */
} anchor_table;

static size_t anchor_probe(const anchor_table *t, const char *name)
{
    size_t i = (size_t)fnv1a64(name, strlen(name)) & (t->cap - 1);
    while (t->slot[i].name && strcmp(t->slot[i].name, name) != 0)
        i = (i + 1) & (t->cap - 1);
    return i;
}

static const ynode *anchor_find(const anchor_table *t, const char *name)
{
    if (t->cap == 0)
        return NULL;
    const anchor *a = &t->slot[anchor_probe(t, name)];
    return a->name ? a->node : NULL;
}

static bool anchor_grow(anchor_table *t)
{
    anchor_table g = {.cap = t->cap ? t->cap * 2 : 16};
    g.slot = calloc(g.cap, sizeof *g.slot);
    if (!g.slot)
        return false;
    for (size_t i = 0; i < t->cap; i++)
        if (t->slot[i].name)
            g.slot[anchor_probe(&g, t->slot[i].name)] = t->slot[i];
    g.n = t->n;
    free(t->slot);
    *t = g;
    return true;
}

/* A later anchor of the same name replaces the earlier one, as YAML says. Takes
 * ownership of name. */
static bool anchor_set(anchor_table *t, char *name, const ynode *node)
{
    if ((t->n + 1) * 2 > t->cap && !anchor_grow(t)) {
        free(name);
        return false;
    }
    anchor *a = &t->slot[anchor_probe(t, name)];
    if (a->name) {
        free(name);
    } else {
        a->name = name;
        t->n++;
    }
    a->node = node;
    return true;
}

static void anchor_table_free(anchor_table *t)
{
    for (size_t i = 0; i < t->cap; i++)
        free(t->slot[i].name);
    free(t->slot);
}

/* >>errors */

/* Line and column (1-based, in characters) of a byte offset: libyaml's reader
 * reports its problems by offset only. */
static void offset_mark(const unsigned char *buf, size_t len, size_t off, int *line, int *col)
{
    int l = 1, c = 1;
    if (off > len)
        off = len;
    for (size_t i = 0; i < off; i++) {
        if (buf[i] == '\n') {
            l++;
            c = 1;
        } else if ((buf[i] & 0xc0) != 0x80) {
            c++;
        }
    }
    *line = l;
    *col = c;
}

static void parser_error(const yaml_parser_t *p, const char *file, const void *buf, size_t len,
                         diag_list *d)
{
    const char *problem = p->problem ? p->problem : "an unknown problem";
    switch (p->error) {
    case YAML_MEMORY_ERROR:
        diag_add(d, file, 0, 0, "", "expected to load the manifest, found no memory left");
        break;
    case YAML_READER_ERROR: {
        int line, col;
        offset_mark(buf, len, p->problem_offset, &line, &col);
        if (p->problem_value >= 0)
            diag_add(d, file, line, col, "", "expected UTF-8 text, found %s (#x%02X)", problem,
                     (unsigned)p->problem_value);
        else
            diag_add(d, file, line, col, "", "expected UTF-8 text, found %s", problem);
        break;
    }
    default:
        if (p->context)
            diag_add(d, file, (int)p->problem_mark.line + 1, (int)p->problem_mark.column + 1, "",
                     "expected valid YAML, found a syntax error: %s (%s at %d:%d)", problem,
                     p->context, (int)p->context_mark.line + 1, (int)p->context_mark.column + 1);
        else
            diag_add(d, file, (int)p->problem_mark.line + 1, (int)p->problem_mark.column + 1, "",
                     "expected valid YAML, found a syntax error: %s", problem);
        break;
    }
}

/* >>load */

typedef struct frame {
    ynode *node;               /* an open sequence or mapping */
    size_t cap;                /* of node->items or node->pairs */
    bool want_value;           /* mapping: a key is in, its value is not */
    char *anchor;              /* registered when the node closes */
} frame;

typedef struct loader {
    const char *file;
    const void *buf;
    size_t len;
    diag_list *d;
    ydoc *doc;
    frame stack[YDOC_MAX_DEPTH];
    size_t depth;
    anchor_table anchors;
    size_t ndocs;
} loader;

static bool oom(loader *L)
{
    diag_add(L->d, L->file, 0, 0, "", "expected to load the manifest, found no memory left");
    return false;
}

/* Puts a finished node (new or aliased) into its parent, or makes it the root. */
static bool attach(loader *L, const ynode *n)
{
    if (L->depth == 0) {
        L->doc->root = n;
        return true;
    }
    frame *f = &L->stack[L->depth - 1];
    ynode *p = f->node;
    p->expanded = add_sat(p->expanded, n->expanded);
    if (p->kind == YNODE_SEQUENCE) {
        if (!GROW(p->items, f->cap, p->n + 1, 4))
            return oom(L);
        p->items[p->n++] = n;
        return true;
    }
    if (f->want_value) {
        p->pairs[p->n - 1].value = n;
        f->want_value = false;
        return true;
    }
    if (!GROW(p->pairs, f->cap, p->n + 1, 4))
        return oom(L);
    p->pairs[p->n++] = (ypair){.key = n, .value = NULL};
    f->want_value = true;
    return true;
}

static bool register_anchor(loader *L, const yaml_char_t *name, const ynode *n)
{
    if (!name)
        return true;
    char *copy = strdup((const char *)name);
    if (!copy || !anchor_set(&L->anchors, copy, n))
        return oom(L);
    return true;
}

static bool on_scalar(loader *L, const yaml_event_t *ev)
{
    ynode *n = node_new(L->doc, YNODE_SCALAR, ev->start_mark, ev->data.scalar.tag);
    if (!n)
        return oom(L);
    n->len = ev->data.scalar.length;
    n->text = malloc(n->len + 1);
    if (!n->text)
        return oom(L);
    memcpy(n->text, ev->data.scalar.value, n->len);
    n->text[n->len] = '\0';
    switch (ev->data.scalar.style) {
    case YAML_SINGLE_QUOTED_SCALAR_STYLE: n->style = YSTYLE_SINGLE_QUOTED; break;
    case YAML_DOUBLE_QUOTED_SCALAR_STYLE: n->style = YSTYLE_DOUBLE_QUOTED; break;
    case YAML_LITERAL_SCALAR_STYLE: n->style = YSTYLE_LITERAL; break;
    case YAML_FOLDED_SCALAR_STYLE: n->style = YSTYLE_FOLDED; break;
    default: n->style = YSTYLE_PLAIN; break;
    }
    return register_anchor(L, ev->data.scalar.anchor, n) && attach(L, n);
}

static bool on_open(loader *L, const yaml_event_t *ev, ynode_kind kind)
{
    if (L->depth == YDOC_MAX_DEPTH) {
        diag_add(L->d, L->file, (int)ev->start_mark.line + 1, (int)ev->start_mark.column + 1,
                 "", "expected nesting at most %d deep, found deeper", YDOC_MAX_DEPTH);
        return false;
    }
    const yaml_char_t *tag = kind == YNODE_MAPPING ? ev->data.mapping_start.tag
                                                   : ev->data.sequence_start.tag;
    const yaml_char_t *name = kind == YNODE_MAPPING ? ev->data.mapping_start.anchor
                                                    : ev->data.sequence_start.anchor;
    ynode *n = node_new(L->doc, kind, ev->start_mark, tag);
    if (!n)
        return oom(L);
    frame *f = &L->stack[L->depth];
    *f = (frame){.node = n};
    if (name) {
        f->anchor = strdup((const char *)name);
        if (!f->anchor)
            return oom(L);
    }
    L->depth++;
    return true;
}

static bool on_close(loader *L)
{
    frame *f = &L->stack[--L->depth];
    ynode *n = f->node;
    bool ok = true;
    if (f->anchor) {
        ok = anchor_set(&L->anchors, f->anchor, n) || oom(L);
        f->anchor = NULL;
    }
    return ok && attach(L, n);
}

static bool on_alias(loader *L, const yaml_event_t *ev)
{
    const char *name = (const char *)ev->data.alias.anchor;
    int line = (int)ev->start_mark.line + 1, col = (int)ev->start_mark.column + 1;
    for (size_t i = 0; i < L->depth; i++)
        if (L->stack[i].anchor && strcmp(L->stack[i].anchor, name) == 0) {
            diag_add(L->d, L->file, line, col, "",
                     "expected an alias to a complete node, found a recursive alias '*%s'", name);
            return false;
        }
    const ynode *n = anchor_find(&L->anchors, name);
    if (!n) {
        diag_add(L->d, L->file, line, col, "",
                 "expected an alias to an earlier anchor, found an undefined alias '*%s'", name);
        return false;
    }
    L->doc->alias_nodes = add_sat(L->doc->alias_nodes, n->expanded);
    if (L->doc->alias_nodes > YDOC_MAX_ALIAS_NODES) {
        diag_add(L->d, L->file, line, col, "",
                 "expected at most %d nodes reached through aliases, found more at alias '*%s'",
                 YDOC_MAX_ALIAS_NODES, name);
        return false;
    }
    return attach(L, n);
}

/* One event; false stops loading (the reason is in L->d). *done at stream end. */
static bool on_event(loader *L, const yaml_event_t *ev, bool *done)
{
    switch (ev->type) {
    case YAML_DOCUMENT_START_EVENT:
        if (++L->ndocs > 1) {
            diag_add(L->d, L->file, (int)ev->start_mark.line + 1,
                     (int)ev->start_mark.column + 1, "",
                     "expected one YAML document, found a second document");
            return false;
        }
        return true;
    case YAML_SCALAR_EVENT:
        return on_scalar(L, ev);
    case YAML_SEQUENCE_START_EVENT:
        return on_open(L, ev, YNODE_SEQUENCE);
    case YAML_MAPPING_START_EVENT:
        return on_open(L, ev, YNODE_MAPPING);
    case YAML_SEQUENCE_END_EVENT:
    case YAML_MAPPING_END_EVENT:
        return on_close(L);
    case YAML_ALIAS_EVENT:
        return on_alias(L, ev);
    case YAML_STREAM_END_EVENT:
        *done = true;
        return true;
    default:
        return true;
    }
}

bool ydoc_load(const char *file, const void *buf, size_t len, ydoc **out, diag_list *d)
{
    *out = NULL;
    loader L = {.file = file, .buf = buf, .len = len, .d = d};
    yaml_parser_t parser;
    bool parser_ok = false, ok = false;

    L.doc = calloc(1, sizeof *L.doc);
    if (!L.doc) {
        oom(&L);
        goto done;
    }
    if (!yaml_parser_initialize(&parser)) {
        oom(&L);
        goto done;
    }
    parser_ok = true;
    yaml_parser_set_input_string(&parser, buf, len);

    for (bool end = false; !end;) {
        yaml_event_t ev;
        if (!yaml_parser_parse(&parser, &ev)) {
            parser_error(&parser, file, buf, len, d);
            goto done;
        }
        bool go = on_event(&L, &ev, &end);
        yaml_event_delete(&ev);
        if (!go)
            goto done;
    }

    if (L.ndocs == 0) {
        diag_add(d, file, 1, 1, "", "expected a YAML document, found nothing");
        goto done;
    }
    if (ynode_empty(L.doc->root)) {
        diag_add(d, file, L.doc->root->line, L.doc->root->col, "",
                 "expected a YAML document, found an empty document");
        goto done;
    }
    ok = true;

done:
    for (size_t i = 0; i < L.depth; i++)
        free(L.stack[i].anchor);
    anchor_table_free(&L.anchors);
    if (parser_ok)
        yaml_parser_delete(&parser);
    if (ok)
        *out = L.doc;
    else
        ydoc_free(L.doc);
    return ok;
}
