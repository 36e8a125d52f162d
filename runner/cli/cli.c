#define _DEFAULT_SOURCE   /* open_memstream */
#include "runner/cli/cli.h"
#include "runner/folder/columns.h"
#include "runner/answer/commands.h"
#include "runner/answer/summary_md.h"
#include "runner/cli/probe.h"
#include "runner/history/history.h"

#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "config.h"
#include "results/jsonout.h"
#include "version.h"
#include "renderers/gl/context.h"
#include "renderers/renderer.h"
#include "runner/manifest/manifest.h"
#include "runner/folder/merge.h"
#include "runner/manifest/params.h"
#include "runner/plan/plan_check.h"
#include "runner/trial/run.h"
#include "scenes/scene.h"

static const char usage_text[] =
    "usage: shadesweep COMMAND [OPTIONS]\n"
    "\n"
    "commands:\n"
    "  run [OPTIONS] MANIFEST     render every run of the manifest and write the results\n"
    "      -o, --out DIR          output folder (default: out/<name>)\n"
    "      --force                replace an existing output folder made by shadesweep\n"
    "      --resume               keep the complete runs of an existing output folder and\n"
    "                             run the others (a killed sweep goes on where it stopped)\n"
    "      --retry-failed         with --resume: run the failed runs again too\n"
    "      --round K              only up to round K (trial K of every run), adding to\n"
    "                             the folder's earlier rounds: what compare --exe runs\n"
    "      --backend egl|osmesa   GL backend (default: egl)\n"
    "      --device N             EGL device N instead of Mesa's surfaceless platform\n"
    "      --shard I/N            only the runs of shard I of N (1 <= I <= N)\n"
    "      --debug-gl             debug context; any GL error fails the run\n"
    "                             (also SHADESWEEP_GL_DEBUG=1)\n"
    "      --scale S              every resolution times S (e.g. 0.25: a paper's sweep\n"
    "                             at a size llvmpipe renders in time)\n"
    "      --smoke                the manifest's smoke variant: 160x120, one trial, no\n"
    "                             warm-up, at most 2 s of frames a run, priming included\n"
    "                             (draw_limit: 2; start-up and reference comparisons\n"
    "                             not counted); out/<name>-smoke\n"
    "      --set KEY=VALUE        KEY: VALUE as if written in the manifest, checked the\n"
    "                             same way (repeatable; VALUE is YAML, KEY as in\n"
    "                             docs/manifest.md). It replaces KEY wherever the manifest\n"
    "                             has it: a swept KEY becomes that one value, and\n"
    "                             --set 'sweep.KEY=[A, B]' sweeps KEY instead of a value\n"
    "                             set in place (a sweep of blocks: --set 'sweep=[...]')\n"
    "      --renderer R[,R...]    only the runs of the named renderers: as if the manifest's\n"
    "                             renderers: listed only those of its own (in its order).\n"
    "                             --set and --renderer are part of the manifest hash\n"
    "                             (--resume, merge) and recorded in each run's meta.yaml\n"
    "  validate [--set KEY=VALUE] [--renderer R[,R...]] [--gl|--no-gl] [--backend B]\n"
    "      [--device N] MANIFEST...  check manifests (with run's --set and --renderer)\n"
    "                             and print every error; exit 0 when all are valid, 2\n"
    "                             when one is not (or --gl had no GL context)\n"
    "      --gl                   check the runs against the limits of the GL context\n"
    "                             run would get (--backend, --device): forward-spml's\n"
    "                             uniform block, samples, framebuffer size; a run past\n"
    "                             them is an error. Waits up to 10 s for the context;\n"
    "                             none is an error. Default: so checked when a context\n"
    "                             is had within 1 s, else (saying why) warned about\n"
    "                             against what every GL has, as --no-gl does\n"
    "      --no-gl                no GL: only what every GL has, as warnings\n"
    "  list [--shard I/N] [--smoke] [--scale S] [--set KEY=VALUE] [--renderer R[,R...]]\n"
    "      [--json] MANIFEST      the expanded runs, one per line (--json: every run's\n"
    "                             every parameter, typed); options as run's\n"
    "  info [--backend B] [--device N] [--json]  the GL context's vendor, renderer and\n"
    "                             limits, the renderers and scenes (--json: one object)\n"
    "  probe [--backend B] [--device N] [--json] [--quick]  measure the device: fill\n"
    "                             rate, bandwidth, arithmetic, call costs (about a\n"
    "                             minute; --quick: the smallest sizes); cache it and print\n"
    "                             it as device.yaml (--json: one object). run copies the\n"
    "                             cached profile into every output folder on that device\n"
    "  merge -o OUT [--force] [--allow-mixed-builds] DIR...\n"
    "                             combine the output folders of a sweep's shards (runs\n"
    "                             of different builds only with --allow-mixed-builds)\n"
    "  compare [OPTIONS] BASE NEW  a regression gate over two output folders (--json:\n"
    "                             the verdicts as JSON)\n"
    "  compare --exe OTHER [OPTIONS] MANIFEST  the manifest with OTHER (BASE) and this\n"
    "                             build (NEW) in interleaved rounds, compared paired\n"
    "  history add|show|check [OPTIONS]  a results history: output folders into a\n"
    "                             database (SQLite or PostgreSQL), the change points of\n"
    "                             each run's series; check exits 1 on a regression\n"
    "                             (history --help)\n"
    "  report [OPTIONS] DIR...    the report over output folders (Python; --cross-device\n"
    "                             A B: two devices' rankings side by side)\n"
    "  bound [--profile DEVICE.yaml] [--passes] DIR  each run's bound from the device\n"
    "                             profile (DIR/device.yaml): a CSV row per run (--passes:\n"
    "                             per run and pass of passes.csv), the limiter named\n"
    "  ratios < REQUESTS          trial-level ratios, intervals and crossovers for\n"
    "                             scripts (the report's statistics; ratios --help)\n"
    "  params [--markdown|--bash|--json]  every manifest key: type, default, range, the\n"
    "                             renderers that read it (docs/manifest.md is --markdown)\n"
    "  columns [--markdown]       the columns of frames.csv and summary.csv and what each\n"
    "                             measured one is (docs/columns.md is --markdown)\n"
    "  version, -V, --version     the version and the commit it was built from\n"
    "  help, -h, --help           this (COMMAND --help: that command's options)\n"
    "\n"
    "exit status: 0 all runs complete and ok; 1 some run failed, partial or missing;\n"
    "2 bad input or a fatal error; 128 + the signal when interrupted.\n";

