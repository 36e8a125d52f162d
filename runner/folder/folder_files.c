/* Per-run completion manifests: files.txt, written last, names every file of a complete
 * run with its size and checksum (runner/folder/folder.h). */
#define _DEFAULT_SOURCE   /* dirfd */
#include "runner/folder/folder.h"
#include "runner/folder/folder_internal.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "results/csv.h"
#include "common/fsutil.h"
#include "common/grow.h"
#include "runner/manifest/hash.h"

#define RUN_FILES_HEADER "# shadesweep run files 1"
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
        if (!folder_is_run_file(ent->d_name, &temp) || temp || strcmp(ent->d_name, "log.txt") == 0 ||
            strcmp(ent->d_name, "files.txt") == 0)
            continue;
        if (!GROW(names, cap, n + 1, 16)) {
            ok = false;
            break;
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
            folder_path_join(p, sizeof p, run_dir, names[i]);
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
            line[used] != 0 || strlen(hex) != 16 || !folder_is_run_file(name, &(bool){0})) {
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
        folder_path_join(p, sizeof p, run_dir, name);
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
