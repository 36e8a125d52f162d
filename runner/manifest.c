/* Experiment manifests, schema 1 (manifest.h, DESIGN.md).
 *
 * One table of parameters drives everything: which keys exist at each level,
 * the type, range and default of each, how a value is validated (the same code
 * for a key in the manifest, a sweep value and a default), the canonical text of
 * each run parameter (run_params_kv, hence run ids) and which keys can be swept.
 *
 * >>table     the parameters
 * >>text      canonical numbers, quoting what was found, lists
 * >>scalars   integers, numbers, booleans and strings out of YAML scalars
 * >>values    one parser per parameter type
 * >>checks    what needs the whole manifest: required keys, swept-and-set,
 *             lights placement against count
 * >>load      manifest_load (a file), manifest_load_mem (bytes), experiment_free
 * >>kv        run_params_kv */
#include "runner/manifest.h"

#include <errno.h>
#include <float.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/renderer.h"
#include "runner/hash.h"
#include "runner/sweep_axis.h"
#include "runner/yamldoc.h"
#include "scenes/scene.h"

#define MANIFEST_MAX_BYTES (1u << 20)
#define MAX_SIDE 32768
#define MAX_LIGHTS 1000000u
#define MAX_EVERY 604800.0
#define MAX_AXIS_VALUES 10000

