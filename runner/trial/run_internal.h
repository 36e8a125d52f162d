#pragma once
/* What the files of one run share (runner/trial/run.c runs it, in its child process):
 *   run_setup.c  the context, scene, renderers, reference and files of a trial
 *   run_trial.c  the frame loop: priming, measuring, screenshots, error comparisons
 *   run_meta.c   the trial's meta.yaml
 *   run_clocks.c NVML's GPU clocks over the trial (meta.yaml's clocks:)
 *   run.c        one trial in a child process, its result, signals, its timeout
 * Nothing here is for code outside these files (runner/trial/run.h is). */
#include "runner/trial/run.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/renderer.h"
#include "results/stream_stats.h"
#include "results/yamlout.h"
#include "runner/folder/output.h"
#include "runner/trial/provenance.h"
#include "scenes/scene.h"

/* A fence wait longer than this is a hung GPU: the run fails rather than waits forever. */
#define SYNC_TIMEOUT_S 60.0

typedef struct run_clocks run_clocks;   /* run_clocks.c */

/* Everything one run holds while it executes. */
typedef struct run_state {
    const experiment *e;
    const run_spec *s;
    const run_options *o;
    progress *pg;
    uint32_t trial;            /* the trial this process runs, 1.. */
    uint32_t order;            /* its place in its round (runner/cli/schedule.c) */
    char metric[8];            /* measure.metric resolved for this context ("": none yet) */
    char dir[4300];            /* OUT/runs/<id>/trial-<k> */
    gl_context *ctx;
    scene *sc;
    renderer *r;
    renderer *ref;             /* error: the reference configuration; NULL without one */
    gl_offscreen ref_fb;       /* error.reference.supersample K > 1: its K W x K H output */
    float *ref_hdr;            /* ... and its HDR image read back, K W x K H RGBA */
    pass_plan plan;
    run_files files;
    trial_stream *stream;      /* the per-trial statistics, fed frame by frame */
    double prime_s;            /* prime_variants: wall time of the frames it drew */
    size_t prime_frames;
    double paused_s;           /* measured clock paused (comparisons, screenshots) */
    trial_result result;       /* this trial's row (result.trial 0: it never ran) */
    char started[32], finished[32];
    provenance_start prov;     /* the machine's load and memory at the trial's start */
    char status[96];
    char message[1024];        /* why it failed, for summary.csv */
    char err[512];
    scene_file_info scene_info; /* a file scene: what scene_file_check found */
    struct {                   /* how the scene was loaded (meta.yaml's scene_load) */
        const char *source;    /* "catalog", "file" or "cache" */
        const char *cache;     /* "off", "hit", "written", "not written", "animated" (not
                                * cached), "" (catalog) */
        char note[640];        /* why a cache file was ignored or not written, or "" */
        double import_s, decode_s, build_s, cache_s, prepare_s, upload_s, total_s;
        double total_cpu_s;    /* the process's CPU seconds over total_s: what a busy
                                * machine's waits do not inflate */
    } load;
    uint32_t made_opaque;      /* translucency: opaque: the materials it made opaque */
    double meter_lum;          /* exposure.mode auto: the metering frame's log-average
                                * luminance (0: black; NAN: not metered) */
    bool meter_lights_off;     /* ... drawn without the placed lights (lights.sizing) */
    double lights_radius;      /* the placed lights' mean range as used (NAN: none) */
    bool priming;              /* run_prime_variants is drawing: renderer_prime */
    run_clocks *clocks;        /* NVML's readings of this trial; NULL: no NVIDIA device */
    bool in_child;             /* this is the trial's own process (run.c's child_main) */
    long child_rss_kb;         /* written by the parent for a child that died or hung: its
                                * peak resident size (wait4), kB; 0: none */
} run_state;

/* "YYYY-MM-DDTHH:MM:SSZ", now. */
void run_utc_now(char *buf, size_t len);
/* Polls the GL errors of `where`; true when there were none in the whole trial. */
bool run_gl_clean(run_state *st, const char *where);
/* The trial failed for `reason` (the status `failed:<reason>`), unless it already had. */
void run_set_status(run_state *st, const char *reason);
/* A file of the trial could not be written: whatever else the trial's status said, it
 * is now RUN_STATUS_WRITE (the run is not complete: --resume runs it again), and the
 * message names the file (the first such). */
void run_set_unwritten(char *status, size_t len, char *msg, size_t msglen, const char *why);

/* Sets up one run; on failure st->status says why and st->err holds the message. */
bool run_setup(run_state *st);
/* exposure.*, tonemap and lights.sizing onto st->sc (runner/trial/run_display.c), before any
 * renderer is made: ro are the run's renderer options (the metering frame's, single-
 * sampled). False with st->status and st->err set. */
bool run_display(run_state *st, const struct renderer_options *ro);
/* Releases what run_setup and the trial made. */
void run_teardown(run_state *st);
/* Draws, unrecorded, the frames whose shader variants the trial will need (run_trial.c
 * says which); false with st->status and st->err set. */
bool run_prime_variants(run_state *st);
/* Trial `trial` of the run: warm-up, the measured frames, its row in tr. */
void run_one_trial(run_state *st, uint32_t trial, trial_result *tr);
/* NVML's clocks (run_clocks.c): open (before warm-up), the start reading (right before
 * the first measured frame), a reading between measured frames when due (at most every
 * 100 ms; the caller pauses the measured clock), the end reading, meta.yaml's block
 * (nothing without NVML), free. Each does nothing while st->clocks is NULL. */
void run_clocks_open(run_state *st);
void run_clocks_start(run_state *st);
bool run_clocks_due(const run_state *st);
void run_clocks_tick(run_state *st);
void run_clocks_end(run_state *st);
void run_clocks_meta(const run_state *st, yaml_out *y);
double run_clocks_median_sm(const run_state *st);   /* MHz; NAN: no readings */
void run_clocks_free(run_state *st);
/* The trial's meta.yaml, atomically; false with a message. */
bool run_write_meta(run_state *st, char *err, size_t errlen);
