/* Output folders: the names shadesweep writes, ownership, the lock (folder.h); the
 * per-run completion manifests are runner/folder/folder_files.c. */
#define _DEFAULT_SOURCE   /* realpath, dirfd */
#include "runner/folder/folder.h"
#include "runner/folder/folder_internal.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>   /* major, minor */
#include <unistd.h>

#include "results/csv.h"
#include "common/fsutil.h"

/* sweep.yaml last: clear_folder removes the others and may keep it. Every file a sweep
 * and a rerun leave behind from an older sweep, whose killed write's ".tmp.<pid>" is
 * never swept, and (in a run folder) that files.txt does not vouch for. */
static const char *const top_names[] = {"plan.csv",     "summary.csv",      "summary.md",
                                         "summary.json", "summary_long.csv", "device.yaml",
                                         "sweep.yaml"};
static const char *const run_names[] = {
    "frames.csv", "seconds.csv", "passes.csv", "convergence.csv", "errors.csv",
    "coverage.csv", "lightgrid.csv", "lights.csv", "summary.csv", "meta.yaml", "log.txt",
    "files.txt",
};
#define NAMES(a) (sizeof(a) / sizeof((a)[0]))

/* dir/name; false (and a cut path) when it does not fit. */
bool folder_path_join(char *dst, size_t n, const char *dir, const char *name)
{
    int k = snprintf(dst, n, "%s/%s", dir, name);
    return k >= 0 && (size_t)k < n;
}

static bool ends_with(const char *s, size_t n, const char *suffix)
{
    size_t k = strlen(suffix);
    return n >= k && memcmp(s + n - k, suffix, k) == 0;
}

/* The length of name without a ".tmp.<digits>" suffix; *temp says whether it had one. */
static size_t base_len(const char *name, bool *temp)
{
    size_t n = strlen(name);
    *temp = false;
    const char *t = NULL;
    for (const char *p = strstr(name, ".tmp."); p; p = strstr(p + 1, ".tmp."))
        t = p;
    if (!t || !t[5])
        return n;
    for (const char *d = t + 5; *d; d++)
        if (*d < '0' || *d > '9')
            return n;
    *temp = true;
    return (size_t)(t - name);
}

static bool in_list(const char *name, size_t n, const char *const *list, size_t nlist)
{
    for (size_t i = 0; i < nlist; i++)
        if (strlen(list[i]) == n && memcmp(list[i], name, n) == 0)
            return true;
    return false;
}

static bool is_top_file(const char *name, bool *temp)
{
    size_t n = base_len(name, temp);
    return in_list(name, n, top_names, NAMES(top_names));
}

/* A file of a run folder: the fixed names, screenshot-trial*.png, lights-heat-trial*.png,
 * error-trial*.{png,exr}. */
bool folder_is_run_file(const char *name, bool *temp)
{
    size_t n = base_len(name, temp);
    if (in_list(name, n, run_names, NAMES(run_names)))
        return true;
    if (n > 16 && strncmp(name, "screenshot-trial", 16) == 0 && ends_with(name, n, ".png"))
        return true;
    if (n > 17 && strncmp(name, "lights-heat-trial", 17) == 0 && ends_with(name, n, ".png"))
        return true;
    return n > 11 && strncmp(name, "error-trial", 11) == 0 &&
           (ends_with(name, n, ".png") || ends_with(name, n, ".exr"));
}

/* runs/<id>/trial-<k>: one trial's files while its run is not complete (runner/folder/trials.c). */
bool folder_is_trial_dir(const char *name)
{
    if (strncmp(name, "trial-", 6) != 0 || !name[6])
        return false;
    for (const char *d = name + 6; *d; d++)
        if (*d < '0' || *d > '9')
            return false;
    return strlen(name) <= 6 + 10;
}

static bool is_run_id(const char *name)
{
    size_t n = 0;
    for (; name[n]; n++)
        if (!((name[n] >= '0' && name[n] <= '9') || (name[n] >= 'a' && name[n] <= 'f')))
            return false;
    return n == 12;
}

