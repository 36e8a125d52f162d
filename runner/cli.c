#include "runner/cli.h"
#include "runner/commands.h"
#include "runner/summary_md.h"

#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "config.h"
#include "version.h"
#include "renderers/forward_common.h"
#include "renderers/gl/context.h"
#include "renderers/renderer.h"
#include "results/fsutil.h"
#include "runner/manifest.h"
#include "runner/merge.h"
#include "runner/run.h"
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
    "      --backend egl|osmesa   GL backend (default: egl)\n"
    "      --device N             EGL device N instead of Mesa's surfaceless platform\n"
    "      --shard I/N            only the runs of shard I of N (1 <= I <= N)\n"
    "      --debug-gl             debug context; any GL error fails the run\n"
    "                             (also SHADESWEEP_GL_DEBUG=1)\n"
    "      --scale S              every resolution times S (e.g. 0.25: a paper's sweep\n"
    "                             at a size llvmpipe renders in time)\n"
    "      --smoke                the manifest's smoke variant: 160x120, one trial, no\n"
    "                             warm-up, at most 2 s a run; out/<name>-smoke\n"
    "  validate MANIFEST...       check manifests; print every error\n"
    "  list [--shard I/N] [--smoke] [--scale S] MANIFEST  the expanded runs, one per line\n"
    "  info [--backend B] [--device N]  the GL context's vendor, renderer and limits\n"
    "  merge -o OUT [--force] DIR...  combine the output folders of a sweep's shards\n"
    "  --version, --help\n"
    "\n"
    "exit status: 0 all runs succeeded; 1 some run failed (summary.csv says which);\n"
    "2 bad input or a fatal error.\n";

typedef struct cli_opts {
    const char *out;
    bool force, resume, debug_gl, smoke;
    gl_backend backend;
    int device;
    unsigned shard, nshards;
    double scale;              /* 0: not given */
} cli_opts;

