#pragma once
/* What a run's meta.yaml records of where and how it was made, beyond the GL strings:
 * the command line and folder it was started from, the environment variables that
 * change what GL does or how fast (Mesa's, llvmpipe's, the GL loader's, ours), the
 * kernel, and the machine's load and memory when the trial started. */
#include <stdbool.h>
#include "results/yamlout.h"

/* Keeps the command line (main calls it once, before anything else). */
void provenance_set_command(int argc, char **argv);

/* The machine when a trial starts. */
typedef struct provenance_start {
    double load_1m;            /* /proc/loadavg; NAN when unreadable */
    double mem_total_mb, mem_available_mb;   /* /proc/meminfo; NAN when unreadable */
} provenance_start;
void provenance_sample(provenance_start *out);

/* Writes `invocation: {command, cwd}` and `environment: {NAME: value, ...}` (the
 * variables that are set, of those that matter: provenance.c's prefixes). */
void provenance_write_invocation(yaml_out *y);
/* The CPU's model name (/proc/cpuinfo), or "unknown". */
void provenance_cpu_model(char *buf, size_t len);
/* Writes the host map's extra members: kernel, cpus_usable, load_1m_at_start,
 * mem_total_mb, mem_available_mb_at_start. */
void provenance_write_host(yaml_out *y, const provenance_start *s);
