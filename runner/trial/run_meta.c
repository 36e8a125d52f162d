/* A trial's meta.yaml (runner/trial/run_internal.h). */
#define _DEFAULT_SOURCE
#include "runner/trial/run_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "config.h"
#include "version.h"
#include "runner/manifest/hash.h"
#include "runner/plan/memory.h"
#include "runner/plan/workload.h"

/* The process's peak resident size (VmHWM in /proc/self/status), kB; -1 unknown. */
static int64_t vm_hwm_kb(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    if (!f)
        return -1;
    char line[256];
    long long kb = -1;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "VmHWM: %lld kB", &kb) == 1)
            break;
    fclose(f);
    return kb;
}

bool run_write_meta(run_state *st, char *err, size_t errlen)
{
    char path[4500];
    snprintf(path, sizeof path, "%s/meta.yaml", st->dir);
    yaml_out *y = yo_open(path, err, errlen);
    if (!y)
        return false;
    const experiment *e = st->e;
    yo_map_begin(y);
    yo_key(y, "run_id"); yo_str(y, st->s->id);
    yo_key(y, "experiment"); yo_str(y, e->name);
    yo_key(y, "status"); yo_str(y, st->status);
    yo_key(y, "manifest");
    yo_map_begin(y);
    yo_key(y, "path"); yo_str(y, e->path);
    yo_key(y, "hash"); yo_str(y, e->hash);
    yo_key(y, "description"); yo_str(y, e->description);
    yo_key(y, "text"); yo_str(y, e->text);   /* verbatim: what the hash is of, with: */
    yo_key(y, "set");   /* run --set KEY=VALUE, verbatim, in order: applied over the text */
    yo_seq_begin(y);
    for (size_t i = 0; i < e->nsets; i++)
        yo_str(y, e->sets[i]);
    yo_seq_end(y);
    yo_key(y, "renderer_filter"); yo_str(y, e->renderer_filter);   /* run --renderer; null */
    yo_map_end(y);
    yo_key(y, "shadesweep");
    yo_map_begin(y);
    yo_key(y, "version"); yo_str(y, SHADESWEEP_VERSION);
    yo_key(y, "commit"); yo_str(y, SHADESWEEP_COMMIT);
    yo_key(y, "dirty"); yo_bool(y, strstr(SHADESWEEP_COMMIT, "-dirty") != NULL);
    yo_map_end(y);
    provenance_write_invocation(y);

    yo_key(y, "parameters");
    yo_map_begin(y);
    param_kv kv[PARAM_KV_MAX];
    size_t nkv = run_params_kv(&st->s->p, kv, PARAM_KV_MAX);
    for (size_t i = 0; i < nkv; i++) {
        yo_key(y, kv[i].key);
        yo_str(y, kv[i].value);
    }
    yo_map_end(y);

    const run_params *p = &st->s->p;
    if (p->translucency == RUN_TRANSLUCENCY_OPAQUE) {
        yo_key(y, "made_opaque");   /* translucency: opaque */
        yo_i64(y, st->made_opaque);
    }
    if (st->load.source) {
        /* seconds: the file's import (twice where the scene is not read from the cache:
         * the check, then the build) and texture decode, the building of the scene from
         * it, the cache file's read and write, the scene in all (load), and the
         * renderer's prepare (the scene's upload to the GPU and the programs) */
        yo_key(y, "scene_load");
        yo_map_begin(y);
        yo_key(y, "source"); yo_str(y, st->load.source);
        if (st->load.cache[0]) {
            yo_key(y, "cache"); yo_str(y, st->load.cache);
        }
        if (st->load.note[0]) {
            yo_key(y, "cache_note"); yo_str(y, st->load.note);
        }
        yo_key(y, "import_s"); yo_f64(y, st->load.import_s);
        yo_key(y, "decode_s"); yo_f64(y, st->load.decode_s);
        yo_key(y, "build_s"); yo_f64(y, st->load.build_s);
        yo_key(y, "cache_s"); yo_f64(y, st->load.cache_s);
        yo_key(y, "load_s"); yo_f64(y, st->load.total_s);
        yo_key(y, "load_cpu_s"); yo_f64(y, st->load.total_cpu_s);
        yo_key(y, "prepare_s"); yo_f64(y, st->load.prepare_s);
        yo_key(y, "upload_s"); yo_f64(y, st->load.upload_s);
        yo_map_end(y);
    }
    if (p->scene_file[0]) {
        const scene_file_info *si = &st->scene_info;
        char hash[17];
        hash_hex(si->hash, 16, hash);
        yo_key(y, "scene_file");
        yo_map_begin(y);
        yo_key(y, "path"); yo_str(y, p->scene_file);
        yo_key(y, "hash"); yo_str(y, hash);
        yo_key(y, "scale");   /* the one applied: fit's factor */
        yo_f64(y, si->scale);
        yo_key(y, "fit"); yo_bool(y, p->scene_scale == 0);
        yo_key(y, "light_bounds"); yo_str(y, p->scene_around ? "around" : "model");
        yo_key(y, "up"); yo_str(y, p->scene_up == SCENE_UP_Z ? "z" : "y");
        yo_key(y, "camera"); yo_str(y, p->scene_camera);
        yo_key(y, "view"); yo_str(y, si->view);
        if (st->sc) {
            /* near and far: the file camera's own (world units, 0 where it gave none)
             * and those the run used (scene_fit_planes', or camera.near and far) */
            yo_key(y, "camera_planes");
            yo_map_begin(y);
            yo_key(y, "file");
            if (st->sc->file_camera) {
                yo_seq_begin(y);
                yo_f64(y, st->sc->file_planes[0]);
                yo_f64(y, st->sc->file_planes[1]);
                yo_seq_end(y);
            } else {
                yo_str(y, NULL);
            }
            yo_key(y, "used");
            yo_seq_begin(y);
            yo_f64(y, st->sc->znear);
            yo_f64(y, st->sc->zfar);
            yo_seq_end(y);
            yo_map_end(y);
        }
        yo_key(y, "files"); yo_i64(y, si->files);
        yo_key(y, "meshes"); yo_i64(y, si->meshes);
        yo_key(y, "triangles"); yo_i64(y, (int64_t)si->triangles);
        yo_key(y, "objects"); yo_i64(y, si->objects);
        yo_key(y, "materials"); yo_i64(y, si->materials);
        yo_key(y, "materials_mask"); yo_i64(y, si->materials_mask);
        yo_key(y, "materials_blend"); yo_i64(y, si->materials_blend);
        yo_key(y, "blend"); yo_str(y, !si->materials_blend ? "none"
                                      : p->translucency == RUN_TRANSLUCENCY_OPAQUE ? "made opaque (translucency: opaque)"
                                                             : "translucent, in the translucent pass");
        yo_key(y, "textures"); yo_i64(y, si->textures);
        yo_key(y, "lights"); yo_i64(y, si->lights);
        yo_key(y, "cameras"); yo_i64(y, si->cameras);
        yo_key(y, "not_rendered");   /* read from the file, drawn by no renderer */
        yo_seq_begin(y);
        for (uint32_t i = 0; i < si->nnot_rendered; i++)
            yo_str(y, si->not_rendered[i]);
        yo_seq_end(y);
        yo_key(y, "bounds_min");
        yo_seq_begin(y);
        for (int i = 0; i < 3; i++)
            yo_f64(y, si->bounds_min[i]);
        yo_seq_end(y);
        yo_key(y, "bounds_max");
        yo_seq_begin(y);
        for (int i = 0; i < 3; i++)
            yo_f64(y, si->bounds_max[i]);
        yo_seq_end(y);
        yo_map_end(y);
    }

    /* the display and the lights' sizing as this trial applied them (run_display.c);
     * absent when the trial failed before its scene was built */
    if (st->sc) {
        const scene_display *d = &st->sc->display;
        yo_key(y, "display");
        yo_map_begin(y);
        static const char *const modes[] = {"none", "auto", "fixed"};
        yo_key(y, "exposure_mode");
        yo_str(y, (unsigned)p->exposure_mode < 3 ? modes[p->exposure_mode] : "?");
        yo_key(y, "exposure"); yo_f64(y, d->exposed ? d->exposure : 1.0);
        yo_key(y, "ev100");   /* exposure = 1 / (1.2 x 2^EV100) */
        yo_f64(y, log2(1.0 / (1.2 * (d->exposed ? d->exposure : 1.0))));
        if (p->exposure_mode == EXPOSURE_AUTO) {
            yo_key(y, "metered_by");
            yo_str(y, "forward-spml at schedule time 0, longest side at most 256");
            yo_key(y, "metered_luminance"); yo_f64(y, st->meter_lum);
            yo_key(y, "metered_without_placed_lights"); yo_bool(y, st->meter_lights_off);
        }
        yo_key(y, "tonemap");
        yo_str(y, d->tonemap == TONEMAP_PBR_NEUTRAL ? "pbr-neutral (then sRGB)" : "none");
        static const char *const sizings[] = {"radius", "range-from-intensity",
                                              "intensity-from-range"};
        yo_key(y, "lights_sizing");
        yo_str(y, (unsigned)p->lights.sizing < 3 ? sizings[p->lights.sizing] : "?");
        yo_key(y, "lights_range_mean"); yo_f64(y, st->lights_radius);
        yo_map_end(y);
    }

    yo_key(y, "gl");
    yo_map_begin(y);
    const gl_info *gi = st->ctx ? gl_context_info(st->ctx) : NULL;
    yo_key(y, "backend"); yo_str(y, gi ? gi->backend : NULL);
    yo_key(y, "device"); yo_str(y, gi ? gi->device : NULL);
    yo_key(y, "vendor"); yo_str(y, gi ? gi->vendor : NULL);
    yo_key(y, "renderer"); yo_str(y, gi ? gi->renderer : NULL);
    yo_key(y, "version"); yo_str(y, gi ? gi->version : NULL);
    yo_key(y, "glsl"); yo_str(y, gi ? gi->glsl_version : NULL);
    yo_key(y, "debug_context"); yo_bool(y, gi && gi->debug_context);
    yo_key(y, "timer_query"); yo_bool(y, gi && gi->timer_query);
    yo_key(y, "pipeline_statistics"); yo_bool(y, gi && gi->pipeline_statistics);
    /* LP_NUM_THREADS as this trial ran (measure.rasterizer); null: llvmpipe's own, one a CPU */
    yo_key(y, "lp_num_threads"); yo_str(y, getenv("LP_NUM_THREADS"));
    yo_map_end(y);
    run_clocks_meta(st, y);

    char cpu[256], host[256] = "unknown";
    provenance_cpu_model(cpu, sizeof cpu);
    gethostname(host, sizeof host - 1);
    yo_key(y, "host");
    yo_map_begin(y);
    yo_key(y, "cpu"); yo_str(y, cpu);
    yo_key(y, "threads"); yo_i64(y, sysconf(_SC_NPROCESSORS_ONLN));
    yo_key(y, "hostname"); yo_str(y, host);
    provenance_write_host(y, &st->prov);
    yo_map_end(y);
    yo_key(y, "started"); yo_str(y, st->started);
    yo_key(y, "finished"); yo_str(y, st->finished);

    /* The trial process's peak resident size, kB: its own VmHWM as it writes this (the
     * counter that wait4's ru_maxrss reads when it exits), or the parent's wait4 figure
     * for a child that died or was killed; -1 when no child ran (a refused run). */
    int64_t hwm = st->child_rss_kb > 0 ? st->child_rss_kb : st->in_child ? vm_hwm_kb() : -1;
    yo_key(y, "timing");
    yo_map_begin(y);
    yo_key(y, "clock_source"); yo_str(y, "CLOCK_MONOTONIC");
    yo_key(y, "frame_end"); yo_str(y, st->s->p.sync == RUN_SYNC_FINISH ? "glFinish" : "fence");
    yo_key(y, "ci95_method"); yo_str(y, "batch means, 10 batches, Student t");
    yo_key(y, "percentiles"); yo_str(y, "nearest rank; exact up to 1024 frames, then a log histogram within 0.5%");
    yo_key(y, "prime_frames"); yo_i64(y, (int64_t)st->prime_frames);
    yo_key(y, "prime_s"); yo_f64(y, st->prime_s);
    yo_key(y, "paused_s"); yo_f64(y, st->paused_s);
    yo_key(y, "vm_hwm_kb"); yo_i64(y, hwm);
    yo_map_end(y);

    /* runner/plan/memory.h's estimate (with the built scene when there is one) next to what
     * the trial's process held at its peak */
    memory_estimate me;
    memory_estimate_run(&st->s->p, st->sc, &me);
    yo_key(y, "memory");
    yo_map_begin(y);
    yo_key(y, "estimate_mb"); yo_i64(y, (int64_t)((me.resident + (1u << 19)) >> 20));
    yo_key(y, "peak_rss_mb"); yo_i64(y, hwm < 0 ? -1 : (hwm + 512) / 1024);
    yo_map_end(y);

    /* what the trial measured (runner/plan/workload.h), and whether it was brute force */
    const metric_totals *m = &st->result.m;
    char warning[256];
    bool brute = workload_brute_force(m->lights_reaching_mean, (double)st->result.lights_max,
                                      warning, sizeof warning);
    yo_key(y, "workload");
    yo_map_begin(y);
    yo_key(y, "counted_at"); yo_str(y, "the first measured frame, over its covered pixels");
    yo_key(y, "lights_reaching_mean"); yo_f64(y, m->lights_reaching_mean);
    yo_key(y, "lights_reaching_p50"); yo_f64(y, m->lights_reaching_p50);
    yo_key(y, "lights_reaching_p99"); yo_f64(y, m->lights_reaching_p99);
    yo_key(y, "lights_reaching_max"); yo_f64(y, m->lights_reaching_max);
    yo_key(y, "coverage"); yo_f64(y, m->coverage);
    yo_key(y, "warning"); yo_str(y, brute ? warning : NULL);
    yo_map_end(y);

    yo_key(y, "pass_plan");
    yo_map_begin(y);
    yo_key(y, "passes");
    yo_seq_begin(y);
    for (size_t i = 0; i < st->plan.npasses; i++) {
        yo_map_begin(y);
        yo_key(y, "name"); yo_str(y, st->plan.pass[i].name);
        yo_key(y, "run"); yo_bool(y, st->plan.pass[i].run);
        yo_key(y, "reason"); yo_str(y, st->plan.pass[i].reason);
        yo_map_end(y);
    }
    yo_seq_end(y);
    yo_key(y, "programs");
    yo_seq_begin(y);
    for (size_t i = 0; i < st->plan.nprograms; i++)
        yo_str(y, st->plan.program[i]);
    yo_seq_end(y);
    yo_key(y, "lighting"); yo_str(y, st->plan.lighting);
    yo_key(y, "targets");
    yo_seq_begin(y);
    for (size_t i = 0; i < st->plan.ntargets; i++) {
        const target_plan_entry *t = &st->plan.target[i];
        yo_map_begin(y);
        yo_key(y, "name"); yo_str(y, t->name);
        yo_key(y, "format"); yo_str(y, t->format);
        yo_key(y, "width"); yo_i64(y, t->width);
        yo_key(y, "height"); yo_i64(y, t->height);
        yo_key(y, "bytes"); yo_i64(y, (int64_t)t->bytes);
        yo_map_end(y);
    }
    yo_seq_end(y);
    yo_key(y, "gbuffer_bytes"); yo_i64(y, (int64_t)st->plan.gbuffer_bytes);
    yo_key(y, "target_bytes"); yo_i64(y, (int64_t)st->plan.target_bytes);
    yo_map_end(y);
    yo_map_end(y);
    return yo_commit(y, err, errlen);
}