enum { OPT_FORCE = 1000, OPT_BACKEND, OPT_DEVICE, OPT_SHARD, OPT_DEBUG_GL, OPT_RESUME, OPT_SMOKE, OPT_SCALE };

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
        {NULL, 0, NULL, 0},
    };
    memset(o, 0, sizeof *o);
    o->device = -1;
    o->nshards = 1;
    const char *env = getenv("SHADESWEEP_GL_DEBUG");
    o->debug_gl = env && strcmp(env, "1") == 0;
    optind = 1;
    opterr = 0;
    int c, li = -1;
    while ((c = getopt_long(argc, argv, "+:o:", longopts, &li)) != -1) {
        const char *name = NULL;
        if (c == 'o')
            name = "out";
        else if (c >= OPT_FORCE)
            name = longopts[c - OPT_FORCE + 1].name;
        if (c == '?' || c == ':' || (name && !strstr(allowed, name))) {
            const char *bad = argv[optind - 1];
            fprintf(stderr, "shadesweep %s: %s: %s\n", argv[0], bad,
                    c == ':' ? "option needs a value" : "unknown option here");
            return -1;
        }
        char err[256];
        switch (c) {
        case 'o': o->out = optarg; break;
        case OPT_FORCE: o->force = true; break;
        case OPT_DEBUG_GL: o->debug_gl = true; break;
        case OPT_RESUME: o->resume = true; break;
        case OPT_SMOKE: o->smoke = true; break;
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

/* Loads and expands a manifest, printing every problem. */
static bool load_plan(const char *path, const cli_opts *o, experiment **e, plan *p)
{
    diag_list d = {0};
    *e = NULL;
    memset(p, 0, sizeof *p);
    bool ok = manifest_load(path, e, &d);
    char err[256];
    if (ok && o->scale > 0 && !experiment_scale_resolution(*e, o->scale, err, sizeof err)) {
        diag_add(&d, path, 0, 0, "", "%s", err);
        ok = false;
    }
    if (ok && o->smoke)
        experiment_make_smoke(*e);
    ok = ok && plan_expand(*e, o->nshards, p, &d);
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
    int first = parse_opts(argc, argv, "", &o);
    if (first < 0)
        return 2;
    if (first >= argc) {
        fprintf(stderr, "shadesweep validate: expected one or more manifests\n");
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
        printf("%s: ok, %zu run%s\n", argv[i], p.nruns, p.nruns == 1 ? "" : "s");
        plan_free(&p);
        experiment_free(e);
    }
    return bad ? 2 : 0;
}

static int cmd_list(int argc, char **argv)
{
    cli_opts o;
    int first = parse_opts(argc, argv, "shard smoke scale", &o);
    if (first < 0)
        return 2;
    if (argc - first != 1) {
        fprintf(stderr, "shadesweep list: expected one manifest\n");
        return 2;
    }
    experiment *e;
    plan p;
    if (!load_plan(argv[first], &o, &e, &p))
        return 2;
    plan_print(&p, o.shard, stdout);
    plan_free(&p);
    experiment_free(e);
    return 0;
}

static int cmd_info(int argc, char **argv)
{
    cli_opts o;
    int first = parse_opts(argc, argv, "backend device debug-gl", &o);
    if (first < 0)
        return 2;
    if (first != argc) {
        fprintf(stderr, "shadesweep info: unexpected argument '%s'\n", argv[first]);
        return 2;
    }
    char err[512];
    if (o.backend == GL_BACKEND_EGL) {
        int n = gl_egl_device_count(err, sizeof err);
        if (n >= 0)
            printf("egl_devices: %d\n", n);
        else
            printf("egl_devices: none (%s)\n", err);
    }
    gl_context_desc d = {.backend = o.backend, .device = o.device, .debug = o.debug_gl};
    gl_context *ctx = gl_context_create(&d, err, sizeof err);
    if (!ctx) {
        fprintf(stderr, "shadesweep info: %s\n", err);
        return 2;
    }
    gl_context_print_info(ctx, stdout);
    printf("forward_spml_max_lights: %u\n",
           (unsigned)forward_spml_max_lights(gl_context_info(ctx)->max_uniform_block_size));
    gl_context_destroy(ctx);
    printf("renderers:");
    for (size_t i = 0; i < renderer_kind_count(); i++)
        printf(" %s", renderer_kind_at(i)->name);
    printf("\nscenes:");
    for (size_t i = 0; i < scene_catalog_count(); i++)
        printf(" %s", scene_catalog_at(i)->name);
    printf("\n");
    return 0;
}

/* The end-of-run table (runner/summary_md.c) on stdout and OUT/summary.md; a
 * problem with it is reported and changes no exit status. */
static void print_summary_table(const char *dir)
{
    char err[600];
    fflush(stderr);
    if (!summary_table_write(dir, stdout, err, sizeof err))
        fprintf(stderr, "shadesweep: no summary table: %s\n", err);
    fflush(stdout);
}

static int cmd_run(int argc, char **argv)
{
    cli_opts o;
    int first = parse_opts(argc, argv, "out force resume backend device shard debug-gl smoke scale", &o);
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
    experiment *e;
    plan p;
    if (!load_plan(argv[first], &o, &e, &p))
        return 2;

    int rc = 2;
    char dir[4096], err[512];
    if (o.out)
        snprintf(dir, sizeof dir, "%s", o.out);
    else
        snprintf(dir, sizeof dir, "out/%s", e->name);
    if (fs_exists(dir)) {
        char marker[4200];
        snprintf(marker, sizeof marker, "%s/plan.csv", dir);
        if (!o.force && !o.resume) {
            fprintf(stderr,
                    "shadesweep run: %s exists; use --resume to finish it, --force to replace "
                    "it, or --out DIR\n",
                    dir);
            goto done;
        }
        if (!fs_exists(marker)) {
            fprintf(stderr,
                    "shadesweep run: %s exists and has no plan.csv: not a shadesweep output "
                    "folder, not replacing it\n",
                    dir);
            goto done;
        }
        if (o.force && !fs_remove_tree(dir, err, sizeof err)) {
            fprintf(stderr, "shadesweep run: %s\n", err);
            goto done;
        }
    }
    char runs[4200];
    snprintf(runs, sizeof runs, "%s/runs", dir);
    if (!fs_mkdirs(runs, err, sizeof err)) {
        fprintf(stderr, "shadesweep run: %s\n", err);
        goto done;
    }
    run_options ro = {
        .out_dir = dir,
        .backend = o.backend,
        .device = o.device,
        .debug_gl = o.debug_gl,
        .shard = o.nshards > 1 ? o.shard : 0,
        .nshards = o.nshards,
        .resume = o.resume,
    };
    rc = run_plan(e, &p, &ro);
    if (rc != 2) {
        fprintf(stderr, "results: %s/summary.csv\n", dir);
        print_summary_table(dir);
    }
done:
    plan_free(&p);
    experiment_free(e);
    return rc;
}

static int cmd_merge(int argc, char **argv)
{
    cli_opts o;
    int first = parse_opts(argc, argv, "out force", &o);
    if (first < 0)
        return 2;
    if (!o.out || first >= argc) {
        fprintf(stderr, "shadesweep merge: expected -o OUT and one or more shard folders\n");
        return 2;
    }
    int rc = merge_main(o.out, o.force, argc - first, argv + first);
    if (rc != 2)
        print_summary_table(o.out);
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
    if (strcmp(cmd, "--version") == 0) {
        printf("shadesweep %s (%s)\n", SHADESWEEP_VERSION, SHADESWEEP_COMMIT);
        return 0;
    }
    /* Each command parses argv[1..]: its name plays argv[0]. */
    if (strcmp(cmd, "run") == 0)
        return cmd_run(argc - 1, argv + 1);
    if (strcmp(cmd, "validate") == 0)
        return cmd_validate(argc - 1, argv + 1);
    if (strcmp(cmd, "list") == 0)
        return cmd_list(argc - 1, argv + 1);
    if (strcmp(cmd, "info") == 0)
        return cmd_info(argc - 1, argv + 1);
    if (strcmp(cmd, "merge") == 0)
        return cmd_merge(argc - 1, argv + 1);
    if (strcmp(cmd, "compare") == 0)
        return cmd_compare(argc - 1, argv + 1);
    if (strcmp(cmd, "report") == 0)
        return cmd_report(argc - 1, argv + 1);
    fprintf(stderr, "shadesweep: unknown command '%s'\n\n%s", cmd, usage_text);
    return 2;
}
