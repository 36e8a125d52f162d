/* Setting up and tearing down one trial (runner/trial/run_internal.h). */
#define _DEFAULT_SOURCE
#include "runner/trial/run_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/gl/context.h"
#include "renderers/renderer.h"
#include "results/contention.h"
#include "results/gl_device.h"
#include "common/fsutil.h"
#include "runner/manifest/hash.h"
#include "runner/manifest/params.h"
#include "runner/plan/plan_check.h"
#include "runner/plan/progress.h"

/* measure.metric for this context. auto: the process's CPU time on a software
 * rasteriser (its threads are ours, and load that takes a core moves its wall time,
 * not its work: docs/architecture.md "What decides"), the GPU timer on hardware that
 * has one, else wall time. An explicit gpu needs timer queries. */
static bool resolve_metric(run_metric m, const gl_info *gi, char *out, size_t len, char *err,
                           size_t errlen)
{
    bool software = gl_software_rasterizer(gi->renderer, gi->vendor, gi->version) != NULL;
    if (m == RUN_METRIC_GPU && !gi->timer_query) {
        snprintf(err, errlen, "measure.metric: gpu, but %s has no timer queries", gi->renderer);
        return false;
    }
    snprintf(out, len, "%s", m == RUN_METRIC_WALL ? "wall"
                             : m == RUN_METRIC_CPU ? "cpu"
                             : m == RUN_METRIC_GPU ? "gpu"
                             : software ? "cpu" : gi->timer_query ? "gpu" : "wall");
    return true;
}

/* The scene's cache file for this run (outputs.scene_cache), OUT/.cache/scenes/NAME:
 * inside the output folder, which the run may write and which its trials and the other
 * runs of its sweep share, and which goes when the results go; "" when off. */
static void cache_path(const run_state *st, const scene_file_options *fo, uint64_t hash,
                       char *out, size_t len)
{
    const run_params *p = &st->s->p;
    out[0] = '\0';
    if (!p->scene_cache || !p->scene_file[0])
        return;
    char name[SCENE_CACHE_NAME_LEN];
    scene_cache_name(fo, hash, p->width, p->height, name);
    snprintf(out, len, "%s/.cache/scenes/%s", st->o->out_dir, name);
}

static void load_note(run_state *st, const char *note)
{
    snprintf(st->load.note, sizeof st->load.note, "%s", note);
    if (note[0])
        fprintf(stderr, "shadesweep: scene cache: %s\n", note);
}

/* The run's scene, from its cache file when that holds (file scenes), else loaded and
 * built (and cached); st->load says how and what it took. */
