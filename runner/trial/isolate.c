#define _DEFAULT_SOURCE   /* wait4 */
#include "runner/trial/isolate.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "runner/plan/memory.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void nap(double s)
{
    struct timespec ts = {.tv_sec = (time_t)s, .tv_nsec = (long)((s - (double)(time_t)s) * 1e9)};
    while (nanosleep(&ts, &ts) == -1 && errno == EINTR)
        ;
}

/* SIGTERM, then SIGKILL if it has not ended after a second; returns its wait status,
 * and its peak resident size (wait4's ru_maxrss, kB) in *rss_kb when wait4 says. */
static int kill_and_reap(pid_t pid, long *rss_kb)
{
    int st = 0;
    struct rusage ru;
    kill(pid, SIGTERM);
    for (int i = 0; i < 100; i++) {
        if (wait4(pid, &st, WNOHANG, &ru) == pid) {
            *rss_kb = ru.ru_maxrss;
            return st;
        }
        nap(0.01);
    }
    kill(pid, SIGKILL);
    pid_t r;
    while ((r = wait4(pid, &st, 0, &ru)) == -1 && errno == EINTR)
        ;
    if (r == pid)
        *rss_kb = ru.ru_maxrss;
    return st;
}

/* "oom_kill N" of one cgroup file; -1 when it has none. */
static long oom_kill_in(const char *path)
{
    FILE *f = fopen(path, "re");
    if (!f)
        return -1;
    char line[256];
    long n = -1;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "oom_kill %ld", &n) == 1)
            break;
    fclose(f);
    return n;
}

long isolate_oom_kills(void)
{
    FILE *f = fopen("/proc/self/cgroup", "re");
    if (!f)
        return -1;
    char line[4096], v2[4096] = "", v1[4096] = "";
    bool have_v1 = false, have_v2 = false;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        char *c1 = strchr(line, ':');
        char *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
        if (!c2)
            continue;
        *c1 = *c2 = 0;
        const char *ctrl = c1 + 1, *path = c2 + 1;
        if (strcmp(line, "0") == 0 && !ctrl[0]) {
            snprintf(v2, sizeof v2, "%s", path);
            have_v2 = true;
        }
        for (const char *t = ctrl; (t = strstr(t, "memory")); t += 6)
            if ((t == ctrl || t[-1] == ',') && (t[6] == 0 || t[6] == ',')) {
                snprintf(v1, sizeof v1, "%s", path);
                have_v1 = true;
                break;
            }
    }
    fclose(f);
    char p[4400];
    long n = -1;
    if (have_v1) {
        snprintf(p, sizeof p, "/sys/fs/cgroup/memory%s/memory.oom_control",
                 strcmp(v1, "/") == 0 ? "" : v1);
        n = oom_kill_in(p);
    }
    if (n < 0 && have_v2) {
        snprintf(p, sizeof p, "/sys/fs/cgroup%s/memory.events", strcmp(v2, "/") == 0 ? "" : v2);
        n = oom_kill_in(p);
        if (n < 0) {
            snprintf(p, sizeof p, "/sys/fs/cgroup/unified%s/memory.events",
                     strcmp(v2, "/") == 0 ? "" : v2);
            n = oom_kill_in(p);
        }
    }
    return n;
}

static bool stop_signal_kind(int sig)
{
    return sig == SIGINT || sig == SIGTERM || sig == SIGHUP;
}

