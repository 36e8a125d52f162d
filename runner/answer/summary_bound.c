/* summary.md's bounds (runner/answer/summary_bound.h). */
#include "runner/answer/summary_bound.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "results/mdtext.h"
#include "runner/answer/commands.h"
#include "runner/folder/bound_folder.h"

/* milliseconds, or "-" */
static void ms(FILE *md, double us)
{
    if (isfinite(us))
        fprintf(md, " %.3f |", us / 1e3);
    else
        fputs(" - |", md);
}

void summary_bound_md(FILE *md, const char *out_dir, const csv_table *sm)
{
    static folder_bound fb;
    fputs("\n## Bounds\n\n", md);
    if (!folder_bound_open(&fb, out_dir, NULL)) {
        if (strcmp(fb.why, folder_bound_no_profile) == 0)
            fputs(fb.why, md);
        else
            md_put(md, fb.why);   /* an unreadable device.yaml: its path is in it */
        fputs(".\n", md);
        folder_bound_close(&fb);
        return;
    }
    fputs("The time the device needs for each run's counted work, by its profile "
          "(device.yaml: ", md);
    md_put(md, fb.prof.renderer);
    fputs(", probed ", md);
    md_put(md, fb.prof.date[0] ? fb.prof.date : "at an unknown date");
    fprintf(md, "%s): bytes / bandwidth, samples / fill rate, light evaluations x %.0f "
            "flops / arithmetic rate, draws, state changes and dispatches x their cost; "
            "the largest is the bound, its resource the limiter, `bound %%` the bound over "
            "the measured frame time (docs/notes/device-profile.md \"The bound\").\n\n",
            fb.prof.quick ? ", --quick" : "", BOUND_FLOPS_PER_EVALUATION);
    size_t n;
    run_bound *rb = folder_bound_runs(&fb, sm, &n);
    fputs("| run | renderer | measured (ms) | bound (ms) | limiter | bound % | bytes (ms) | "
          "fill (ms) | alu (ms) | draws (ms) | dispatches (ms) |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|\n", md);
    size_t nerr = 0;
    for (size_t i = 0; rb && i < n; i++) {
        fprintf(md, "| %s | ", rb[i].id);
        md_put(md, rb[i].renderer);
        fputs(" |", md);
        ms(md, rb[i].measured_us);
        ms(md, rb[i].b.bound_us);
        fprintf(md, " %s |", rb[i].b.limiter >= 0 ? bound_resource_names[rb[i].b.limiter] : "-");
        if (isfinite(rb[i].b.pct))
            fprintf(md, " %.1f |", rb[i].b.pct);
        else
            fputs(" - |", md);
        for (int r = 0; r < BOUND_NRESOURCES; r++)
            ms(md, rb[i].b.us[r]);
        fputc('\n', md);
        nerr += rb[i].b.model_error;
    }
    fputc('\n', md);
    if (!nerr)
        fputs("Model errors: none (every bound is at most its run's measured time).\n", md);
    for (size_t i = 0; rb && i < n; i++)
        if (rb[i].b.model_error) {
            fprintf(md, "- model error: run %s (", rb[i].id);
            md_put(md, rb[i].renderer);
            fprintf(md, "): the %s bound, %.3f ms, is above the measured %.3f ms (%.1f%%)\n",
                    bound_resource_names[rb[i].b.limiter], rb[i].b.bound_us / 1e3,
                    rb[i].measured_us / 1e3, rb[i].b.pct);
        }
    free(rb);
    folder_bound_close(&fb);
}

/* A CSV row's bound fields: measured, bound, limiter, pct, each resource, model error. */
static void print_bound(double measured_us, const bound_result *b)
{
    const double v[] = {measured_us, b->bound_us};
    for (size_t k = 0; k < 2; k++)
        isfinite(v[k]) ? printf("%.3f,", v[k]) : printf(",");
    printf("%s,", b->limiter >= 0 ? bound_resource_names[b->limiter] : "");
    if (isfinite(b->pct))
        printf("%.1f", b->pct);
    for (int r = 0; r < BOUND_NRESOURCES; r++)
        isfinite(b->us[r]) ? printf(",%.3f", b->us[r]) : printf(",");
    printf(",%s", b->model_error ? "yes" : "");
}

static void print_header(const char *first)
{
    printf("%s,measured_us,bound_us,limiter,bound_pct", first);
    for (int r = 0; r < BOUND_NRESOURCES; r++)
        printf(",%s_us", bound_resource_names[r]);
    printf(",model_error");
}