/* The usage of one command: its lines of usage_text, from "  NAME " to the next
 * command. False for a name that is not a command. */
static bool print_command_help(const char *name)
{
    size_t n = strlen(name);
    const char *s = strstr(usage_text, "commands:\n");
    for (s = s ? strchr(s, '\n') + 1 : NULL; s && *s == ' '; s = strchr(s, '\n') + 1) {
        if (strncmp(s, "  ", 2) == 0 && s[2] != ' ' && strncmp(s + 2, name, n) == 0 &&
            s[2 + n] == ' ') {
            printf("usage: shadesweep ");
            const char *e = s;
            do {
                const char *nl = strchr(e, '\n');
                fwrite(e == s ? e + 2 : e, 1, (size_t)(nl + 1 - (e == s ? e + 2 : e)), stdout);
                e = nl + 1;
            } while (strncmp(e, "    ", 4) == 0);
            return true;
        }
        if (!strchr(s, '\n'))
            break;
    }
    return false;
}

typedef struct cli_opts {
    const char *out;
    bool force, resume, debug_gl, smoke, retry_failed, json, allow_mixed, quick;
    gl_backend backend;
    int device;
    unsigned shard, nshards;
    double scale;              /* 0: not given */
    unsigned round;            /* --round K; 0: not given */
    const char *sets[64];      /* --set KEY=VALUE, in order */
    manifest_overrides ov;     /* the --set and --renderer that load_plan applies */
    int gl;                    /* --gl 1, --no-gl -1; 0: when a context is had in time */
    bool refuse_gl;            /* runs past the GL's limits are errors (validate), not
                                * warnings (run) */
    int gl_state;              /* 0: not asked yet; 1: gi holds the limits; -1: gl_why */
    gl_info gi;
    char gl_why[512];
} cli_opts;

enum { OPT_FORCE = 1000, OPT_BACKEND, OPT_DEVICE, OPT_SHARD, OPT_DEBUG_GL, OPT_RESUME, OPT_SMOKE, OPT_SCALE,
       OPT_RETRY_FAILED, OPT_ROUND, OPT_JSON, OPT_SET, OPT_RENDERER, OPT_ALLOW_MIXED, OPT_GL,
       OPT_NO_GL, OPT_QUICK };