bool isolate_run(int (*fn)(void *), void *arg, double timeout_s, const char *log_path,
                 volatile const int *stop, isolate_result *out)
{
    memset(out, 0, sizeof *out);
    out->peak_rss_kb = out->peak_vm_kb = -1;
    long oom_before = isolate_oom_kills();
    fflush(NULL);   /* or the child would write the parent's buffered output again */
    double t0 = now_s();
    pid_t parent = getpid();
    pid_t pid = fork();
    if (pid < 0) {
        out->outcome = ISOLATE_FORK_FAILED;
        return false;
    }
    if (pid == 0) {
        /* The child: dies with the parent (a sweep killed with SIGKILL must not leave
         * a run writing on behind the one that resumes it), its own default signal
         * dispositions, stderr into the log. */
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (getppid() != parent)
            _exit(125);   /* the parent died before prctl: nobody waits for this run */
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        signal(SIGHUP, SIG_DFL);
        signal(SIGPIPE, SIG_DFL);
        int fd = open(log_path, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW, 0644);
        if (fd >= 0) {
            dup2(fd, STDERR_FILENO);
            close(fd);
        }
        int rc = fn(arg);
        fflush(NULL);
        _exit(rc & 0xff);
    }

    int st = 0;
    struct rusage ru;
    for (unsigned polls = 0;; polls++) {
        pid_t r = wait4(pid, &st, WNOHANG, &ru);
        if (r == pid) {
            out->peak_rss_kb = ru.ru_maxrss;
            break;
        }
        if (polls % 20 == 0) {   /* VmPeak only grows: its last sample is nearly the peak */
            long vm = memory_proc_kb(pid, "VmPeak");
            if (vm > out->peak_vm_kb)
                out->peak_vm_kb = vm;
        }
        if (r < 0 && errno != EINTR) {
            st = kill_and_reap(pid, &out->peak_rss_kb);
            break;
        }
        if (stop && *stop) {
            kill_and_reap(pid, &out->peak_rss_kb);
            out->outcome = ISOLATE_INTERRUPTED;
            out->seconds = now_s() - t0;
            return true;
        }
        if (timeout_s > 0 && now_s() - t0 > timeout_s) {
            kill_and_reap(pid, &out->peak_rss_kb);
            out->outcome = ISOLATE_TIMEOUT;
            out->seconds = now_s() - t0;
            return true;
        }
        nap(0.005);
    }
    out->seconds = now_s() - t0;
    if (WIFEXITED(st)) {
        out->outcome = ISOLATE_EXITED;
        out->exit_code = WEXITSTATUS(st);
    } else {
        out->outcome = ISOLATE_SIGNALED;
        out->signal = WIFSIGNALED(st) ? WTERMSIG(st) : 0;
        /* A signal to the whole group can reach the child before our own handler has
         * run (or a sender may signal the processes one by one): a child that died of
         * a stop signal is interrupted when ours follows soon after. */
        if (stop && stop_signal_kind(out->signal)) {
            for (int i = 0; i < 100 && !*stop; i++)
                nap(0.005);
            if (*stop)
                out->outcome = ISOLATE_INTERRUPTED;
        }
        if (out->signal == SIGKILL) {
            long now = isolate_oom_kills();
            out->oom_killed = oom_before >= 0 && now > oom_before;
        }
    }
    return true;
}

static const char *signal_name(int sig)
{
    switch (sig) {
    case SIGSEGV: return "SIGSEGV";
    case SIGABRT: return "SIGABRT";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGTERM: return "SIGTERM";
    case SIGINT: return "SIGINT";
    case SIGPIPE: return "SIGPIPE";
    case SIGHUP: return "SIGHUP";
    case SIGTRAP: return "SIGTRAP";
    default: return NULL;
    }
}

void isolate_status(const isolate_result *r, char *buf, size_t len)
{
    switch (r->outcome) {
    case ISOLATE_EXITED:
        snprintf(buf, len, r->exit_code == 0 ? "ok" : "failed:exit-%d", r->exit_code);
        break;
    case ISOLATE_SIGNALED: {
        const char *name = signal_name(r->signal);
        if (r->signal == SIGKILL)   /* not ours: the kernel's, or someone's kill -9 */
            snprintf(buf, len, r->oom_killed ? "failed:oom" : "failed:SIGKILL");
        else if (name)
            snprintf(buf, len, "failed:%s", name);
        else
            snprintf(buf, len, "failed:signal-%d", r->signal);
        break;
    }
    case ISOLATE_TIMEOUT: snprintf(buf, len, "failed:timeout"); break;
    case ISOLATE_INTERRUPTED: snprintf(buf, len, "failed:interrupted"); break;
    case ISOLATE_FORK_FAILED: snprintf(buf, len, "failed:fork"); break;
    }
}

void isolate_log_tail(const char *log_path, int lines, char *buf, size_t len)
{
    buf[0] = 0;
    FILE *f = fopen(log_path, "rb");
    if (!f)
        return;
    char tail[4096];
    long size = 0;
    if (fseek(f, 0, SEEK_END) == 0)
        size = ftell(f);
    long from = size > (long)sizeof tail - 1 ? size - (long)sizeof tail + 1 : 0;
    fseek(f, from, SEEK_SET);
    size_t n = fread(tail, 1, sizeof tail - 1, f);
    fclose(f);
    tail[n] = 0;
    while (n > 0 && (tail[n - 1] == '\n' || tail[n - 1] == '\r'))
        tail[--n] = 0;
    /* the start of the last `lines` lines */
    char *start = tail;
    int seen = 0;
    for (char *p = tail + n; p > tail; p--) {
        if (p[-1] == '\n' && ++seen == lines) {
            start = p;
            break;
        }
    }
    size_t o = 0;
    for (char *p = start; *p && o + 4 < len; p++) {
        if (*p == '\n') {
            o += (size_t)snprintf(buf + o, len - o, " | ");
        } else if (*p != '\r') {
            buf[o++] = *p;
            buf[o] = 0;
        }
    }
}
