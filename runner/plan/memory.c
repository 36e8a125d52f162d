/* A run's memory: the estimate, the limits, and the diagnosis of a trial that ran out
 * (memory.h says how the estimate is computed). */
#include "runner/plan/memory.h"

#include <ctype.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "renderers/renderer.h"
#include "runner/manifest/params.h"
#include "runner/plan/plan_check.h"
#include "scenes/scene.h"

enum {
    MIB = 1 << 20,
    BASE_RESIDENT = 128 * MIB,   /* a 16x16 run on llvmpipe: 130-136 MiB resident */
    BASE_NULL = 96 * MIB,        /* ... of null, which compiles no program: 88-96 MiB */
    BASE_ADDRESS = 192 * MIB,    /* ... and about 170 MiB of address space beyond the parent */
    INDEX_CAP = 1u << 25,        /* forward_plus.c's PLUS_INDEX_CAP */
};

void memory_format(uint64_t b, char *buf, size_t len)
{
    static const char *unit[] = {"B", "KiB", "MiB", "GiB", "TiB"};
    double v = (double)b;
    int u = 0;
    while (v >= 1024 && u < 4) {
        v /= 1024;
        u++;
    }
    if (u == 0)
        snprintf(buf, len, "%" PRIu64 " B", b);
    else
        snprintf(buf, len, v < 10 ? "%.1f %s" : "%.0f %s", v, unit[u]);
}

static bool is(const char *a, const char *b) { return strcmp(a, b) == 0; }

/* What the estimate takes from a built scene (so that the parent can keep it without
 * the scene): the materials' G-buffer needs, shadow maps, lights, its bytes, and the
 * depth slices of its camera for every clustered.slices. */
typedef struct scene_facts {
    deferred_needs needs;
    uint32_t shadow_layers, nlights, nmeshes;
    uint64_t bytes;
    uint32_t slices[65];
} scene_facts;

static uint64_t scene_of(const scene *sc);

static void facts_of(const scene *sc, scene_facts *f)
{
    memset(f, 0, sizeof *f);
    f->needs = deferred_needs_of(sc);
    f->nlights = sc->nlights_total;
    f->nmeshes = sc->nmeshes;
    for (uint32_t i = 0; i < sc->nlights_total; i++)
        f->shadow_layers += sc->lights[i].shadows && sc->lights[i].type != LIGHT_POINT;
    f->bytes = scene_of(sc);
    for (int k = 1; k <= 64; k++)
        f->slices[k] = renderer_cluster_slices(sc, k);
}

/* Bytes of the targets renderer `kind` (options of q) allocates at w x h, beyond the
 * context's own framebuffer. */
static uint64_t targets_of(const char *kind, const run_params *q, int w, int h, int msaa_log2,
                           const scene_facts *sc)
{
    const renderer_impl *impl = renderer_kind_find(kind);
    if (!impl || impl->no_base)   /* null: no target of its own */
        return 0;
    const uint64_t px = (uint64_t)w * (uint64_t)h, s = 1u << msaa_log2;
    const uint64_t hdr = q->hdr == HDR_RGBA32F ? 16 : 8, depth = 4;
    uint64_t b = (hdr + depth) * s * px + (s > 1 ? hdr * px : 0);
    renderer_options ro = {0};
    params_to_renderer_options(q, &ro);
    ro.msaa = (int)s;
    /* what the design makes beyond the base (renderer_impl.own_bytes) */
    renderer_estimate e = {.opts = &ro, .pixels = px, .samples = s, .hdr_bytes = hdr,
                           .scene = sc != NULL, .needs = sc ? sc->needs : (deferred_needs){0},
                           .scene_bytes = sc ? sc->bytes : 0, .nmeshes = sc ? sc->nmeshes : 0};
    b += renderer_own_bytes(kind, &e);
    if (q->aa == AA_EDGE)
        b += (hdr + depth) * px;   /* edge AA's output and single-sample depth */
    if (sc && q->shadows != SHADOWS_OFF)
        b += (uint64_t)sc->shadow_layers * renderer_shadow_layer_bytes();
    return b;
}