static bool run_setup_scene(run_state *st)
{
    const run_params *p = &st->s->p;
    double t0 = progress_now(), cpu0 = contention_process_cpu_s();
    scene_file_times ft;
    scene_file_times_take(&ft);   /* what loads before this run's spent is not its */
    scene_file_options fo;
    scene_source src;
    run_params_scene(p, &fo, &src);
    st->load.source = p->scene_file[0] ? "file" : "catalog";
    st->load.cache = !p->scene_file[0] ? "" : p->scene_cache ? "not written" : "off";
    uint64_t planned = strtoull(p->scene_hash, NULL, 16);
    char path[4400];
    cache_path(st, &fo, planned, path, sizeof path);
    scene_cached *cached = NULL;
    if (path[0]) {
        char note[640];
        cached = scene_cache_read(path, &fo, planned, p->width, p->height, &st->scene_info,
                                  note, sizeof note);
        load_note(st, note);
    }
    scene_file_list files = {0};
    scene_cache_store store = {.path = path[0] ? path : NULL, .o = &fo,
                               .content_hash = planned, .info = &st->scene_info,
                               .files = &files};
    if (cached) {
        st->load.source = "cache";
        st->load.cache = "hit";
        store.path = NULL;
    } else if (p->scene_file[0]) {
        /* A file scene is checked again here: the plan named it by its content hash, and
         * a file edited since then must not be measured under the old id. */
        char hash[17];
        if (!scene_file_check_list(&fo, &st->scene_info, store.path ? &files : NULL, st->err,
                                   sizeof st->err)) {
            run_set_status(st, "scene");
            return false;
        }
        hash_hex(st->scene_info.hash, 16, hash);
        if (strcmp(hash, p->scene_hash) != 0) {
            snprintf(st->err, sizeof st->err,
                     "%.300s changed since the plan was made (content hash %s, now %s)",
                     p->scene_file, p->scene_hash, hash);
            scene_file_list_free(&files);
            run_set_status(st, "scene");
            return false;
        }
        char why[512];
        if (store.path) {
            *strrchr(path, '/') = '\0';
            bool made = fs_mkdirs_tail(path, 2, why, sizeof why);   /* .cache/scenes: no links */
            *strchr(path, '\0') = '/';
            if (!made) {
                char note[640];
                snprintf(note, sizeof note, "not cached: %.500s", why);
                load_note(st, note);
                store.path = NULL;
            }
        }
    }
    double cache_s = progress_now() - t0;
    scene_file_times_take(&ft);
    double t1 = progress_now();
    st->sc = scene_build_cache(&src, cached, store.path ? &store : NULL, &p->lights, p->width,
                               p->height, st->err, sizeof st->err);
    double built = progress_now() - t1;
    scene_file_list_free(&files);
    if (store.path) {
        st->load.cache = store.written ? "written" : store.animated ? "animated" : "not written";
        if (store.note[0])
            load_note(st, store.note);
    }
    scene_file_times bt;
    scene_file_times_take(&bt);
    st->load.import_s = ft.import_s + bt.import_s;
    st->load.decode_s = ft.decode_s + bt.decode_s;
    /* the check's load (before t1) is import and decode; the cache's read is cache_s */
    st->load.cache_s = (cached ? cache_s : cache_s - ft.import_s - ft.decode_s) + store.write_s;
    st->load.build_s = built - bt.import_s - bt.decode_s - store.write_s;
    if (!st->sc || !scene_set_camera(st->sc, &p->camera, st->err, sizeof st->err)) {
        run_set_status(st, "scene");
        return false;
    }
    st->load.total_s = progress_now() - t0;
    st->load.total_cpu_s = contention_process_cpu_s() - cpu0;
    return true;
}

