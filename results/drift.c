/* The common change between two folders and the corrected ratios: results/drift.h. */
#include "results/drift.h"

#include <math.h>
#include <stdlib.h>

#include "results/stats.h"

bool drift_common_change(const ratio_ci *r, size_t n, common_change *out)
{
    *out = (common_change){.ratio = NAN, .lo = NAN, .hi = NAN};
    double *buf = malloc(3 * (n ? n : 1) * sizeof *buf);
    if (!buf)
        return false;
    double *l = buf, *h = buf + n, *scratch = buf + 2 * n;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (!(isfinite(r[i].ratio) && r[i].ratio > 0 && isfinite(r[i].lo) &&
              isfinite(r[i].hi) && r[i].lo > 0 && r[i].hi >= r[i].lo))
            continue;
        l[k] = log(r[i].ratio);
        h[k] = log(r[i].hi / r[i].lo) / 2;
        k++;
    }
    out->n = k;
    if (k < DRIFT_MIN_RUNS) {
        free(buf);
        return false;
    }
    double m, mad, hmed;
    verdict_median(l, k, scratch, &m);
    verdict_median(h, k, scratch, &hmed);
    for (size_t i = 0; i < k; i++)
        h[i] = fabs(l[i] - m);   /* h's median is taken: reuse it for the deviations */
    verdict_median(h, k, scratch, &mad);
    /* the median of k values has sqrt(pi / 2) times the standard error of their mean */
    const double eff = 1.2533141373155;
    double half = fmax(stats_t975(k - 1) * eff * 1.4826 * mad, eff * hmed) / sqrt((double)k);
    out->ratio = exp(m);
    out->lo = exp(m - half);
    out->hi = exp(m + half);
    out->applied = out->lo > 1 || out->hi < 1;
    free(buf);
    return true;
}

void drift_correct(const ratio_ci *raw, const common_change *c, ratio_ci *out)
{
    *out = *raw;
    if (!c->applied)
        return;
    double lc = log(c->ratio), hc = log(c->hi / c->lo) / 2;
    out->ratio = raw->ratio / c->ratio;
    if (!(isfinite(raw->lo) && isfinite(raw->hi) && raw->lo > 0))
        return;
    double lr = log(raw->ratio) - lc;
    double hr = log(raw->hi / raw->lo) / 2;
    double half = sqrt(hr * hr + hc * hc);
    out->lo = exp(lr - half);
    out->hi = exp(lr + half);
}