/* The light lists of the renderers with a light grid (whose design for q reads tiles.*:
 * deferred-lighting's only with deferred_lighting.lights: tiled) at w x h: heads (offset
 * and count) and indices, as tiled/grid.c sizes them, on the GPU and read back;
 * clustered (reads clustered.*) per cluster; with tiles.levels: 2 the big tiles' heads
 * and indices too (tiled/coarse.c: every light in every big tile); zbin (reads zbin.*)
 * its sorted lights, bins and tile masks. */
static uint64_t lists_of(const char *kind, const run_params *q, int w, int h,
                         const scene_facts *sc, uint64_t *untouched)
{
    renderer_options ro = {0};
    params_to_renderer_options(q, &ro);
    if (!renderer_design_reads(kind, &ro, "tiles.size"))
        return 0;
    const uint64_t tile = 8u << q->tile_size;
    uint64_t cells = ((uint64_t)w + tile - 1) / tile * (((uint64_t)h + tile - 1) / tile);
    if (param_read_by(param_find("clustered.slices"), kind)) {
        uint32_t k = q->clustered_slices >= 1 && q->clustered_slices <= 64 ? q->clustered_slices : 24;
        uint32_t slices = sc ? sc->slices[k] : 0;
        cells *= slices ? slices : 1024;
    }
    uint64_t n = sc ? sc->nlights : MAX_LIGHTS;
    uint64_t heads = 2 * cells;   /* opaque cells, then the translucent lists */
    uint64_t cap = heads * (q->max_lights_per_tile ? q->max_lights_per_tile : (n ? n : 1));
    if (cap > INDEX_CAP)
        cap = INDEX_CAP;
    /* the indices are mapped twice, but only about one copy's pages are ever touched
     * (clustered, 4096 lights at 256x256: 300 MiB peak, 457 MiB estimated with both) */
    if (untouched)
        *untouched += cap * 4;
    uint64_t coarse = 0;
    if (q->tile_levels == 2 && param_read_by(param_find("tiles.levels"), kind)) {
        uint64_t side = q->coarse_size ? q->coarse_size : 64;
        uint64_t big = ((uint64_t)w + side - 1) / side * (((uint64_t)h + side - 1) / side);
        uint64_t entries = big * (n ? n : 1);
        coarse = big * 16 + (entries < INDEX_CAP ? entries : INDEX_CAP) * 4;
    }
    uint64_t zbin = 0;
    if (param_read_by(param_find("zbin.bins"), kind)) {
        /* zbin (tiled/zbin.c): its tiles hold masks, not lists (only the translucent
         * lists take indices), and the sorted lights, their sort keys, the bins and
         * tiles x ceil(lights / 32) mask words besides */
        uint64_t bins = q->zbin_bins ? q->zbin_bins : 1024, tcap = cells * (n ? n : 1);
        cap = tcap < INDEX_CAP ? tcap : INDEX_CAP;
        zbin = n * (renderer_light_bytes() + 8) + 16 + bins * 4 + cells * ((n + 31) / 32) * 4;
    }
    return 2 * (heads * 8 + cap * 4) + coarse + n * renderer_light_bytes() * 2 + zbin;
}

/* llvmpipe's binning of one frame's draws, which it keeps until the frame ends: a
 * draw call costs about 32 KiB at 64x64 and 12 KiB more each time the pixels quadruple
 * (measured on deferred's light volumes: 32, 44, 54, 68 KiB a draw at 64x64 .. 512x512,
 * 8205 draws). The draws that grow with the lights: deferred and deferred-lighting
 * draw each light's volume (and mark its stencil); forward-mpml draws the meshes each
 * light reaches, counted as half of them (shapes: 3.4 draws a light, 45-64 KiB each at
 * 128x128, dearer than a volume: more triangles). */
