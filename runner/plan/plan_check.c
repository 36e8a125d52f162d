/* What would make every run of a plan fail or mean nothing, refused before anything
 * is written (validate, list and run call plan_check after plan_expand): times
 * beyond a run's end, an attenuation that never falls off, and every scene and
 * camera the plan builds (scenes/ has no GL: a scene that cannot be built, such as
 * placement scene on a scene without authored lights or near not below far, fails
 * here with the message scene_build or scene_set_camera gives); and the runs past
 * a GL's limits (plan_check_gl: the context run would get) or, without one, past what
 * every GL has (plan_warnings). */
#include "runner/plan/plan_check.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/gl/context.h"
#include "renderers/renderer.h"
#include "runner/manifest/hash.h"
#include "runner/manifest/params.h"
#include "scenes/scene.h"

/* The last schedule time a run surely reaches, or -1 when only the run knows it
 * (a wall clock counting frames, a fixed clock counting seconds); `open` when the
 * end itself is not reached (a wall clock stops at its duration). */
static double schedule_end(const run_params *p, bool *open)
{
    *open = false;
    if (p->clock == RUN_CLOCK_FIXED && p->duration.kind == SPAN_FRAMES)
        return (double)(p->duration.frames - 1) * p->step;
    if (p->clock == RUN_CLOCK_WALL && p->duration.kind == SPAN_SECONDS) {
        *open = true;
        return p->duration.seconds;
    }
    return -1;
}

static void describe_duration(const run_params *p, char *out, size_t len)
{
    if (p->duration.kind == SPAN_FRAMES)
        snprintf(out, len, "{frames: %" PRIu32 "} at step %g s: the last frame is at %g s",
                 p->duration.frames, p->step, (double)(p->duration.frames - 1) * p->step);
    else
        snprintf(out, len, "{seconds: %g}: frames start before %g s", p->duration.seconds,
                 p->duration.seconds);
}

static bool check_times(const experiment *e, const run_spec *r, const char *key,
                        const double *t, size_t n, diag_list *d)
{
    bool open;
    double end = schedule_end(&r->p, &open);
    if (end < 0)
        return true;
    for (size_t i = 0; i < n; i++)
        if (open ? t[i] >= end : t[i] > end) {
            char dur[160];
            describe_duration(&r->p, dur, sizeof dur);
            diag_add(d, e->path, 0, 0, key,
                     "expected a time the run reaches (duration %s), found %g in run %s "
                     "(%s)", dur, t[i], r->id, r->p.renderer);
            return false;
        }
    return true;
}

void run_params_scene(const run_params *p, scene_file_options *fo, scene_source *src)
{
    *fo = (scene_file_options){.path = p->scene_file, .scale = p->scene_scale,
                               .fit = p->scene_scale == 0, .up = (scene_up)p->scene_up,
                               .camera = p->scene_camera, .allow_outside = p->scene_outside,
                               .lights_around = p->scene_around,
                               .phong = p->shading_model == RUN_SHADING_MODEL_PHONG,
                               .max_image_bytes = p->scene_max_image_bytes,
                               .max_triangles = p->scene_max_triangles,
                               .max_vertices = p->scene_max_vertices};
    *src = (scene_source){.name = p->scene, .file = p->scene_file[0] ? fo : NULL};
}

uint32_t run_params_shape_scene(const run_params *p, scene *s)
{
    uint32_t opaque = p->translucency == RUN_TRANSLUCENCY_OPAQUE ? scene_make_opaque(s) : 0;
    shading_model m = p->shading_model == RUN_SHADING_MODEL_PHONG ? SHADING_PHONG
                      : p->shading_model == RUN_SHADING_MODEL_PBR ? SHADING_PBR
                                                                : scene_own_shading(s);
    scene_set_shading(s, m);   /* a freshly built scene is Phong's: never refused */
    bool sky = p->environment == RUN_ENVIRONMENT_SKY ||
               (p->environment == RUN_ENVIRONMENT_SCENE && s->from_file);
    scene_set_environment(s, sky ? ENVIRONMENT_SKY : ENVIRONMENT_NONE,
                          p->environment_intensity);
    return opaque;
}