/* Enumerations are stored through their int representation. */
_Static_assert(sizeof(run_clock) == sizeof(int), "enum size");
_Static_assert(sizeof(run_sync) == sizeof(int), "enum size");
_Static_assert(sizeof(light_placement) == sizeof(int), "enum size");
_Static_assert(sizeof(rng_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(attenuation_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(gbuffer_preset) == sizeof(int), "enum size");
_Static_assert(sizeof(gbuffer_position) == sizeof(int), "enum size");
_Static_assert(sizeof(gbuffer_normal) == sizeof(int), "enum size");
_Static_assert(sizeof(light_volume_mode) == sizeof(int), "enum size");

/* >>table */

typedef enum ptype {
    PT_SCHEMA,       /* the integer 1 */
    PT_NAME,         /* [a-z0-9-]{1,63} -> experiment.name */
    PT_TEXT,         /* any string -> experiment.description */
    PT_SCENE,        /* a catalog name -> char[32] */
    PT_RENDERERS,    /* non-empty sequence of unique renderer names -> experiment.renderers */
    PT_RESOLUTION,   /* "WxH" -> int width, height */
    PT_UINT,         /* integer min..max -> uint32_t */
    PT_NUMBER,       /* finite number in range -> double, or float with PF_FLOAT */
    PT_ENUM,         /* one of values[] -> int (the index) */
    PT_BOOL,         /* true | false -> bool */
    PT_SPAN,         /* {seconds: min..max} | {frames: fmin..fmax} -> span */
    PT_COUNT,        /* integer 0..MAX_LIGHTS | {start, step, every, max} -> light_count */
    PT_TIMES,        /* sequence of numbers >= 0, at most MAX_SCREENSHOTS -> size_t n, double[] */
    PT_RENDERER,     /* one renderer name -> char[32] */
    PT_VEC3,         /* [x, y, z] finite numbers, or `scene` (PF_SCENE_DEFAULT) -> float[3] */
    PT_GROUP,        /* a mapping of the parameters whose path continues this one */
    PT_SWEEP,        /* parameter path -> non-empty sequence of its values */
} ptype;

enum {
    PF_REQUIRED = 1u << 0,
    PF_SWEEP = 1u << 1,        /* may be a key of `sweep` */
    PF_MIN_OPEN = 1u << 2,     /* PT_NUMBER, PT_SPAN seconds: value > min rather than >= */
    PF_FLOAT = 1u << 3,        /* PT_NUMBER stored as float */
    PF_NOT_IN_ID = 1u << 4,    /* recorded, but changes no result: not part of the run id */
    PF_SCENE_DEFAULT = 1u << 5,/* PT_NUMBER (float), PT_VEC3: `scene` (stored as NAN) keeps
                                  the scene's own value */
    /* >>helper-tiled keys */
    PF_ID_UNLESS_DEFAULT = 1u << 6,   /* part of the run id only when not at its default:
                                         a key added later leaves every earlier run's id
                                         (and results folder name) as it was */
    /* <<helper-tiled keys */
};

typedef struct param {
    const char *path;          /* dotted */
    ptype type;
    unsigned flags;
    const char *def;           /* the default as YAML text, validated like any value; NULL: none */
    double min, max;           /* PT_UINT, PT_NUMBER, PT_SPAN seconds, PT_TIMES items */
    double fmin, fmax;         /* PT_SPAN frames */
    const char *const *values; /* PT_ENUM, NULL-terminated; the index is the stored value */
    size_t off, size;          /* where it lives in run_params; size 0: not a run parameter */
    const char *column;        /* its run_params_kv key if not its path */
    const char *shorthand;     /* PT_GROUP: the member a plain scalar sets (`gbuffer: fat`) */
    const char *description;
} param;

#define RP(f) .off = offsetof(run_params, f), .size = sizeof(((run_params *)0)->f)
#define RP_SPAN(a, b)                                                                         \
    .off = offsetof(run_params, a),                                                           \
    .size = offsetof(run_params, b) + sizeof(((run_params *)0)->b) - offsetof(run_params, a)

static const char *const clock_names[] = {"wall", "fixed", NULL};
static const char *const sync_names[] = {"finish", "fence", NULL};
/* In the order of light_placement (scenes/lights.h). */
static const char *const placement_names[] = {"random", "none", "grid", "scene", NULL};
static const char *const shadows_names[] = {"auto", "off", NULL};
static const char *const rng_names[] = {"msvc", "pcg32", "mt19937", NULL};
static const char *const attenuation_names[] = {"inverse-square", "linear-range", "quadratic",
                                                NULL};
/* In the order of the enums of renderers/renderer.h. */
static const char *const gbuffer_names[] = {"curtis", "fat", "compact", "spheremap", "reference",
                                            NULL};
static const char *const gbuffer_position_names[] = {"preset", "stored16", "stored32", "depth",
                                                     NULL};
static const char *const gbuffer_normal_names[] = {"preset", "float16", "float32", "unorm10",
                                                   "spheremap8", "spheremap16", NULL};
static const char *const light_volume_names[] = {"stencil", "fullscreen", "volume",
                                                 "stencil-two-pass", NULL};
/* >>helper-tiled keys */
static const char *const light_buffer_names[] = {"uniform", "storage", NULL};
static const char *const tile_size_names[] = {"8", "16", "32", NULL};   /* 8 << index */
static const char *const clustered_shading_names[] = {"forward", "deferred", NULL};
/* <<helper-tiled keys */

static const param table[] = {
    {.path = "shadesweep", .type = PT_SCHEMA, .flags = PF_REQUIRED,
     .description = "schema version of the manifest: 1"},
    {.path = "name", .type = PT_NAME, .flags = PF_REQUIRED,
     .description = "names the experiment and its output folder: 1..63 of a-z, 0-9 and -"},
    {.path = "description", .type = PT_TEXT,
     .description = "free text, recorded with the results"},
    {.path = "scene", .type = PT_SCENE, .flags = PF_REQUIRED | PF_SWEEP, RP(scene),
     .description = "the catalog scene to render"},
    {.path = "renderers", .type = PT_RENDERERS, .flags = PF_REQUIRED, RP(renderer),
     .column = "renderer",
     .description = "renderers to run, each on every point of the sweep (fastest varying)"},
    {.path = "resolution", .type = PT_RESOLUTION, .flags = PF_SWEEP, .def = "640x360",
     RP_SPAN(width, height),
     .description = "WxH of the off-screen framebuffer; the context's own limit is checked at run time"},
    {.path = "trials", .type = PT_UINT, .flags = PF_SWEEP, .def = "1", .min = 1, .max = 1000,
     RP(trials), .description = "times each run is repeated"},
    {.path = "warmup", .type = PT_SPAN, .flags = PF_SWEEP, .def = "{frames: 0}",
     .min = 0, .max = 3600, .fmin = 0, .fmax = 10000000, RP(warmup),
     .description = "rendered before measuring, excluded from every result: {seconds: S} or {frames: N}"},
    {.path = "duration", .type = PT_SPAN, .flags = PF_REQUIRED | PF_SWEEP | PF_MIN_OPEN,
     .min = 0, .max = 604800, .fmin = 1, .fmax = 100000000, RP(duration),
     .description = "measured part of each trial: {seconds: S} or {frames: N}"},
    {.path = "clock", .type = PT_ENUM, .flags = PF_SWEEP, .def = "wall", .values = clock_names,
     RP(clock),
     .description = "wall: scene time follows elapsed wall time (as the papers); "
                    "fixed: each frame advances scene time by step (deterministic)"},
    {.path = "step", .type = PT_NUMBER, .flags = PF_SWEEP | PF_MIN_OPEN,
     .def = "0.016666666666666666", .min = 0, .max = 3600, RP(step),
     .description = "seconds of scene time per frame with clock: fixed (default 1/60); "
                    "accepted and recorded with clock: wall, where it has no effect"},
    {.path = "sync", .type = PT_ENUM, .flags = PF_SWEEP, .def = "finish", .values = sync_names,
     RP(sync), .description = "how a frame's end is measured: glFinish or a fence wait"},
    {.path = "timeout", .type = PT_NUMBER, .flags = PF_SWEEP | PF_NOT_IN_ID, .def = "0",
     .min = 0, .max = 2592000, RP(timeout_s),
     .description = "seconds a run (all its trials) may take before it is stopped and recorded "
                    "as failed:timeout; 0: 600 + 3 x trials x (warm-up + duration) seconds"},
    {.path = "gbuffer", .type = PT_GROUP, .shorthand = "gbuffer.preset",
     .description = "the deferred renderer's G-buffer: a preset name, or {preset, position, "
                    "normal} to change fields of it"},
    {.path = "gbuffer.preset", .type = PT_ENUM, .flags = PF_SWEEP, .def = "curtis",
     .values = gbuffer_names, RP(gbuffer),
     .description = "curtis (seed 003), fat (seed 000), compact (seed 002), spheremap "
                    "(seed 004), reference (RGBA32F, position stored)"},
    {.path = "gbuffer.position", .type = PT_ENUM, .flags = PF_SWEEP, .def = "preset",
     .values = gbuffer_position_names, RP(gbuffer_position),
     .description = "how the light passes get a pixel's position: as the preset does, "
                    "stored in 16 or 32-bit floats, or rebuilt from depth"},
    {.path = "gbuffer.normal", .type = PT_ENUM, .flags = PF_SWEEP, .def = "preset",
     .values = gbuffer_normal_names, RP(gbuffer_normal),
     .description = "how normals are stored: as the preset does, float16, float32, unorm10, "
                    "or Lambert azimuthal (spheremap) in 8 or 16 bits"},
    {.path = "deferred", .type = PT_GROUP, .description = "options of the deferred renderer"},
    {.path = "deferred.light_volumes", .type = PT_ENUM, .flags = PF_SWEEP, .def = "stencil",
     .values = light_volume_names, RP(light_volumes),
     .description = "stencil (seed 003, one two-sided pass), fullscreen, volume (back faces, "
                    "depth GREATER), stencil-two-pass (seed 000)"},
    {.path = "deferred.separate_specular", .type = PT_BOOL, .flags = PF_SWEEP, .def = "false",
     RP(separate_specular),
     .description = "diffuse and specular light in separate targets (seed 001)"},
    {.path = "forward", .type = PT_GROUP, .description = "options of the forward renderers"},
    {.path = "forward.illumination_sets", .type = PT_BOOL, .flags = PF_SWEEP, .def = "true",
     RP(illumination_sets),
     .description = "forward-mpml draws, per light, only the visible objects its volume "
                    "reaches (false: every visible object, seed 000 5.6)"},
    {.path = "shadows", .type = PT_ENUM, .flags = PF_SWEEP, .def = "auto",
     .values = shadows_names, RP(shadows),
     .description = "auto: the lights the scene marks as shadow-casting get shadow maps; off: none do"},
    {.path = "camera", .type = PT_GROUP,
     .description = "the scene's camera path, changed: each key defaults to `scene` (the "
                    "scene's own value)"},
    {.path = "camera.radius", .type = PT_NUMBER,
     .flags = PF_SWEEP | PF_FLOAT | PF_MIN_OPEN | PF_SCENE_DEFAULT, .def = "scene", .min = 0,
     .max = 1e7, RP(camera.radius), .description = "orbit radius, world units"},
    {.path = "camera.height", .type = PT_NUMBER, .flags = PF_SWEEP | PF_FLOAT | PF_SCENE_DEFAULT,
     .def = "scene", .min = -1e7, .max = 1e7, RP(camera.height),
     .description = "orbit height above the target, world units"},
    {.path = "camera.period", .type = PT_NUMBER,
     .flags = PF_SWEEP | PF_FLOAT | PF_MIN_OPEN | PF_SCENE_DEFAULT, .def = "scene", .min = 0,
     .max = 1e7, RP(camera.period),
     .description = "seconds of schedule time for one orbit, or for the scripted path"},
    {.path = "camera.target", .type = PT_VEC3, .flags = PF_SWEEP | PF_SCENE_DEFAULT,
     .def = "scene", .min = -1e7, .max = 1e7, RP(camera.target),
     .description = "the point the orbit circles and looks at: [x, y, z]"},
    {.path = "camera.near", .type = PT_NUMBER,
     .flags = PF_SWEEP | PF_FLOAT | PF_MIN_OPEN | PF_SCENE_DEFAULT, .def = "scene", .min = 0,
     .max = 1e9, RP(camera.znear), .description = "near plane distance"},
    {.path = "camera.far", .type = PT_NUMBER,
     .flags = PF_SWEEP | PF_FLOAT | PF_MIN_OPEN | PF_SCENE_DEFAULT, .def = "scene", .min = 0,
     .max = 1e9, RP(camera.zfar), .description = "far plane distance (the draw distance)"},
    {.path = "camera.hold", .type = PT_NUMBER, .flags = PF_SWEEP | PF_FLOAT | PF_SCENE_DEFAULT,
     .def = "scene", .min = 0, .max = 1, RP(camera.hold),
     .description = "stop the camera at this fraction of its path (orbit: of a turn) for the "
                    "whole run; scene: move along it"},
    {.path = "error", .type = PT_GROUP,
     .description = "image error against a reference configuration rendering the same "
                    "frame: RMSE, PSNR, max error, pixels off by > 1/255, non-finite values"},
    {.path = "error.reference", .type = PT_GROUP,
     .description = "the reference: {renderer, gbuffer, light_volumes}"},
    {.path = "error.reference.renderer", .type = PT_RENDERER, RP(error_renderer),
     .description = "the renderer that draws the reference image"},
    {.path = "error.reference.gbuffer", .type = PT_ENUM, .def = "reference",
     .values = gbuffer_names, RP(error_gbuffer),
     .description = "the reference's G-buffer preset, when it is deferred"},
    {.path = "error.reference.light_volumes", .type = PT_ENUM, .def = "stencil",
     .values = light_volume_names, RP(error_light_volumes),
     .description = "the reference's light-volume mode, when it is deferred"},
    {.path = "error.at", .type = PT_TIMES, .def = "[]", .min = 0, .max = INFINITY,
     RP_SPAN(nerror_at, error_at),
     .description = "schedule times (seconds) at which both render the same frame, at most 16"},
    {.path = "error.max_rmse", .type = PT_NUMBER, .def = "0", .min = 0, .max = 1,
     RP(error_max_rmse),
     .description = "a run whose RMSE exceeds this fails as failed:error (0: no limit)"},
    {.path = "error.save_images", .type = PT_BOOL, .def = "false", RP(error_save_images),
     .description = "save both images (PNG) and the error heat map (PNG and EXR)"},
    {.path = "lights", .type = PT_GROUP,
     .description = "light placement; without it (and without a swept lights.* key) "
                    "a run has no lights: placement none, count 0"},
    {.path = "lights.placement", .type = PT_ENUM, .flags = PF_SWEEP, .def = "random",
     .values = placement_names, RP(lights.placement),
     .description = "random: uniform in the scene's light bounds; grid: non-overlapping, on a "
                    "grid in them; scene: the scene's own lights (count caps them); none: no "
                    "lights (count must be 0)"},
    {.path = "lights.seed", .type = PT_UINT, .flags = PF_SWEEP, .def = "1337", .min = 0,
     .max = 4294967295.0, RP(lights.seed),
     .description = "seed of the placement generator"},
    {.path = "lights.rng", .type = PT_ENUM, .flags = PF_SWEEP, .def = "msvc", .values = rng_names,
     RP(lights.rng),
     .description = "placement generator: msvc (Visual C++ rand), pcg32, mt19937"},
    {.path = "lights.count", .type = PT_COUNT, .flags = PF_SWEEP, .def = "0", RP(lights.count),
     .description = "lights: a number 0..1000000, or growth {start, step, every (seconds), max}: "
                    "min(max, start + step * floor(t / every)) at schedule time t"},
    {.path = "lights.radius", .type = PT_NUMBER, .flags = PF_SWEEP | PF_MIN_OPEN | PF_FLOAT,
     .def = "10", .min = 0, .max = 1e9, RP(lights.radius),
     .description = "range of each point light, world units"},
    {.path = "lights.overlap", .type = PT_NUMBER, .flags = PF_SWEEP | PF_FLOAT, .def = "0",
     .min = 0, .max = 1e6, RP(lights.overlap),
     .description = "> 0: the radius is derived so that on average this many lights reach a "
                    "point of the light bounds (random and grid placement); 0: lights.radius"},
    {.path = "lights.color_max", .type = PT_NUMBER, .flags = PF_SWEEP | PF_FLOAT, .def = "0.3",
     .min = 0, .max = 1e6, RP(lights.color_max),
     .description = "each colour channel uniform in [0, color_max]"},
    {.path = "lights.attenuation", .type = PT_ENUM, .flags = PF_SWEEP, .def = "inverse-square",
     .values = attenuation_names, RP(lights.attenuation),
     .description = "inverse-square (1/d^2, as seed 003), linear-range (1 - d/radius), "
                    "quadratic (1/(a d^2 + b d + c), lights.quadratic); none reaches past radius"},
    {.path = "lights.quadratic", .type = PT_GROUP,
     .description = "coefficients of the quadratic attenuation"},
    {.path = "lights.quadratic.a", .type = PT_NUMBER, .flags = PF_SWEEP | PF_FLOAT, .def = "1",
     .min = 0, .max = 1e9, RP(lights.quadratic[0]), .description = "d^2 coefficient"},
    {.path = "lights.quadratic.b", .type = PT_NUMBER, .flags = PF_SWEEP | PF_FLOAT, .def = "0",
     .min = 0, .max = 1e9, RP(lights.quadratic[1]), .description = "d coefficient"},
    {.path = "lights.quadratic.c", .type = PT_NUMBER, .flags = PF_SWEEP | PF_FLOAT, .def = "1",
     .min = 0, .max = 1e9, RP(lights.quadratic[2]), .description = "constant term"},
    {.path = "outputs", .type = PT_GROUP, .description = "what each run writes"},
    {.path = "outputs.frames", .type = PT_BOOL, .def = "true", RP(out_frames),
     .description = "write frames.csv"},
    {.path = "outputs.seconds", .type = PT_BOOL, .def = "true", RP(out_seconds),
     .description = "write seconds.csv"},
    {.path = "outputs.screenshots", .type = PT_TIMES, .def = "[]", .min = 0, .max = INFINITY,
     RP_SPAN(nscreenshots, screenshots),
     .description = "schedule times (seconds) of screenshots, at most 16"},
    {.path = "sweep", .type = PT_SWEEP,
     .description = "parameter path -> list of values; the runs are the cartesian product "
                    "(first key slowest) times the renderers"},
    /* >>helper-tiled keys */
    {.path = "forward.light_buffer", .type = PT_ENUM, .flags = PF_SWEEP | PF_ID_UNLESS_DEFAULT,
     .def = "uniform", .values = light_buffer_names, RP(light_buffer),
     .description = "where forward-spml reads its lights: uniform (seed 003's block, at most "
                    "GL_MAX_UNIFORM_BLOCK_SIZE / 80 lights) or storage (a storage buffer, no "
                    "such limit)"},
    {.path = "tiles", .type = PT_GROUP,
     .description = "options of the tiled renderers (forward-plus)"},
    {.path = "tiles.size", .type = PT_ENUM, .flags = PF_SWEEP | PF_ID_UNLESS_DEFAULT,
     .def = "16", .values = tile_size_names, RP(tile_size),
     .description = "side of a screen tile in pixels: 8, 16 or 32"},
    {.path = "tiles.max_lights_per_tile", .type = PT_UINT,
     .flags = PF_SWEEP | PF_ID_UNLESS_DEFAULT, .def = "0", .min = 0, .max = 1000000,
     RP(max_lights_per_tile),
     .description = "the light index buffer's size in entries per tile on average; 0: every "
                    "light in every tile (no frame can overflow); a frame whose lists do not "
                    "fit fails the run as failed:overflow"},
    {.path = "clustered", .type = PT_GROUP,
     .description = "options of the clustered renderer"},
    {.path = "clustered.slices", .type = PT_UINT, .flags = PF_SWEEP | PF_ID_UNLESS_DEFAULT,
     .def = "24", .min = 1, .max = 64, RP(clustered_slices),
     .description = "S_y of Olsson et al.'s depth slices, k = floor(log(-z/near) / log(1 + "
                    "2 tan(fov/2) / S_y)): slices about as deep as a tile of a screen cut "
                    "into S_y rows is wide; as many as reach the far plane (at most 1024)"},
    {.path = "clustered.shading", .type = PT_ENUM, .flags = PF_SWEEP | PF_ID_UNLESS_DEFAULT,
     .def = "forward", .values = clustered_shading_names, RP(clustered_shading),
     .description = "forward: a depth pre-pass, then the objects shaded with their "
                    "clusters' lights; deferred: the G-buffer (every gbuffer option), then "
                    "one compute pass shading from it with the same cluster lists"},
    /* <<helper-tiled keys */
};

#define NPARAMS (sizeof table / sizeof table[0])

static const param *param_find(const char *path)
{
    for (size_t i = 0; i < NPARAMS; i++)
        if (strcmp(table[i].path, path) == 0)
            return &table[i];
    return NULL;
}

/* The part of a path before its last dot ("" for a top-level key), and after. */
static bool path_parent_is(const char *path, const char *parent)
{
    const char *dot = strrchr(path, '.');
    size_t plen = dot ? (size_t)(dot - path) : 0;
    return strlen(parent) == plen && strncmp(path, parent, plen) == 0;
}

static const char *path_leaf(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot ? dot + 1 : path;
}

/* >>text */

/* A bounded string builder: appends what fits, always NUL-terminated. */
typedef struct sbuf {
    char *s;
    size_t cap, len;
} sbuf;

static void sb_add(sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void sb_add(sbuf *b, const char *fmt, ...)
{
    if (b->len + 1 >= b->cap)
        return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(b->s + b->len, b->cap - b->len, fmt, ap);
    va_end(ap);
    if (n > 0)
        b->len = b->len + (size_t)n < b->cap ? b->len + (size_t)n : b->cap - 1;
}

/* The shortest %.*g text that reads back as the same value (10 is "10", not
 * "1e+01"; 1e9 is "1e+09"; 0.1 is "0.1"). */
static void fmt_double(double v, char *out, size_t len)
{
    char t[40];
    size_t best = SIZE_MAX;
    for (int prec = 1; prec <= 17; prec++) {
        snprintf(t, sizeof t, "%.*g", prec, v);
        if (strtod(t, NULL) == v && strlen(t) < best) {
            best = strlen(t);
            snprintf(out, len, "%s", t);
        }
    }
}

static void fmt_float(float v, char *out, size_t len)
{
    char t[40];
    size_t best = SIZE_MAX;
    for (int prec = 1; prec <= 9; prec++) {
        snprintf(t, sizeof t, "%.*g", prec, (double)v);
        if (strtof(t, NULL) == v && strlen(t) < best) {
            best = strlen(t);
            snprintf(out, len, "%s", t);
        }
    }
}

/* Scalar text for a one-line message: escapes, truncated at a character boundary. */
static void escape_text(sbuf *b, const char *s, size_t len)
{
    size_t shown = len;
    if (shown > 60) {
        shown = 60;
        while (shown > 0 && ((unsigned char)s[shown] & 0xc0) == 0x80)
            shown--;
    }
    for (size_t i = 0; i < shown; i++) {
        unsigned char ch = (unsigned char)s[i];
        if (ch == '\'' || ch == '\\')
            sb_add(b, "\\%c", ch);
        else if (ch == '\n')
            sb_add(b, "\\n");
        else if (ch == '\t')
            sb_add(b, "\\t");
        else if (ch < 0x20 || ch == 0x7f)
            sb_add(b, "\\x%02x", ch);
        else
            sb_add(b, "%c", ch);
    }
    if (shown < len)
        sb_add(b, "...");
}

#define STR_TAG "tag:yaml.org,2002:str"
#define CORE_TAG_PREFIX "tag:yaml.org,2002:"

/* Explicit tags other than the string ones are not part of the schema. */
static bool tag_ok(const ynode *n)
{
    return !n->tag || strcmp(n->tag, "!") == 0 || strcmp(n->tag, STR_TAG) == 0;
}

/* What a node is, for "found ...": 'text' for a scalar (with `want_string` false a
 * quoted one is "a string 'text'", since its quotes are what makes it wrong),
 * "nothing" for an empty plain scalar, else the kind of node. */
static const char *found(const ynode *n, bool want_string, char *buf, size_t len)
{
    sbuf b = {buf, len, 0};
    buf[0] = '\0';
    if (!n) {
        sb_add(&b, "nothing");
    } else if (n->kind == YNODE_MAPPING) {
        sb_add(&b, n->n ? "a mapping" : "an empty mapping");
    } else if (n->kind == YNODE_SEQUENCE) {
        sb_add(&b, n->n ? "a sequence" : "an empty sequence");
    } else if (!tag_ok(n)) {
        const char *t = n->tag;
        bool core = strncmp(t, CORE_TAG_PREFIX, strlen(CORE_TAG_PREFIX)) == 0;
        sb_add(&b, "'");
        escape_text(&b, n->text, n->len);
        sb_add(&b, "' tagged %s%s", core ? "!!" : "", core ? t + strlen(CORE_TAG_PREFIX) : t);
    } else if (ynode_empty(n)) {
        sb_add(&b, "nothing");
    } else {
        bool quoted = n->style != YSTYLE_PLAIN || n->tag;
        sb_add(&b, "%s'", quoted && !want_string ? "a string " : "");
        escape_text(&b, n->text, n->len);
        sb_add(&b, "'");
    }
    return buf;
}

/* "one of a, b, c" */
static void list_enum(sbuf *b, const char *const *names)
{
    sb_add(b, "one of ");
    for (size_t i = 0; names[i]; i++)
        sb_add(b, "%s%s", i ? ", " : "", names[i]);
}

static void list_scenes(sbuf *b)
{
    sb_add(b, "one of ");
    for (size_t i = 0; i < scene_catalog_count(); i++)
        sb_add(b, "%s%s", i ? ", " : "", scene_catalog_at(i)->name);
}

static void list_renderers(sbuf *b)
{
    sb_add(b, "one of ");
    for (size_t i = 0; i < renderer_kind_count(); i++)
        sb_add(b, "%s%s", i ? ", " : "", renderer_kind_at(i)->name);
}

static void range_number(sbuf *b, double min, double max, bool min_open)
{
    char lo[32], hi[32];
    fmt_double(min, lo, sizeof lo);
    sb_add(b, "a number %s %s", min_open ? ">" : ">=", lo);
    if (isfinite(max)) {
        fmt_double(max, hi, sizeof hi);
        sb_add(b, " and <= %s", hi);
    }
}

/* What a parameter expects, as the "expected ..." of its messages. */
static const char *expect(const param *pd, char *buf, size_t len)
{
    sbuf b = {buf, len, 0};
    buf[0] = '\0';
    switch (pd->type) {
    case PT_SCHEMA: sb_add(&b, "1"); break;
    case PT_NAME: sb_add(&b, "a name of 1..63 characters from a-z, 0-9 and -"); break;
    case PT_TEXT: sb_add(&b, "a string"); break;
    case PT_SCENE: list_scenes(&b); break;
    case PT_RENDERERS: sb_add(&b, "a non-empty sequence of renderer names"); break;
    case PT_RENDERER: list_renderers(&b); break;
    case PT_RESOLUTION: sb_add(&b, "WxH with each side 1..%d", MAX_SIDE); break;
    case PT_UINT: sb_add(&b, "an integer %.0f..%.0f", pd->min, pd->max); break;
    case PT_NUMBER:
        range_number(&b, pd->min, pd->max, pd->flags & PF_MIN_OPEN);
        if (pd->flags & PF_SCENE_DEFAULT)
            sb_add(&b, ", or scene");
        break;
    case PT_VEC3: sb_add(&b, "[x, y, z] (finite numbers) or scene"); break;
    case PT_ENUM: list_enum(&b, pd->values); break;
    case PT_BOOL: sb_add(&b, "true or false"); break;
    case PT_SPAN: sb_add(&b, "{seconds: S} or {frames: N}"); break;
    case PT_COUNT:
        sb_add(&b, "an integer 0..%u, all, or {start, step, every, max}", MAX_LIGHTS);
        break;
    case PT_TIMES: sb_add(&b, "a sequence of at most %d times in seconds", MAX_SCREENSHOTS); break;
    case PT_GROUP:
        if (pd->shorthand) {
            list_enum(&b, param_find(pd->shorthand)->values);
            sb_add(&b, " or a mapping");
        } else {
            sb_add(&b, "a mapping");
        }
        break;
    case PT_SWEEP: sb_add(&b, "a mapping from parameters to sequences of values"); break;
    }
    return buf;
}

static bool wants_string(const param *pd)
{
    return pd->type == PT_NAME || pd->type == PT_TEXT || pd->type == PT_SCENE ||
           pd->type == PT_RESOLUTION || pd->type == PT_ENUM;
}

/* >>scalars */

/* Text a string parameter can take: any non-empty scalar without a non-string
 * tag and without NUL bytes. */
static bool stringish(const ynode *n)
{
    return n && n->kind == YNODE_SCALAR && tag_ok(n) && !ynode_empty(n) &&
           strlen(n->text) == n->len;
}

/* A plain scalar that is a decimal integer: [-+]?[0-9]+. Negative or too large
 * for 64 bits is out of every range here, so those read as "not an integer". */
static bool get_uint(const ynode *n, uint64_t *out)
{
    if (!ynode_plain(n))
        return false;
    const char *s = n->text;
    bool neg = *s == '-';
    if (*s == '-' || *s == '+')
        s++;
    if (!*s)
        return false;
    uint64_t v = 0;
    for (; *s; s++) {
        if (*s < '0' || *s > '9')
            return false;
        unsigned dgt = (unsigned)(*s - '0');
        if (v > (UINT64_MAX - dgt) / 10)
            return false;
        v = v * 10 + dgt;
    }
    if (neg && v != 0)
        return false;
    *out = v;
    return true;
}

static bool all_digits(const char *s, const char *end)
{
    if (s == end)
        return false;
    for (; s < end; s++)
        if (*s < '0' || *s > '9')
            return false;
    return true;
}

/* A plain scalar that is a YAML 1.2 core-schema number:
 * [-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?, or [-+]?.inf or .nan in
 * their three spellings. *finite is false for those and for overflow (1e999). */
static bool get_number(const ynode *n, double *out, bool *finite)
{
    if (!ynode_plain(n))
        return false;
    const char *s = n->text, *p = s;
    if (*p == '-' || *p == '+')
        p++;
    static const char *const specials[] = {".inf", ".Inf", ".INF", ".nan", ".NaN", ".NAN", NULL};
    for (size_t i = 0; specials[i]; i++)
        if (strcmp(p, specials[i]) == 0 && (i < 3 || p == s)) {
            *finite = false;
            *out = i < 3 ? (s[0] == '-' ? -INFINITY : INFINITY) : NAN;
            return true;
        }
    const char *q = p;
    while (*q >= '0' && *q <= '9')
        q++;
    bool int_part = q > p;
    if (*q == '.') {
        const char *frac = ++q;
        while (*q >= '0' && *q <= '9')
            q++;
        if (!int_part && q == frac)
            return false;
    } else if (!int_part) {
        return false;
    }
    if (*q == 'e' || *q == 'E') {
        q++;
        if (*q == '-' || *q == '+')
            q++;
        if (!all_digits(q, q + strlen(q)))
            return false;
        q += strlen(q);
    }
    if (*q)
        return false;
    errno = 0;
    double v = strtod(s, NULL);
    *finite = isfinite(v);
    *out = v == 0 ? 0.0 : v;   /* -0 reads as 0: one canonical text */
    return true;
}

/* >>values */

typedef struct vctx {
    const char *file;
    diag_list *d;
    size_t nerr;
    experiment *e;
    const ynode *root;
    const ynode *set_key[NPARAMS];     /* where each parameter is set in place */
    const ynode *set_val[NPARAMS];
    const ynode *swept[NPARAMS];       /* its key in `sweep` */
    size_t axis_of[NPARAMS];           /* its axis index + 1, 0 if not swept */
} vctx;

static void err(vctx *c, const ynode *at, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void err(vctx *c, const ynode *at, const char *key, const char *fmt, ...)
{
    char msg[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    diag_add(c->d, c->file, at->line, at->col, key, "%s", msg);
    c->nerr++;
}

/* The usual message: "expected <what the parameter takes>, found <the node>". */
static bool bad(vctx *c, const param *pd, const ynode *n, const char *key)
{
    char e[512], f[128];
    err(c, n, key, "expected %s, found %s", expect(pd, e, sizeof e),
        found(n, wants_string(pd), f, sizeof f));
    return false;
}

static bool parse_uint_in(vctx *c, const ynode *n, const char *key, uint64_t min, uint64_t max,
                          const char *note, uint64_t *out)
{
    uint64_t v;
    if (!get_uint(n, &v) || v < min || v > max) {
        char f[128];
        err(c, n, key, "expected an integer %" PRIu64 "..%" PRIu64 "%s, found %s", min, max, note,
            found(n, false, f, sizeof f));
        return false;
    }
    *out = v;
    return true;
}

static bool parse_number_in(vctx *c, const ynode *n, const char *key, double min, double max,
                            unsigned flags, double *out)
{
    double v;
    bool finite;
    char e[128], f[128];
    sbuf b = {e, sizeof e, 0};
    range_number(&b, min, max, flags & PF_MIN_OPEN);
    if (flags & PF_SCENE_DEFAULT)
        sb_add(&b, ", or scene");
    if (!get_number(n, &v, &finite)) {
        err(c, n, key, "expected %s, found %s", e, found(n, false, f, sizeof f));
        return false;
    }
    if (!finite) {
        err(c, n, key, "expected a finite number, found %s", found(n, false, f, sizeof f));
        return false;
    }
    if (flags & PF_FLOAT)
        v = (double)(float)v;  /* what will be stored is what is checked */
    if (((flags & PF_MIN_OPEN) ? v <= min : v < min) || v > max) {
        err(c, n, key, "expected %s, found %s", e, found(n, false, f, sizeof f));
        return false;
    }
    *out = v;
    return true;
}

/* Checks the keys of a mapping against names[0..nnames): an unknown key, a key
 * that is not a scalar and a second occurrence are errors. vals[i] (and keys[i])
 * get the first occurrence of names[i], NULL if absent. Returns false if any key
 * was wrong. */
static bool map_keys(vctx *c, const ynode *map, const char *prefix, const char *const *names,
                     size_t nnames, const ynode **keys, const ynode **vals)
{
    bool ok = true;
    for (size_t i = 0; i < nnames; i++)
        keys[i] = vals[i] = NULL;
    for (size_t p = 0; p < map->n; p++) {
        const ynode *k = map->pairs[p].key;
        char f[128];
        if (k->kind != YNODE_SCALAR) {
            err(c, k, prefix, "expected a key, found %s", found(k, true, f, sizeof f));
            ok = false;
            continue;
        }
        size_t i = 0;
        while (i < nnames && strcmp(names[i], k->text) != 0)
            i++;
        char path[256];
        sbuf pb = {path, sizeof path, 0};
        sb_add(&pb, "%s%s", prefix, prefix[0] ? "." : "");
        escape_text(&pb, k->text, k->len);
        if (i == nnames) {
            char list[1024];
            sbuf lb = {list, sizeof list, 0};
            list[0] = '\0';
            for (size_t j = 0; j < nnames; j++)
                sb_add(&lb, "%s%s", j ? ", " : "", names[j]);
            err(c, k, path, "expected one of %s, found %s", list, found(k, true, f, sizeof f));
            ok = false;
        } else if (keys[i]) {
            err(c, k, path, "expected a key used once, found a second '%s' (first at %d:%d)",
                names[i], keys[i]->line, keys[i]->col);
            ok = false;
        } else {
            keys[i] = k;
            vals[i] = map->pairs[p].value;
        }
    }
    return ok;
}

static bool parse_value(vctx *c, const param *pd, const ynode *n, const char *key,
                        run_params *dst);

/* A mapping whose keys are the table's parameters under `prefix` ("" at the top). */
static void parse_group(vctx *c, const char *prefix, const ynode *map, run_params *dst)
{
    size_t idx[NPARAMS], nk = 0;
    const char *names[NPARAMS];
    for (size_t i = 0; i < NPARAMS; i++)
        if (path_parent_is(table[i].path, prefix)) {
            idx[nk] = i;
            names[nk++] = path_leaf(table[i].path);
        }
    const ynode *keys[NPARAMS], *vals[NPARAMS];
    map_keys(c, map, prefix, names, nk, keys, vals);
    for (size_t j = 0; j < nk; j++) {
        if (!keys[j])
            continue;
        c->set_key[idx[j]] = keys[j];
        c->set_val[idx[j]] = vals[j];
        parse_value(c, &table[idx[j]], vals[j], table[idx[j]].path, dst);
    }
}

static bool parse_span(vctx *c, const param *pd, const ynode *n, const char *key, span *out)
{
    if (n->kind != YNODE_MAPPING)
        return bad(c, pd, n, key);
    static const char *const names[] = {"seconds", "frames"};
    const ynode *keys[2], *vals[2];
    bool keys_ok = map_keys(c, n, key, names, 2, keys, vals);
    char e[64], sub[160];
    if (vals[0] && vals[1]) {
        err(c, n, key, "expected %s, found both seconds and frames", expect(pd, e, sizeof e));
        return false;
    }
    if (!vals[0] && !vals[1]) {
        if (keys_ok)
            bad(c, pd, n, key);
        return false;
    }
    if (vals[0]) {
        double v;
        snprintf(sub, sizeof sub, "%s.seconds", key);
        if (!parse_number_in(c, vals[0], sub, pd->min, pd->max, pd->flags, &v))
            return false;
        *out = (span){.kind = SPAN_SECONDS, .seconds = v};
    } else {
        uint64_t v;
        snprintf(sub, sizeof sub, "%s.frames", key);
        if (!parse_uint_in(c, vals[1], sub, (uint64_t)pd->fmin, (uint64_t)pd->fmax, "", &v))
            return false;
        *out = (span){.kind = SPAN_FRAMES, .frames = (uint32_t)v};
    }
    return keys_ok;
}

static bool parse_count(vctx *c, const param *pd, const ynode *n, const char *key,
                        light_count *out)
{
    if (n->kind == YNODE_SCALAR) {
        uint64_t v;
        if (ynode_plain(n) && strcmp(n->text, "all") == 0) {
            *out = (light_count){.growth = false, .start = LIGHT_COUNT_ALL,
                                 .max = LIGHT_COUNT_ALL};
            return true;
        }
        if (!get_uint(n, &v) || v > MAX_LIGHTS)
            return bad(c, pd, n, key);
        *out = (light_count){.growth = false, .start = (uint32_t)v, .max = (uint32_t)v};
        return true;
    }
    if (n->kind != YNODE_MAPPING)
        return bad(c, pd, n, key);

    static const char *const names[] = {"start", "step", "every", "max"};
    const ynode *keys[4], *vals[4];
    bool ok = map_keys(c, n, key, names, 4, keys, vals);
    char sub[4][160];
    for (size_t i = 0; i < 4; i++) {
        snprintf(sub[i], sizeof sub[i], "%s.%s", key, names[i]);
        if (!vals[i]) {
            err(c, n, sub[i], "expected %s, found nothing",
                i == 2 ? "a number > 0 and <= 604800" : "an integer 0..1000000");
            ok = false;
        }
    }
    uint64_t start = 0, step = 0, max = 0;
    double every = 0;
    bool have_start = vals[0] && parse_uint_in(c, vals[0], sub[0], 0, MAX_LIGHTS, "", &start);
    if (vals[1] && !parse_uint_in(c, vals[1], sub[1], 0, MAX_LIGHTS, "", &step))
        ok = false;
    if (vals[2] && !parse_number_in(c, vals[2], sub[2], 0, MAX_EVERY, PF_MIN_OPEN, &every))
        ok = false;
    if (vals[3] &&
        !parse_uint_in(c, vals[3], sub[3], have_start ? start : 0, MAX_LIGHTS,
                       have_start ? " (at least start)" : "", &max))
        ok = false;
    if (!ok || !have_start)
        return false;
    *out = (light_count){.growth = true, .start = (uint32_t)start, .step = (uint32_t)step,
                         .max = (uint32_t)max, .every = every};
    return true;
}

static bool parse_times(vctx *c, const param *pd, const ynode *n, const char *key,
                        run_params *dst)
{
    if (n->kind != YNODE_SEQUENCE)
        return bad(c, pd, n, key);
    if (n->n > MAX_SCREENSHOTS) {
        char e[128];
        err(c, n, key, "expected %s, found %zu times", expect(pd, e, sizeof e), n->n);
        return false;
    }
    /* a size_t count followed by MAX_SCREENSHOTS doubles at pd->off (RP_SPAN) */
    size_t *count = (size_t *)((char *)dst + pd->off);
    double *times = (double *)((char *)dst + pd->off + sizeof(size_t));
    bool ok = true;
    for (size_t i = 0; i < n->n; i++) {
        char sub[160];
        snprintf(sub, sizeof sub, "%s[%zu]", key, i);
        if (!parse_number_in(c, n->items[i], sub, pd->min, pd->max, 0, &times[i]))
            ok = false;
    }
    if (ok)
        *count = n->n;
    return ok;
}

static bool parse_renderers(vctx *c, const param *pd, const ynode *n, const char *key)
{
    if (n->kind != YNODE_SEQUENCE || n->n == 0)
        return bad(c, pd, n, key);
    experiment *e = c->e;
    free(e->renderers);
    e->nrenderers = 0;
    e->renderers = calloc(n->n, sizeof *e->renderers);
    if (!e->renderers) {
        err(c, n, key, "expected a sequence that fits in memory, found no memory left");
        return false;
    }
    bool ok = true;
    for (size_t i = 0; i < n->n; i++) {
        const ynode *it = n->items[i];
        char sub[160], f[128];
        snprintf(sub, sizeof sub, "%s[%zu]", key, i);
        const renderer_impl *impl = stringish(it) ? renderer_kind_find(it->text) : NULL;
        if (!impl || strlen(impl->name) >= sizeof e->renderers[0]) {
            char list[512];
            sbuf lb = {list, sizeof list, 0};
            list_renderers(&lb);
            err(c, it, sub, "expected %s, found %s", list, found(it, true, f, sizeof f));
            ok = false;
            continue;
        }
        const ynode *first = NULL;
        for (size_t j = 0; j < i && !first; j++)
            if (n->items[j]->kind == YNODE_SCALAR && strcmp(n->items[j]->text, it->text) == 0)
                first = n->items[j];
        if (first) {
            err(c, it, sub, "expected a renderer listed once, found a second '%s' (first at %d:%d)",
                impl->name, first->line, first->col);
            ok = false;
            continue;
        }
        strcpy(e->renderers[e->nrenderers++], impl->name);
    }
    return ok;
}

static bool parse_resolution(vctx *c, const param *pd, const ynode *n, const char *key,
                             run_params *dst)
{
    if (!stringish(n))
        return bad(c, pd, n, key);
    const char *s = n->text, *x = strchr(s, 'x');
    if (!x || !all_digits(s, x) || !all_digits(x + 1, s + n->len) || x - s > 9 ||
        (s + n->len) - (x + 1) > 9)
        return bad(c, pd, n, key);
    long w = strtol(s, NULL, 10), h = strtol(x + 1, NULL, 10);
    if (w < 1 || w > MAX_SIDE || h < 1 || h > MAX_SIDE)
        return bad(c, pd, n, key);
    dst->width = (int)w;
    dst->height = (int)h;
    return true;
}

static bool parse_name(vctx *c, const param *pd, const ynode *n, const char *key)
{
    if (!stringish(n) || n->len > 63)
        return bad(c, pd, n, key);
    for (const char *s = n->text; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') || *s == '-'))
            return bad(c, pd, n, key);
    strcpy(c->e->name, n->text);
    return true;
}

static bool parse_text(vctx *c, const param *pd, const ynode *n, const char *key)
{
    /* an explicitly empty string ("") is a string too */
    bool empty_quoted = n->kind == YNODE_SCALAR && n->len == 0 && n->style != YSTYLE_PLAIN;
    if (!stringish(n) && !empty_quoted)
        return bad(c, pd, n, key);
    char *d = strdup(n->text);
    if (!d) {
        err(c, n, key, "expected a string that fits in memory, found no memory left");
        return false;
    }
    free(c->e->description);
    c->e->description = d;
    return true;
}

static void parse_sweep(vctx *c, const param *pd, const ynode *map);

/* Validates n as parameter pd; a run parameter's value goes into dst (at pd->off),
 * the experiment's own (name, renderers...) into c->e. The one path for keys in
 * place, sweep values and defaults. */
static bool parse_value(vctx *c, const param *pd, const ynode *n, const char *key,
                        run_params *dst)
{
    char *at = (char *)dst + pd->off;
    if (n->kind == YNODE_SCALAR && !tag_ok(n))
        return bad(c, pd, n, key);
    switch (pd->type) {
    case PT_SCHEMA: {
        uint64_t v;
        if (!get_uint(n, &v) || v != 1)
            return bad(c, pd, n, key);
        return true;
    }
    case PT_NAME:
        return parse_name(c, pd, n, key);
    case PT_TEXT:
        return parse_text(c, pd, n, key);
    case PT_SCENE:
        if (!stringish(n) || !scene_catalog_find(n->text) || n->len >= sizeof dst->scene)
            return bad(c, pd, n, key);
        strcpy(dst->scene, n->text);
        return true;
    case PT_RENDERERS:
        return parse_renderers(c, pd, n, key);
    case PT_RENDERER:
        if (!stringish(n) || !renderer_kind_find(n->text) || n->len >= 32)
            return bad(c, pd, n, key);
        memcpy(at, n->text, n->len + 1);
        return true;
    case PT_RESOLUTION:
        return parse_resolution(c, pd, n, key, dst);
    case PT_UINT: {
        uint64_t v;
        if (!parse_uint_in(c, n, key, (uint64_t)pd->min, (uint64_t)pd->max, "", &v))
            return false;
        uint32_t u = (uint32_t)v;
        memcpy(at, &u, sizeof u);
        return true;
    }
    case PT_NUMBER: {
        double v;
        if ((pd->flags & PF_SCENE_DEFAULT) && ynode_plain(n) && strcmp(n->text, "scene") == 0) {
            float f = NAN;   /* PF_SCENE_DEFAULT numbers are floats */
            memcpy(at, &f, sizeof f);
            return true;
        }
        if (!parse_number_in(c, n, key, pd->min, pd->max, pd->flags, &v))
            return false;
        if (pd->flags & PF_FLOAT) {
            float f = (float)v;
            memcpy(at, &f, sizeof f);
        } else {
            memcpy(at, &v, sizeof v);
        }
        return true;
    }
    case PT_VEC3: {
        float v[3] = {NAN, NAN, NAN};
        if (ynode_plain(n) && strcmp(n->text, "scene") == 0) {
            memcpy(at, v, sizeof v);
            return true;
        }
        if (n->kind != YNODE_SEQUENCE || n->n != 3)
            return bad(c, pd, n, key);
        for (size_t i = 0; i < 3; i++) {
            char k[160];
            double d;
            snprintf(k, sizeof k, "%s[%zu]", key, i);
            if (!parse_number_in(c, n->items[i], k, pd->min, pd->max, PF_FLOAT, &d))
                return false;
            v[i] = (float)d;
        }
        memcpy(at, v, sizeof v);
        return true;
    }
    case PT_ENUM:
        if (stringish(n))
            for (int i = 0; pd->values[i]; i++)
                if (strcmp(pd->values[i], n->text) == 0) {
                    memcpy(at, &i, sizeof i);
                    return true;
                }
        return bad(c, pd, n, key);
    case PT_BOOL: {
        bool t = ynode_plain(n) && strcmp(n->text, "true") == 0;
        bool f = ynode_plain(n) && strcmp(n->text, "false") == 0;
        if (!t && !f)
            return bad(c, pd, n, key);
        memcpy(at, &t, sizeof t);
        return true;
    }
    case PT_SPAN: {
        span s;
        if (!parse_span(c, pd, n, key, &s))
            return false;
        memcpy(at, &s, sizeof s);
        return true;
    }
    case PT_COUNT: {
        light_count lc;
        if (!parse_count(c, pd, n, key, &lc))
            return false;
        memcpy(at, &lc, sizeof lc);
        return true;
    }
    case PT_TIMES:
        return parse_times(c, pd, n, key, dst);
    case PT_GROUP:
        if (n->kind == YNODE_SCALAR && pd->shorthand) {
            const param *member = param_find(pd->shorthand);
            return parse_value(c, member, n, key, dst);
        }
        if (n->kind != YNODE_MAPPING)
            return bad(c, pd, n, key);
        parse_group(c, pd->path, n, dst);
        return true;
    case PT_SWEEP:
        if (n->kind != YNODE_MAPPING)
            return bad(c, pd, n, key);
        parse_sweep(c, pd, n);
        return true;
    }
    return false;
}

static void list_sweepable(sbuf *b)
{
    bool first = true;
    for (size_t i = 0; i < NPARAMS; i++)
        if (table[i].flags & PF_SWEEP) {
            sb_add(b, "%s%s", first ? "" : ", ", table[i].path);
            first = false;
        }
}

static void parse_sweep(vctx *c, const param *pd, const ynode *map)
{
    experiment *e = c->e;
    e->axes = calloc(map->n ? map->n : 1, sizeof *e->axes);
    if (!e->axes) {
        err(c, map, pd->path, "expected a sweep that fits in memory, found no memory left");
        return;
    }
    for (size_t p = 0; p < map->n; p++) {
        const ynode *k = map->pairs[p].key, *v = map->pairs[p].value;
        char f[128], key[256];
        if (k->kind != YNODE_SCALAR) {
            err(c, k, pd->path, "expected a parameter, found %s", found(k, true, f, sizeof f));
            continue;
        }
        sbuf kb = {key, sizeof key, 0};
        sb_add(&kb, "%s.", pd->path);
        escape_text(&kb, k->text, k->len);
        const param *sp = param_find(k->text);
        if (!sp || !(sp->flags & PF_SWEEP)) {
            char list[1024];
            sbuf lb = {list, sizeof list, 0};
            list_sweepable(&lb);
            err(c, k, key, "expected a sweepable parameter (one of %s), found %s", list,
                found(k, true, f, sizeof f));
            continue;
        }
        size_t idx = (size_t)(sp - table);
        if (c->swept[idx]) {
            err(c, k, key, "expected a key used once, found a second '%s' (first at %d:%d)",
                sp->path, c->swept[idx]->line, c->swept[idx]->col);
            continue;
        }
        c->swept[idx] = k;
        if (v->kind != YNODE_SEQUENCE || v->n == 0) {
            err(c, v, key, "expected a non-empty sequence of values, found %s",
                found(v, false, f, sizeof f));
            continue;
        }
        if (v->n > MAX_AXIS_VALUES) {
            err(c, v, key, "expected at most %d values, found %zu", MAX_AXIS_VALUES, v->n);
            continue;
        }
        struct sweep_axis *ax = &e->axes[e->naxes];
        ax->path = sp->path;
        ax->off = sp->off;
        ax->size = sp->size;
        ax->values = calloc(v->n, sizeof *ax->values);
        ax->line = calloc(v->n, sizeof *ax->line);
        ax->col = calloc(v->n, sizeof *ax->col);
        if (!ax->values || !ax->line || !ax->col) {
            free(ax->values);
            free(ax->line);
            free(ax->col);
            *ax = (struct sweep_axis){0};
            err(c, v, key, "expected a sweep that fits in memory, found no memory left");
            continue;
        }
        ax->nvalues = v->n;
        e->naxes++;
        c->axis_of[idx] = e->naxes;
        for (size_t j = 0; j < v->n; j++) {
            char sub[300];
            snprintf(sub, sizeof sub, "%s[%zu]", key, j);
            ax->line[j] = v->items[j]->line;
            ax->col[j] = v->items[j]->col;
            parse_value(c, sp, v->items[j], sub, &ax->values[j]);
        }
    }
}

/* >>checks */

/* Required keys: missing ones are reported at the mapping they belong in, unless
 * swept; a key both set and swept would have its set value silently unused. */
static void check_required_and_swept(vctx *c)
{
    for (size_t i = 0; i < NPARAMS; i++) {
        const param *pd = &table[i];
        if ((pd->flags & PF_REQUIRED) && !c->set_key[i] && !c->swept[i]) {
            char e[512];
            err(c, c->root, pd->path, "expected %s, found nothing", expect(pd, e, sizeof e));
        }
        if (c->set_key[i] && c->swept[i]) {
            char key[160];
            snprintf(key, sizeof key, "sweep.%s", pd->path);
            err(c, c->swept[i], key,
                "expected %s either set or swept, found both (set at %d:%d)", pd->path,
                c->set_key[i]->line, c->set_key[i]->col);
        }
    }
}

static bool lights_swept(const vctx *c)
{
    for (size_t i = 0; i < NPARAMS; i++)
        if (c->swept[i] && path_parent_is(table[i].path, "lights"))
            return true;
    return false;
}

/* An error block names a reference renderer and at least one time, or neither. */
static void check_error(vctx *c)
{
    const run_params *b = &c->e->base;
    size_t ir = (size_t)(param_find("error.reference.renderer") - table);
    size_t ia = (size_t)(param_find("error.at") - table);
    bool named = b->error_renderer[0] || c->set_key[ir];   /* set, even if invalid */
    if (b->error_renderer[0] && b->nerror_at == 0)
        err(c, c->set_key[ir], "error.at",
            "expected at least one time to compare at, found none");
    for (size_t i = 0; i < NPARAMS; i++) {
        if (named || !c->set_key[i] || i == ia ||
            strncmp(table[i].path, "error.", 6) != 0 || table[i].type == PT_GROUP)
            continue;
        char e[512];
        err(c, c->set_key[i], "error.reference.renderer", "expected %s, found nothing",
            expect(&table[ir], e, sizeof e));
        break;
    }
    if (c->set_key[ia] && b->nerror_at > 0 && !named) {
        char e[512];
        err(c, c->set_key[ia], "error.reference.renderer", "expected %s, found nothing",
            expect(&table[ir], e, sizeof e));
    }
}

/* Count `all` means the scene's authored lights: every placement it can meet must be
 * scene; and placement scene without a count (set or swept) means all of them. */
static void check_count_all(vctx *c)
{
    experiment *e = c->e;
    size_t ip = (size_t)(param_find("lights.placement") - table);
    size_t ic = (size_t)(param_find("lights.count") - table);
    bool all_scene = e->base.lights.placement == PLACEMENT_SCENE;
    if (c->axis_of[ip]) {
        const struct sweep_axis *ax = &e->axes[c->axis_of[ip] - 1];
        all_scene = true;
        for (size_t j = 0; j < ax->nvalues; j++)
            all_scene = all_scene && ax->values[j].lights.placement == PLACEMENT_SCENE;
    }
    if (all_scene && !c->set_val[ic] && !c->axis_of[ic]) {
        e->base.lights.count = (light_count){.start = LIGHT_COUNT_ALL, .max = LIGHT_COUNT_ALL};
        return;
    }
    if (all_scene)
        return;
    static const char msg[] = "expected a number of lights (all is for lights.placement scene "
                              "only), found all";
    if (c->axis_of[ic]) {
        const struct sweep_axis *ax = &e->axes[c->axis_of[ic] - 1];
        for (size_t j = 0; j < ax->nvalues; j++)
            if (ax->values[j].lights.count.max == LIGHT_COUNT_ALL) {
                char key[160];
                snprintf(key, sizeof key, "sweep.lights.count[%zu]", j);
                diag_add(c->d, c->file, ax->line[j], ax->col[j], key, "%s", msg);
                c->nerr++;
            }
    } else if (c->set_val[ic] && e->base.lights.count.max == LIGHT_COUNT_ALL) {
        err(c, c->set_val[ic], "lights.count", "%s", msg);
    }
}

/* Placement none means no lights: every count it can meet must be 0. */
static void check_lights(vctx *c)
{
    const experiment *e = c->e;
    size_t ip = (size_t)(param_find("lights.placement") - table);
    size_t ic = (size_t)(param_find("lights.count") - table);

    size_t nerr = c->nerr;
    check_count_all(c);
    if (c->nerr > nerr)
        return;   /* a count of all is wrong already */

    bool none = e->base.lights.placement == PLACEMENT_NONE;
    if (c->axis_of[ip]) {
        const struct sweep_axis *ax = &e->axes[c->axis_of[ip] - 1];
        none = false;
        for (size_t j = 0; j < ax->nvalues; j++)
            none = none || ax->values[j].lights.placement == PLACEMENT_NONE;
    }
    if (!none)
        return;

    if (c->axis_of[ic]) {
        const struct sweep_axis *ax = &e->axes[c->axis_of[ic] - 1];
        for (size_t j = 0; j < ax->nvalues; j++) {
            uint32_t m = ax->values[j].lights.count.max;
            if (m != 0) {
                char key[160];
                snprintf(key, sizeof key, "sweep.lights.count[%zu]", j);
                diag_add(c->d, c->file, ax->line[j], ax->col[j], key,
                         "expected 0 lights with lights.placement none, found %s%" PRIu32
                         " lights", ax->values[j].lights.count.growth ? "up to " : "", m);
                c->nerr++;
            }
        }
    } else if (e->base.lights.count.max != 0 && c->set_val[ic]) {
        err(c, c->set_val[ic], "lights.count",
            "expected 0 lights with lights.placement none, found %s%" PRIu32 " lights",
            e->base.lights.count.growth ? "up to " : "", e->base.lights.count.max);
    }
}

/* >>load */

void experiment_free(experiment *e)
{
    if (!e)
        return;
    for (size_t i = 0; i < e->naxes; i++) {
        free(e->axes[i].values);
        free(e->axes[i].line);
        free(e->axes[i].col);
    }
    free(e->axes);
    free(e->renderers);
    free(e->description);
    free(e->path);
    free(e);
}

static bool read_file(const char *path, unsigned char **out, size_t *outlen, diag_list *d)
{
    *out = NULL;
    FILE *f = fopen(path, "rb");
    if (!f) {
        diag_add(d, path, 0, 0, "", "expected a readable file, found %s", strerror(errno));
        return false;
    }
    size_t cap = 4096, len = 0;
    unsigned char *buf = malloc(cap);
    bool ok = false;
    if (!buf) {
        diag_add(d, path, 0, 0, "", "expected to load the manifest, found no memory left");
        goto done;
    }
    for (;;) {
        if (len == cap) {
            if (cap > MANIFEST_MAX_BYTES) {
                diag_add(d, path, 0, 0, "", "expected a manifest of at most %u bytes, found more",
                         MANIFEST_MAX_BYTES);
                goto done;
            }
            unsigned char *b = realloc(buf, cap * 2);
            if (!b) {
                diag_add(d, path, 0, 0, "", "expected to load the manifest, found no memory left");
                goto done;
            }
            buf = b;
            cap *= 2;
        }
        size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0)
            break;
    }
    if (ferror(f)) {
        diag_add(d, path, 0, 0, "", "expected a readable file, found %s", strerror(errno));
        goto done;
    }
    if (len > MANIFEST_MAX_BYTES) {
        diag_add(d, path, 0, 0, "", "expected a manifest of at most %u bytes, found %zu bytes",
                 MANIFEST_MAX_BYTES, len);
        goto done;
    }
    ok = true;
done:
    fclose(f);
    if (ok) {
        *out = buf;
        *outlen = len;
    } else {
        free(buf);
    }
    return ok;
}

/* The table's defaults go through the same validation as any value: a default
 * that fails its own parameter is a bug, caught by every load. */
static bool apply_defaults(vctx *c, run_params *dst)
{
    bool ok = true;
    for (size_t i = 0; i < NPARAMS && ok; i++) {
        const param *pd = &table[i];
        if (!pd->def)
            continue;
        diag_list scratch = {0};
        ydoc *doc = NULL;
        vctx dc = {.file = "<default>", .d = &scratch, .e = c->e};
        ok = ydoc_load(dc.file, pd->def, strlen(pd->def), &doc, &scratch) &&
             parse_value(&dc, pd, doc->root, pd->path, dst) && dc.nerr == 0;
        if (!ok)
            diag_add(c->d, c->file, 0, 0, "", "bug: the default of %s (%s) does not validate",
                     pd->path, pd->def);
        ydoc_free(doc);
        diag_free(&scratch);
    }
    return ok;
}

typedef struct diag_seq {
    diag g;
    size_t seq;
} diag_seq;

static int diag_seq_cmp(const void *a, const void *b)
{
    const diag_seq *x = a, *y = b;
    if (x->g.line != y->g.line)
        return x->g.line < y->g.line ? -1 : 1;
    if (x->g.col != y->g.col)
        return x->g.col < y->g.col ? -1 : 1;
    return x->seq < y->seq ? -1 : x->seq > y->seq;
}

/* Document order (line, column), stable: required keys are found missing only
 * at the end, and belong where their mapping starts. */
static void sort_diags(diag_list *d, size_t from)
{
    size_t n = d->n - from;
    if (n < 2)
        return;
    diag_seq *t = malloc(n * sizeof *t);
    if (!t)
        return;   /* unsorted is still complete */
    for (size_t i = 0; i < n; i++)
        t[i] = (diag_seq){d->v[from + i], i};
    qsort(t, n, sizeof *t, diag_seq_cmp);
    for (size_t i = 0; i < n; i++)
        d->v[from + i] = t[i].g;
    free(t);
}

bool manifest_load_mem(const char *name, const char *data, size_t len, experiment **out,
                       diag_list *diags)
{
    *out = NULL;
    size_t from = diags->n;
    ydoc *doc = NULL;
    bool ok = false;
    vctx c = {.file = name, .d = diags};

    experiment *e = calloc(1, sizeof *e);
    if (!e || !(e->path = strdup(name)) || !(e->description = strdup(""))) {
        diag_add(diags, name, 0, 0, "", "expected to load the manifest, found no memory left");
        goto done;
    }
    c.e = e;
    if (len > MANIFEST_MAX_BYTES) {
        diag_add(diags, name, 0, 0, "", "expected a manifest of at most %u bytes, found %zu bytes",
                 MANIFEST_MAX_BYTES, len);
        goto done;
    }
    if (!data)
        data = "";   /* libyaml wants a buffer even for no bytes */
    hash_hex(fnv1a64(data, len), 16, e->hash);
    e->scale = 1;
    if (!apply_defaults(&c, &e->base))
        goto done;
    if (!ydoc_load(name, data, len, &doc, diags))
        goto done;

    c.root = doc->root;
    if (doc->root->kind != YNODE_MAPPING) {
        char f[128];
        err(&c, doc->root, "", "expected a mapping, found %s", found(doc->root, false, f, sizeof f));
        goto done;
    }
    parse_group(&c, "", doc->root, &e->base);
    check_required_and_swept(&c);
    if (!c.set_key[(size_t)(param_find("lights") - table)] && !lights_swept(&c))
        e->base.lights.placement = PLACEMENT_NONE;
    check_lights(&c);
    check_error(&c);
    ok = c.nerr == 0;

done:
    sort_diags(diags, from);
    ydoc_free(doc);
    if (ok)
        *out = e;
    else
        experiment_free(e);
    return ok;
}

bool manifest_load(const char *path, experiment **out, diag_list *diags)
{
    *out = NULL;
    unsigned char *buf = NULL;
    size_t len = 0;
    if (!read_file(path, &buf, &len, diags))
        return false;
    bool ok = manifest_load_mem(path, (const char *)buf, len, out, diags);
    free(buf);
    return ok;
}

/* >>smoke */

static void smoke_span(span *s, double max_s, uint32_t max_frames)
{
    if (s->kind == SPAN_FRAMES)
        s->frames = s->frames < max_frames ? s->frames : max_frames;
    else
        s->seconds = s->seconds < max_s ? s->seconds : max_s;
}

/* Times past the smoke run's end (schedule seconds) move to its middle; duplicates go. */
static void smoke_times(double *t, size_t *n, double end)
{
    size_t k = 0;
    for (size_t i = 0; i < *n; i++) {
        double v = t[i] < end ? t[i] : end / 2;
        bool dup = false;
        for (size_t j = 0; j < k; j++)
            dup = dup || t[j] == v;
        if (!dup)
            t[k++] = v;
    }
    *n = k;
}

void experiment_make_smoke(experiment *e)
{
    static const char *const collapse[] = {"resolution", "trials", "warmup", "duration"};
    size_t k = 0;
    for (size_t i = 0; i < e->naxes; i++) {
        bool drop = false;
        for (size_t j = 0; j < sizeof collapse / sizeof collapse[0]; j++)
            drop = drop || strcmp(e->axes[i].path, collapse[j]) == 0;
        if (drop) {
            free(e->axes[i].values);
            free(e->axes[i].line);
            free(e->axes[i].col);
        } else {
            e->axes[k++] = e->axes[i];
        }
    }
    e->naxes = k;

    run_params *b = &e->base;
    if (b->width > 160 || b->height > 120) {
        b->width = 160;
        b->height = 120;
    }
    b->trials = 1;
    b->warmup = (span){.kind = SPAN_FRAMES, .frames = 0};
    smoke_span(&b->duration, 2.0, 120);
    double end = b->duration.kind == SPAN_FRAMES
                     ? b->duration.frames * (b->clock == RUN_CLOCK_FIXED ? b->step : 1.0 / 60)
                     : b->duration.seconds;
    smoke_times(b->screenshots, &b->nscreenshots, end);
    smoke_times(b->error_at, &b->nerror_at, end);

    size_t len = strlen(e->name);
    if (len > sizeof e->name - 7)
        len = sizeof e->name - 7;
    snprintf(e->name + len, sizeof e->name - len, "-smoke");
    char salted[32];
    e->smoke = true;
    snprintf(salted, sizeof salted, "%s+smoke", e->hash);
    hash_hex(fnv1a64(salted, strlen(salted)), 16, e->hash);
}

static bool scale_side(int *side, double scale)
{
    double v = floor(*side * scale + 0.5);
    *side = v < 1 ? 1 : v > MAX_SIDE ? MAX_SIDE + 1 : (int)v;
    return *side <= MAX_SIDE;
}

/* Both sides scaled (neither skipped when the other is too large). */
static bool scale_size(int *w, int *h, double scale)
{
    bool ok_w = scale_side(w, scale);
    bool ok_h = scale_side(h, scale);
    return ok_w && ok_h;
}

bool experiment_scale_resolution(experiment *e, double scale, char *err, size_t errlen)
{
    if (!(scale > 0 && scale <= 16)) {
        snprintf(err, errlen, "--scale: expected a number > 0 and <= 16, found %g", scale);
        return false;
    }
    run_params *b = &e->base;
    bool ok = scale_size(&b->width, &b->height, scale);
    for (size_t i = 0; i < e->naxes && ok; i++) {
        struct sweep_axis *ax = &e->axes[i];
        if (strcmp(ax->path, "resolution") != 0)
            continue;
        for (size_t j = 0; j < ax->nvalues && ok; j++) {
            run_params *v = &ax->values[j];
            ok = scale_size(&v->width, &v->height, scale);
            for (size_t k = 0; k < j && ok; k++)
                if (ax->values[k].width == v->width && ax->values[k].height == v->height) {
                    snprintf(err, errlen,
                             "--scale %g: swept resolutions %zu and %zu both become %dx%d",
                             scale, k + 1, j + 1, v->width, v->height);
                    return false;
                }
        }
    }
    if (!ok) {
        snprintf(err, errlen, "--scale %g: a resolution would exceed %dx%d", scale, MAX_SIDE,
                 MAX_SIDE);
        return false;
    }
    e->scale = scale;
    char salted[64];
    snprintf(salted, sizeof salted, "%s+scale=%.17g", e->hash, scale);
    hash_hex(fnv1a64(salted, strlen(salted)), 16, e->hash);
    return true;
}

/* >>kv */

static void format_value(const param *pd, const run_params *p, char *out, size_t len)
{
    const char *at = (const char *)p + pd->off;
    char a[32];
    out[0] = '\0';
    switch (pd->type) {
    case PT_SCENE:
        snprintf(out, len, "%s", p->scene);
        break;
    case PT_RENDERERS:
        snprintf(out, len, "%s", p->renderer);
        break;
    case PT_RENDERER:
        snprintf(out, len, "%.31s", at);
        break;
    case PT_RESOLUTION:
        snprintf(out, len, "%dx%d", p->width, p->height);
        break;
    case PT_UINT: {
        uint32_t u;
        memcpy(&u, at, sizeof u);
        snprintf(out, len, "%" PRIu32, u);
        break;
    }
    case PT_NUMBER:
        if (pd->flags & PF_FLOAT) {
            float f;
            memcpy(&f, at, sizeof f);
            if (isnan(f))
                snprintf(out, len, "scene");   /* PF_SCENE_DEFAULT */
            else
                fmt_float(f, out, len);
        } else {
            double v;
            memcpy(&v, at, sizeof v);
            fmt_double(v, out, len);
        }
        break;
    case PT_VEC3: {
        float v[3];
        char y[32], z[32];
        memcpy(v, at, sizeof v);
        if (isnan(v[0])) {
            snprintf(out, len, "scene");
        } else {
            fmt_float(v[0], a, sizeof a);
            fmt_float(v[1], y, sizeof y);
            fmt_float(v[2], z, sizeof z);
            snprintf(out, len, "%s,%s,%s", a, y, z);
        }
        break;
    }
    case PT_ENUM: {
        int i;
        memcpy(&i, at, sizeof i);
        int n = 0;
        while (pd->values[n])
            n++;
        snprintf(out, len, "%s", i >= 0 && i < n ? pd->values[i] : "?");
        break;
    }
    case PT_BOOL: {
        bool b;
        memcpy(&b, at, sizeof b);
        snprintf(out, len, "%s", b ? "true" : "false");
        break;
    }
    case PT_SPAN: {
        span s;
        memcpy(&s, at, sizeof s);
        if (s.kind == SPAN_FRAMES) {
            snprintf(out, len, "frames:%" PRIu32, s.frames);
        } else {
            fmt_double(s.seconds, a, sizeof a);
            snprintf(out, len, "seconds:%s", a);
        }
        break;
    }
    case PT_COUNT: {
        light_count lc;
        memcpy(&lc, at, sizeof lc);
        if (!lc.growth && lc.start == LIGHT_COUNT_ALL) {
            snprintf(out, len, "all");
        } else if (lc.growth) {
            fmt_double(lc.every, a, sizeof a);
            snprintf(out, len, "start:%" PRIu32 ",step:%" PRIu32 ",every:%s,max:%" PRIu32,
                     lc.start, lc.step, a, lc.max);
        } else {
            snprintf(out, len, "%" PRIu32, lc.start);
        }
        break;
    }
    case PT_TIMES: {
        /* Comma-separated; a list too long for the column is named by its count and
         * hash instead, so that two different lists never share a text. */
        char all[MAX_SCREENSHOTS * 32 + 1];
        sbuf b = {all, sizeof all, 0};
        all[0] = '\0';
        size_t count;
        memcpy(&count, at, sizeof count);
        const double *times = (const double *)(at + sizeof(size_t));
        size_t n = count < MAX_SCREENSHOTS ? count : MAX_SCREENSHOTS;
        for (size_t i = 0; i < n; i++) {
            fmt_double(times[i], a, sizeof a);
            sb_add(&b, "%s%s", i ? "," : "", a);
        }
        if (b.len < len) {
            snprintf(out, len, "%s", all);
        } else {
            char h[17];
            hash_hex(fnv1a64(all, b.len), 16, h);
            snprintf(out, len, "times:%zu,fnv:%s", n, h);
        }
        break;
    }
    case PT_SCHEMA:
    case PT_NAME:
    case PT_TEXT:
    case PT_GROUP:
    case PT_SWEEP:
        break;
    }
}

size_t run_params_kv(const run_params *p, param_kv *out, size_t max)
{
    size_t k = 0;
    for (size_t i = 0; i < NPARAMS && k < max; i++) {
        const param *pd = &table[i];
        if (pd->size == 0)
            continue;
        out[k].key = pd->column ? pd->column : pd->path;
        out[k].in_id = !(pd->flags & PF_NOT_IN_ID);
        format_value(pd, p, out[k].value, sizeof out[k].value);
        /* >>helper-tiled keys */
        if ((pd->flags & PF_ID_UNLESS_DEFAULT) && pd->def && strcmp(out[k].value, pd->def) == 0)
            out[k].in_id = false;
        /* <<helper-tiled keys */
        k++;
    }
    return k;
}