static uint64_t draws_of(const char *kind, int w, int h, const scene_facts *sc)
{
    if (!sc)
        return 0;
    renderer_estimate e = {.scene = true, .needs = sc->needs, .scene_bytes = sc->bytes,
                           .nmeshes = sc->nmeshes};
    uint64_t per_light = renderer_draws_per_light(kind, &e);
    uint64_t px = (uint64_t)w * (uint64_t)h, kib = 32;
    for (uint64_t q = 4096 * 4; q <= px; q *= 4)
        kib += 12;
    return per_light * sc->nlights * kib * 1024;
}

static uint64_t scene_of(const scene *sc)
{
    if (!sc)
        return 0;
    uint64_t b = (uint64_t)sc->nlights_total * (sizeof(scene_light) + 2 * renderer_light_bytes());
    for (uint32_t i = 0; i < sc->nmeshes; i++)
        b += 2 * ((uint64_t)sc->meshes[i].nvertices *
                      (sizeof(mesh_vertex) + (sc->meshes[i].colors ? 4 : 0) +
                       (sc->meshes[i].uv2 ? 8 : 0) + (sc->meshes[i].joints ? 24 : 0)) +
                  (uint64_t)sc->meshes[i].nindices * 4);
    for (uint32_t i = 0; i < sc->ntextures; i++)   /* ours, and the driver's with mipmaps */
        b += (uint64_t)sc->textures[i].width * sc->textures[i].height *
             sc->textures[i].channels * 7 / 3;
    return b;
}

static void estimate(const run_params *p, const scene_facts *sc, memory_estimate *out)
{
    memset(out, 0, sizeof *out);
    const int w = p->width, h = p->height;
    const uint64_t px = (uint64_t)w * (uint64_t)h;
    out->targets = 8 * px + targets_of(p->renderer, p, w, h, p->msaa, sc);
    uint64_t untouched = 0;
    out->lists = lists_of(p->renderer, p, w, h, sc, &untouched);
    /* single-threaded llvmpipe (measure.rasterizer) rasterizes each binned scene as it
     * fills rather than queueing a frame's: no binning held across draws (tests/cli/
     * memory_peak.sh: 4,096 deferred lights at 128x128 peak at 181 MiB, not 487) */
    const bool binning = !params_rasterizer_single(p);
    out->draws = binning ? draws_of(p->renderer, w, h, sc) : 0;
    out->scene = sc ? sc->bytes : 0;
    /* screenshots and error images: RGBA8 and float RGBA copies of the frame; else the
     * first measured frame's check (run_trial.c's check_shown) reads an RGBA8 copy, in
     * every renderer with a depth target */
    const renderer_impl *ri = renderer_kind_find(p->renderer);
    if (p->nscreenshots || p->error_renderer[0])
        out->readback = px * (4 + 16);
    else if (ri && !ri->no_base)
        out->readback = px * 4;
    if (p->error_renderer[0]) {
        run_params rp;
        params_reference(p, &rp);
        snprintf(rp.renderer, sizeof rp.renderer, "%s", p->error_renderer);
        const uint64_t k = p->error_supersample ? p->error_supersample : 1;
        const int kw = (int)(k * (uint64_t)w), kh = (int)(k * (uint64_t)h);
        const uint64_t kpx = (uint64_t)kw * (uint64_t)kh;
        out->targets += targets_of(rp.renderer, &rp, kw, kh, rp.msaa, sc) +
                        (k > 1 ? 8 * kpx : 0);   /* its own framebuffer at K W x K H */
        out->lists += lists_of(rp.renderer, &rp, kw, kh, sc, &untouched);
        out->draws += binning ? draws_of(rp.renderer, kw, kh, sc) : 0;
        out->readback += (k > 1 ? 16 * kpx : 0) + 3 * 16 * px;   /* its HDR, the compared */
    }
    const uint64_t v = out->targets + out->lists + out->scene + out->readback;
    out->base = ri && ri->no_base ? BASE_NULL : BASE_RESIDENT;
    out->resident = out->base + (v - untouched) * 5 / 4 + out->draws;
    out->address_space = BASE_ADDRESS + v * 5 / 2 + out->draws;
    char t[32], l[32], s[32], r[32];
    memory_format(out->targets, t, sizeof t);
    memory_format(out->lists, l, sizeof l);
    memory_format(out->scene, s, sizeof s);
    memory_format(out->readback, r, sizeof r);
    int n = snprintf(out->what, sizeof out->what, "targets %s at %dx%d", t, w, h);
    if (p->msaa && n > 0 && (size_t)n < sizeof out->what)
        n += snprintf(out->what + n, sizeof out->what - (size_t)n, " x %dx MSAA", 1 << p->msaa);
    if (p->error_renderer[0] && n > 0 && (size_t)n < sizeof out->what)
        n += snprintf(out->what + n, sizeof out->what - (size_t)n, " and the reference's at %" PRIu64 "x%" PRIu64,
                      (uint64_t)w * (p->error_supersample ? p->error_supersample : 1),
                      (uint64_t)h * (p->error_supersample ? p->error_supersample : 1));
    if (n > 0 && (size_t)n < sizeof out->what)
        snprintf(out->what + n, sizeof out->what - (size_t)n,
                 ", light lists %s, scene %s, read-back %s", l, s, r);
}

