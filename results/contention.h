#pragma once
/* How much of the machine a run got: the process's CPU time, its context switches,
 * the machine's steal time and load. Read from the kernel (clock_gettime, getrusage,
 * sched_getaffinity, /proc/stat, /proc/loadavg); no GL. The columns they make are
 * entries of results/metrics.def (cpu_us, cpu_share, invol_csw, vol_csw, steal_frac,
 * loadavg_1m). */
#include <stdbool.h>
#include <stdint.h>

/* CPU seconds of this process over all its threads (CLOCK_PROCESS_CPUTIME_ID): on
 * llvmpipe the rasteriser threads are ours. NAN when unreadable. */
double contention_process_cpu_s(void);
/* The CPUs this process may run on (CPU_COUNT of sched_getaffinity); at least 1. */
unsigned contention_usable_cpus(void);

/* One frame's CPU: us, the process CPU time between the two readings that bracket
 * its frametime_us; share = us / (frametime_us x cpus). NAN where unknown. */
typedef struct frame_cpu {
    double us, share;
} frame_cpu;
frame_cpu contention_frame_cpu(double cpu0_s, double cpu1_s, double frametime_us,
                               unsigned cpus);

/* The first line of /proc/stat ("cpu  user nice system idle iowait irq softirq steal
 * guest guest_nice", in ticks). total: user .. steal (guest time is already in user
 * and nice); has_steal: the line has the steal field (Linux 2.6.11 on). */
typedef struct cpu_times {
    uint64_t total, steal;
    bool has_steal;
} cpu_times;
/* Parses one such line; false when it is not an aggregate "cpu" line with at least
 * the four fields user, nice, system, idle. */
bool contention_parse_cpu_line(const char *line, cpu_times *out);
/* The 1-minute load average from /proc/loadavg's text; false when it has none. */
bool contention_parse_loadavg(const char *text, double *out);

/* What a trial's two readings (at its measured part's start and end) differ by. */
typedef struct contention_sample {
    bool cpu_ok, rusage_ok;
    cpu_times cpu;             /* /proc/stat */
    long nvcsw, nivcsw;        /* getrusage(RUSAGE_SELF) */
} contention_sample;
void contention_sample_now(contention_sample *s);

/* A trial's values (NAN: unknown): context switches between the samples, steal /
 * total CPU time of the machine between them, and the load average given. */
typedef struct contention_trial {
    double invol_csw, vol_csw, steal_frac, loadavg_1m;
} contention_trial;
void contention_between(const contention_sample *a, const contention_sample *b,
                        double loadavg_1m, contention_trial *out);
/* /proc/loadavg's 1-minute figure now; NAN when unreadable. */
double contention_loadavg_1m(void);
