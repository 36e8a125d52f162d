#pragma once
/* The experiment's files (DESIGN.md "Output files"):
 *   OUT/plan.csv                 every run of the manifest, in plan order
 *   OUT/summary.csv              one row per run x trial (merged from the runs)
 *   OUT/summary_long.csv         one row per run x trial x measure (runner/answer/summary_long.c)
 *   OUT/runs/<id>/frames.csv     one row per measured frame
 *   OUT/runs/<id>/seconds.csv    one row per second bin
 *   OUT/runs/<id>/passes.csv     one row per frame x pass
 *   OUT/runs/<id>/summary.csv    this run's rows of OUT/summary.csv
 *   OUT/runs/<id>/meta.yaml      provenance and the pass plan
 * Each file is written under a temporary name and renamed when complete. */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include "results/bound.h"
#include "results/csv.h"
#include "results/csvread.h"
#include "common/image_io.h"
#include "results/metrics.h"
#include "results/record.h"
#include "results/stats.h"
#include "renderers/renderer.h"
#include "runner/manifest/manifest.h"

extern const char *const summary_columns[];
extern const size_t summary_ncolumns;
/* The unit of a measured column of summary.csv ("us", "bytes", "1": a ratio, ...);
 * NULL for the others (identity, parameters, trial, order, metric, status, message). */
const char *summary_column_unit(const char *column);
/* summary_column_unit of each column of t, in order (NULL: not a measure); free() the
 * array. NULL when out of memory. */
const char **summary_units_of(const csv_table *t);
extern const char *const frames_columns[];
extern const size_t frames_ncolumns;

bool output_write_plan(const char *out_dir, const plan *p, char *err, size_t errlen);

/* OUT/sweep.yaml: which manifest (path and hash) the folder's runs come from, how
 * many runs the plan has and which shard this folder holds ("2/4", "all", or
 * "merged from N folders"). merge refuses folders whose hashes differ. */
#define OUTPUT_FORMAT "shadesweep-output 1"   /* sweep.yaml's first key: folder.h */
typedef struct sweep_meta {
    char format[64];           /* OUTPUT_FORMAT in a folder this version owns */
    char experiment[64];
    char manifest_path[4096];
    char manifest_hash[17];
    size_t runs;
    char shard[64];
    double scale;              /* run --scale (0 read as 1) */
    bool smoke;                /* run --smoke */
} sweep_meta;
/* The meta of a sweep of e (shard 0: all of it). */
void output_sweep_meta_of(const experiment *e, unsigned shard, unsigned nshards, size_t nruns,
                          sweep_meta *m);
bool output_write_sweep_meta(const char *out_dir, const sweep_meta *m, char *err, size_t errlen);
bool output_read_sweep_meta(const char *out_dir, sweep_meta *m, char *err, size_t errlen);

/* The per-run CSV streams, open across the run's trials. */
typedef struct run_files {
    csv_writer *frames, *seconds, *passes, *convergence, *errors, *coverage, *lightgrid;
    /* passes.csv's gpu_us_attributed and cpu_us_attributed are 0: the device (a software
     * rasterizer, results/gl_device.h) runs a pass's work where it flushes, so only the
     * frame's total time is trusted; the counters per pass are kept as they are */
    bool pass_times_frame_only;
    /* passes.csv's bound_us, limiter and bound_pct (issue 38): the rates of the cached
     * profile of the run's device for its target (run_files_bound_rates); without a
     * profile the columns are empty */
    bool has_rates;
    bound_rates rates;
} run_files;

/* The rates passes.csv's bounds divide by: the profile `probe` cached for the device of
 * GL strings gl (vendor, renderer, version, GLSL, backend, device:
 * device_profile_set_gl), for the run's HDR target `format` at `samples`. False, the
 * columns left empty, when none is cached or it cannot be read. */
bool run_files_bound_rates(run_files *f, const char *const gl[6], const char *format,
                           int samples);

bool run_files_open(run_files *f, const char *run_dir, const run_params *p, char *err,
                    size_t errlen);
void run_files_frame(run_files *f, const char *run_id, uint32_t trial, const frame_record *r,
                     const frame_stats *fs);
/* One row of seconds.csv, of convergence.csv (when the run writes them). */
void run_files_second(run_files *f, const char *run_id, uint32_t trial, const second_bin *b);
void run_files_convergence(run_files *f, const char *run_id, uint32_t trial,
                           const convergence_point *p);

/* One comparison with the reference: errors.csv, opened when the run has one. */
bool run_files_open_errors(run_files *f, const char *run_dir, char *err, size_t errlen);
void run_files_error(run_files *f, const char *run_id, uint32_t trial, uint32_t frame,
                     double t_scene, const image_error *e);
/* Screen coverage of the scene's coverage lights (scene_light_coverage), a row per
 * light per frame: coverage.csv, opened when the scene has such lights. */
bool run_files_open_coverage(run_files *f, const char *run_dir, char *err, size_t errlen);
void run_files_coverage(run_files *f, const char *run_id, uint32_t trial, uint32_t frame,
                        double t_scene, uint32_t light, double coverage);
/* The histogram of the light-list lengths of a tiled or clustered renderer's frame
 * (renderer_light_grid), a row per length that some tile or cluster has (lights,
 * cells): lightgrid.csv, opened when the renderer has a light grid and the run takes
 * screenshots; written for the screenshot frames. False when memory runs out. */
bool run_files_open_lightgrid(run_files *f, const char *run_dir, char *err, size_t errlen);
bool run_files_lightgrid(run_files *f, const char *run_id, uint32_t trial, uint32_t frame,
                         double t_scene, const uint32_t *lengths, size_t n);
bool run_files_commit(run_files *f, char *err, size_t errlen);
void run_files_abort(run_files *f);

/* What one trial measured, as summary.csv states it. */
typedef struct trial_result {
    uint32_t trial;
    size_t frames;
    double measured_s;         /* end of the last frame since measurement start */
    double fps_mean;           /* frames / measured_s */
    sample_summary ft;         /* frame time, us */
    double ft_ci95;            /* half-width, us (batch means) */
    metric_totals m;           /* results/metrics.def's summary columns (NAN: empty) */
    double harness_us_mean;    /* runner bookkeeping between frames, us */
    double ci1pct_after_s;     /* the CI stayed within 1% of the mean from then on; NAN: never */
    unsigned gpu_dropped;      /* pass GPU times longer than their frame, made NAN (run.c) */
    /* the worst comparison with the reference (NAN: none made): largest RMSE and max
     * error, smallest PSNR; non-finite values summed over the comparisons */
    double image_rmse, image_psnr_db, image_max_abs;
    double nonfinite;
    /* the largest RMSE over the reference's edge pixels (image_ref.h) and their count in
     * that comparison (NAN: no comparison, or no edge in any) */
    double image_edge_rmse, image_edge_pixels;
    unsigned lights_max;
    double lights_radius;      /* the placed lights' range as used, mean (NAN: unknown) */
    uint32_t order;            /* its place in its round (schedule); 0: unknown */
    char metric[8];            /* what decides: "wall", "cpu", "gpu" ("" : no context) */
    double metric_us;          /* the trial's mean of it per frame (NAN: none) */
    char status[96];           /* "ok" or "failed:<reason>" */
} trial_result;

/* message: why the run failed ("" when it did not), into the `message` column. */
bool output_write_run_summary(const char *run_dir, const experiment *e, const run_spec *s,
                              const pass_plan *pp, const trial_result *t, size_t ntrials,
                              const char *message, char *err, size_t errlen);

