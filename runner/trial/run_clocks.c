/* A trial's GPU clocks from NVML (common/nvml.h), for its meta.yaml's `clocks:` block:
 * a reading at the trial's start and end and, between measured frames with the measured
 * clock paused, one at most every CLOCKS_INTERVAL_S; their medians. Without NVML or an
 * NVIDIA device st->clocks stays NULL and nothing here writes anything. */
#include "runner/trial/run_internal.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "common/grow.h"
#include "common/nvml.h"
#include "runner/plan/progress.h"

#define CLOCKS_INTERVAL_S 0.1

struct run_clocks {
    nvml *n;
    nvml_sample start, end;
    nvml_sample *s;            /* every reading, start and end included */
    size_t ns, cap;
    double last;               /* progress_now() of the latest reading */
    uint64_t throttle_seen;    /* the bits of every reading */
    char notes[NVML_FIELDS][128];   /* each quantity's first failure, "" if none */
};

void run_clocks_open(run_state *st)
{
    char why[256];
    const gl_info *gi = st->ctx ? gl_context_info(st->ctx) : NULL;
    char pci[32];
    bool has_pci = gi && nvml_drm_pci(NULL, gi->device, pci, sizeof pci);
    nvml *n = nvml_open(gi ? gi->renderer : NULL, has_pci ? pci : NULL, why, sizeof why);
    if (!n)
        return;
    st->clocks = calloc(1, sizeof *st->clocks);
    if (!st->clocks) {
        nvml_close(n);
        return;
    }
    st->clocks->n = n;
}

static void take(run_clocks *c, nvml_sample *out)
{
    nvml_sample s;
    char notes[NVML_FIELDS][128];
    nvml_read(c->n, &s, notes);
    for (int i = 0; i < NVML_FIELDS; i++)
        if (notes[i][0] && !c->notes[i][0])
            memcpy(c->notes[i], notes[i], sizeof notes[i]);
    c->last = progress_now();
    c->throttle_seen |= s.throttle;
    if (GROW(c->s, c->cap, c->ns + 1, 64))
        c->s[c->ns++] = s;
    if (out)
        *out = s;
}

void run_clocks_start(run_state *st)
{
    if (st->clocks)
        take(st->clocks, &st->clocks->start);
}

bool run_clocks_due(const run_state *st)
{
    return st->clocks && progress_now() - st->clocks->last >= CLOCKS_INTERVAL_S;
}

void run_clocks_tick(run_state *st)
{
    if (st->clocks)
        take(st->clocks, NULL);
}

void run_clocks_end(run_state *st)
{
    if (st->clocks)
        take(st->clocks, &st->clocks->end);
}

void run_clocks_free(run_state *st)
{
    if (!st->clocks)
        return;
    nvml_close(st->clocks->n);
    free(st->clocks->s);
    free(st->clocks);
    st->clocks = NULL;
}

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* The median of field `off` over the readings that have it (NAN: none has). */
static double median_of(const run_clocks *c, size_t off, double *tmp)
{
    size_t k = 0;
    for (size_t i = 0; i < c->ns; i++) {
        double v = *(const double *)((const char *)&c->s[i] + off);
        if (!isnan(v))
            tmp[k++] = v;
    }
    if (!k)
        return NAN;
    qsort(tmp, k, sizeof *tmp, cmp_double);
    return k % 2 ? tmp[k / 2] : (tmp[k / 2 - 1] + tmp[k / 2]) / 2;
}

double run_clocks_median_sm(const run_state *st)
{
    const run_clocks *c = st->clocks;
    double *tmp = c && c->ns ? malloc(c->ns * sizeof *tmp) : NULL;
    double v = tmp ? median_of(c, offsetof(nvml_sample, sm_mhz), tmp) : NAN;
    free(tmp);
    return v;
}

static void num(yaml_out *y, const char *key, double v)
{
    yo_key(y, key);
    if (isnan(v))
        yo_str(y, NULL);
    else
        yo_f64(y, v);
}

static void throttle_list(yaml_out *y, bool known, uint64_t mask)
{
    if (!known) {
        yo_str(y, NULL);
        return;
    }
    const char *names[64];
    char buf[64][16];
    size_t k = nvml_throttle_names(mask, names, buf, 64);
    yo_seq_begin(y);
    for (size_t i = 0; i < k; i++)
        yo_str(y, names[i]);
    yo_seq_end(y);
}

static void reading(yaml_out *y, const char *key, const nvml_sample *s, bool with_throttle)
{
    yo_key(y, key);
    yo_map_begin(y);
    num(y, "sm_mhz", s->sm_mhz);
    num(y, "mem_mhz", s->mem_mhz);
    num(y, "power_w", s->power_w);
    num(y, "temp_c", s->temp_c);
    if (with_throttle) {
        yo_key(y, "throttle");
        throttle_list(y, s->throttle_known, s->throttle);
    }
    yo_map_end(y);
}

void run_clocks_meta(const run_state *st, yaml_out *y)
{
    const run_clocks *c = st->clocks;
    if (!c || !c->ns)
        return;
    yo_key(y, "clocks");   /* NVML's readings (docs/notes/output-files.md) */
    yo_map_begin(y);
    yo_key(y, "source"); yo_str(y, "nvml");
    yo_key(y, "device"); yo_str(y, nvml_device_name(c->n));
    yo_key(y, "uuid"); yo_str(y, nvml_device_uuid(c->n)[0] ? nvml_device_uuid(c->n) : NULL);
    yo_key(y, "matched_by"); yo_str(y, nvml_matched_by(c->n));   /* pci, name, none */
    yo_key(y, "interval_ms"); yo_i64(y, (int64_t)(CLOCKS_INTERVAL_S * 1000));
    yo_key(y, "samples"); yo_i64(y, (int64_t)c->ns);
    reading(y, "start", &c->start, true);
    reading(y, "end", &c->end, true);
    double *tmp = malloc(c->ns * sizeof *tmp);
    nvml_sample med = {.sm_mhz = NAN, .mem_mhz = NAN, .power_w = NAN, .temp_c = NAN};
    if (tmp) {
        med.sm_mhz = median_of(c, offsetof(nvml_sample, sm_mhz), tmp);
        med.mem_mhz = median_of(c, offsetof(nvml_sample, mem_mhz), tmp);
        med.power_w = median_of(c, offsetof(nvml_sample, power_w), tmp);
        med.temp_c = median_of(c, offsetof(nvml_sample, temp_c), tmp);
        free(tmp);
    }
    reading(y, "median", &med, false);
    bool any_known = false;
    for (size_t i = 0; i < c->ns; i++)
        any_known |= c->s[i].throttle_known;
    yo_key(y, "throttle_seen");   /* every reason any reading had */
    throttle_list(y, any_known, c->throttle_seen);
    yo_key(y, "unread");   /* each quantity NVML could not give: its first error */
    yo_seq_begin(y);
    for (int i = 0; i < NVML_FIELDS; i++)
        if (c->notes[i][0])
            yo_str(y, c->notes[i]);
    yo_seq_end(y);
    yo_map_end(y);
}