static const scene_facts *cached_facts(const run_params *p, bool build);

void memory_estimate_run(const run_params *p, const scene *sc, memory_estimate *out)
{
    scene_facts f;
    if (sc)
        facts_of(sc, &f);
    estimate(p, sc ? &f : cached_facts(p, false), out);
}

/* ---- limits */

/* What follows "FIELD:" on the first line of a /proc file (status, meminfo) that
 * starts so, read into line (len bytes); NULL when there is none or no such file. */
static const char *field_text(const char *path, const char *field, char *line, size_t len)
{
    FILE *f = fopen(path, "re");
    if (!f)
        return NULL;
    const char *v = NULL;
    size_t fl = strlen(field);
    while (!v && fgets(line, (int)len, f))
        if (strncmp(line, field, fl) == 0 && line[fl] == ':')
            v = line + fl + 1;
    fclose(f);
    return v;
}

long memory_proc_kb(int pid, const char *field)
{
    char path[64];
    if (pid > 0)
        snprintf(path, sizeof path, "/proc/%d/status", pid);
    else
        snprintf(path, sizeof path, "/proc/self/status");
    char line[256];
    const char *v = field_text(path, field, line, sizeof line);
    return v ? strtol(v, NULL, 10) : -1;
}

/* A cgroup limit file's value: a number of bytes; "max" or v1's "no limit" (page
 * counter's maximum, about 2^63) are unlimited (UINT64_MAX); unreadable: 0. */
static uint64_t read_limit(const char *path)
{
    FILE *f = fopen(path, "re");
    if (!f)
        return 0;
    char buf[64] = "";
    bool got = fgets(buf, sizeof buf, f) != NULL;
    fclose(f);
    if (!got)
        return 0;
    if (strncmp(buf, "max", 3) == 0)
        return UINT64_MAX;
    char *end;
    unsigned long long v = strtoull(buf, &end, 10);
    if (end == buf)
        return 0;
    return v >= (1ull << 62) ? UINT64_MAX : (uint64_t)v;
}

/* The smallest memory limit of this process's cgroup and its ancestors, less what the
 * cgroup uses now; UINT64_MAX when none. */