static uint64_t hash_str(uint64_t h, const char *s)
{
    return fnv1a64_update(h, s, strlen(s) + 1);
}

/* Two runs build their scenes from one source when these agree (what scene_probe_build
 * takes), and the same scene and camera when run_params_same_scene also holds; each
 * key's hash agrees where the comparison does. */
static bool same_source(const run_params *a, const run_params *b)
{
    return strcmp(a->scene, b->scene) == 0 && strcmp(a->scene_file, b->scene_file) == 0 &&
           a->scene_scale == b->scene_scale && a->scene_up == b->scene_up &&
           strcmp(a->scene_camera, b->scene_camera) == 0 && a->scene_around == b->scene_around;
}

static uint64_t source_hash(const run_params *a)
{
    uint64_t h = hash_str(FNV1A64_OFFSET_BASIS, a->scene);
    h = hash_str(h, a->scene_file);
    float scale = a->scene_scale == 0 ? 0.0f : a->scene_scale;   /* -0 == 0 */
    h = fnv1a64_update(h, &scale, sizeof scale);
    h = fnv1a64_update(h, &a->scene_up, sizeof a->scene_up);
    h = fnv1a64_update(h, &a->scene_around, sizeof a->scene_around);
    return hash_str(h, a->scene_camera);
}

bool run_params_same_scene(const run_params *a, const run_params *b)
{
    return same_source(a, b) && a->width == b->width && a->height == b->height &&
           memcmp(&a->lights, &b->lights, sizeof a->lights) == 0 &&
           memcmp(&a->camera, &b->camera, sizeof a->camera) == 0;
}

static uint64_t scene_hash(const run_params *a)
{
    uint64_t h = source_hash(a);
    h = fnv1a64_update(h, &a->width, sizeof a->width);
    h = fnv1a64_update(h, &a->height, sizeof a->height);
    h = fnv1a64_update(h, &a->lights, sizeof a->lights);
    return fnv1a64_update(h, &a->camera, sizeof a->camera);
}

typedef struct key_ref {
    uint64_t h;
    size_t k;
} key_ref;

static int key_ref_cmp(const void *x, const void *y)
{
    const key_ref *a = x, *b = y;
    if (a->h != b->h)
        return a->h < b->h ? -1 : 1;
    return a->k < b->k ? -1 : a->k > b->k;
}

bool plan_first_of_key(const plan *p, uint64_t (*hash)(const run_params *),
                       bool (*same)(const run_params *, const run_params *), size_t *first)
{
    size_t n = p->nruns ? p->nruns : 1;
    key_ref *refs = malloc(n * sizeof *refs);
    size_t *reps = malloc(n * sizeof *reps);   /* the distinct keys of the current hash */
    if (!refs || !reps) {
        free(refs);
        free(reps);
        return false;
    }
    for (size_t k = 0; k < p->nruns; k++)
        refs[k] = (key_ref){hash(&p->runs[k].p), k};
    qsort(refs, p->nruns, sizeof *refs, key_ref_cmp);
    size_t nreps = 0;
    for (size_t i = 0; i < p->nruns; i++) {
        if (i == 0 || refs[i].h != refs[i - 1].h)
            nreps = 0;
        size_t k = refs[i].k, r = 0;
        while (r < nreps && same && !same(&p->runs[reps[r]].p, &p->runs[k].p))
            r++;
        if (r == nreps)
            reps[nreps++] = k;   /* in index order within the hash: k is the first */
        first[k] = reps[r];
    }
    free(refs);
    free(reps);
    return true;
}

/* clustered's depth slices for run r's renderer (or its error reference: what) over the
 * view v, refused past what the light grid holds with the message the grid gives at
 * prepare (renderers/tiled/grid.c), here before any run starts. */
static void check_slices(const experiment *e, const run_spec *r, const run_params *q,
                         const scene_view *v, const char *what, diag_list *d)
{
    if (!param_read_by(param_find("clustered.slices"), q->renderer))   /* either design */
        return;
    char err[512];
    if (!renderer_cluster_slices_ok(q->renderer, v->proj11, v->znear, v->zfar,
                                    (int)q->clustered_slices, err, sizeof err))
        diag_add(d, e->path, 0, 0, "clustered.slices", "expected depth slices the light grid "
                 "holds, found: %s (run %s%s)", err, r->id, what);
}