/* How long validate waits for the GL context whose limits it checks against: by
 * default (no context in time: the checks are warnings), and with --gl. */
#define GL_WAIT_DEFAULT_S 1.0
#define GL_WAIT_GL_S 10.0

/* Whether `name` is one of the space-separated words of `words`. */
static bool has_word(const char *words, const char *name)
{
    size_t n = strlen(name);
    for (const char *w = strstr(words, name); w; w = strstr(w + 1, name))
        if ((w == words || w[-1] == ' ') && (w[n] == ' ' || w[n] == 0))
            return true;
    return false;
}

/* Parses the options a command accepts; `allowed` lists their long names. Returns
 * the index of the first operand, or -1 after printing the problem. */
static int parse_opts(int argc, char **argv, const char *allowed, cli_opts *o)
{
    static const struct option longopts[] = {
        {"out", required_argument, NULL, 'o'},
        {"force", no_argument, NULL, OPT_FORCE},
        {"backend", required_argument, NULL, OPT_BACKEND},
        {"device", required_argument, NULL, OPT_DEVICE},
        {"shard", required_argument, NULL, OPT_SHARD},
        {"debug-gl", no_argument, NULL, OPT_DEBUG_GL},
        {"resume", no_argument, NULL, OPT_RESUME},
        {"smoke", no_argument, NULL, OPT_SMOKE},
        {"scale", required_argument, NULL, OPT_SCALE},
        {"retry-failed", no_argument, NULL, OPT_RETRY_FAILED},
        {"round", required_argument, NULL, OPT_ROUND},
        {"json", no_argument, NULL, OPT_JSON},
        {"set", required_argument, NULL, OPT_SET},
        {"renderer", required_argument, NULL, OPT_RENDERER},
        {"allow-mixed-builds", no_argument, NULL, OPT_ALLOW_MIXED},
        {"gl", no_argument, NULL, OPT_GL},
        {"no-gl", no_argument, NULL, OPT_NO_GL},
        {"quick", no_argument, NULL, OPT_QUICK},
        {NULL, 0, NULL, 0},
    };
    memset(o, 0, sizeof *o);
    o->ov.sets = o->sets;
    o->device = -1;
    o->nshards = 1;
    const char *env = getenv("SHADESWEEP_GL_DEBUG");
    o->debug_gl = env && strcmp(env, "1") == 0;
    optind = 1;
    opterr = 0;
    int c, li = -1;
    /* no leading '+': options may come before or after the operands (GNU getopt
     * permutes argv), as `shadesweep run MANIFEST -o DIR` is written */
    while ((c = getopt_long(argc, argv, ":o:", longopts, &li)) != -1) {
        const char *name = NULL;
        if (c == 'o')
            name = "out";
        for (size_t k = 1; c >= OPT_FORCE && longopts[k].name; k++)
            if (longopts[k].val == c)
                name = longopts[k].name;
        if (c == '?' || c == ':' || (name && !has_word(allowed, name))) {
            /* a known option by its name: argv[optind - 1] may be its value */
            char known[40];
            snprintf(known, sizeof known, c == 'o' ? "-o" : "--%s", name ? name : "");
            fprintf(stderr, "shadesweep %s: %s: %s\n", argv[0], name ? known : argv[optind - 1],
                    c == ':' ? "option needs a value" : "unknown option here");
            return -1;
        }
        char err[512];
        switch (c) {
        case 'o': o->out = optarg; break;
        case OPT_FORCE: o->force = true; break;
        case OPT_DEBUG_GL: o->debug_gl = true; break;
        case OPT_RESUME: o->resume = true; break;
        case OPT_SMOKE: o->smoke = true; break;
        case OPT_JSON: o->json = true; break;
        case OPT_RETRY_FAILED: o->retry_failed = true; break;
        case OPT_ALLOW_MIXED: o->allow_mixed = true; break;
        case OPT_GL: o->gl = 1; break;
        case OPT_NO_GL: o->gl = -1; break;
        case OPT_QUICK: o->quick = true; break;
        case OPT_ROUND: {
            char *end;
            errno = 0;
            unsigned long v = strtoul(optarg, &end, 10);
            if (errno || *end || end == optarg || v < 1 || v > 1000 || optarg[0] == '-') {
                fprintf(stderr, "shadesweep: --round: expected a round 1..1000, found '%s'\n",
                        optarg);
                return -1;
            }
            o->round = (unsigned)v;
            break;
        }
        case OPT_SCALE: {
            char *end;
            errno = 0;
            double v = strtod(optarg, &end);
            if (errno || *end || end == optarg || !(v > 0 && v <= 16)) {
                fprintf(stderr, "shadesweep: --scale: expected a number > 0 and <= 16, found '%s'\n",
                        optarg);
                return -1;
            }
            o->scale = v;
            break;
        }
        case OPT_BACKEND:
            if (strcmp(optarg, "egl") == 0)
                o->backend = GL_BACKEND_EGL;
            else if (strcmp(optarg, "osmesa") == 0 && HAVE_OSMESA)
                o->backend = GL_BACKEND_OSMESA;
            else {
                fprintf(stderr, "shadesweep: --backend: expected %s, found '%s'\n",
                        HAVE_OSMESA ? "egl or osmesa" : "egl (built without OSMesa)", optarg);
                return -1;
            }
            break;
        case OPT_DEVICE: {
            char *end;
            errno = 0;
            long v = strtol(optarg, &end, 10);
            if (errno || *end || end == optarg || v < 0 || v > 1024) {
                fprintf(stderr, "shadesweep: --device: expected an index 0..1024, found '%s'\n",
                        optarg);
                return -1;
            }
            o->device = (int)v;
            break;
        }
        case OPT_SET:
            if (!override_check_set(optarg, err, sizeof err)) {
                fprintf(stderr, "shadesweep: %s\n", err);
                return -1;
            }
            if (o->ov.nsets == sizeof o->sets / sizeof *o->sets) {
                fprintf(stderr, "shadesweep: --set: expected at most %zu, found more\n",
                        sizeof o->sets / sizeof *o->sets);
                return -1;
            }
            o->sets[o->ov.nsets++] = optarg;
            break;
        case OPT_RENDERER:
            if (o->ov.renderers) {
                fprintf(stderr, "shadesweep: --renderer: given twice; name every renderer in "
                        "one, separated by commas\n");
                return -1;
            }
            if (!override_check_renderers(optarg, err, sizeof err)) {
                fprintf(stderr, "shadesweep: %s\n", err);
                return -1;
            }
            o->ov.renderers = optarg;
            break;
        case OPT_SHARD:
            if (!parse_shard(optarg, &o->shard, &o->nshards, err, sizeof err)) {
                fprintf(stderr, "shadesweep: %s\n", err);
                return -1;
            }
            break;
        }
    }
    if (o->device >= 0 && o->backend != GL_BACKEND_EGL) {
        fprintf(stderr, "shadesweep: --device: only with --backend egl\n");
        return -1;
    }
    return optind;
}