/* unlink for a regular file only; ENOENT is fine. */
static bool remove_file(const char *path, char *err, size_t errlen)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return errno == ENOENT ? true : (snprintf(err, errlen, "%s: %s", path, strerror(errno)), false);
    if (!S_ISREG(st.st_mode))
        return true;   /* not a file we wrote */
    if (unlink(path) != 0 && errno != ENOENT) {
        snprintf(err, errlen, "%s: cannot remove: %s", path, strerror(errno));
        return false;
    }
    return true;
}

static bool is_dir_nofollow(const char *path)
{
    struct stat st;
    return lstat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

bool folder_each(const char *dir, folder_entry_fn each, void *ctx, char *err, size_t errlen)
{
    DIR *d = opendir(dir);
    if (!d) {
        snprintf(err, errlen, "%s: %s", dir, strerror(errno));
        return false;
    }
    bool ok = true;
    struct dirent *ent;
    char path[4608];
    while (ok && (ent = readdir(d))) {
        folder_path_join(path, sizeof path, dir, ent->d_name);
        ok = each(path, ent->d_name, ctx, err, errlen);
    }
    closedir(d);
    return ok;
}

/* folder_clear_run's part of one entry of a run folder: a trial's folder is cleared
 * the same way, a file of shadesweep's removed. */
static bool clear_run_entry(const char *path, const char *name, void *ctx, char *err,
                            size_t errlen)
{
    bool temp;
    if (folder_is_trial_dir(name))
        return !is_dir_nofollow(path) || folder_clear_run(path, err, errlen);
    return !folder_is_run_file(name, &temp) || remove_file(path, err, errlen);
}

bool folder_clear_run(const char *run_dir, char *err, size_t errlen)
{
    if (!is_dir_nofollow(run_dir))
        return true;
    char path[4608];
    snprintf(path, sizeof path, "%s/files.txt", run_dir);
    if (!remove_file(path, err, errlen) ||
        !folder_each(run_dir, clear_run_entry, NULL, err, errlen))
        return false;
    if (rmdir(run_dir) != 0 && errno != ENOTEMPTY && errno != EEXIST && errno != ENOENT) {
        snprintf(err, errlen, "%s: cannot remove: %s", run_dir, strerror(errno));
        return false;
    }
    return true;
}

void folder_remove_temp(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct dirent *ent;
    char path[4608], err[256];
    while ((ent = readdir(d))) {
        bool temp = false;
        bool ours = is_top_file(ent->d_name, &temp) || folder_is_run_file(ent->d_name, &temp);
        if (ours && temp) {
            folder_path_join(path, sizeof path, dir, ent->d_name);
            remove_file(path, err, sizeof err);
        }
    }
    closedir(d);
}

/* clear_folder's part of one entry of runs/: a run's folder is cleared. */
static bool clear_runs_entry(const char *path, const char *name, void *ctx, char *err,
                             size_t errlen)
{
    return !is_run_id(name) || folder_clear_run(path, err, errlen);
}

/* Removes shadesweep's files of an output folder (not the lock, not anyone else's).
 * keep_sweep: sweep.yaml stays (it is replaced next, atomically), so that a process
 * killed half-way leaves a folder that still says it is shadesweep's. */
static bool clear_folder(const char *dir, bool keep_sweep, char *err, size_t errlen)
{
    char path[4608];
    for (size_t i = 0; i + 1 < NAMES(top_names); i++) {   /* all but sweep.yaml */
        folder_path_join(path, sizeof path, dir, top_names[i]);
        if (!remove_file(path, err, errlen))
            return false;
    }
    folder_remove_temp(dir);
    char runs[4200];
    snprintf(runs, sizeof runs, "%s/runs", dir);
    if (is_dir_nofollow(runs) && !folder_each(runs, clear_runs_entry, NULL, err, errlen))
        return false;
    if (keep_sweep)
        return true;
    snprintf(path, sizeof path, "%s/sweep.yaml", dir);
    return remove_file(path, err, errlen);
}

/* ---- no link below the folder ------------------------------------------------------- */

/* A symbolic link where shadesweep writes, replaces or removes one of its names below
 * OUT is refused by name, before anything is written: a link there (a run folder
 * linked to another sweep's) would have its target's files overwritten. OUT itself may
 * be a link (a results disk linked into a checkout). */
static bool no_link(const char *path, char *err, size_t errlen)
{
    struct stat st;
    if (lstat(path, &st) != 0 || !S_ISLNK(st.st_mode))
        return true;
    char to[1024];
    ssize_t n = readlink(path, to, sizeof to - 1);
    to[n > 0 ? n : 0] = 0;
    snprintf(err, errlen, "%s is a symbolic link (to %.1000s): shadesweep never writes "
             "through a link below its output folder; remove the link, or give the folder "
             "it leads to as -o", path, to);
    return false;
}

/* check_links' part of a run folder's (or a trial folder's) entry. */
static bool run_entry_links(const char *path, const char *name, void *ctx, char *err,
                            size_t errlen)
{
    (void)ctx;
    bool temp;
    if (folder_is_trial_dir(name))
        return no_link(path, err, errlen) &&
               (!is_dir_nofollow(path) || folder_each(path, run_entry_links, NULL, err, errlen));
    return !folder_is_run_file(name, &temp) || no_link(path, err, errlen);
}

/* check_links' part of an entry of runs/. */
static bool runs_entry_links(const char *path, const char *name, void *ctx, char *err,
                             size_t errlen)
{
    (void)ctx;
    if (!is_run_id(name))
        return true;
    return no_link(path, err, errlen) &&
           (!is_dir_nofollow(path) || folder_each(path, run_entry_links, NULL, err, errlen));
}

/* Every name of shadesweep's below dir: the top files, lock, runs/, runs/<id>/, their
 * files and trial folders, and the trials' files. */
static bool check_links(const char *dir, char *err, size_t errlen)
{
    char path[4608];
    for (size_t i = 0; i < NAMES(top_names); i++) {
        folder_path_join(path, sizeof path, dir, top_names[i]);
        if (!no_link(path, err, errlen))
            return false;
    }
    folder_path_join(path, sizeof path, dir, "lock");
    if (!no_link(path, err, errlen))
        return false;
    folder_path_join(path, sizeof path, dir, "runs");
    return no_link(path, err, errlen) &&
           (!is_dir_nofollow(path) || folder_each(path, runs_entry_links, NULL, err, errlen));
}

/* ---- what a folder is ------------------------------------------------------------ */

typedef enum probe_kind { P_ABSENT, P_EMPTY, P_OURS, P_FOREIGN, P_ERROR } probe_kind;

/* A lock file is the only thing in a folder that was never written to otherwise:
 * empty, or a pid and a line end. */
static bool is_lock_only(const char *dir)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/lock", dir);
    struct stat st;
    if (lstat(path, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size > 24)
        return false;
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    char buf[32];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    size_t i = 0;
    while (i < n && buf[i] >= '0' && buf[i] <= '9')
        i++;
    return n == 0 || (i > 0 && i + 1 == n && buf[i] == '\n');
}

/* "sweep.yaml.tmp.PID": what afile_open makes while sweep.yaml is written; a process
 * killed then leaves it in a folder it had just made. */
static bool is_sweep_tmp(const char *name)
{
    static const char prefix[] = "sweep.yaml.tmp.";
    if (strncmp(name, prefix, sizeof prefix - 1) != 0 || !name[sizeof prefix - 1])
        return false;
    for (const char *c = name + sizeof prefix - 1; *c; c++)
        if (*c < '0' || *c > '9')
            return false;
    return true;
}

/* A fresh folder's leftovers of a killed first write (is_sweep_tmp), removed under the
 * lock before sweep.yaml is written again. */
static void remove_sweep_tmps(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *ent;
    while (d && (ent = readdir(d))) {
        if (!is_sweep_tmp(ent->d_name))
            continue;
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", dir, ent->d_name);
        unlink(path);
    }
    if (d)
        closedir(d);
}

static probe_kind probe(const char *dir, sweep_meta *meta, char *why, size_t whylen)
{
    struct stat st;
    if (stat(dir, &st) != 0) {
        if (errno == ENOENT && lstat(dir, &st) != 0)
            return P_ABSENT;
        snprintf(why, whylen, "%s: %s", dir, strerror(errno));
        return P_ERROR;
    }
    if (!S_ISDIR(st.st_mode)) {
        snprintf(why, whylen, "%s exists and is not a folder", dir);
        return P_ERROR;
    }
    DIR *d = opendir(dir);
    if (!d) {
        snprintf(why, whylen, "%s: %s", dir, strerror(errno));
        return P_ERROR;
    }
    size_t others = 0;
    bool lock = false, sweep = false;
    struct dirent *ent;
    while ((ent = readdir(d))) {
        if (strcmp(ent->d_name, ".") == 0 || strcmp(ent->d_name, "..") == 0)
            continue;
        if (strcmp(ent->d_name, "lock") == 0)
            lock = true;
        else if (strcmp(ent->d_name, "sweep.yaml") == 0)
            sweep = true;
        else if (!is_sweep_tmp(ent->d_name))
            others++;
    }
    closedir(d);
    if (!sweep && !others && (!lock || is_lock_only(dir)))
        return P_EMPTY;
    char err[4608];
    if (!sweep) {
        snprintf(why, whylen, "no sweep.yaml");
        return P_FOREIGN;
    }
    if (!output_read_sweep_meta(dir, meta, err, sizeof err) && !meta->format[0]) {
        snprintf(why, whylen, "%.300s", err);
        return P_FOREIGN;
    }
    if (strcmp(meta->format, OUTPUT_FORMAT) != 0) {
        if (meta->format[0])
            snprintf(why, whylen, "its sweep.yaml says format: %.100s, this version writes %s",
                     meta->format, OUTPUT_FORMAT);
        else
            snprintf(why, whylen, "its sweep.yaml lacks format: %s (an older shadesweep's, "
                     "or not shadesweep's)", OUTPUT_FORMAT);
        return P_FOREIGN;
    }
    if (!meta->manifest_hash[0]) {
        snprintf(why, whylen, "its sweep.yaml has no manifest_hash");
        return P_FOREIGN;
    }
    return P_OURS;
}

bool folder_is_output(const char *dir, sweep_meta *meta, char *why, size_t whylen)
{
    memset(meta, 0, sizeof *meta);
    switch (probe(dir, meta, why, whylen)) {
    case P_OURS:
        return true;
    case P_ABSENT:
        snprintf(why, whylen, "no such folder");
        return false;
    case P_EMPTY:
        snprintf(why, whylen, "it is empty");
        return false;
    case P_FOREIGN:
    case P_ERROR:
        return false;
    }
    return false;
}

/* ---- open, lock, close ------------------------------------------------------------- */

/* The pid that holds a flock on the file or folder fd names, from /proc/locks ("1: FLOCK
 * ADVISORY WRITE 1234 08:01:5678 0 EOF"); 0 when it cannot be told. */
static long flock_holder(int fd)
{
    struct stat st;
    FILE *f = fstat(fd, &st) == 0 ? fopen("/proc/locks", "re") : NULL;
    if (!f)
        return 0;
    char line[256];
    long pid = 0;
    while (!pid && fgets(line, sizeof line, f)) {
        char kind[16];
        long p;
        unsigned maj, min;
        unsigned long long ino;
        if (sscanf(line, "%*d: %15s %*s %*s %ld %x:%x:%llu", kind, &p, &maj, &min, &ino) == 5 &&
            strcmp(kind, "FLOCK") == 0 && maj == major(st.st_dev) && min == minor(st.st_dev) &&
            ino == (unsigned long long)st.st_ino)
            pid = p;
    }
    fclose(f);
    return pid;
}

/* The lock is a flock on the folder itself (its descriptor, O_CLOEXEC), not on the lock
 * file: a lock file deleted under a running sweep would let a second one lock a new
 * file of the same name. The file still holds the holder's pid (and is flocked too, as
 * older versions did, so that one of them running into the folder is kept out). */
static bool take_lock(folder *f, char *err, size_t errlen)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/lock", f->dir);
    int dfd = open(f->dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd < 0) {
        snprintf(err, errlen, "%s: cannot open: %s", f->dir, strerror(errno));
        return false;
    }
    int fd = -1;
    int e = flock(dfd, LOCK_EX | LOCK_NB) == 0 ? 0 : errno;
    /* NFS emulates flock with fcntl locks, which need a descriptor open for writing, and
     * a folder cannot be: there the lock file's flock alone holds, as it did before. */
    if (e == EBADF || e == ENOLCK || e == EINVAL || e == EOPNOTSUPP)
        e = 0;
    if (!e) {
        fd = openat(dfd, "lock", O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0666);
        if (fd < 0) {
            if (errno == ELOOP)
                snprintf(err, errlen, "%s is a symbolic link: shadesweep never writes through a "
                         "link below its output folder (remove it)", path);
            else
                snprintf(err, errlen, "%s: cannot create: %s", path, strerror(errno));
            close(dfd);
            return false;
        }
        e = flock(fd, LOCK_EX | LOCK_NB) == 0 ? 0 : errno;
    }
    if (e) {
        long holder = flock_holder(fd >= 0 ? fd : dfd);
        char pid[32] = "";
        int pfd = openat(dfd, "lock", O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
        ssize_t n = e == EWOULDBLOCK && pfd >= 0 ? pread(pfd, pid, sizeof pid - 1, 0) : -1;
        if (pfd >= 0)
            close(pfd);
        if (fd >= 0)
            close(fd);
        close(dfd);
        if (e != EWOULDBLOCK) {
            snprintf(err, errlen, "%s: cannot lock: %s", fd >= 0 ? path : f->dir, strerror(e));
            return false;
        }
        pid[n > 0 ? n : 0] = 0;
        pid[strcspn(pid, "\n")] = 0;
        if (holder)   /* the kernel's word before the file's (which may be gone) */
            snprintf(pid, sizeof pid, "%ld", holder);
        if (pid[0])
            snprintf(err, errlen, "%s is in use by shadesweep process %s (it holds the lock "
                     "on %s); wait for it to end, or stop it", f->dir, pid, f->dir);
        else
            snprintf(err, errlen, "%s is in use by another shadesweep process (it holds the "
                     "lock on %s)", f->dir, f->dir);
        return false;
    }
    char pid[32];
    int len = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) != 0 || pwrite(fd, pid, (size_t)len, 0) != len) {
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        close(fd);
        close(dfd);
        return false;
    }
    f->lock_fd = fd;
    f->dir_fd = dfd;
    return true;
}

