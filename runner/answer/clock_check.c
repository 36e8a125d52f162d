/* compare's clock check (runner/answer/clock_check.h). */
#include "runner/answer/clock_check.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* the median of the finite x[0..n) (NAN: none) */
static double median_finite(const double *x, size_t n)
{
    double *scratch = malloc((n ? n : 1) * sizeof *scratch), med = NAN;
    if (scratch)
        verdict_median(x, n, scratch, &med);
    free(scratch);
    return med;
}

static bool differ(double a, double b)
{
    return isfinite(a) && isfinite(b) && a > 0 && fabs(b / a - 1) > CLOCK_TOLERANCE;
}

void clock_check_pair(const run_result *a, const run_result *b, bool paired,
                      clock_check *out)
{
    memset(out, 0, sizeof *out);
    out->base_mhz = median_finite(a->sm_mhz, a->nvalues);
    out->new_mhz = median_finite(b->sm_mhz, b->nvalues);
    out->any = isfinite(out->base_mhz) || isfinite(out->new_mhz);
    out->gpu = out->gpu_norm = (ratio_ci){.ratio = NAN, .lo = NAN, .hi = NAN};
    size_t n = a->nvalues > b->nvalues ? a->nvalues : b->nvalues;
    double *ga = calloc(n ? n : 1, sizeof *ga), *gb = calloc(n ? n : 1, sizeof *gb);
    double *na = calloc(n ? n : 1, sizeof *na), *nb = calloc(n ? n : 1, sizeof *nb);
    if (!ga || !gb || !na || !nb)
        goto done;
    /* a side's trial k, NAN past its trials: GPU time raw and at BASE's median clock */
    bool norm = isfinite(out->base_mhz);
    for (size_t k = 0; k < n; k++) {
        ga[k] = k < a->nvalues ? a->gpu[k] : NAN;
        gb[k] = k < b->nvalues ? b->gpu[k] : NAN;
        double ca = k < a->nvalues ? a->sm_mhz[k] : NAN;
        double cb = k < b->nvalues ? b->sm_mhz[k] : NAN;
        na[k] = ga[k] * ca / out->base_mhz;
        nb[k] = gb[k] * cb / out->base_mhz;
        norm &= !(isfinite(ga[k]) && !isfinite(ca)) && !(isfinite(gb[k]) && !isfinite(cb));
        if (paired && differ(ca, cb) && out->nflagged++ < CLOCK_MAX_FLAGGED)
            out->flagged[out->nflagged - 1] = (unsigned)k + 1;
    }
    if (!paired && differ(out->base_mhz, out->new_mhz))
        out->nflagged = 1;
    if (paired) {
        verdict_paired_ratio(gb, ga, n, &out->gpu);
        if (norm)
            verdict_paired_ratio(nb, na, n, &out->gpu_norm);
    } else {
        verdict_unpaired_ratio(gb, b->nvalues, ga, a->nvalues, &out->gpu);
        if (norm)
            verdict_unpaired_ratio(nb, b->nvalues, na, a->nvalues, &out->gpu_norm);
    }
done:
    free(ga);
    free(gb);
    free(na);
    free(nb);
}