/* `bound --passes`: a row per run and pass of DIR/runs/<id>/passes.csv, the means over
 * its rows: samples shaded, draws and dispatches over the pass's gpu_us
 * (no bytes or evaluations are counted per pass). `attributed` is passes.csv's
 * gpu_us_attributed: on a CPU rasterizer a pass's time is not its own. */
static void print_passes(const folder_bound *fb, const char *dir, const run_bound *rb)
{
    enum { MAXP = 32 };
    char path[4300], err[4400];
    snprintf(path, sizeof path, "%s/runs/%s/passes.csv", dir, rb->id);
    csv_table t;
    if (!csv_read(path, &t, err, sizeof err))
        return;   /* a run without passes.csv (failed, or its files not kept) */
    static const char *const col[] = {"samples_shaded", "draw_calls", "dispatches", "gpu_us"};
    int c[4], cp = csv_col(&t, "pass"), ca = csv_col(&t, "gpu_us_attributed");
    for (size_t k = 0; k < 4; k++)
        c[k] = csv_col(&t, col[k]);
    char name[MAXP][64];
    double sum[MAXP][4] = {{0}}, n[MAXP] = {0};
    size_t np = 0;
    for (size_t r = 0; r < t.nrows; r++) {
        size_t p = 0;
        while (p < np && strcmp(name[p], csv_get(&t, r, cp)) != 0)
            p++;
        if (p == MAXP)
            continue;
        if (p == np)
            snprintf(name[np++], sizeof name[0], "%s", csv_get(&t, r, cp));
        for (size_t k = 0; k < 4; k++)
            sum[p][k] += csv_num(&t, r, c[k]);
        n[p]++;
    }
    bound_rates rates;
    if (!folder_bound_rates(fb, rb->id, &rates))
        memset(&rates, 0xff, sizeof rates);
    for (size_t p = 0; p < np; p++) {
        bound_work w = {NAN, sum[p][0] / n[p], NAN, sum[p][1] / n[p], sum[p][2] / n[p]};
        bound_result b;
        bound_compute(&rates, &w, sum[p][3] / n[p], &b);
        printf("%s,%s,%s,", rb->id, rb->renderer, name[p]);
        print_bound(sum[p][3] / n[p], &b);
        printf(",%s\n", ca >= 0 && t.nrows ? csv_get(&t, 0, ca) : "");
    }
    csv_table_free(&t);
}

/* `shadesweep bound [--profile FILE] [--passes] DIR`: a CSV row per run, or per run and
 * pass (commands.h). */
int cmd_bound(int argc, char **argv)
{
    const char *dir = NULL, *profile = NULL;
    bool passes = false;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--profile") == 0 && i + 1 < argc)
            profile = argv[++i];
        else if (strcmp(argv[i], "--passes") == 0)
            passes = true;
        else if (argv[i][0] != '-' && !dir)
            dir = argv[i];
        else {
            fprintf(stderr, "shadesweep bound: %s: unexpected (usage: shadesweep bound "
                    "[--profile DEVICE.yaml] [--passes] DIR)\n", argv[i]);
            return 2;
        }
    }
    if (!dir) {
        fprintf(stderr, "shadesweep bound: expected an output folder (usage: shadesweep "
                "bound [--profile DEVICE.yaml] [--passes] DIR)\n");
        return 2;
    }
    char path[4200], err[4400];
    snprintf(path, sizeof path, "%s/summary.csv", dir);
    csv_table sm;
    if (!csv_read(path, &sm, err, sizeof err)) {
        fprintf(stderr, "shadesweep bound: %s\n", err);
        return 2;
    }
    static folder_bound fb;
    if (!folder_bound_open(&fb, dir, profile)) {
        if (profile) {
            fprintf(stderr, "shadesweep bound: %s\n", fb.why);
            folder_bound_close(&fb);
            csv_table_free(&sm);
            return 2;
        }
        fprintf(stderr, "shadesweep bound: %s: %s\n", dir, fb.why);
    }
    size_t n;
    run_bound *rb = folder_bound_runs(&fb, &sm, &n);
    print_header(passes ? "run_id,renderer,pass" : "run_id,renderer");
    printf(passes ? ",attributed\n" : "\n");
    for (size_t i = 0; rb && i < n; i++) {
        if (passes) {
            print_passes(&fb, dir, &rb[i]);
            continue;
        }
        printf("%s,%s,", rb[i].id, rb[i].renderer);
        print_bound(rb[i].measured_us, &rb[i].b);
        putchar('\n');
    }
    free(rb);
    folder_bound_close(&fb);
    csv_table_free(&sm);
    return 0;
}