static bool same_meta(const char *dir, const sweep_meta *have, const sweep_meta *want,
                      char *err, size_t errlen)
{
    if (strcmp(have->manifest_hash, want->manifest_hash) != 0) {
        snprintf(err, errlen,
                 "--resume: %s was made from manifest %.1000s (hash %s), this is %.1000s "
                 "(hash %s): not the same sweep (the hash is of the manifest's text and "
                 "any --set, --renderer, --smoke, --scale); use --force to replace it, or "
                 "another -o",
                 dir, have->manifest_path, have->manifest_hash, want->manifest_path,
                 want->manifest_hash);
        return false;
    }
    const char *what = NULL;
    char a[96], b[96];
    if (strcmp(have->shard, want->shard) != 0) {
        what = "shard";
        snprintf(a, sizeof a, "%s", have->shard);
        snprintf(b, sizeof b, "%s", want->shard);
    } else if (fabs((have->scale > 0 ? have->scale : 1) - (want->scale > 0 ? want->scale : 1)) > 1e-9) {
        what = "--scale";
        snprintf(a, sizeof a, "%g", have->scale > 0 ? have->scale : 1);
        snprintf(b, sizeof b, "%g", want->scale > 0 ? want->scale : 1);
    } else if (have->smoke != want->smoke) {
        what = "--smoke";
        snprintf(a, sizeof a, "%s", have->smoke ? "smoke" : "full");
        snprintf(b, sizeof b, "%s", want->smoke ? "smoke" : "full");
    } else if (have->runs != want->runs) {
        what = "number of runs";
        snprintf(a, sizeof a, "%zu", have->runs);
        snprintf(b, sizeof b, "%zu", want->runs);
    }
    if (what) {
        snprintf(err, errlen, "--resume: %s holds %s %s, this run is %s: not the same sweep",
                 dir, what, a, b);
        return false;
    }
    return true;
}

