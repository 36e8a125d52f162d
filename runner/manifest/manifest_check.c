/* Manifest rules that need the whole manifest: required keys, swept-and-set, the
 * lights placement against its count, the error block, and what would make every
 * run fail or mean nothing. */
#include "runner/manifest/manifest_parse.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/renderer.h"
#include "runner/manifest/hash.h"
#include "runner/manifest/sweep_axis.h"
#include "scenes/scene.h"

/* >>checks */

/* Required keys: missing ones are reported at the mapping they belong in, unless
 * swept (in every block); a key both set and swept would have its set value silently
 * unused (in a list of blocks the set value is the base of the blocks that do not
 * sweep it). */
static void check_required_and_swept(vctx *c)
{
    for (size_t i = 0; i < NPARAMS; i++) {
        const param *pd = &params_table[i];
        bool everywhere = c->blocks ? c->swept_in[i] >= sweep_nblocks(c->e) : c->swept[i] != NULL;
        if ((pd->flags & PF_REQUIRED) && !c->set_key[i] && !everywhere) {
            char e[512];
            mf_err(c, c->root, pd->path, "expected %s, found nothing", mf_expect(pd, e, sizeof e));
        }
        if (c->set_key[i] && c->swept[i] && !c->blocks) {
            char key[160];
            snprintf(key, sizeof key, "sweep.%s", pd->path);
            mf_err(c, c->swept[i], key,
                "expected %s either set or swept, found both (set at %d:%d)", pd->path,
                c->set_key[i]->line, c->set_key[i]->col);
        }
    }
}

static bool lights_swept(const vctx *c)
{
    for (size_t i = 0; i < NPARAMS; i++)
        if (c->swept[i] && path_parent_is(params_table[i].path, "lights"))
            return true;
    return false;
}

/* An error block names a reference renderer and at least one time, or neither. */
static void check_error(vctx *c)
{
    const run_params *b = &c->e->base;
    size_t ir = (size_t)(param_find("error.reference.renderer") - params_table);
    size_t ia = (size_t)(param_find("error.at") - params_table);
    bool named = b->error_renderer[0] || c->set_key[ir];   /* set, even if invalid */
    if (b->error_renderer[0] && b->nerror_at == 0)
        mf_err(c, c->set_key[ir], "error.at",
            "expected at least one time to compare at, found none");
    for (size_t i = 0; i < NPARAMS; i++) {
        if (named || !c->set_key[i] || i == ia ||
            strncmp(params_table[i].path, "error.", 6) != 0 || params_table[i].type == PT_GROUP)
            continue;
        char e[512];
        mf_err(c, c->set_key[i], "error.reference.renderer", "expected %s, found nothing",
            mf_expect(&params_table[ir], e, sizeof e));
        break;
    }
    if (c->set_key[ia] && b->nerror_at > 0 && !named) {
        char e[512];
        mf_err(c, c->set_key[ia], "error.reference.renderer", "expected %s, found nothing",
            mf_expect(&params_table[ir], e, sizeof e));
    }
}

#define NO_AXIS ((size_t)-1)

/* The axis of block b that sweeps the parameter at run_params offset off; NO_AXIS:
 * the block's runs take the base value. */
static size_t block_axis(const experiment *e, size_t b, size_t off)
{
    for (size_t a = sweep_block_first(e, b); a < sweep_block_end(e, b); a++)
        if (e->axes[a].off == off)
            return a;
    return NO_AXIS;
}

/* Does some run of block b meet lights.placement p (every run: all_of)? */
static bool block_placement(const experiment *e, size_t b, light_placement p, bool all_of)
{
    size_t a = block_axis(e, b, offsetof(run_params, lights.placement));
    if (a == NO_AXIS)
        return e->base.lights.placement == p;
    bool any = false, all = true;
    for (size_t j = 0; j < e->axes[a].nvalues; j++) {
        bool is = e->axes[a].values[j].lights.placement == p;
        any = any || is;
        all = all && is;
    }
    return all_of ? all : any;
}

/* The counts of lights of block b: `bad` says which are wrong (msg, or "expected 0
 * lights" with the count), each reported at its value; the base's once, at its key. */