static uint64_t cgroup_room(char *which, size_t len)
{
    FILE *f = fopen("/proc/self/cgroup", "re");
    if (!f)
        return UINT64_MAX;
    char line[4096], path[4096] = "";
    const char *root = NULL, *lim = NULL, *use = NULL;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        char *c1 = strchr(line, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
        if (!c2)
            continue;
        *c1 = *c2 = 0;
        const char *ctrl = c1 + 1;
        bool v1 = false;
        for (const char *t = ctrl; (t = strstr(t, "memory")); t += 6)
            if ((t == ctrl || t[-1] == ',') && (t[6] == 0 || t[6] == ','))
                v1 = true;
        if (v1) {
            snprintf(path, sizeof path, "%s", c2 + 1);
            root = "/sys/fs/cgroup/memory", lim = "memory.limit_in_bytes";
            use = "memory.usage_in_bytes";
            break;
        }
        if (strcmp(line, "0") == 0 && !ctrl[0] && !root) {
            snprintf(path, sizeof path, "%s", c2 + 1);
            root = "/sys/fs/cgroup", lim = "memory.max", use = "memory.current";
        }
    }
    fclose(f);
    if (!root)
        return UINT64_MAX;
    uint64_t best = UINT64_MAX;
    for (;;) {   /* the cgroup, then each ancestor: the tightest one binds */
        char p[4400];
        snprintf(p, sizeof p, "%s%s/%s", root, strcmp(path, "/") == 0 ? "" : path, lim);
        uint64_t l = read_limit(p);
        if (l && l != UINT64_MAX) {
            snprintf(p, sizeof p, "%s%s/%s", root, strcmp(path, "/") == 0 ? "" : path, use);
            uint64_t u = read_limit(p);
            if (u == UINT64_MAX)
                u = 0;
            uint64_t room = l > u ? l - u : 0;
            if (room < best) {
                best = room;
                char m[32];
                memory_format(l, m, sizeof m);
                snprintf(which, len, "the memory cgroup's %s %s, less what it uses", lim, m);
            }
        }
        char *slash = strrchr(path, '/');
        if (!slash || slash == path)
            break;
        *slash = 0;
    }
    return best;
}

static uint64_t meminfo_kb(const char *field)
{
    char line[256];
    const char *v = field_text("/proc/meminfo", field, line, sizeof line);
    return v ? strtoull(v, NULL, 10) : UINT64_MAX;
}

/* Two runs have the same scene facts when they build the same scene and camera and shape
 * it alike (run_params_shape_scene). */
static bool same_scene(const run_params *a, const run_params *b)
{
    return run_params_same_scene(a, b) && a->translucency == b->translucency &&
           a->shading_model == b->shading_model && a->environment == b->environment &&
           a->environment_intensity == b->environment_intensity;
}

/* The facts of p's scene, built without GL in this process once per scene and camera
 * (a sweep's trials and renderers share them: canyon takes a second to build); NULL when
 * it does not build, or when it is not built yet and `build` is false. */
static const scene_facts *cached_facts(const run_params *p, bool build)
{
    enum { SLOTS = 8 };
    static struct {
        bool used, built;
        run_params key;
        scene_facts facts;
    } cache[SLOTS];
    static unsigned next;
    for (unsigned i = 0; i < SLOTS; i++)
        if (cache[i].used && same_scene(&cache[i].key, p))
            return cache[i].built ? &cache[i].facts : NULL;
    if (!build)
        return NULL;
    unsigned i = next++ % SLOTS;
    char err[512];
    scene_file_options fo;
    scene_source src;
    run_params_scene(p, &fo, &src);
    scene *sc = scene_build_source(&src, &p->lights, p->width, p->height, err, sizeof err);
    cache[i].used = true;
    cache[i].key = *p;
    cache[i].built = sc && scene_set_camera(sc, &p->camera, err, sizeof err);
    if (cache[i].built) {
        run_params_shape_scene(p, sc);   /* the G-buffer's needs follow the model */
        facts_of(sc, &cache[i].facts);
    }
    scene_destroy(sc);
    return cache[i].built ? &cache[i].facts : NULL;
}

