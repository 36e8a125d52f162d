#pragma once
/* Runs a function in a child process with a time limit, so that a crash, an
 * abort, a GL hang or the OOM killer ends one run and not the sweep.
 * The child's stderr goes to a log file; its exit code is the function's result. */
#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

typedef enum isolate_outcome {
    ISOLATE_EXITED = 0,        /* exit_code holds the function's result */
    ISOLATE_SIGNALED,          /* killed by a signal it did not get from us */
    ISOLATE_TIMEOUT,           /* still running after timeout_s: we killed it */
    ISOLATE_INTERRUPTED,       /* *stop became true: we killed it */
    ISOLATE_FORK_FAILED,
} isolate_outcome;

typedef struct isolate_result {
    isolate_outcome outcome;
    int exit_code;
    int signal;                /* ISOLATE_SIGNALED */
    bool oom_killed;           /* SIGKILL, and the cgroup's OOM-kill count went up */
    double seconds;            /* wall time the child ran */
    long peak_rss_kb;          /* the child's peak resident size (wait4's ru_maxrss, kB), however
                                * it ended (killed ones too); -1 unknown (no fork) */
    long peak_vm_kb;           /* its peak address space (VmPeak, sampled every 0.1 s); -1 unknown */
} isolate_result;

/* fn(arg) runs in a child whose stderr is appended to log_path; fn's return is the
 * child's exit code (0..255). The parent polls until the child ends, timeout_s
 * passes, or *stop (set by a signal handler) becomes true; then it kills the child
 * (SIGTERM, SIGKILL after a grace second) and reaps it. A child that died of SIGINT,
 * SIGTERM or SIGHUP while *stop became true within half a second (the signal went to
 * the whole process group, or to both) is ISOLATE_INTERRUPTED too, not a failure. */
bool isolate_run(int (*fn)(void *), void *arg, double timeout_s, const char *log_path,
                 volatile const int *stop, isolate_result *out);

/* "failed:<reason>" for a result that is not a clean exit: timeout, SIGSEGV, SIGABRT,
 * SIGKILL (from outside), oom (a SIGKILL while the cgroup's count of OOM kills went up:
 * memory.events of cgroup v2 or memory.oom_control of v1), interrupted. */
void isolate_status(const isolate_result *r, char *buf, size_t len);

/* The last `lines` lines of a log file, at most len-1 bytes, newlines turned into
 * " | "; "" if there is none. */
/* The OOM kills the kernel counted in this process's memory cgroup; -1 when it does not
 * say (no memory cgroup readable). */
long isolate_oom_kills(void);

void isolate_log_tail(const char *log_path, int lines, char *buf, size_t len);