/* The limits of the GL context run would get, asked once (run_probe_gl, within
 * GL_WAIT_GL_S with --gl, else GL_WAIT_DEFAULT_S); false with o->gl_why. */
static bool get_gl(cli_opts *o)
{
    if (!o->gl_state)
        o->gl_state = run_probe_gl(o->backend, o->device,
                                   o->gl > 0 ? GL_WAIT_GL_S : GL_WAIT_DEFAULT_S, &o->gi,
                                   o->gl_why, sizeof o->gl_why) ? 1 : -1;
    return o->gl_state > 0;
}

/* The plan's runs against the GL's limits (where some run is past what every GL has,
 * or with --gl): errors in d (refuse_gl) or warnings; without a GL, or with --no-gl,
 * the warnings against what every GL has, and why (only a GL can refuse them). */
static bool check_plan_gl(const char *path, cli_opts *o, const experiment *e, const plan *p,
                          diag_list *d)
{
    if (o->gl < 0 || (o->gl == 0 && !plan_needs_gl(p))) {
        plan_warnings(e, p, stderr);
        return true;
    }
    if (!get_gl(o)) {
        fprintf(stderr, "%s: note: not checked against this GL (%s): the warnings say what "
                "every GL has\n", path, o->gl_why);
        plan_warnings(e, p, stderr);
        return true;
    }
    if (o->refuse_gl)
        return plan_check_gl(e, p, &o->gi, d);
    diag_list w = {0};
    plan_check_gl(e, p, &o->gi, &w);
    for (size_t i = 0; i < w.n; i++)
        fprintf(stderr, "%s: warning: %s: %s\n", path, w.v[i].key, w.v[i].msg);
    diag_free(&w);
    return true;
}