static void release(folder *f)
{
    if (f->lock_fd >= 0)
        close(f->lock_fd);
    if (f->dir_fd >= 0)
        close(f->dir_fd);
    f->lock_fd = f->dir_fd = -1;
}

/* Removes what a fresh folder got from this process (only shadesweep's names). */
static void undo_fresh(folder *f)
{
    char path[4608], err[512];
    clear_folder(f->dir, false, err, sizeof err);
    snprintf(path, sizeof path, "%s/runs", f->dir);
    rmdir(path);
    if (f->created) {
        snprintf(path, sizeof path, "%s/lock", f->dir);
        unlink(path);
        rmdir(f->dir);
    }
}

bool folder_open(folder *f, const char *dir, folder_mode mode, const sweep_meta *meta,
                 char *err, size_t errlen)
{
    memset(f, 0, sizeof *f);
    f->lock_fd = f->dir_fd = -1;
    if (!dir || !dir[0]) {
        snprintf(err, errlen, "the output folder is empty (-o \"\" or an empty name)");
        return false;
    }
    if (strlen(dir) >= sizeof f->dir - 64) {
        snprintf(err, errlen, "%.200s...: output folder path too long", dir);
        return false;
    }
    snprintf(f->dir, sizeof f->dir, "%s", dir);
    sweep_meta have;
    char why[1024];
    probe_kind k = probe(dir, &have, why, sizeof why);
    if (k == P_ERROR) {
        snprintf(err, errlen, "%s", why);
        return false;
    }
    if (k == P_FOREIGN) {
        snprintf(err, errlen, "%s exists and is not a shadesweep output folder (%s): %s",
                 dir, why, mode == FOLDER_NEW ? "choose another -o" : "not touching it");
        return false;
    }
    if (k == P_OURS && mode == FOLDER_NEW) {
        snprintf(err, errlen,
                 "%s exists; use --resume to finish it, --force to replace it, or --out DIR", dir);
        return false;
    }
    /* Refusals that can be told before the lock leave the folder as it was, lock too. */
    if (k == P_OURS && mode == FOLDER_RESUME && !same_meta(dir, &have, meta, err, errlen))
        return false;
    if (k == P_OURS && !check_links(dir, err, errlen))
        return false;
    if (k == P_ABSENT) {
        char parent[4096];
        snprintf(parent, sizeof parent, "%s", dir);
        char *slash = strrchr(parent, '/');
        while (slash && slash > parent && slash[1] == 0) {   /* "a/b/" */
            *slash = 0;
            slash = strrchr(parent, '/');
        }
        if (slash && slash > parent) {
            *slash = 0;
            if (!fs_mkdirs(parent, err, errlen))
                return false;
        }
        if (mkdir(dir, 0777) == 0)
            f->created = true;
        else if (errno != EEXIST) {
            snprintf(err, errlen, "%s: cannot create directory: %s", dir, strerror(errno));
            return false;
        }
    }
    if (!take_lock(f, err, errlen)) {
        if (f->created)
            rmdir(dir);
        return false;
    }
    /* Under the lock, again: another process may have made or changed it meanwhile. */
    probe_kind k2 = probe(dir, &have, why, sizeof why);
    bool accept = k2 == P_EMPTY || (k2 == P_OURS && mode != FOLDER_NEW);
    if (!accept) {
        if (k2 == P_OURS)
            snprintf(err, errlen, "%s exists; use --resume to finish it, --force to replace it, "
                     "or --out DIR", dir);
        else if (k2 == P_FOREIGN)
            snprintf(err, errlen, "%s is not a shadesweep output folder (%s): not touching it",
                     dir, why);
        else
            snprintf(err, errlen, "%s", k2 == P_ERROR ? why : "the output folder vanished");
        if (f->created) {
            char path[4200];
            snprintf(path, sizeof path, "%s/lock", dir);
            unlink(path);
            rmdir(dir);
        }
        release(f);
        return false;
    }
    if (k2 == P_OURS && !check_links(dir, err, errlen)) {   /* again, under the lock */
        release(f);
        return false;
    }
    f->fresh = k2 == P_EMPTY;
    if (f->fresh)
        remove_sweep_tmps(dir);
    bool write_meta = true;
    if (k2 == P_OURS && mode == FOLDER_FORCE) {
        if (!clear_folder(dir, true, err, errlen)) {
            release(f);
            return false;
        }
    } else if (k2 == P_OURS && mode == FOLDER_RESUME) {
        if (!same_meta(dir, &have, meta, err, errlen)) {
            release(f);
            return false;
        }
        write_meta = false;
    }
    char runs[4200];
    snprintf(runs, sizeof runs, "%s/runs", dir);
    if ((write_meta && !output_write_sweep_meta(dir, meta, err, errlen)) ||
        !fs_mkdirs_tail(runs, 1, err, errlen)) {
        if (f->fresh)
            undo_fresh(f);
        release(f);
        return false;
    }
    return true;
}