static void check_block_counts(vctx *c, size_t b, bool (*bad)(uint32_t max), const char *msg,
                               bool *base_done)
{
    experiment *e = c->e;
    size_t ic = (size_t)(param_find("lights.count") - params_table);
    size_t a = block_axis(e, b, offsetof(run_params, lights.count));
    if (a != NO_AXIS) {
        const struct sweep_axis *ax = &e->axes[a];
        for (size_t j = 0; j < ax->nvalues; j++) {
            const light_count *lc = &ax->values[j].lights.count;
            if (!bad(lc->max))
                continue;
            char key[200];
            mf_axis_key(e, a, key, sizeof key);
            snprintf(key + strlen(key), sizeof key - strlen(key), "[%zu]", j);
            if (msg)
                overrides_diag(c->d, c->e, c->file, ax->line[j], ax->col[j], key, "%s", msg);
            else
                overrides_diag(c->d, c->e, c->file, ax->line[j], ax->col[j], key,
                               "expected 0 lights with lights.placement none, found %s%" PRIu32
                               " lights", lc->growth ? "up to " : "", lc->max);
            c->nerr++;
        }
    } else if (c->set_val[ic] && !*base_done && bad(e->base.lights.count.max)) {
        *base_done = true;
        if (msg)
            mf_err(c, c->set_val[ic], "lights.count", "%s", msg);
        else
            mf_err(c, c->set_val[ic], "lights.count",
                "expected 0 lights with lights.placement none, found %s%" PRIu32 " lights",
                e->base.lights.count.growth ? "up to " : "", e->base.lights.count.max);
    }
}

static bool count_is_all(uint32_t max)
{
    return max == LIGHT_COUNT_ALL;
}

static bool count_not_zero(uint32_t max)
{
    return max != 0;
}

/* Count `all` means the scene's authored lights: every placement it can meet (in its
 * block) must be scene; and placement scene without a count (set or swept) means all
 * of them. */
static void check_count_all(vctx *c)
{
    experiment *e = c->e;
    size_t ic = (size_t)(param_find("lights.count") - params_table);
    bool base_all = !c->set_val[ic], base_used = false, base_done = false;
    for (size_t b = 0; b < sweep_nblocks(e); b++)
        if (block_axis(e, b, offsetof(run_params, lights.count)) == NO_AXIS) {
            base_used = true;
            base_all = base_all && block_placement(e, b, PLACEMENT_SCENE, true);
        }
    if (base_all && base_used)
        e->base.lights.count = (light_count){.start = LIGHT_COUNT_ALL, .max = LIGHT_COUNT_ALL};
    static const char msg[] = "expected a number of lights (all is for lights.placement scene "
                              "only), found all";
    for (size_t b = 0; b < sweep_nblocks(e); b++)
        if (!block_placement(e, b, PLACEMENT_SCENE, true))
            check_block_counts(c, b, count_is_all, msg, &base_done);
}

/* Placement none means no lights: every count it can meet (in its block) must be 0. */
static void check_lights(vctx *c)
{
    size_t nerr = c->nerr;
    check_count_all(c);
    if (c->nerr > nerr)
        return;   /* a count of all is wrong already */
    bool base_done = false;
    for (size_t b = 0; b < sweep_nblocks(c->e); b++)
        if (block_placement(c->e, b, PLACEMENT_NONE, false))
            check_block_counts(c, b, count_not_zero, NULL, &base_done);
}

/* trials: auto decides by rounds: a sequential schedule has none. */
static void check_schedule(vctx *c)
{
    size_t it = (size_t)(param_find("trials") - params_table);
    size_t is = (size_t)(param_find("schedule") - params_table);
    bool auto_trials = c->e->base.trials == 0;
    for (size_t a = 0; !auto_trials && a < c->e->naxes; a++)
        for (size_t v = 0; v < c->e->axes[a].nvalues; v++)
            auto_trials |= c->e->axes[a].off == offsetof(run_params, trials) &&
                           c->e->axes[a].values[v].trials == 0;
    if (auto_trials && c->e->base.schedule == RUN_SCHEDULE_SEQUENTIAL)
        mf_err(c, c->set_key[is] ? c->set_key[is] : c->set_key[it] ? c->set_key[it] : c->root,
            "schedule", "expected interleaved with trials: auto (it adds rounds of trials "
            "until the ranking is decided), found sequential");
}

void manifest_check(vctx *c)
{
    check_required_and_swept(c);
    if (!c->set_key[(size_t)(param_find("lights") - params_table)] && !lights_swept(c))
        c->e->base.lights.placement = PLACEMENT_NONE;
    check_lights(c);
    check_error(c);
    check_schedule(c);
}
