/* Process CPU time, context switches, steal time and load. See contention.h. */
#define _GNU_SOURCE   /* sched_getaffinity, CPU_COUNT */
#include "results/contention.h"

#include <ctype.h>
#include <math.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

double contention_process_cpu_s(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0)
        return NAN;
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

unsigned contention_usable_cpus(void)
{
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0)
        return 1;
    int n = CPU_COUNT(&set);
    return n > 0 ? (unsigned)n : 1;
}

frame_cpu contention_frame_cpu(double cpu0_s, double cpu1_s, double frametime_us,
                               unsigned cpus)
{
    frame_cpu c = {NAN, NAN};
    if (!isfinite(cpu0_s) || !isfinite(cpu1_s))
        return c;
    c.us = (cpu1_s - cpu0_s) * 1e6;
    if (frametime_us > 0 && cpus > 0)
        c.share = c.us / (frametime_us * (double)cpus);
    return c;
}

bool contention_parse_cpu_line(const char *line, cpu_times *out)
{
    *out = (cpu_times){0};
    if (strncmp(line, "cpu", 3) != 0 || !isspace((unsigned char)line[3]))
        return false;   /* also "cpu0 ...": one CPU's line, not the machine's */
    const char *p = line + 3;
    uint64_t v[8];
    int n = 0;
    while (n < 8) {
        while (*p == ' ' || *p == '\t')
            p++;
        if (!isdigit((unsigned char)*p))
            break;
        char *end;
        v[n++] = strtoull(p, &end, 10);
        p = end;
    }
    if (n < 4)
        return false;
    for (int i = 0; i < n; i++)   /* user nice system idle iowait irq softirq steal */
        out->total += v[i];
    out->has_steal = n == 8;
    out->steal = n == 8 ? v[7] : 0;
    return true;
}

bool contention_parse_loadavg(const char *text, double *out)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || !isfinite(v) || v < 0)
        return false;
    *out = v;
    return true;
}

double contention_loadavg_1m(void)
{
    char buf[128] = "";
    FILE *f = fopen("/proc/loadavg", "r");
    bool ok = f && fgets(buf, sizeof buf, f);
    if (f)
        fclose(f);
    double v;
    return ok && contention_parse_loadavg(buf, &v) ? v : NAN;
}

void contention_sample_now(contention_sample *s)
{
    *s = (contention_sample){0};
    char line[512];
    FILE *f = fopen("/proc/stat", "r");
    if (f) {
        s->cpu_ok = fgets(line, sizeof line, f) && contention_parse_cpu_line(line, &s->cpu);
        fclose(f);
    }
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) == 0) {
        s->rusage_ok = true;
        s->nvcsw = ru.ru_nvcsw;
        s->nivcsw = ru.ru_nivcsw;
    }
}

void contention_between(const contention_sample *a, const contention_sample *b,
                        double loadavg_1m, contention_trial *out)
{
    out->loadavg_1m = loadavg_1m;
    out->invol_csw = out->vol_csw = out->steal_frac = NAN;
    if (a->rusage_ok && b->rusage_ok) {
        out->invol_csw = (double)(b->nivcsw - a->nivcsw);
        out->vol_csw = (double)(b->nvcsw - a->nvcsw);
    }
    if (a->cpu_ok && b->cpu_ok && a->cpu.has_steal && b->cpu.has_steal &&
        b->cpu.total > a->cpu.total && b->cpu.steal >= a->cpu.steal)
        out->steal_frac =
            (double)(b->cpu.steal - a->cpu.steal) / (double)(b->cpu.total - a->cpu.total);
}
