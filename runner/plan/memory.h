#pragma once
/* What a run needs in memory, what the process may use, and whether a failed trial
 * ran out of it (README "Memory", docs/reliability.md "Memory": the calibration).
 * The estimate, from the run's parameters and its built scene, without GL: V = render
 * targets (every target the renderer allocates, width x height x samples x bytes per
 * texel: HDR, depth, the MSAA resolve, renderer_impl.own_bytes (a G-buffer layout, a
 * light buffer, visibility ids), edge AA, shadow maps, the context's own framebuffer)
 * + light lists (tiles or clusters x their index cap, as forward_plus.c sizes them,
 * with their CPU copies) + scene (vertices, indices, textures, ours and the driver's)
 * + read-back and reference (screenshots, the error reference at K W x K H). llvmpipe
 * keeps all of it in host memory. Calibrated on llvmpipe (LLVM 15): resident = base
 * (128 MiB: context, JIT, threads; 96 MiB for null) + 1.25 V (one copy of the list
 * indices: the other is never touched) + D; address space (beyond what the parent
 * maps) = 192 MiB + 2.5 V + D, where D is llvmpipe's binning of a frame's draws for
 * renderers that draw once per light (32 KiB a draw at 64x64, 12 KiB more each time the
 * pixels quadruple). */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "runner/manifest/manifest.h"

struct scene;

typedef struct memory_estimate {
    uint64_t targets, lists, scene, readback;   /* bytes, the parts of V */
    uint64_t draws;                             /* the driver's binning of a frame's draws */
    uint64_t base;                              /* the context's own (null: less) */
    uint64_t resident;                          /* what it keeps resident, about */
    uint64_t address_space;                     /* what it maps beyond the parent */
    char what[320];                             /* "targets 2.9 GiB at 16384x16384 x 4x MSAA, ..." */
} memory_estimate;

/* The estimate of run p with its built scene sc (NULL: the facts memory_check_run kept
 * of its scene, or without the scene's share when it kept none). */
void memory_estimate_run(const run_params *p, const struct scene *sc, memory_estimate *out);

/* Whether run p fits what this process may use now: the smallest of RLIMIT_AS (less
 * what the process maps already), the memory cgroup's limit (cgroup v2 memory.max or
 * v1 memory.limit_in_bytes, of its cgroup and every ancestor, less what it uses) and
 * /proc/meminfo's MemAvailable + SwapFree. False with the message "needs about ... ,
 * the process may use ... (SOURCE)" when it does not; true when it fits, when no
 * limit is known, when its scene does not build (the trial says why), or when
 * SHADESWEEP_MEMORY_CHECK=off. */
bool memory_check_run(const run_params *p, char *msg, size_t len);

/* "1.5 GiB", "320 MiB", "12 KiB", "100 B". */
void memory_format(uint64_t bytes, char *buf, size_t len);

/* Whether a trial that failed with `status` and `message` (its log's tail included)
 * most likely ran out of memory: GL_OUT_OF_MEMORY, "out of memory" or "Cannot allocate
 * memory" in the text, or a child whose peak address space (peak_vm_kb) or peak
 * resident size (peak_rss_kb; -1: unknown) came within 80% of RLIMIT_AS or of the
 * memory cgroup's limit. True with `note` ("memory is the likely cause: peak address
 * space 1.0 GiB of RLIMIT_AS 1.1 GiB, peak resident 340 MiB") when so. failed:oom
 * (the kernel's word), timeouts, interruptions and verdicts (failed:error,
 * failed:nonfinite) are never re-explained. */
bool memory_explain(const char *status, const char *message, long peak_vm_kb,
                    long peak_rss_kb, char *note, size_t len);

/* The process's VmSize (kB) from /proc/self/status, or of pid when pid > 0 (VmPeak:
 * its peak); -1 when unknown. */
long memory_proc_kb(int pid, const char *field);
