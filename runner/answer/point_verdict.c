/* Who wins at a sweep point, in one line (runner/answer/point_verdict.h). */
#include "runner/answer/point_verdict.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* "1.23x (1.10-1.35)"; "1.23x (no interval: fewer than 3 trials)"; of the means where
 * no trial pairs (means: x's over the fastest's) */
static void ratio_text(const ratio_ci *r, double means, char *out, size_t len)
{
    if (isfinite(r->lo))
        snprintf(out, len, "%.2fx (%.2f-%.2f)", r->ratio, r->lo, r->hi);
    else if (isfinite(r->ratio))
        snprintf(out, len, "%.2fx (no interval: fewer than 3 trials)", r->ratio);
    else
        snprintf(out, len, "%.2fx (of the means: no paired trials)", means);
}

bool point_verdict(const run_result *runs, const summary_point *p, char *const *cfg,
                   char *out, size_t len)
{
    out[0] = '\0';
    size_t n = 0;   /* the ranked runs with a value come first */
    while (n < p->nruns && isfinite(runs[p->runs[n]].mean))
        n++;
    /* one configuration at several points (one renderer): no contest */
    if (n < 2 || strcmp(cfg[p->runs[0]], cfg[p->runs[1]]) == 0)
        return false;
    const run_result *fastest = &runs[p->runs[0]];
    /* the runs that tie with the fastest: the paired ratio's interval holds 1 */
    size_t ties = 1;
    ratio_ci r = {0};
    for (; ties < n; ties++) {
        summary_paired_ratio(&runs[p->runs[ties]], fastest, &r);
        if (!isfinite(r.lo) || r.lo > 1 || r.hi < 1)
            break;
    }
    size_t at = 0;
    if (ties == 1) {
        at += (size_t)snprintf(out, len, "fastest %s", cfg[p->runs[0]]);
    } else {
        for (size_t k = 0; k < ties && at < len; k++)
            at += (size_t)snprintf(out + at, len - at, "%s%s", k == 0 ? "" : k + 1 < ties
                                   ? ", " : " and ", cfg[p->runs[k]]);
        ratio_ci t;
        summary_paired_ratio(&runs[p->runs[1]], fastest, &t);
        if (at < len && ties == 2)
            at += (size_t)snprintf(out + at, len - at, " tie (%.2fx, interval %.2f-%.2f "
                                   "holds 1)", t.ratio, t.lo, t.hi);
        else if (at < len)
            at += (size_t)snprintf(out + at, len - at, " tie (each one's ratio to %s: an "
                                   "interval that holds 1)", cfg[p->runs[0]]);
    }
    if (ties < n && at < len) {
        char rt[96];
        ratio_text(&r, runs[p->runs[ties]].mean / fastest->mean, rt, sizeof rt);
        snprintf(out + at, len - at, ", then %s at %s", cfg[p->runs[ties]], rt);
    }
    return true;
}

#define TERM_MAX_VERDICTS 24

void point_verdicts_print(FILE *t, const run_result *runs, const summary_point *pts, size_t n,
                          char *const *cfg)
{
    size_t shown = 0, more = 0;
    for (size_t k = 0; k < n; k++) {
        char v[1024];
        if (!point_verdict(runs, &pts[k], cfg, v, sizeof v))
            continue;
        if (shown < TERM_MAX_VERDICTS) {
            fprintf(t, "verdict: %s: %s\n", pts[k].label, v);
            shown++;
        } else {
            more++;
        }
    }
    if (more)
        fprintf(t, "... %zu more verdicts in summary.md\n", more);
}
