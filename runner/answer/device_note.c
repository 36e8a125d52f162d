/* Which device measured a folder, said where it matters (runner/answer/device_note.h). */
#include "runner/answer/device_note.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "results/gl_device.h"
#include "runner/folder/meta_read.h"

#define MAX_DEVICES 8   /* told apart; more are counted with the last */

typedef struct device {
    char renderer[256], version[256];
    const char *software;      /* gl_software_rasterizer's name; NULL: a GPU */
    size_t runs;
} device;

__attribute__((format(printf, 3, 4)))
static void add(char *line, size_t len, const char *fmt, ...)
{
    size_t n = strlen(line);
    va_list ap;
    va_start(ap, fmt);
    if (n + 1 < len)
        vsnprintf(line + n, len - n, fmt, ap);
    va_end(ap);
}

/* Whether the renderer string says the rasterizer's name itself ("llvmpipe (LLVM...)"). */
static bool named(const device *d)
{
    return strstr(d->renderer, d->software) != NULL;
}

static const char cpu_words[] =
    "these rankings measure a CPU, not a GPU, and per-pass times are not attributed "
    "(passes.csv: only the frame total is trusted)";

void device_note_of(const char *dir, const run_result *runs, size_t n, device_note *out)
{
    memset(out, 0, sizeof *out);
    device dev[MAX_DEVICES];
    size_t nd = 0, more = 0;
    static const char *const keys[] = {"renderer", "vendor", "version"};
    char v[3][256];
    for (size_t i = 0; i < n; i++) {
        char run_dir[4300];
        snprintf(run_dir, sizeof run_dir, "%s/runs/%s", dir, runs[i].id);
        if (!meta_read_block(run_dir, "gl", keys, 3, v[0], sizeof v[0]) || !v[0][0])
            continue;
        size_t d = 0;
        while (d < nd && strcmp(dev[d].renderer, v[0]) != 0)
            d++;
        if (d == nd && nd == MAX_DEVICES) {
            more++;
            continue;
        }
        if (d == nd) {
            snprintf(dev[d].renderer, sizeof dev[d].renderer, "%s", v[0]);
            snprintf(dev[d].version, sizeof dev[d].version, "%s", v[2]);
            dev[d].software = gl_software_rasterizer(v[0], v[1], v[2]);
            dev[d].runs = 0;
            nd++;
            out->nsoftware += dev[d].software != NULL;
        }
        dev[d].runs++;
    }
    out->ndevices = nd + (more ? 1 : 0);
    size_t len = sizeof out->line;
    if (nd == 1 && !more) {
        if (!dev[0].software)
            return;   /* one GPU: nothing to say */
        add(out->line, len, "measured on %s", dev[0].renderer);
        if (dev[0].version[0])
            add(out->line, len, ", OpenGL %s", dev[0].version);
        add(out->line, len, ": a CPU rasterizer%s%s%s, so ", named(&dev[0]) ? "" : " (",
            named(&dev[0]) ? "" : dev[0].software, named(&dev[0]) ? "" : ")");
        add(out->line, len, "%s", cpu_words);
        return;
    }
    if (nd < 2)
        return;
    add(out->line, len, "measured on %zu devices, a ranking across them compares the "
        "devices as well as the renderers: ", out->ndevices);
    for (size_t d = 0; d < nd; d++) {
        add(out->line, len, "%s%s (%zu run%s", d ? "; " : "", dev[d].renderer, dev[d].runs,
            dev[d].runs == 1 ? "" : "s");
        if (dev[d].software)
            add(out->line, len, ", a CPU rasterizer%s%s", named(&dev[d]) ? "" : ": ",
                named(&dev[d]) ? "" : dev[d].software);
        add(out->line, len, ")");
    }
    if (more)
        add(out->line, len, "; %zu run%s on others", more, more == 1 ? "" : "s");
    if (out->nsoftware)
        add(out->line, len, "; on a CPU rasterizer %s", cpu_words);
}
