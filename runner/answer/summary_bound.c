/* summary.md's bounds (runner/answer/summary_bound.h). */
#include "runner/answer/summary_bound.h"

#include <math.h>
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

/* `shadesweep bound [--profile FILE] DIR`: a CSV row per run (commands.h). */
int cmd_bound(int argc, char **argv)
{
    const char *dir = NULL, *profile = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--profile") == 0 && i + 1 < argc)
            profile = argv[++i];
        else if (argv[i][0] != '-' && !dir)
            dir = argv[i];
        else {
            fprintf(stderr, "shadesweep bound: %s: unexpected (usage: shadesweep bound "
                    "[--profile DEVICE.yaml] DIR)\n", argv[i]);
            return 2;
        }
    }
    if (!dir) {
        fprintf(stderr, "shadesweep bound: expected an output folder (usage: shadesweep "
                "bound [--profile DEVICE.yaml] DIR)\n");
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
    printf("run_id,renderer,measured_us,bound_us,limiter,bound_pct");
    for (int r = 0; r < BOUND_NRESOURCES; r++)
        printf(",%s_us", bound_resource_names[r]);
    printf(",model_error\n");
    for (size_t i = 0; rb && i < n; i++) {
        printf("%s,%s,", rb[i].id, rb[i].renderer);
        const double v[] = {rb[i].measured_us, rb[i].b.bound_us};
        for (size_t k = 0; k < 2; k++)
            isfinite(v[k]) ? printf("%.3f,", v[k]) : printf(",");
        printf("%s,", rb[i].b.limiter >= 0 ? bound_resource_names[rb[i].b.limiter] : "");
        if (isfinite(rb[i].b.pct))
            printf("%.1f", rb[i].b.pct);
        for (int r = 0; r < BOUND_NRESOURCES; r++)
            isfinite(rb[i].b.us[r]) ? printf(",%.3f", rb[i].b.us[r]) : printf(",");
        printf(",%s\n", rb[i].b.model_error ? "yes" : "");
    }
    free(rb);
    folder_bound_close(&fb);
    csv_table_free(&sm);
    return 0;
}
