/* Output folders: ownership, the lock, per-run completion manifests (folder.h). */
#define _DEFAULT_SOURCE   /* realpath, dirfd */
#include "runner/folder.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "results/csv.h"
#include "results/fsutil.h"
#include "runner/hash.h"

#define RUN_FILES_HEADER "# shadesweep run files 1"

/* ---- the names shadesweep writes ------------------------------------------------- */

/* sweep.yaml last: clear_folder removes the others and may keep it. Every file a sweep
 * writes must be named here (or in is_run_file): a name missing is a file that --force
 * and a rerun leave behind from an older sweep, whose killed write's ".tmp.<pid>" is
 * never swept, and (in a run folder) that files.txt does not vouch for. */
static const char *const top_names[] = {"plan.csv",     "summary.csv",      "summary.md",
                                         "summary.json", "summary_long.csv", "sweep.yaml"};
static const char *const run_names[] = {
    "frames.csv", "seconds.csv", "passes.csv", "convergence.csv", "errors.csv",
    "coverage.csv", "lightgrid.csv", "summary.csv", "meta.yaml", "log.txt", "files.txt",
};
#define NAMES(a) (sizeof(a) / sizeof((a)[0]))

/* dir/name; false (and a cut path) when it does not fit. */
static bool pjoin(char *dst, size_t n, const char *dir, const char *name)
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

/* A file of a run folder: the fixed names, screenshot-trial*.png, error-trial*.{png,exr}. */
static bool is_run_file(const char *name, bool *temp)
{
    size_t n = base_len(name, temp);
    if (in_list(name, n, run_names, NAMES(run_names)))
        return true;
    if (n > 16 && strncmp(name, "screenshot-trial", 16) == 0 && ends_with(name, n, ".png"))
        return true;
    return n > 11 && strncmp(name, "error-trial", 11) == 0 &&
           (ends_with(name, n, ".png") || ends_with(name, n, ".exr"));
}

/* runs/<id>/trial-<k>: one trial's files while its run is not complete (runner/trials.c). */
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

bool folder_clear_run(const char *run_dir, char *err, size_t errlen)
{
    if (!is_dir_nofollow(run_dir))
        return true;
    char path[4608];
    snprintf(path, sizeof path, "%s/files.txt", run_dir);
    if (!remove_file(path, err, errlen))
        return false;
    DIR *d = opendir(run_dir);
    if (!d) {
        snprintf(err, errlen, "%s: %s", run_dir, strerror(errno));
        return false;
    }
    bool ok = true;
    struct dirent *ent;
    while (ok && (ent = readdir(d))) {
        bool temp;
        if (folder_is_trial_dir(ent->d_name)) {
            pjoin(path, sizeof path, run_dir, ent->d_name);
            if (is_dir_nofollow(path))
                ok = folder_clear_run(path, err, errlen);
            continue;
        }
        if (!is_run_file(ent->d_name, &temp))
            continue;
        pjoin(path, sizeof path, run_dir, ent->d_name);
        ok = remove_file(path, err, errlen);
    }
    closedir(d);
    if (ok && rmdir(run_dir) != 0 && errno != ENOTEMPTY && errno != EEXIST && errno != ENOENT) {
        snprintf(err, errlen, "%s: cannot remove: %s", run_dir, strerror(errno));
        ok = false;
    }
    return ok;
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
        bool ours = is_top_file(ent->d_name, &temp) || is_run_file(ent->d_name, &temp);
        if (ours && temp) {
            pjoin(path, sizeof path, dir, ent->d_name);
            remove_file(path, err, sizeof err);
        }
    }
    closedir(d);
}

/* Removes shadesweep's files of an output folder (not the lock, not anyone else's).
 * keep_sweep: sweep.yaml stays (it is replaced next, atomically), so that a process
 * killed half-way leaves a folder that still says it is shadesweep's. */
