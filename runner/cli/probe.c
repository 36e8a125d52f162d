/* `shadesweep probe` and device.yaml in output folders (runner/cli/probe.h). */
#define _DEFAULT_SOURCE   /* gethostname */
#include "runner/cli/probe.h"
#include "runner/folder/meta_read.h"
#include "runner/trial/provenance.h"
#include "runner/trial/run.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "common/fsutil.h"
#include "renderers/probe/probe.h"
#include "results/device_profile.h"
#include "config.h"
#include "version.h"

int probe_main(gl_backend backend, int device, bool json, bool quick)
{
    char err[1024], path[4096];
    if (device >= 0 && !run_probe_device(device, err, sizeof err)) {
        fprintf(stderr, "shadesweep probe: %s\n", err);
        return 2;
    }
    gl_context_desc d = {.backend = backend, .device = device};
    gl_context *ctx = gl_context_create(&d, err, sizeof err);
    if (!ctx) {
        fprintf(stderr, "shadesweep probe: %s\n", err);
        return 2;
    }
    static device_profile prof;
    memset(&prof, 0, sizeof prof);
    bool ok = gl_probe_run(ctx, quick, &prof, err, sizeof err);
    gl_context_destroy(ctx);
    if (!ok) {
        fprintf(stderr, "shadesweep probe: %s\n", err);
        return 2;
    }
    snprintf(prof.shadesweep_version, sizeof prof.shadesweep_version, "%s (%s)",
             SHADESWEEP_VERSION, SHADESWEEP_COMMIT);
    snprintf(prof.host, sizeof prof.host, "unknown");
    gethostname(prof.host, sizeof prof.host - 1);
    provenance_cpu_model(prof.cpu, sizeof prof.cpu);
    time_t now = time(NULL);
    struct tm tm;
    strftime(prof.date, sizeof prof.date, "%Y-%m-%dT%H:%M:%SZ", gmtime_r(&now, &tm));
    char dir[3800];
    if (!device_profile_cache_dir(dir, sizeof dir) || !device_profile_cache_path(&prof, path,
                                                                                 sizeof path)) {
        fprintf(stderr, "shadesweep probe: no cache folder: set XDG_CACHE_HOME or HOME\n");
        return 2;
    }
    if (!fs_mkdirs(dir, err, sizeof err) ||
        !device_profile_write_yaml(&prof, path, err, sizeof err)) {
        fprintf(stderr, "shadesweep probe: %s\n", err);
        return 2;
    }
    if (json) {
        device_profile_print_json(&prof, stdout);
    } else {
        size_t len;
        int e;
        char *text = fs_read_all(path, 0, &len, &e);
        if (!text) {
            fs_error_message(err, sizeof err, path, e);
            fprintf(stderr, "shadesweep probe: %s\n", err);
            return 2;
        }
        fwrite(text, 1, len, stdout);
        free(text);
    }
    fprintf(stderr, "device profile: %s\n", path);
    return 0;
}

void probe_copy_to_folder(const char *out_dir, const plan *p)
{
    static const char *const keys[] = {"vendor", "renderer", "version", "glsl", "backend",
                                       "device"};
    char v[6][256], run_dir[4300];
    size_t i = 0;
    for (; i < p->nruns; i++) {
        snprintf(run_dir, sizeof run_dir, "%s/runs/%s", out_dir, p->runs[i].id);
        if (meta_read_block(run_dir, "gl", keys, 6, v[0], sizeof v[0]) && v[1][0])
            break;
    }
    if (i == p->nruns)
        return;   /* no run reached a GL context: no device to name */
    static device_profile prof;
    memset(&prof, 0, sizeof prof);
    device_profile_set_gl(&prof, (const char *const[6]){v[0], v[1], v[2], v[3], v[4], v[5]});
    char src[4096], dst[4300], err[4400];
    if (!device_profile_cache_path(&prof, src, sizeof src) || !fs_exists(src)) {
        fprintf(stderr, "no device profile of %s cached: `shadesweep probe` makes one (about a "
                "minute), and later runs copy it into their folders as device.yaml\n", v[1]);
        return;
    }
    size_t len;
    int e;
    char *text = fs_read_all(src, 1 << 20, &len, &e);
    snprintf(dst, sizeof dst, "%s/device.yaml", out_dir);
    afile f;
    bool ok = text && afile_open(&f, dst, err, sizeof err);
    if (!text)
        fs_error_message(err, sizeof err, src, e);
    else if (ok) {
        afile_write(&f, text, len);
        ok = afile_commit(&f, err, sizeof err);
    }
    free(text);
    if (!ok)
        fprintf(stderr, "shadesweep run: no device.yaml: %s\n", err);
}
