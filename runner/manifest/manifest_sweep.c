/* `sweep:` (params.def): a mapping, one cartesian product, or a sequence of blocks,
 * each a mapping of the same kind whose product the plan takes in turn
 * (runner/plan/sweep.c). Every block's axes go into experiment.axes in order;
 * experiment.block_first marks where each block starts. */
#include "runner/manifest/manifest_parse.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "runner/manifest/sweep_axis.h"

static void list_sweepable(sbuf *b)
{
    bool first = true;
    for (size_t i = 0; i < NPARAMS; i++)
        if (params_table[i].flags & PF_SWEEP) {
            mf_sb_add(b, "%s%s", first ? "" : ", ", params_table[i].path);
            first = false;
        }
}

/* The axes of one block (the mapping `map`, its keys named `prefix`.KEY) appended
 * to e->axes, which has room for them; seen[]: where each parameter is swept in this
 * block already. */
static void parse_block(vctx *c, const ynode *map, const char *prefix, const ynode **seen)
{
    experiment *e = c->e;
    for (size_t p = 0; p < map->n; p++) {
        const ynode *k = map->pairs[p].key, *v = map->pairs[p].value;
        char f[128], key[256];
        if (k->kind != YNODE_SCALAR) {
            mf_err(c, k, prefix, "expected a parameter, found %s", mf_found(k, true, f, sizeof f));
            continue;
        }
        sbuf kb = {key, sizeof key, 0};
        mf_sb_add(&kb, "%s.", prefix);
        mf_escape_text(&kb, k->text, k->len);
        const param *sp = param_find(k->text);
        if (sp && sp->type == PT_GROUP && sp->shorthand)
            sp = param_find(sp->shorthand);   /* `gbuffer: [fat, curtis]` as in place */
        if (!sp || !(sp->flags & PF_SWEEP)) {
            char list[2048];   /* every sweepable key: 1,100 bytes with zbin.* */
            sbuf lb = {list, sizeof list, 0};
            list_sweepable(&lb);
            mf_err(c, k, key, "expected a sweepable parameter (one of %s), found %s", list,
                mf_found(k, true, f, sizeof f));
            continue;
        }
        size_t idx = (size_t)(sp - params_table);
        if (seen[idx]) {
            mf_err(c, k, key, "expected a key used once, found a second '%s' (first at %d:%d)",
                sp->path, seen[idx]->line, seen[idx]->col);
            continue;
        }
        seen[idx] = k;
        if (!c->swept[idx])
            c->swept[idx] = k;
        c->swept_in[idx]++;
        if (v->kind != YNODE_SEQUENCE || v->n == 0) {
            mf_err(c, v, key, "expected a non-empty sequence of values, found %s",
                mf_found(v, false, f, sizeof f));
            continue;
        }
        if (v->n > MAX_AXIS_VALUES) {
            mf_err(c, v, key, "expected at most %d values, found %zu", MAX_AXIS_VALUES, v->n);
            continue;
        }
        struct sweep_axis *ax = &e->axes[e->naxes];
        ax->path = sp->path;
        ax->off = sp->off;
        ax->size = sp->size;
        ax->values = calloc(v->n, sizeof *ax->values);
        ax->line = calloc(v->n, sizeof *ax->line);
        ax->col = calloc(v->n, sizeof *ax->col);
        if (!ax->values || !ax->line || !ax->col) {
            free(ax->values);
            free(ax->line);
            free(ax->col);
            *ax = (struct sweep_axis){0};
            mf_err(c, v, key, "expected a sweep that fits in memory, found no memory left");
            continue;
        }
        ax->nvalues = v->n;
        e->naxes++;
        if (!c->axis_of[idx])
            c->axis_of[idx] = e->naxes;
        for (size_t j = 0; j < v->n; j++) {
            char sub[300];
            snprintf(sub, sizeof sub, "%s[%zu]", key, j);
            ax->line[j] = v->items[j]->line;
            ax->col[j] = v->items[j]->col;
            mf_parse_value(c, sp, v->items[j], sub, &ax->values[j]);
        }
    }
}

/* A sequence of blocks: each a non-empty mapping (or one that a --set emptied,
 * overrides.c: no axis, the base point once). */
static void parse_blocks(vctx *c, const param *pd, const ynode *seq)
{
    experiment *e = c->e;
    char f[128];
    c->blocks = true;
    if (seq->n == 0) {
        mf_err(c, seq, pd->path, "expected a non-empty sequence of blocks (mappings from "
            "parameters to sequences of values), found an empty sequence");
        return;
    }
    size_t naxes = 0;
    for (size_t i = 0; i < seq->n; i++)
        naxes += seq->items[i]->kind == YNODE_MAPPING ? seq->items[i]->n : 0;
    const ynode **seen = calloc(NPARAMS, sizeof *seen);
    e->axes = calloc(naxes ? naxes : 1, sizeof *e->axes);
    e->block_first = calloc(seq->n + 1, sizeof *e->block_first);
    if (!seen || !e->axes || !e->block_first) {
        free(seen);
        mf_err(c, seq, pd->path, "expected a sweep that fits in memory, found no memory left");
        return;
    }
    for (size_t i = 0; i < seq->n; i++) {
        const ynode *b = seq->items[i];
        char key[64];
        snprintf(key, sizeof key, "%s[%zu]", pd->path, i);
        if (b->kind != YNODE_MAPPING) {
            mf_err(c, b, key, "expected a block (a mapping from parameters to sequences of "
                "values), found %s", mf_found(b, false, f, sizeof f));
            continue;
        }
        if (b->n == 0 && b->col >= 0) {   /* col -1: a --set emptied it, the base point */
            mf_err(c, b, key, "expected a block with at least one parameter, found an empty "
                "mapping");
            continue;
        }
        memset(seen, 0, NPARAMS * sizeof *seen);
        e->block_first[e->nblocks] = e->naxes;
        parse_block(c, b, key, seen);
        e->nblocks++;
    }
    e->block_first[e->nblocks] = e->naxes;
    free(seen);
}

bool mf_parse_sweep(vctx *c, const param *pd, const ynode *n)
{
    if (n->kind == YNODE_SEQUENCE) {
        parse_blocks(c, pd, n);
        return true;
    }
    if (n->kind != YNODE_MAPPING)
        return mf_bad(c, pd, n, pd->path);
    c->e->axes = calloc(n->n ? n->n : 1, sizeof *c->e->axes);
    if (!c->e->axes) {
        mf_err(c, n, pd->path, "expected a sweep that fits in memory, found no memory left");
        return true;
    }
    parse_block(c, n, pd->path, c->swept);
    return true;
}

void mf_axis_key(const experiment *e, size_t a, char *buf, size_t len)
{
    size_t b = 0;
    while (b + 1 < sweep_nblocks(e) && a >= sweep_block_end(e, b))
        b++;
    if (e->nblocks)
        snprintf(buf, len, "sweep[%zu].%s", b, e->axes[a].path);
    else
        snprintf(buf, len, "sweep.%s", e->axes[a].path);
}