bool plan_check(const experiment *e, const plan *p, diag_list *d)
{
    size_t nerr = d->n;
    for (size_t k = 0; k < p->nruns && d->n - nerr < 8; k++) {
        const run_spec *r = &p->runs[k];
        const run_params *q = &r->p;
        check_times(e, r, "error.at", q->error_at, q->nerror_at, d);
        check_times(e, r, "outputs.screenshots", q->screenshots, q->nscreenshots, d);
        if (q->lights.attenuation == ATTENUATION_QUADRATIC && q->lights.quadratic[0] == 0 &&
            q->lights.quadratic[1] == 0 && q->lights.quadratic[2] == 0)
            diag_add(d, e->path, 0, 0, "lights.quadratic",
                     "expected a, b and c not all 0 (1/(a d^2 + b d + c) would be infinite), "
                     "found all 0 in run %s", r->id);
    }
    if (d->n - nerr >= 8 || p->nruns == 0)
        return d->n == nerr;
    /* every distinct scene and camera of the plan, as the runs would build them without
     * GL (the lights are placed too, so a radius that makes grid neighbours overlap
     * fails here): each source is built once (a probe), and each distinct set of lights
     * and camera is checked against its source's probe, with the messages
     * scene_build_source and scene_set_camera give */
    size_t *scene_first = malloc(p->nruns * sizeof *scene_first);
    size_t *source_first = malloc(p->nruns * sizeof *source_first);
    scene_probe **probes = calloc(p->nruns, sizeof *probes);   /* at a source's first run */
    scene_view *views = malloc(p->nruns * sizeof *views);     /* at a scene's first run */
    bool *viewed = calloc(p->nruns, sizeof *viewed);
    char (*probe_err)[512] = NULL;
    bool ok = scene_first && source_first && probes && views && viewed &&
              plan_first_of_key(p, scene_hash, run_params_same_scene, scene_first) &&
              plan_first_of_key(p, source_hash, same_source, source_first);
    if (!ok) {
        diag_add(d, e->path, 0, 0, "", "expected a plan that fits in memory, found no memory left");
        goto done;
    }
    for (size_t k = 0; k < p->nruns && d->n - nerr < 8; k++) {
        if (scene_first[k] != k)
            continue;
        const run_params *q = &p->runs[k].p;
        size_t s = source_first[k];
        char err[512] = "";
        if (s == k) {
            scene_file_options fo;
            scene_source src;
            run_params_scene(q, &fo, &src);
            probes[k] = scene_probe_build(&src, err, sizeof err);
            if (!probes[k]) {
                /* kept for this source's other runs: the message each would get */
                if (!probe_err && !(probe_err = calloc(p->nruns, sizeof *probe_err))) {
                    diag_add(d, e->path, 0, 0, "", "expected a plan that fits in memory, "
                             "found no memory left");
                    goto done;
                }
                snprintf(probe_err[k], sizeof probe_err[k], "%s", err);
            }
        }
        bool built = probes[s] != NULL;
        if (!built)
            snprintf(err, sizeof err, "%s", probe_err[s]);
        if (!built || !scene_probe_check(probes[s], &q->lights, &q->camera, q->width,
                                         q->height, &views[k], err, sizeof err))
            diag_add(d, e->path, 0, 0, "scene", "expected a scene the runs can render, found: %s "
                     "(run %s)", err, p->runs[k].id);
        else
            viewed[k] = true;
    }
    /* the renderers' limits on a view: clustered's depth slices (the reference renders
     * the run's scene, so its view) */
    for (size_t k = 0; k < p->nruns && d->n - nerr < 8; k++) {
        if (!viewed[scene_first[k]])
            continue;
        const run_params *q = &p->runs[k].p;
        check_slices(e, &p->runs[k], q, &views[scene_first[k]], "", d);
        if (q->error_renderer[0] && d->n - nerr < 8) {
            run_params rp;
            params_reference(q, &rp);
            snprintf(rp.renderer, sizeof rp.renderer, "%s", q->error_renderer);
            check_slices(e, &p->runs[k], &rp, &views[scene_first[k]],
                         "'s error.reference.renderer", d);
        }
    }
done:
    if (probes)
        for (size_t k = 0; k < p->nruns; k++)
            scene_probe_destroy(probes[k]);
    free(probes);
    free(views);
    free(viewed);
    free(probe_err);
    free(scene_first);
    free(source_first);
    return d->n == nerr;
}