void folder_close(folder *f, bool abandon)
{
    if (f->lock_fd < 0)
        return;
    if (abandon && f->fresh) {
        char runs[4200];
        snprintf(runs, sizeof runs, "%s/runs", f->dir);
        DIR *d = opendir(runs);
        bool empty = true;
        struct dirent *ent;
        while (d && (ent = readdir(d)))
            if (strcmp(ent->d_name, ".") != 0 && strcmp(ent->d_name, "..") != 0)
                empty = false;
        if (d)
            closedir(d);
        if (empty)
            undo_fresh(f);
    }
    release(f);
}

/* ---- paths ----------------------------------------------------------------------- */

/* realpath of a path that may not exist yet: its nearest existing ancestor resolved,
 * the rest appended as written. */
static bool resolve(const char *path, char *out, size_t len)
{
    char buf[PATH_MAX];
    if (realpath(path, buf)) {
        snprintf(out, len, "%s", buf);
        return true;
    }
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s", path);
    size_t n = strlen(tmp);
    while (n > 1 && tmp[n - 1] == '/')
        tmp[--n] = 0;
    char *slash = strrchr(tmp, '/');
    const char *rest = slash ? slash + 1 : tmp;
    char parent[4096];
    if (!slash)
        snprintf(parent, sizeof parent, ".");
    else if (slash == tmp)
        snprintf(parent, sizeof parent, "/");
    else
        snprintf(parent, sizeof parent, "%.*s", (int)(slash - tmp), tmp);
    if (!rest[0] || strcmp(parent, path) == 0 || !resolve(parent, buf, sizeof buf))
        return false;
    int k = snprintf(out, len, "%s%s%s", buf, strcmp(buf, "/") == 0 ? "" : "/", rest);
    return k >= 0 && (size_t)k < len;
}

static bool inside(const char *a, const char *b)   /* a is b or under b */
{
    size_t n = strlen(b);
    if (strcmp(b, "/") == 0)
        return true;
    return strncmp(a, b, n) == 0 && (a[n] == 0 || a[n] == '/');
}

bool folder_overlaps(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino)
        return true;
    char ra[4200], rb[4200];
    if (!resolve(a, ra, sizeof ra) || !resolve(b, rb, sizeof rb))
        return false;
    return inside(ra, rb) || inside(rb, ra);
}

void folder_std_fds(void)
{
    int fd;
    while ((fd = open("/dev/null", O_RDWR)) >= 0 && fd <= 2)
        ;
    if (fd > 2)
        close(fd);
}