bool memory_check_run(const run_params *p, char *msg, size_t len)
{
    const char *env = getenv("SHADESWEEP_MEMORY_CHECK");
    if (env && strcmp(env, "off") == 0)
        return true;
    const scene_facts *f = cached_facts(p, true);
    if (!f)
        return true;   /* the scene does not build: the trial says why */
    memory_estimate e;
    estimate(p, f, &e);

    char need[32], room[32], src_text[200] = "", draws[64] = "";
    if (e.draws) {
        char d[32];
        memory_format(e.draws, d, sizeof d);
        snprintf(draws, sizeof draws, " + %s for its draws", d);
    }
    struct rlimit rl;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) {
        long mapped = memory_proc_kb(0, "VmSize");
        uint64_t have = mapped > 0 ? (uint64_t)mapped * 1024 : 0;
        uint64_t left = (uint64_t)rl.rlim_cur > have ? (uint64_t)rl.rlim_cur - have : 0;
        if (e.address_space > left) {
            char lim[32], m[32];
            memory_format(e.address_space, need, sizeof need);
            memory_format(left, room, sizeof room);
            memory_format((uint64_t)rl.rlim_cur, lim, sizeof lim);
            memory_format(have, m, sizeof m);
            snprintf(msg, len, "needs about %s of address space (%s; 2.5 times that + %d MiB "
                     "for the driver%s), the process may map %s more (RLIMIT_AS %s, %s mapped "
                     "already)", need, e.what, BASE_ADDRESS / MIB, draws, room, lim, m);
            return false;
        }
    }
    uint64_t cg = cgroup_room(src_text, sizeof src_text);
    uint64_t avail = meminfo_kb("MemAvailable"), swap = meminfo_kb("SwapFree");
    uint64_t mem = avail == UINT64_MAX ? UINT64_MAX
                                       : (avail + (swap == UINT64_MAX ? 0 : swap)) * 1024;
    uint64_t left = cg < mem ? cg : mem;
    if (left == UINT64_MAX || e.resident <= left)
        return true;
    if (mem <= cg)
        snprintf(src_text, sizeof src_text, "/proc/meminfo MemAvailable + SwapFree");
    memory_format(e.resident, need, sizeof need);
    memory_format(left, room, sizeof room);
    snprintf(msg, len, "needs about %s (%s; 1.25 times that + %d MiB for the driver%s), the "
             "process may use %s (%s)", need, e.what, (int)(e.base / MIB), draws, room, src_text);
    return false;
}

/* ---- after the fact */

static bool says_out_of_memory(const char *text)
{
    static const char *words[] = {"GL_OUT_OF_MEMORY", "out of memory", "Out of memory",
                                  "Cannot allocate memory", "bad_alloc", NULL};
    for (int i = 0; words[i]; i++)
        if (strstr(text, words[i]))
            return true;
    return false;
}

bool memory_explain(const char *status, const char *message, long peak_vm_kb,
                    long peak_rss_kb, char *note, size_t len)
{
    note[0] = 0;
    if (strncmp(status, "failed:", 7) != 0)
        return false;
    const char *why = status + 7;
    if (is(why, "oom") || is(why, "memory") || is(why, "timeout") || is(why, "interrupted") ||
        is(why, "error") || is(why, "nonfinite") || is(why, "overflow") || is(why, "empty"))
        return false;
    char peaks[160] = "", a[32], b[32];
    uint64_t vm = peak_vm_kb > 0 ? (uint64_t)peak_vm_kb * 1024 : 0;
    uint64_t rss = peak_rss_kb > 0 ? (uint64_t)peak_rss_kb * 1024 : 0;
    bool near = false;
    struct rlimit rl;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY && vm) {
        memory_format(vm, a, sizeof a);
        memory_format((uint64_t)rl.rlim_cur, b, sizeof b);
        snprintf(peaks, sizeof peaks, "peak address space %s of RLIMIT_AS %s", a, b);
        near = vm >= (uint64_t)rl.rlim_cur / 5 * 4;
    }
    char which[200] = "";
    uint64_t cg = cgroup_room(which, sizeof which);
    if (cg != UINT64_MAX && rss) {
        /* the room left now, plus what the dead child held, is about its limit */
        memory_format(rss, a, sizeof a);
        memory_format(cg + rss, b, sizeof b);
        size_t n = strlen(peaks);
        snprintf(peaks + n, sizeof peaks - n, "%speak resident %s of the cgroup's %s",
                 n ? ", " : "", a, b);
        near = near || rss >= (cg + rss) / 5 * 4;
    } else if (rss) {
        memory_format(rss, a, sizeof a);
        size_t n = strlen(peaks);
        snprintf(peaks + n, sizeof peaks - n, "%speak resident %s", n ? ", " : "", a);
    }
    if (!near && !says_out_of_memory(message))
        return false;
    snprintf(note, len, "memory is the likely cause%s%s", peaks[0] ? ": " : "", peaks);
    return true;
}
