/* Files that appear under their final name only when complete, and small
 * directory helpers (mkdir -p, rm -rf). See fsutil.h. */
/* nftw() and FTW_DEPTH/FTW_PHYS are XSI: glibc hides them under plain POSIX. */
#define _XOPEN_SOURCE 700

#include "results/fsutil.h"

#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

static char *dup_str(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s, n);
    return d;
}

char *fs_read_all(const char *path, size_t max, size_t *len, int *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        *err = errno;
        return NULL;
    }
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    *err = buf ? 0 : ENOMEM;
    while (buf) {
        if (n + 1 == cap) {
            if (max && n > max) {
                *err = EFBIG;
                break;
            }
            char *nb = realloc(buf, cap * 2);
            if (!nb) {
                *err = ENOMEM;
                break;
            }
            buf = nb;
            cap *= 2;
        }
        size_t got = fread(buf + n, 1, cap - n - 1, f);
        n += got;
        if (got == 0)
            break;
    }
    if (!*err && ferror(f))
        *err = EIO;
    if (!*err && max && n > max)
        *err = EFBIG;
    fclose(f);
    if (*err) {
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    *len = n;
    return buf;
}

static void afile_clear(afile *f)
{
    free(f->final_path);
    free(f->tmp_path);
    f->fp = NULL;
    f->final_path = NULL;
    f->tmp_path = NULL;
}

bool afile_open(afile *f, const char *final_path, char *err, size_t errlen)
{
    f->fp = NULL;
    f->final_path = NULL;
    f->tmp_path = NULL;

    if (final_path == NULL || final_path[0] == '\0') {
        snprintf(err, errlen, "cannot create file: empty path");
        return false;
    }
    long pid = (long)getpid();
    int len = snprintf(NULL, 0, "%s.tmp.%ld", final_path, pid);
    f->final_path = dup_str(final_path);
    f->tmp_path = len > 0 ? malloc((size_t)len + 1) : NULL;
    if (f->final_path == NULL || f->tmp_path == NULL) {
        snprintf(err, errlen, "%s: out of memory", final_path);
        goto fail;
    }
    snprintf(f->tmp_path, (size_t)len + 1, "%s.tmp.%ld", final_path, pid);

    int fd = open(f->tmp_path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot create: %s", f->tmp_path, strerror(errno));
        goto fail;
    }
    f->fp = fdopen(fd, "w");
    if (f->fp == NULL) {
        int e = errno;
        close(fd);
        unlink(f->tmp_path);
        snprintf(err, errlen, "%s: cannot open stream: %s", f->tmp_path, strerror(e));
        goto fail;
    }
    return true;

fail:
    afile_clear(f);
    return false;
}

bool afile_commit(afile *f, char *err, size_t errlen)
{
    if (f->fp == NULL || f->tmp_path == NULL || f->final_path == NULL) {
        snprintf(err, errlen, "bug: afile_commit on a file that is not open");
        afile_clear(f);
        return false;
    }
    bool ok = true;
    int e = 0;
    const char *what = "";

    /* The first error wins; every step still runs so that the stream is closed. */
    if (fflush(f->fp) != 0) {
        e = errno;
        what = "write";
        ok = false;
    } else if (ferror(f->fp)) { /* an earlier buffered write failed */
        e = EIO;
        what = "write";
        ok = false;
    }
    if (ok && fsync(fileno(f->fp)) != 0) {
        e = errno;
        what = "fsync";
        ok = false;
    }
    if (fclose(f->fp) != 0 && ok) {
        e = errno;
        what = "close";
        ok = false;
    }
    f->fp = NULL;
    if (ok && rename(f->tmp_path, f->final_path) != 0) {
        e = errno;
        snprintf(err, errlen, "%s: cannot rename to %s: %s", f->tmp_path, f->final_path,
                 strerror(e));
        unlink(f->tmp_path);
        afile_clear(f);
        return false;
    }
    if (!ok) {
        /* Name the file the user knows; the temporary one is gone. */
        snprintf(err, errlen, "%s: %s failed: %s", f->final_path, what, strerror(e));
        unlink(f->tmp_path);
    }
    afile_clear(f);
    return ok;
}

void afile_abort(afile *f)
{
    if (f == NULL)
        return;
    if (f->fp != NULL)
        fclose(f->fp);
    if (f->tmp_path != NULL)
        unlink(f->tmp_path);
    afile_clear(f);
}

static bool is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

bool fs_mkdirs(const char *path, char *err, size_t errlen)
{
    if (path == NULL || path[0] == '\0') {
        snprintf(err, errlen, "cannot create directory: empty path");
        return false;
    }
    char *p = dup_str(path);
    if (p == NULL) {
        snprintf(err, errlen, "%s: out of memory", path);
        return false;
    }
    bool ok = true;
    /* Create every prefix ending before a '/', then the whole path. */
    for (char *c = p + 1;; c++) {
        bool end = (*c == '\0');
        if (!end && *c != '/')
            continue;
        if (c[-1] != '/') { /* skip empty components ("a//b", trailing '/') */
            char saved = *c;
            *c = '\0';
            if (mkdir(p, 0777) != 0 && !(errno == EEXIST && is_dir(p))) {
                int e = errno == EEXIST ? ENOTDIR : errno;
                snprintf(err, errlen, "%s: cannot create directory: %s", p, strerror(e));
                ok = false;
            }
            *c = saved;
            if (!ok)
                break;
        }
        if (end)
            break;
    }
    if (ok && !is_dir(path)) {
        snprintf(err, errlen, "%s: not a directory after mkdir", path);
        ok = false;
    }
    free(p);
    return ok;
}

bool fs_exists(const char *path)
{
    struct stat st;
    return path != NULL && lstat(path, &st) == 0;
}

/* nftw() has no user pointer: the failing path is kept here for the message. */
static _Thread_local char remove_failed_path[512];
static _Thread_local int remove_failed_errno;

static int remove_entry(const char *path, const struct stat *st, int type, struct FTW *ftw)
{
    (void)st;
    (void)ftw;
    bool dir = (type == FTW_DP || type == FTW_D || type == FTW_DNR);
    int rc = dir ? rmdir(path) : unlink(path);
    if (rc != 0 && errno != ENOENT) {
        remove_failed_errno = errno;
        snprintf(remove_failed_path, sizeof remove_failed_path, "%s", path);
        return 1;
    }
    return 0;
}

/* Removes path and everything under it; a path that does not exist is not an error
 * (rm -rf). Symbolic links are removed, never followed. */
bool fs_remove_tree(const char *path, char *err, size_t errlen)
{
    struct stat st;
    if (path == NULL || path[0] == '\0') {
        snprintf(err, errlen, "cannot remove: empty path");
        return false;
    }
    if (lstat(path, &st) != 0) {
        if (errno == ENOENT)
            return true;
        snprintf(err, errlen, "%s: cannot remove: %s", path, strerror(errno));
        return false;
    }
    remove_failed_path[0] = '\0';
    remove_failed_errno = 0;
    int rc = nftw(path, remove_entry, 32, FTW_DEPTH | FTW_PHYS);
    if (rc == 0)
        return true;
    if (rc == 1 && remove_failed_path[0] != '\0')
        snprintf(err, errlen, "%s: cannot remove: %s", remove_failed_path,
                 strerror(remove_failed_errno));
    else
        snprintf(err, errlen, "%s: cannot remove: %s", path, strerror(errno));
    return false;
}
