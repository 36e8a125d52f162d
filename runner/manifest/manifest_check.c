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
 * swept; a key both set and swept would have its set value silently unused. */
static void check_required_and_swept(vctx *c)
{
    for (size_t i = 0; i < NPARAMS; i++) {
        const param *pd = &params_table[i];
        if ((pd->flags & PF_REQUIRED) && !c->set_key[i] && !c->swept[i]) {
            char e[512];
            mf_err(c, c->root, pd->path, "expected %s, found nothing", mf_expect(pd, e, sizeof e));
        }
        if (c->set_key[i] && c->swept[i]) {
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

/* Count `all` means the scene's authored lights: every placement it can meet must be
 * scene; and placement scene without a count (set or swept) means all of them. */
static void check_count_all(vctx *c)
{
    experiment *e = c->e;
    size_t ip = (size_t)(param_find("lights.placement") - params_table);
    size_t ic = (size_t)(param_find("lights.count") - params_table);
    bool all_scene = e->base.lights.placement == PLACEMENT_SCENE;
    if (c->axis_of[ip]) {
        const struct sweep_axis *ax = &e->axes[c->axis_of[ip] - 1];
        all_scene = true;
        for (size_t j = 0; j < ax->nvalues; j++)
            all_scene = all_scene && ax->values[j].lights.placement == PLACEMENT_SCENE;
    }
    if (all_scene && !c->set_val[ic] && !c->axis_of[ic]) {
        e->base.lights.count = (light_count){.start = LIGHT_COUNT_ALL, .max = LIGHT_COUNT_ALL};
        return;
    }
    if (all_scene)
        return;
    static const char msg[] = "expected a number of lights (all is for lights.placement scene "
                              "only), found all";
    if (c->axis_of[ic]) {
        const struct sweep_axis *ax = &e->axes[c->axis_of[ic] - 1];
        for (size_t j = 0; j < ax->nvalues; j++)
            if (ax->values[j].lights.count.max == LIGHT_COUNT_ALL) {
                char key[160];
                snprintf(key, sizeof key, "sweep.lights.count[%zu]", j);
                overrides_diag(c->d, c->e, c->file, ax->line[j], ax->col[j], key, "%s", msg);
                c->nerr++;
            }
    } else if (c->set_val[ic] && e->base.lights.count.max == LIGHT_COUNT_ALL) {
        mf_err(c, c->set_val[ic], "lights.count", "%s", msg);
    }
}

/* Placement none means no lights: every count it can meet must be 0. */
static void check_lights(vctx *c)
{
    const experiment *e = c->e;
    size_t ip = (size_t)(param_find("lights.placement") - params_table);
    size_t ic = (size_t)(param_find("lights.count") - params_table);

    size_t nerr = c->nerr;
    check_count_all(c);
    if (c->nerr > nerr)
        return;   /* a count of all is wrong already */

    bool none = e->base.lights.placement == PLACEMENT_NONE;
    if (c->axis_of[ip]) {
        const struct sweep_axis *ax = &e->axes[c->axis_of[ip] - 1];
        none = false;
        for (size_t j = 0; j < ax->nvalues; j++)
            none = none || ax->values[j].lights.placement == PLACEMENT_NONE;
    }
    if (!none)
        return;

    if (c->axis_of[ic]) {
        const struct sweep_axis *ax = &e->axes[c->axis_of[ic] - 1];
        for (size_t j = 0; j < ax->nvalues; j++) {
            uint32_t m = ax->values[j].lights.count.max;
            if (m != 0) {
                char key[160];
                snprintf(key, sizeof key, "sweep.lights.count[%zu]", j);
                overrides_diag(c->d, c->e, c->file, ax->line[j], ax->col[j], key,
                               "expected 0 lights with lights.placement none, found %s%" PRIu32
                               " lights", ax->values[j].lights.count.growth ? "up to " : "", m);
                c->nerr++;
            }
        }
    } else if (e->base.lights.count.max != 0 && c->set_val[ic]) {
        mf_err(c, c->set_val[ic], "lights.count",
            "expected 0 lights with lights.placement none, found %s%" PRIu32 " lights",
            e->base.lights.count.growth ? "up to " : "", e->base.lights.count.max);
    }
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