static bool clear_folder(const char *dir, bool keep_sweep, char *err, size_t errlen)
{
    char path[4608];
    for (size_t i = 0; i + 1 < NAMES(top_names); i++) {   /* all but sweep.yaml */
        pjoin(path, sizeof path, dir, top_names[i]);
        if (!remove_file(path, err, errlen))
            return false;
    }
    folder_remove_temp(dir);
    char runs[4200];
    snprintf(runs, sizeof runs, "%s/runs", dir);
    if (is_dir_nofollow(runs)) {
        DIR *d = opendir(runs);
        if (!d) {
            snprintf(err, errlen, "%s: %s", runs, strerror(errno));
            return false;
        }
        bool ok = true;
        struct dirent *ent;
        while (ok && (ent = readdir(d))) {
            if (!is_run_id(ent->d_name))
                continue;
            pjoin(path, sizeof path, runs, ent->d_name);
            ok = folder_clear_run(path, err, errlen);
        }
        closedir(d);
        if (!ok)
            return false;
    }
    if (keep_sweep)
        return true;
    snprintf(path, sizeof path, "%s/sweep.yaml", dir);
    return remove_file(path, err, errlen);
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

/* ---- open, lock, close ------------------------------------------------------------- */

static bool take_lock(folder *f, char *err, size_t errlen)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/lock", f->dir);
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot create: %s", path, strerror(errno));
        return false;
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        int e = errno;
        char pid[32] = "";
        ssize_t n = e == EWOULDBLOCK ? pread(fd, pid, sizeof pid - 1, 0) : -1;
        close(fd);
        if (e != EWOULDBLOCK) {
            snprintf(err, errlen, "%s: cannot lock: %s", path, strerror(e));
            return false;
        }
        pid[n > 0 ? n : 0] = 0;
        pid[strcspn(pid, "\n")] = 0;
        if (pid[0])
            snprintf(err, errlen, "%s is in use by shadesweep process %s (it holds %s); "
                     "wait for it to end, or stop it", f->dir, pid, path);
        else
            snprintf(err, errlen, "%s is in use by another shadesweep process (it holds %s)",
                     f->dir, path);
        return false;
    }
    char pid[32];
    int len = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) != 0 || pwrite(fd, pid, (size_t)len, 0) != len) {
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        close(fd);
        return false;
    }
    f->lock_fd = fd;
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
    f->lock_fd = -1;
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
    f->lock_fd = -1;
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
        !fs_mkdirs(runs, err, errlen)) {
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

/* ---- per-run completion manifests ---------------------------------------------- */

/* Size and FNV-1a 64 of a regular file (not followed if a link). */
static bool file_sum(const char *path, long long *size, uint64_t *h, char *err, size_t errlen)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        snprintf(err, errlen, "%s", fd < 0 ? (errno == ENOENT ? "missing" : strerror(errno))
                                           : "not a regular file");
        if (fd >= 0)
            close(fd);
        return false;
    }
    char buf[65536];
    uint64_t v = FNV1A64_OFFSET_BASIS;
    long long n = 0;
    ssize_t got;
    while ((got = read(fd, buf, sizeof buf)) > 0) {
        v = fnv1a64_update(v, buf, (size_t)got);
        n += got;
    }
    int e = errno;
    close(fd);
    if (got < 0) {
        snprintf(err, errlen, "read error: %s", strerror(e));
        return false;
    }
    *size = n;
    *h = v;
    return true;
}

static int cmp_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

bool folder_write_run_files(const char *run_dir, char *err, size_t errlen)
{
    DIR *d = opendir(run_dir);
    if (!d) {
        snprintf(err, errlen, "%s: %s", run_dir, strerror(errno));
        return false;
    }
    char **names = NULL;
    size_t n = 0, cap = 0;
    bool ok = true;
    struct dirent *ent;
    while (ok && (ent = readdir(d))) {
        bool temp;
        if (!is_run_file(ent->d_name, &temp) || temp || strcmp(ent->d_name, "log.txt") == 0 ||
            strcmp(ent->d_name, "files.txt") == 0)
            continue;
        if (n == cap) {
            cap = cap ? cap * 2 : 16;
            char **nv = realloc(names, cap * sizeof *nv);
            if (!nv) {
                ok = false;
                break;
            }
            names = nv;
        }
        if (!(names[n] = strdup(ent->d_name))) {
            ok = false;
            break;
        }
        n++;
    }
    closedir(d);
    if (!ok)
        snprintf(err, errlen, "%s: out of memory", run_dir);
    if (n)
        qsort(names, n, sizeof *names, cmp_names);
    char path[4608];
    snprintf(path, sizeof path, "%s/files.txt", run_dir);
    afile out;
    if (ok && !(ok = afile_open(&out, path, err, errlen)))
        ;
    else if (ok) {
        fprintf(out.fp, "%s\n", RUN_FILES_HEADER);
        for (size_t i = 0; ok && i < n; i++) {
            char p[4608], why[256];
            long long size;
            uint64_t h;
            pjoin(p, sizeof p, run_dir, names[i]);
            if (!file_sum(p, &size, &h, why, sizeof why)) {
                snprintf(err, errlen, "%s: %s", p, why);
                ok = false;
                break;
            }
            char hex[17];
            hash_hex(h, 16, hex);
            fprintf(out.fp, "%s %lld %s\n", names[i], size, hex);
        }
        if (ok)
            ok = afile_commit(&out, err, errlen);
        else
            afile_abort(&out);
    }
    for (size_t i = 0; i < n; i++)
        free(names[i]);
    free(names);
    return ok;
}

/* The run's summary.csv: this version's header, every row with its column count and
 * this run's id. */
