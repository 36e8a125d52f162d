#pragma once
/* A YAML document as a small tree of nodes, loaded with libyaml's event API.
 *
 *   ydoc_load()    one document from a buffer into nodes (scalar, sequence,
 *                  mapping), each with the 1-based line and column of its start
 *   ydoc_free()    frees the whole tree (NULL is fine)
 *   ynode_plain()  a plain, untagged scalar: the only kind whose text is read as
 *                  a number, boolean or null (a quoted "3" is a string)
 *   ynode_empty()  a plain, untagged, empty scalar: `key:` with nothing after it
 * Aliases, the bounds on them and on depth, and the errors: the comment above
 * YDOC_MAX_ALIAS_NODES below. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "runner/manifest/diag.h"

/* Aliases resolve to their anchored node, which is then shared (the tree is a
 * DAG; ydoc_free() frees each node once). Every node an alias makes reachable
 * counts against YDOC_MAX_ALIAS_NODES, so a billion-laughs document fails at the
 * alias that crosses the bound, in microseconds and with no more memory than
 * the file's own nodes; walking the tree afterwards visits at most the file's
 * nodes plus that bound. An alias to an anchor whose node is still open (a
 * recursive structure) is an error.
 *
 * Errors (diags with key ""): libyaml's problems (not UTF-8, control characters,
 * tabs as indentation, an unclosed bracket...) at libyaml's problem mark; an
 * empty file or a file of comments only; an empty document (`---` alone); a
 * second document; an undefined or recursive alias; the alias bound; nesting
 * deeper than YDOC_MAX_DEPTH. Loading stops at the first of them. */
#define YDOC_MAX_ALIAS_NODES 10000
#define YDOC_MAX_DEPTH 256

typedef enum ynode_kind { YNODE_SCALAR = 0, YNODE_SEQUENCE, YNODE_MAPPING } ynode_kind;

typedef enum yscalar_style {
    YSTYLE_PLAIN = 0,
    YSTYLE_SINGLE_QUOTED,
    YSTYLE_DOUBLE_QUOTED,
    YSTYLE_LITERAL,            /* | block */
    YSTYLE_FOLDED,             /* > block */
} yscalar_style;

typedef struct ynode ynode;

typedef struct ypair {
    const ynode *key, *value;
} ypair;

struct ynode {
    ynode_kind kind;
    int line, col;             /* 1-based start of the node (of its anchor node for an alias) */
    char *tag;                 /* as libyaml resolved it ("!", "tag:yaml.org,2002:str"); NULL: none */
    yscalar_style style;       /* scalars */
    char *text;                /* scalars: NUL-terminated; may hold NULs ("\0" in double quotes) */
    size_t len;                /* scalars: bytes of text before the terminating NUL */
    size_t n;                  /* sequences: items; mappings: pairs */
    const ynode **items;       /* sequences */
    ypair *pairs;              /* mappings, in document order (duplicates kept) */
    uint64_t expanded;         /* nodes of the subtree with aliases expanded, this one included */
};

typedef struct ydoc {
    const ynode *root;
    ynode **all;               /* every node, each once: what ydoc_free frees */
    size_t nall, capall;
    uint64_t alias_nodes;      /* nodes reached through aliases so far */
} ydoc;

/* Loads the single document in buf[0..len). On success *out holds it; on failure
 * *out is NULL and the problem is in d (with `file` as the diag's file). */
bool ydoc_load(const char *file, const void *buf, size_t len, ydoc **out, diag_list *d);
void ydoc_free(ydoc *doc);

/* Building on a loaded tree (run --set, runner/manifest/overrides.c): a new node of doc at
 * (line, col), freed with it (NULL: no memory); and every node of `from` moved into
 * doc, which then frees them with its own (`from` itself is freed; false: no memory,
 * nothing moved). */
ynode *ydoc_node(ydoc *doc, ynode_kind kind, int line, int col);
bool ydoc_take(ydoc *doc, ydoc *from);

bool ynode_plain(const ynode *n);
bool ynode_empty(const ynode *n);