/* Loads and expands a manifest, printing every problem. */
static bool load_plan(const char *path, cli_opts *o, experiment **e, plan *p)
{
    diag_list d = {0};
    *e = NULL;
    memset(p, 0, sizeof *p);
    bool ok = manifest_load_with(path, &o->ov, e, &d);
    char err[256];
    if (ok && o->scale > 0 && !experiment_scale_resolution(*e, o->scale, err, sizeof err)) {
        diag_add(&d, path, 0, 0, "", "%s", err);
        ok = false;
    }
    if (ok && o->smoke)
        experiment_make_smoke(*e);
    ok = ok && plan_expand(*e, o->nshards, p, &d);
    if (ok && (!plan_check(*e, p, &d) || !check_plan_gl(path, o, *e, p, &d))) {
        plan_free(p);
        ok = false;
    }
    diag_print(&d, stderr);
    diag_free(&d);
    if (!ok) {
        experiment_free(*e);
        *e = NULL;
    }
    return ok;
}

static int cmd_validate(int argc, char **argv)
{
    cli_opts o;
    int first = parse_opts(argc, argv, "set renderer gl no-gl backend device", &o);
    if (first < 0)
        return 2;
    if (first >= argc) {
        fprintf(stderr, "shadesweep validate: expected one or more manifests\n");
        return 2;
    }
    o.refuse_gl = true;
    if (o.gl > 0 && !get_gl(&o)) {
        fprintf(stderr, "shadesweep validate: --gl: %s\n", o.gl_why);
        return 2;
    }
    int bad = 0;
    for (int i = first; i < argc; i++) {
        experiment *e;
        plan p;
        if (!load_plan(argv[i], &o, &e, &p)) {
            bad++;
            continue;
        }
        printf("%s: ok, %zu run%s", argv[i], p.nruns, p.nruns == 1 ? "" : "s");
        if (p.nfolded)
            printf(" (%zu of %zu grid points folded: they differ only in keys their renderer "
                   "does not read)", p.nfolded, p.npoints);
        printf("\n");
        plan_free(&p);
        experiment_free(e);
    }
    return bad ? 2 : 0;
}

static int cmd_list(int argc, char **argv)
{
    cli_opts o;
    int first = parse_opts(argc, argv, "shard smoke scale json set renderer", &o);
    if (first < 0)
        return 2;
    o.gl = -1;   /* list loads no GL: it warns about what every GL has */
    if (argc - first != 1) {
        fprintf(stderr, "shadesweep list: expected one manifest\n");
        return 2;
    }
    experiment *e;
    plan p;
    if (!load_plan(argv[first], &o, &e, &p))
        return 2;
    if (o.json)
        plan_print_json(&p, o.shard, stdout);
    else
        plan_print(&p, o.shard, stdout);
    plan_free(&p);
    experiment_free(e);
    return 0;
}

static bool in_names(const char *const *names, const char *s)
{
    for (; *names; names++)
        if (strcmp(*names, s) == 0)
            return true;
    return false;
}

/* `key: value` lines as one JSON object, each value typed (json_typed; yes and no as
 * booleans); the keys in `lists` hold space-separated names and become arrays, those
 * in `strings` stay strings (a version "4.50" is not the number 4.5). */
static void info_lines_to_json(const char *text, const char *const *lists,
                               const char *const *strings, FILE *out)
{
    bool first = true;
    fputs("{", out);
    for (const char *l = text; *l;) {
        const char *nl = strchr(l, '\n');
        size_t len = nl ? (size_t)(nl - l) : strlen(l);
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)len, l);
        l += len + (nl ? 1 : 0);
        char *colon = strstr(line, ": ");
        if (!colon)
            continue;
        *colon = '\0';
        const char *v = colon + 2;
        json_key(out, &first, line);
        if (in_names(strings, line)) {
            json_string(out, v);
            continue;
        }
        if (strcmp(v, "yes") == 0 || strcmp(v, "no") == 0) {
            fputs(v[0] == 'y' ? "true" : "false", out);
            continue;
        }
        if (!in_names(lists, line)) {
            json_typed(out, v);
            continue;
        }
        json_words(out, v);
    }
    fputs("}\n", out);
}