/* Sets up one run; on failure st->status says why and st->err holds the message. */
bool run_setup(run_state *st)
{
    const run_params *p = &st->s->p;
    gl_context_desc cd = {
        .backend = st->o->backend,
        .device = st->o->device,
        .debug = st->o->debug_gl,
        .width = p->width,
        .height = p->height,
    };
    if (!fs_mkdirs_tail(st->dir, 3, st->err, sizeof st->err)) {   /* runs/<id>/trial-<k> */
        run_set_status(st, "output");
        return false;
    }
    if (!(st->ctx = gl_context_create(&cd, st->err, sizeof st->err))) {
        run_set_status(st, "context");
        return false;
    }
    if (!run_setup_scene(st))
        return false;
    st->made_opaque = run_params_shape_scene(p, st->sc);
    const gl_info *gi = gl_context_info(st->ctx);
    if (!resolve_metric(p->metric, gi, st->metric, sizeof st->metric, st->err, sizeof st->err)) {
        run_set_status(st, "metric");
        return false;
    }
    renderer_options ro = {
        .queries = true,
        .timer_query = gi->timer_query,
        .pipeline_statistics = gi->pipeline_statistics,
        .max_uniform_block_size = gi->max_uniform_block_size,
    };
    params_to_renderer_options(p, &ro);   /* params.def's `apply` column */
    if (!run_display(st, &ro))
        return false;
    double t_prepare = progress_now(), up0 = renderer_upload_s();
    if (!(st->r = renderer_create(p->renderer, &ro, st->err, sizeof st->err)) ||
        !renderer_prepare(st->r, st->sc, st->err, sizeof st->err)) {
        run_set_status(st, "renderer");
        return false;
    }
    st->load.prepare_s = progress_now() - t_prepare;   /* the scene's upload, the programs */
    st->load.upload_s = renderer_upload_s() - up0;
    renderer_describe(st->r, &st->plan);
    if (!run_gl_clean(st, "prepare")) {
        snprintf(st->err, sizeof st->err, "GL error while preparing the renderer");
        run_set_status(st, "gl-error");
        return false;
    }
    if (!run_files_open(&st->files, st->dir, p, st->err, sizeof st->err)) {
        run_set_status(st, "output");
        return false;
    }
    st->files.pass_times_frame_only =
        gl_software_rasterizer(gi->renderer, gi->vendor, gi->version) != NULL;
    run_files_bound_rates(&st->files,
                          (const char *const[6]){gi->vendor, gi->renderer, gi->version,
                                                 gi->glsl_version, gi->backend, gi->device},
                          hdr_names[p->hdr], 1 << p->msaa);
    if (st->sc->ncoverage_lights &&
        !run_files_open_coverage(&st->files, st->dir, st->err, sizeof st->err)) {
        run_set_status(st, "output");
        return false;
    }
    if (p->nscreenshots && renderer_has_light_grid(st->r) &&
        !run_files_open_lightgrid(&st->files, st->dir, st->err, sizeof st->err)) {
        run_set_status(st, "output");
        return false;
    }
    if (p->error_renderer[0]) {
        /* params.def's `ref` column: what the reference inherits, what it resets */
        run_params rp;
        params_reference(p, &rp);
        renderer_options rr = ro;
        params_to_renderer_options(&rp, &rr);
        rr.queries = false;
        /* a reference, not a measurement: forward-spml reads its lights from the
         * uniform block where they fit and from a storage buffer beyond it */
        rr.light_buffer = LIGHT_BUFFER_AUTO;
        char why[512];
        const int k = (int)p->error_supersample;
        if (k > 1) {
            /* its own K W x K H output, bound while renderer_create takes it as the output */
            rr.width = k * p->width;
            rr.height = k * p->height;
            if (!gl_offscreen_create(st->ctx, rr.width, rr.height, &st->ref_fb, why,
                                     sizeof why)) {
                snprintf(st->err, sizeof st->err,
                         "error.reference.supersample %d: the reference at %dx%d: %.400s", k,
                         rr.width, rr.height, why);
                run_set_status(st, "reference");
                return false;
            }
        }
        /* The scene's size is what renderer_base_size checks, the frame's viewport
         * (shading.c) and the projection's aspect (the same at K W x K H): the reference
         * prepares and draws (measure_error) with it at its own size, the run at W x H. */
        st->sc->width = rr.width;
        st->sc->height = rr.height;
        bool made = (st->ref = renderer_create(p->error_renderer, &rr, why, sizeof why)) &&
                    renderer_prepare(st->ref, st->sc, why, sizeof why);
        st->sc->width = p->width;
        st->sc->height = p->height;
        gl_context_bind_default(st->ctx);
        if (!made) {
            snprintf(st->err, sizeof st->err, "reference %.31s: %.400s", p->error_renderer, why);
            run_set_status(st, "reference");
            return false;
        }
        /* the box filter reads the reference's HDR target: one it has (null has none) */
        if (k > 1) {
            size_t n = (size_t)rr.width * (size_t)rr.height * 4u;
            if (!(st->ref_hdr = malloc(n * sizeof *st->ref_hdr))) {
                snprintf(st->err, sizeof st->err, "out of memory for the %dx%d reference",
                         rr.width, rr.height);
                run_set_status(st, "oom");
                return false;
            }
            if (!renderer_read_hdr(st->ref, st->ref_hdr, rr.width, rr.height, NULL)) {
                snprintf(st->err, sizeof st->err,
                         "error.reference.supersample %d: reference %.31s has no HDR image to "
                         "box-filter", k, p->error_renderer);
                run_set_status(st, "reference");
                return false;
            }
        }
        if (!run_files_open_errors(&st->files, st->dir, st->err, sizeof st->err)) {
            run_set_status(st, "output");
            return false;
        }
    }
    if (!(st->stream = trial_stream_new())) {
        snprintf(st->err, sizeof st->err, "out of memory for the trial statistics");
        run_set_status(st, "oom");
        return false;
    }
    return true;
}

/* Releases what run_setup and the trial made. */
void run_teardown(run_state *st)
{
    run_files_abort(&st->files);
    renderer_destroy(st->ref);
    gl_offscreen_destroy(&st->ref_fb);
    free(st->ref_hdr);
    renderer_destroy(st->r);
    scene_destroy(st->sc);
    gl_context_destroy(st->ctx);
    trial_stream_free(st->stream);
    run_clocks_free(st);
}
