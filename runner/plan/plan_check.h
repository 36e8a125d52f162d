#pragma once
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "runner/manifest/diag.h"
#include "runner/manifest/manifest.h"
#include "scenes/scene.h"

/* Refuses a plan some of whose runs would fail, or mean nothing, for reasons known
 * before any GL: every problem in d (at most a few), false if any. */
bool plan_check(const experiment *e, const plan *p, diag_list *d);

/* first[k]: the first run of the plan whose key equals run k's (k itself when none
 * before it does). Sorted by hash, n log n; runs of one hash are told apart by `same`
 * against the few distinct keys of that hash (a NULL same: by the hash alone). False
 * when out of memory. */
bool plan_first_of_key(const plan *p, uint64_t (*hash)(const run_params *),
                       bool (*same)(const run_params *, const run_params *), size_t *first);

/* Prints (one line each) what may make runs fail on some GL but not on others, known
 * before any GL: forward-spml's uniform block beyond the size every GL guarantees.
 * list, validate --no-gl, and validate and run without a GL context print them; they
 * refuse nothing. */
void plan_warnings(const experiment *e, const plan *p, FILE *out);
/* Whether some run is past what every GL guarantees (what plan_warnings names): only
 * then can a GL's own limits refuse a run. */
bool plan_needs_gl(const plan *p);
/* The same limits on the GL gi describes (run_probe_gl: what run would get): one error
 * for each kind of run past them, naming the value, the limit, the first run. */
struct gl_info;
bool plan_check_gl(const experiment *e, const plan *p, const struct gl_info *gi, diag_list *d);

/* Where run p's scene comes from: the catalog, or its file (fo is filled and
 * src->file points at it; both must outlive src). */
void run_params_scene(const run_params *p, scene_file_options *fo, scene_source *src);
/* Whether runs a and b build the same scene, lights and camera from the same source
 * (before run_params_shape_scene: translucency and shading.model are not compared). */
bool run_params_same_scene(const run_params *a, const run_params *b);
/* What the run's keys change in its built scene: translucency: opaque (returns how many
 * materials it made opaque) and shading.model (scene_set_shading). */
uint32_t run_params_shape_scene(const run_params *p, scene *s);