/* parse_opts for a command that takes no operands (argv[0] its name); false after
 * printing the problem. */
static bool parse_opts_only(int argc, char **argv, const char *allowed, cli_opts *o)
{
    int first = parse_opts(argc, argv, allowed, o);
    if (first >= 0 && first != argc)
        fprintf(stderr, "shadesweep %s: unexpected argument '%s'\n", argv[0], argv[first]);
    return first == argc;
}

static int cmd_info(int argc, char **argv)
{
    cli_opts o;
    if (!parse_opts_only(argc, argv, "backend device debug-gl json", &o))
        return 2;
    /* the lines are written once; --json reads them back as an object */
    char *text = NULL;
    size_t text_len = 0;
    FILE *out = o.json ? open_memstream(&text, &text_len) : stdout;
    if (!out) {
        fprintf(stderr, "shadesweep info: out of memory\n");
        return 2;
    }
    char err[512];
    int rc = 0;
    if (o.backend == GL_BACKEND_EGL) {
        int n = gl_egl_device_count(err, sizeof err);
        if (n >= 0)
            fprintf(out, "egl_devices: %d\n", n);
        else
            fprintf(out, "egl_devices: none (%s)\n", err);
    }
    gl_context_desc d = {.backend = o.backend, .device = o.device, .debug = o.debug_gl};
    gl_context *ctx = gl_context_create(&d, err, sizeof err);
    if (!ctx) {
        fprintf(stderr, "shadesweep info: %s\n", err);
        rc = 2;
        goto done;
    }
    gl_context_print_info(ctx, out);
    /* each renderer's light limit on this context ("forward_spml_max_lights: 819") */
    for (size_t i = 0; i < renderer_kind_count(); i++) {
        const renderer_impl *ri = renderer_kind_at(i);
        if (!ri->max_lights)
            continue;
        char key[64];
        snprintf(key, sizeof key, "%s", ri->name);
        for (char *c = key; *c; c++)
            *c = *c == '-' ? '_' : *c;
        fprintf(out, "%s_max_lights: %u\n", key,
                (unsigned)ri->max_lights(NULL, gl_context_info(ctx)->max_uniform_block_size));
    }
    gl_context_destroy(ctx);
    fprintf(out, "renderers:");
    for (size_t i = 0; i < renderer_kind_count(); i++)
        fprintf(out, " %s", renderer_kind_at(i)->name);
    fprintf(out, "\nscenes:");
    for (size_t i = 0; i < scene_catalog_count(); i++)
        fprintf(out, " %s", scene_catalog_at(i)->name);
    fprintf(out, "\n");
done:
    if (o.json) {
        fclose(out);
        static const char *const lists[] = {"renderers", "scenes", NULL};
        static const char *const strings[] = {"version", "glsl", NULL};
        if (rc == 0)
            info_lines_to_json(text, lists, strings, stdout);
        free(text);
    }
    return rc;
}

static int cmd_probe(int argc, char **argv)
{
    cli_opts o;
    if (!parse_opts_only(argc, argv, "backend device json quick", &o))
        return 2;
    return probe_main(o.backend, o.device, o.json, o.quick);
}

/* The end-of-run table (runner/answer/summary_md.c) on stdout and OUT/summary.md; false after
 * reporting a summary that could not be written. */
static bool print_summary_table(const char *dir)
{
    char err[1200];
    fflush(stderr);
    bool ok = summary_table_write(dir, stdout, err, sizeof err);
    if (!ok)
        fprintf(stderr, "shadesweep merge: no summary table: %s\n", err);
    fflush(stdout);
    return ok;
}

static int cmd_run(int argc, char **argv)
{
    cli_opts o;
    int first = parse_opts(argc, argv, "out force resume retry-failed round backend device shard debug-gl "
                           "smoke scale set renderer", &o);
    if (first < 0)
        return 2;
    if (argc - first != 1) {
        fprintf(stderr, "shadesweep run: expected one manifest\n");
        return 2;
    }
    if (o.force && o.resume) {
        fprintf(stderr, "shadesweep run: --force and --resume exclude each other\n");
        return 2;
    }
    if (o.retry_failed && !o.resume) {
        fprintf(stderr, "shadesweep run: --retry-failed: only with --resume\n");
        return 2;
    }
    run_catch_stop_signals();
    experiment *e;
    plan p;
    if (!load_plan(argv[first], &o, &e, &p))
        return 2;
    run_options ro = {
        .backend = o.backend,
        .device = o.device,
        .debug_gl = o.debug_gl,
        .shard = o.nshards > 1 ? o.shard : 0,
        .nshards = o.nshards,
        .resume = o.resume,
        .retry_failed = o.retry_failed,
        .round = o.round,
    };
    int rc = run_sweep(e, &p, o.out, o.force, &ro);
    plan_free(&p);
    experiment_free(e);
    return rc;
}