/* What every GL 4.5 core context has at least (the specification's table 23.64,
 * "Implementation dependent values"): GL_MAX_UNIFORM_BLOCK_SIZE 16384 bytes,
 * GL_MAX_SAMPLES 4, GL_MAX_RENDERBUFFER_SIZE and GL_MAX_TEXTURE_SIZE 16384. */
#define GL_GUARANTEED_UNIFORM_BLOCK_BYTES 16384
#define GL_GUARANTEED_SAMPLES 4
#define GL_GUARANTEED_SIZE 16384

/* The runs past one limit: how many, the first's id, the largest value asked. */
typedef struct beyond {
    size_t n;
    const char *first;
    uint64_t most;
    uint64_t limit;            /* what the first run's renderer holds */
} beyond;

static void note_beyond(beyond *b, const run_spec *r, uint64_t v, uint64_t limit)
{
    if (!b->n++) {
        b->first = r->id;
        b->limit = limit;
    }
    if (v > b->most)
        b->most = v;
}

/* What a GL holds: the bytes of a uniform block (the renderers' lights in it:
 * renderer_max_lights), samples a pixel, pixels a framebuffer's side. */
typedef struct gl_holds {
    int uniform_block;
    uint64_t samples, side;
} gl_holds;

/* The runs past each of `holds`: forward-spml with forward.light_buffer: uniform holds
 * max_uniform_block_size / 80 lights (llvmpipe's 65536 bytes hold 819); samples and
 * sizes count the error reference's too (its lights come from a storage buffer past
 * the block: runner/trial/run_setup.c). */
static void find_beyond(const plan *p, const gl_holds *holds, beyond *lights, beyond *samples,
                        beyond *size)
{
    *lights = *samples = *size = (beyond){0};
    for (size_t k = 0; k < p->nruns; k++) {
        const run_spec *r = &p->runs[k];
        const run_params *q = &r->p;
        renderer_options ro = {0};
        params_to_renderer_options(q, &ro);
        uint32_t held = renderer_max_lights(q->renderer, &ro, holds->uniform_block);
        if (q->lights.placement != PLACEMENT_SCENE && q->lights.count.max > held)
            note_beyond(lights, r, q->lights.count.max, held);
        unsigned msaa = 1u << q->msaa, ref_msaa = q->error_renderer[0] ? 1u << q->error_msaa : 1;
        unsigned most_msaa = msaa > ref_msaa ? msaa : ref_msaa;
        const renderer_impl *impl = renderer_kind_find(q->renderer);
        bool targets = !impl || !impl->no_base;   /* null has none to sample */
        if (targets && most_msaa > holds->samples)
            note_beyond(samples, r, most_msaa, holds->samples);
        uint64_t k_ref = q->error_renderer[0] ? q->error_supersample : 1;
        uint64_t side = (uint64_t)(q->width > q->height ? q->width : q->height) *
                        (k_ref > 1 ? k_ref : 1);
        if (side > holds->side)
            note_beyond(size, r, side, holds->side);
    }
}

static gl_holds guaranteed(void)
{
    return (gl_holds){.uniform_block = GL_GUARANTEED_UNIFORM_BLOCK_BYTES,
                      .samples = GL_GUARANTEED_SAMPLES, .side = GL_GUARANTEED_SIZE};
}

bool plan_needs_gl(const plan *p)
{
    beyond lights, samples, size;
    gl_holds g = guaranteed();
    find_beyond(p, &g, &lights, &samples, &size);
    return lights.n || samples.n || size.n;
}

static int min_int(int a, int b) { return a < b ? a : b; }

/* "16384 in run ID" or "up to 16384 in 3 runs (ID, ...)" */
static const char *found_in(const beyond *b, char *buf, size_t len)
{
    if (b->n == 1)
        snprintf(buf, len, "%" PRIu64 " in run %s", b->most, b->first);
    else
        snprintf(buf, len, "up to %" PRIu64 " in %zu runs (%s, ...)", b->most, b->n, b->first);
    return buf;
}

