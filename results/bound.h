#pragma once
/* The bound of a run (issue 38, item 2; a roofline after Williams, Waterman and
 * Patterson, CACM 2009): the time each resource of the device needs for the run's
 * counted work (bytes / bandwidth, samples / fill rate, light evaluations x FLOPs /
 * arithmetic rate, draws and dispatches x their cost), from the device
 * profile's figures (results/device_profile.h). The largest is the bound, its resource
 * the limiter; a bound above the measured time is a model error, flagged, never
 * clamped. Arithmetic only, no GL. The model, each formula and its limits:
 * docs/notes/device-profile.md "The bound". */
#include <stdbool.h>
#include <stddef.h>

#include "results/device_profile.h"

typedef enum bound_resource {
    BOUND_BYTES, BOUND_FILL, BOUND_ALU, BOUND_DRAWS, BOUND_DISPATCHES, BOUND_NRESOURCES
} bound_resource;
/* "bytes", "fill", "alu", "draws", "dispatches": the limiter's name */
extern const char *const bound_resource_names[BOUND_NRESOURCES];

/* FLOPs of one light evaluation: a hand count of renderers/shaders/lighting.inc.glsl's
 * point light (docs/notes/device-profile.md "The bound"). */
#define BOUND_FLOPS_PER_EVALUATION 64.0

/* The device's side: the peak figures the bound divides by (NAN: not in the profile). */
typedef struct bound_rates {
    double bandwidth_gbps;  /* max(bandwidth_copy, bandwidth_texture_read), GB/s */
    double fill_gsps;       /* fill_FORMAT_Sx (unblended), Gsamples/s */
    double alu_gflops;      /* max(alu_fragment, alu_compute), Gflop/s */
    double draw_us;         /* draw_us */
    double dispatch_us;     /* dispatch_us */
    double spread;          /* the largest spread / median of the figures used */
    char fill_figure[48];   /* the fill figure's name */
} bound_rates;

/* The run's side: a frame's counted work (NAN: not counted). */
typedef struct bound_work {
    double bytes;           /* gbuffer_write_bytes + gbuffer_read_bytes */
    double samples;         /* samples_shaded */
    double evaluations;     /* light evaluations: light_evals_per_pixel x covered pixels */
    double draws, dispatches;   /* state changes are charged nothing: bound_compute */
} bound_work;

typedef struct bound_result {
    double us[BOUND_NRESOURCES]; /* each resource's time; NAN where work or rate lacks */
    double bound_us;        /* the largest; NAN when none */
    int limiter;            /* its bound_resource; -1 when none */
    double pct;             /* 100 x bound / measured; NAN without both */
    bool model_error;       /* bound > measured */
} bound_result;

/* The rates of profile p for a target of `format` ("rgba8", "rgba16f", ...) at
 * `samples` (1 or 4; another count takes 4 above 1): fill_FORMAT_Sx, else
 * fill_FORMAT_1x, else fill_rgba8_1x. False when p has none of the figures. */
bool bound_rates_of(const device_profile *p, const char *format, int samples, bound_rates *r);

void bound_compute(const bound_rates *r, const bound_work *w, double measured_us,
                   bound_result *out);

/* A named value of a row (a summary.csv row, then its plan.csv row): NAN when absent or
 * empty. */
typedef struct bound_row {
    const char *const *names, *const *values;
    size_t n;
} bound_row;
double bound_row_number(const bound_row *rows, size_t nrows, const char *name);
const char *bound_row_text(const bound_row *rows, size_t nrows, const char *name);

/* The work, the measured time (frametime_mean_us) and the target (hdr: rgba16f, else
 * rgba8; msaa) of a summary.csv row and its plan.csv row. */
void bound_work_of_row(const bound_row *rows, size_t nrows, bound_work *w,
                       double *measured_us, const char **format, int *samples);