/* `shadesweep params [--markdown | --bash] [KEY...]`: the manifest keys from
 * runner/manifest/params.def (docs/manifest.md and the bash completion are its output). */
static int cmd_params(int argc, char **argv)
{
    params_format f = PARAMS_TEXT;
    int i = 1;
    for (; i < argc && argv[i][0] == '-'; i++) {
        if (strcmp(argv[i], "--markdown") == 0)
            f = PARAMS_MARKDOWN;
        else if (strcmp(argv[i], "--bash") == 0)
            f = PARAMS_BASH;
        else if (strcmp(argv[i], "--json") == 0)
            f = PARAMS_JSON;
        else {
            fprintf(stderr, "shadesweep params: %s: unknown option here\n", argv[i]);
            return 2;
        }
    }
    if (i < argc) {
        fprintf(stderr, "shadesweep params: unexpected argument '%s'\n", argv[i]);
        return 2;
    }
    params_print(stdout, f);
    return 0;
}

/* `shadesweep columns [--markdown]`: the columns of results/metrics.def and around
 * them (docs/columns.md is the markdown). */
static int cmd_columns(int argc, char **argv)
{
    bool markdown = false;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--markdown") == 0) {
            markdown = true;
        } else {
            fprintf(stderr, "shadesweep columns: unexpected argument '%s'\n", argv[i]);
            return 2;
        }
    }
    columns_print(stdout, markdown);
    return 0;
}

static int cmd_merge(int argc, char **argv)
{
    cli_opts o;
    int first = parse_opts(argc, argv, "out force allow-mixed-builds", &o);
    if (first < 0)
        return 2;
    if (!o.out || first >= argc) {
        fprintf(stderr, "shadesweep merge: expected -o OUT and one or more shard folders\n");
        return 2;
    }
    int rc = merge_main(o.out, o.force, o.allow_mixed, argc - first, argv + first);
    if (rc != 2 && !print_summary_table(o.out))
        rc = 2;
    return rc;
}

int cli_main(int argc, char **argv)
{
    if (argc < 2) {
        fputs(usage_text, stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        fputs(usage_text, stdout);
        return 0;
    }
    if (strcmp(cmd, "--version") == 0 || strcmp(cmd, "-V") == 0 || strcmp(cmd, "version") == 0) {
        printf("shadesweep %s (%s)\n", SHADESWEEP_VERSION, SHADESWEEP_COMMIT);
        return 0;
    }
    /* `shadesweep COMMAND ... --help` anywhere before a `--`: that command's part of
     * the usage, on stdout, exit 0. ratios and compare have a usage of their own,
     * which says more (the top-level lines of ratios point back at its --help). */
    bool own_help = strcmp(cmd, "ratios") == 0 || strcmp(cmd, "compare") == 0 ||
                    strcmp(cmd, "history") == 0;
    for (int i = 2; i < argc && !own_help && strcmp(argv[i], "--") != 0; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            if (print_command_help(cmd))
                return 0;
            break;
        }
    static const struct {
        const char *name;
        int (*fn)(int, char **);
    } commands[] = {
        {"run", cmd_run},         {"validate", cmd_validate}, {"list", cmd_list},
        {"info", cmd_info},       {"merge", cmd_merge},       {"params", cmd_params},
        {"columns", cmd_columns}, {"ratios", cmd_ratios},     {"compare", cmd_compare},
        {"report", cmd_report},   {"probe", cmd_probe},       {"history", cmd_history},
        {"bound", cmd_bound},
    };
    /* Each command parses argv[1..]: its name plays argv[0]. */
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (strcmp(cmd, commands[i].name) == 0)
            return commands[i].fn(argc - 1, argv + 1);
    fprintf(stderr, "shadesweep: unknown command '%s'\n\n%s", cmd, usage_text);
    return 2;
}