bool plan_check_gl(const experiment *e, const plan *p, const gl_info *gi, diag_list *d)
{
    size_t nerr = d->n;
    int side = min_int(min_int(gi->max_renderbuffer_size, gi->max_texture_size),
                       min_int(gi->max_viewport_dims[0], gi->max_viewport_dims[1]));
    gl_holds holds = {.uniform_block = gi->max_uniform_block_size,
                      .samples = gi->max_samples > 0 ? (uint64_t)gi->max_samples : 1,
                      .side = side > 0 ? (uint64_t)side : 0};
    beyond lights, samples, size;
    find_beyond(p, &holds, &lights, &samples, &size);
    char found[160];
    if (lights.n)
        diag_add(d, e->path, 0, 0, "forward.light_buffer",
                 "expected at most %" PRIu64 " lights in forward-spml's uniform block on this "
                 "GL (%.200s: GL_MAX_UNIFORM_BLOCK_SIZE %d bytes), found %s; set "
                 "forward.light_buffer: storage or fewer lights", lights.limit, gi->renderer,
                 gi->max_uniform_block_size, found_in(&lights, found, sizeof found));
    if (samples.n)
        diag_add(d, e->path, 0, 0, "msaa",
                 "expected at most %" PRIu64 " samples a pixel on this GL (%.200s: "
                 "GL_MAX_SAMPLES), found %s (the run's or its error reference's)",
                 holds.samples, gi->renderer, found_in(&samples, found, sizeof found));
    if (size.n)
        diag_add(d, e->path, 0, 0, "resolution",
                 "expected a framebuffer at most %" PRIu64 " pixels a side on this GL (%.200s: "
                 "the least of its renderbuffer, texture and viewport sizes), found %s "
                 "(error.reference.supersample included)", holds.side, gi->renderer,
                 found_in(&size, found, sizeof found));
    return d->n == nerr;
}

/* One warning: "PATH: warning: KEY: N runs (ID, ...) ask for BEFORE<most>AFTER, past the
 * GUARANTEE every GL has; they fail where the GL has less (`shadesweep info`: INFO;
 * llvmpipe: LLVMPIPE)" and the way out, if any. Nothing when no run is beyond. */
static void warn_beyond(FILE *out, const char *path, const char *key, const beyond *b,
                        const char *before, const char *after, const char *guarantee,
                        const char *info, const char *llvmpipe, const char *way_out)
{
    if (!b->n)
        return;
    fprintf(out, "%s: warning: %s: %zu run%s (%s%s) ask%s for %s%" PRIu64 "%s, past the %s "
            "every GL has; %s where the GL has less (`shadesweep info`: %s; llvmpipe: %s)%s\n",
            path, key, b->n, b->n == 1 ? "" : "s", b->first, b->n > 1 ? ", ..." : "",
            b->n == 1 ? "s" : "", before, b->most, after, guarantee,
            b->n == 1 ? "it fails" : "they fail", info, llvmpipe, way_out);
}

void plan_warnings(const experiment *e, const plan *p, FILE *out)
{
    /* samples and sizes past the guarantees fail where the context's limits are the
     * least (llvmpipe: 4 samples, 16384) */
    const gl_holds g = guaranteed();
    beyond lights, samples, size;
    find_beyond(p, &g, &lights, &samples, &size);
    const uint32_t sure = (uint32_t)lights.limit;
    char held[96];
    snprintf(held, sizeof held, "%" PRIu32 " lights of the %d bytes", sure,
             GL_GUARANTEED_UNIFORM_BLOCK_BYTES);
    warn_beyond(out, e->path, "forward.light_buffer", &lights, "up to ",
                " lights in forward-spml's uniform block", held, "forward_spml_max_lights",
                "819", "; or set forward.light_buffer: storage");
    warn_beyond(out, e->path, "msaa", &samples, "", " samples a pixel (or their error "
                "reference does)", "4 samples", "max_samples", "4", "");
    warn_beyond(out, e->path, "resolution", &size, "a framebuffer ", " pixels a side "
                "(error.reference.supersample included)", "16384 pixels",
                "max_renderbuffer_size", "16384", "");
}