static bool check_summary(const char *path, const char *id, run_check *c, char *why,
                          size_t whylen)
{
    size_t len;
    int e;
    char *text = fs_read_all(path, 0, &len, &e);
    if (!text) {
        snprintf(why, whylen, "summary.csv: %s", e == ENOENT ? "missing" : strerror(e));
        return false;
    }
    csv_record r = {0};
    size_t pos = 0, row = 0;
    bool ok = true;
    int k;
    while ((k = csv_next_record(text, len, &pos, &r)) > 0) {
        row++;
        if (row == 1) {
            bool same = r.n == summary_ncolumns;
            for (size_t i = 0; same && i < r.n; i++)
                same = strcmp(r.field[i], summary_columns[i]) == 0;
            if (!same) {
                snprintf(why, whylen, "summary.csv: header differs from this version's columns");
                ok = false;
                break;
            }
            continue;
        }
        if (r.n != summary_ncolumns) {
            snprintf(why, whylen, "summary.csv: row %zu has %zu fields, want %zu", row, r.n,
                     summary_ncolumns);
            ok = false;
            break;
        }
        if (strcmp(r.field[1], id) != 0) {
            snprintf(why, whylen, "summary.csv: row %zu is run %.20s's", row, r.field[1]);
            ok = false;
            break;
        }
        if (strcmp(r.field[summary_ncolumns - 2], "ok") != 0 && !c->failed) {
            c->failed = true;
            snprintf(c->status, sizeof c->status, "%s", r.field[summary_ncolumns - 2]);
        }
        if (strcmp(r.field[summary_ncolumns - 2], RUN_STATUS_WRITE) == 0)
            c->unwritten = true;
        c->rows++;
    }
    if (ok && k < 0) {
        snprintf(why, whylen, "summary.csv: row %zu is cut off or malformed", row + 1);
        ok = false;
    }
    if (ok && c->rows == 0) {
        snprintf(why, whylen, "summary.csv: no rows");
        ok = false;
    }
    csv_record_free(&r);
    free(text);
    return ok;
}

/* The check of folder_check_run on one folder: a run's, or one of its trials'. */
static bool check_dir(const char *run_dir, const char *id, bool all_files, run_check *c,
                      char *why, size_t whylen)
{
    memset(c, 0, sizeof *c);
    char path[4608];
    snprintf(path, sizeof path, "%s/files.txt", run_dir);
    size_t len;
    int e;
    char *text = fs_read_all(path, 0, &len, &e);
    if (!text) {
        snprintf(why, whylen, e == ENOENT ? "no files.txt (the run did not finish)"
                                          : "files.txt: %s", strerror(e));
        return false;
    }
    bool ok = strncmp(text, RUN_FILES_HEADER "\n", strlen(RUN_FILES_HEADER) + 1) == 0;
    if (!ok)
        snprintf(why, whylen, "files.txt: not a run's file list");
    bool have_summary = false, have_meta = false;
    size_t lineno = 1;
    for (char *line = text + strlen(RUN_FILES_HEADER) + 1; ok && line < text + len; lineno++) {
        char *nl = strchr(line, '\n');
        if (!nl) {
            snprintf(why, whylen, "files.txt: line %zu is cut off", lineno + 1);
            ok = false;
            break;
        }
        *nl = 0;
        char name[256], hex[17];
        long long size;
        int used = 0;
        if (sscanf(line, "%255s %lld %16s%n", name, &size, hex, &used) != 3 ||
            line[used] != 0 || strlen(hex) != 16 || !is_run_file(name, &(bool){0})) {
            snprintf(why, whylen, "files.txt: line %zu is malformed", lineno + 1);
            ok = false;
            break;
        }
        line = nl + 1;
        bool summary = strcmp(name, "summary.csv") == 0;
        have_summary |= summary;
        have_meta |= strcmp(name, "meta.yaml") == 0;
        if (!all_files && !summary)
            continue;
        char p[4608], err[256];
        long long got;
        uint64_t h;
        pjoin(p, sizeof p, run_dir, name);
        if (!file_sum(p, &got, &h, err, sizeof err)) {
            snprintf(why, whylen, "%s: %s", name, err);
            ok = false;
        } else if (got != size) {
            snprintf(why, whylen, "%s: %lld bytes, files.txt says %lld", name, got, size);
            ok = false;
        } else {
            char have[17];
            hash_hex(h, 16, have);
            if (strcmp(have, hex) != 0) {
                snprintf(why, whylen, "%s: checksum %s, files.txt says %s", name, have, hex);
                ok = false;
            }
        }
    }
    free(text);
    if (ok && (!have_summary || !have_meta)) {
        snprintf(why, whylen, "files.txt lists no %s", have_summary ? "meta.yaml" : "summary.csv");
        ok = false;
    }
    snprintf(path, sizeof path, "%s/summary.csv", run_dir);
    return ok && check_summary(path, id, c, why, whylen);
}

bool folder_check_run(const char *out_dir, const char *id, bool all_files, run_check *c,
                      char *why, size_t whylen)
{
    char run_dir[4200];
    snprintf(run_dir, sizeof run_dir, "%s/runs/%s", out_dir, id);
    return check_dir(run_dir, id, all_files, c, why, whylen);
}

bool folder_check_trial(const char *out_dir, const char *id, uint32_t trial, run_check *c,
                        char *why, size_t whylen)
{
    char dir[4300];
    snprintf(dir, sizeof dir, "%s/runs/%s/trial-%u", out_dir, id, trial);
    return check_dir(dir, id, true, c, why, whylen);
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
