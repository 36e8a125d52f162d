#pragma once
/* Internal to the manifest's parser (manifest_text.c, manifest_values.c,
 * manifest_check.c, manifest_load.c, manifest_variant.c, overrides.c, params_*.c): the
 * validation context and the helpers the files share; above params.h and manifest.h. The calls go one way: params.c
 * (the table) <- manifest_text.c <- overrides.c <- manifest_values.c (the parser) <-
 * params_defaults.c <- params_print.c, manifest_check.c and the rest. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "runner/manifest/diag.h"
#include "runner/manifest/manifest.h"
#include "runner/manifest/params.h"
#include "runner/manifest/yamldoc.h"

#define MANIFEST_MAX_BYTES (1u << 20)

/* manifest_text.c: scalar text for a one-line message (escaped, cut at 60 bytes) */
void mf_escape_text(sbuf *b, const char *s, size_t len);
bool mf_tag_ok(const ynode *n);
/* what a node is, for "found ..." */
const char *mf_found(const ynode *n, bool want_string, char *buf, size_t len);
void mf_list_enum(sbuf *b, const char *const *names);
void mf_list_scenes(sbuf *b);
void mf_list_renderers(sbuf *b);
void mf_range_number(sbuf *b, double min, double max, bool min_open);
/* what a parameter expects, as the "expected ..." of its messages */
const char *mf_expect(const param *pd, char *buf, size_t len);
bool mf_wants_string(const param *pd);

/* The validation of one manifest. */
typedef struct vctx {
    const char *file;
    diag_list *d;
    size_t nerr;
    experiment *e;
    const ynode *root;
    const ynode *set_key[PARAMS_N];    /* where each parameter is set in place */
    const ynode *set_val[PARAMS_N];
    const ynode *swept[PARAMS_N];      /* its key in `sweep` (a list of blocks: the first) */
    size_t axis_of[PARAMS_N];          /* its axis index + 1, 0 if not swept (the first) */
    size_t swept_in[PARAMS_N];         /* how many blocks sweep it (a mapping: 1 block) */
    bool blocks;                       /* `sweep:` is a list of blocks */
} vctx;

/* manifest_values.c */
bool mf_stringish(const ynode *n);
bool mf_get_uint(const ynode *n, uint64_t *out);
bool mf_get_number(const ynode *n, double *out, bool *finite);
void mf_err(vctx *c, const ynode *at, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
bool mf_bad(vctx *c, const param *pd, const ynode *n, const char *key);
bool mf_parse_uint_in(vctx *c, const ynode *n, const char *key, uint64_t min, uint64_t max,
                   const char *note, uint64_t *out);
bool mf_parse_number_in(vctx *c, const ynode *n, const char *key, double min, double max,
                     unsigned flags, double *out);
bool mf_map_keys(vctx *c, const ynode *map, const char *prefix, const char *const *names,
              size_t nnames, const ynode **keys, const ynode **vals);
/* Validates n as parameter pd; a run parameter's value goes into dst (at pd->off),
 * the experiment's own (name, renderers...) into c->e. */
bool mf_parse_value(vctx *c, const param *pd, const ynode *n, const char *key, run_params *dst);
/* The table's defaults into dst, each through mf_parse_value (params_defaults.c); false
 * (with a "bug:" diagnostic) when one does not validate. */
bool params_apply_defaults(vctx *c, run_params *dst);
/* Schema 2's defaults over schema 1's (params_defaults.c params_schema2): applied to dst before a
 * `shadesweep: 2` manifest's own keys, as if the manifest began with them. A run id
 * leaves out a key only at its schema-1 default, so a schema-2 run's id names each of
 * these: it is the id of the same run written in schema 1 with the keys spelt out. */
bool params_apply_schema_defaults(vctx *c, unsigned schema, run_params *dst);
/* The schema a manifest's root mapping asks for: its `shadesweep` key's plain scalar 2
 * gives 2, anything else 1 (whose errors the key's own parse reports). */
unsigned params_schema_of(const struct ynode *root);
/* A mapping whose keys are the table's parameters under `prefix` ("" at the top). */
void mf_parse_group(vctx *c, const char *prefix, const ynode *map, run_params *dst);

/* manifest_sweep.c: `sweep:` (params.def), a mapping (one block) or a sequence of
 * blocks, into c->e's axes and blocks; false (after mf_bad) when it is neither. */
bool mf_parse_sweep(vctx *c, const param *pd, const ynode *n);
/* "sweep.PATH" (a mapping) or "sweep[B].PATH" (block B, from 0): axis a's key in
 * messages. */
void mf_axis_key(const experiment *e, size_t a, char *buf, size_t len);

/* manifest_check.c: every rule that needs the whole manifest, after parse_group */
void manifest_check(vctx *c);

/* overrides.c: --set and --renderer (manifest.h) */
/* Copies ov into c->e (sets, renderer_filter) and adds them to its hash; false (a
 * diag) when out of memory. */
bool overrides_keep(vctx *c, const manifest_overrides *ov);
/* Grafts c->e's --set values onto doc (a mapping at its root), each key replaced
 * wherever it is; false with the diags of a value that is not one YAML document. */
bool overrides_apply(vctx *c, ydoc *doc);
/* --renderer: keeps those of c->e->renderers that it names; a diag when none is left. */
void overrides_filter(vctx *c);
/* diag_add about a node at (line, col) of e's manifest `file`, or of e's k-th --set
 * (line -k): that one is "FILE: --set KEY=VALUE", with no line or column. */
void overrides_diag(diag_list *d, const experiment *e, const char *file, int line, int col,
                    const char *key, const char *fmt, ...) __attribute__((format(printf, 7, 8)));
