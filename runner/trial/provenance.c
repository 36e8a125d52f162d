/* Provenance for meta.yaml (runner/trial/provenance.h). */
#define _GNU_SOURCE   /* environ */
#include "runner/trial/provenance.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <unistd.h>

#include "results/contention.h"

extern char **environ;

static char *command_line;

/* argv joined by spaces, each argument that holds a space, a quote or nothing in
 * single quotes (as a shell would read it back). */
void provenance_set_command(int argc, char **argv)
{
    size_t len = 1;
    for (int i = 0; i < argc; i++)
        len += 4 * strlen(argv[i]) + 3;
    free(command_line);
    command_line = malloc(len);
    if (!command_line)
        return;
    char *o = command_line;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        bool quote = !*a || strpbrk(a, " \t\n'\"\\$`*?;&|<>()") != NULL;
        if (i)
            *o++ = ' ';
        if (quote)
            *o++ = '\'';
        for (; *a; a++) {
            if (*a == '\'' && quote) {
                memcpy(o, "'\\''", 4);   /* close, an escaped quote, reopen */
                o += 4;
            } else {
                *o++ = *a;
            }
        }
        if (quote)
            *o++ = '\'';
    }
    *o = '\0';
}

/* The environment that changes what is measured: Mesa and its drivers (MESA_*,
 * GALLIUM_*, LP_* for llvmpipe's threads, GALLIVM_* for its JIT, LIBGL_*, EGL_*,
 * __GL*), the loader's preload and search path, the C library's allocator, and ours. */
static const char *const prefixes[] = {
    "MESA_", "GALLIUM_", "LP_", "GALLIVM_", "LIBGL_", "EGL_", "__GL", "__EGL", "DRI_",
    "vblank_mode", "LD_PRELOAD", "LD_LIBRARY_PATH", "MALLOC_", "GLIBC_TUNABLES",
    "SHADESWEEP_", "OMP_", "ASAN_OPTIONS", "UBSAN_OPTIONS",
};

void provenance_write_invocation(yaml_out *y)
{
    char cwd[4096];
    yo_key(y, "invocation");
    yo_map_begin(y);
    yo_key(y, "command"); yo_str(y, command_line);
    yo_key(y, "cwd"); yo_str(y, getcwd(cwd, sizeof cwd) ? cwd : NULL);
    yo_map_end(y);
    yo_key(y, "environment");
    yo_map_begin(y);
    for (char **e = environ; e && *e; e++) {
        const char *eq = strchr(*e, '=');
        if (!eq)
            continue;
        bool keep = false;
        for (size_t i = 0; i < sizeof prefixes / sizeof *prefixes && !keep; i++)
            keep = strncmp(*e, prefixes[i], strlen(prefixes[i])) == 0;
        if (!keep)
            continue;
        char name[256];
        snprintf(name, sizeof name, "%.*s", (int)(eq - *e), *e);
        yo_key(y, name);
        yo_str(y, eq + 1);
    }
    yo_map_end(y);
}

/* "MemTotal:  24570844 kB" -> MB; NAN when the field is missing. */
static double meminfo_mb(const char *text, const char *field)
{
    const char *p = text ? strstr(text, field) : NULL;
    if (!p)
        return NAN;
    double kb = strtod(p + strlen(field), NULL);
    return kb > 0 ? kb / 1024 : NAN;
}

void provenance_sample(provenance_start *out)
{
    out->load_1m = contention_loadavg_1m();
    out->mem_total_mb = out->mem_available_mb = NAN;
    FILE *fp = fopen("/proc/meminfo", "r");
    if (!fp)
        return;
    char buf[4096];
    size_t n = fread(buf, 1, sizeof buf - 1, fp);
    fclose(fp);
    buf[n] = '\0';
    out->mem_total_mb = meminfo_mb(buf, "MemTotal:");
    out->mem_available_mb = meminfo_mb(buf, "MemAvailable:");
}

void provenance_write_host(yaml_out *y, const provenance_start *s)
{
    struct utsname u;
    bool have = uname(&u) == 0;
    yo_key(y, "kernel"); yo_str(y, have ? u.release : NULL);
    yo_key(y, "kernel_version"); yo_str(y, have ? u.version : NULL);
    yo_key(y, "machine"); yo_str(y, have ? u.machine : NULL);
    yo_key(y, "cpus_usable"); yo_i64(y, contention_usable_cpus());
    yo_key(y, "load_1m_at_start"); yo_f64(y, s->load_1m);
    yo_key(y, "mem_total_mb"); yo_f64(y, round(s->mem_total_mb));
    yo_key(y, "mem_available_mb_at_start"); yo_f64(y, round(s->mem_available_mb));
}

void provenance_cpu_model(char *buf, size_t len)
{
    snprintf(buf, len, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "model name", 10) == 0) {
            char *colon = strchr(line, ':');
            if (colon) {
                colon++;
                while (*colon == ' ' || *colon == '\t')
                    colon++;
                colon[strcspn(colon, "\n")] = 0;
                snprintf(buf, len, "%s", colon);
            }
            break;
        }
    }
    fclose(f);
}
