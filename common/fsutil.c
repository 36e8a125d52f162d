/* Files that appear under their final name only when complete, and small
 * directory helpers (mkdir -p, rm -rf). See fsutil.h. */
/* nftw() and FTW_DEPTH/FTW_PHYS are XSI, fopencookie() is glibc's: _GNU_SOURCE has both. */
#define _GNU_SOURCE

#include "common/fsutil.h"

#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

static char *read_stream(FILE *f, size_t max, size_t *len, int *err);

char *fs_read_all(const char *path, size_t max, size_t *len, int *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        *err = errno;
        return NULL;
    }
    return read_stream(f, max, len, err);
}

static const char *kind_of(mode_t m)
{
    return S_ISDIR(m) ? "a directory" : S_ISFIFO(m) ? "a FIFO" : S_ISSOCK(m) ? "a socket"
         : S_ISCHR(m) ? "a character device" : S_ISBLK(m) ? "a block device"
         : "not a regular file";
}

char *fs_read_regular(const char *path, size_t max, size_t *len, int *err, const char **kind)
{
    *kind = NULL;
    /* O_NONBLOCK: opening a FIFO for reading waits for a writer otherwise */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0) {
        *err = errno;
        if (fd >= 0)
            close(fd);
        return NULL;
    }
    if (!S_ISREG(st.st_mode)) {
        *err = 0;
        *kind = kind_of(st.st_mode);
        close(fd);
        return NULL;
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        *err = errno;
        close(fd);
        return NULL;
    }
    return read_stream(f, max, len, err);
}

/* The rest of f, which it closes. */
static char *read_stream(FILE *f, size_t max, size_t *len, int *err)
{
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

static const char *errno_hint(int e)
{
    return e == ENOSPC ? " (the disk is full)"
           : e == EDQUOT ? " (the disk quota is exhausted)"
           : e == EROFS ? " (the file system is read-only)"
           : e == EIO ? " (the device reported an I/O error)"
           : e == EFBIG ? " (over the file-size limit, ulimit -f, or the file system's largest "
                          "file)"
           : "";
}

void afile_fail_once(const afile *f, const char *fallback, bool *failed, char *msg,
                     size_t msglen, const char *what)
{
    if (*failed)
        return;
    *failed = true;
    snprintf(msg, msglen, "%s: %s", f->final_path ? f->final_path : fallback, what);
}

bool afile_finish(afile *f, bool failed, const char *msg, char *err, size_t errlen)
{
    if (!failed)
        return afile_commit(f, err, errlen);
    snprintf(err, errlen, "%s", msg);
    afile_abort(f);
    return false;
}

void fs_error_message(char *err, size_t errlen, const char *path, int e)
{
    snprintf(err, errlen, "%s: %s%s", path, strerror(e), errno_hint(e));
}

/* What the stream of an afile writes through: every write(2) checked, the first error
 * kept, the bytes that reached the file counted (afile_commit compares the file's size). */
struct afile_sink {
    int fd;
    int err;                   /* the first write error's errno; 0: none */
    uint64_t written;
};

static ssize_t sink_write(void *cookie, const char *buf, size_t size)
{
    afile_sink *k = cookie;
    if (k->err)
        return 0;   /* the file is lost already: nothing more goes to it */
    size_t done = 0;
    while (done < size) {
        ssize_t w = write(k->fd, buf + done, size - done);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            k->err = w < 0 ? errno : EIO;   /* a write of 0 bytes: nothing will come */
            errno = k->err;
            return 0;   /* fopencookie: 0 is an error, and the stream's error flag is set */
        }
        done += (size_t)w;
        k->written += (uint64_t)w;
    }
    return (ssize_t)size;
}

static int sink_close(void *cookie)
{
    afile_sink *k = cookie;
    int rc = close(k->fd);
    k->fd = -1;
    if (rc != 0 && !k->err)
        k->err = errno;
    return rc;
}

static void afile_clear(afile *f)
{
    free(f->final_path);
    free(f->tmp_path);
    free(f->sink);
    *f = (afile){0};
}

bool afile_open(afile *f, const char *final_path, char *err, size_t errlen)
{
    *f = (afile){0};

    if (final_path == NULL || final_path[0] == '\0') {
        snprintf(err, errlen, "cannot create file: empty path");
        return false;
    }
    long pid = (long)getpid();
    int len = snprintf(NULL, 0, "%s.tmp.%ld", final_path, pid);
    f->final_path = strdup(final_path);
    f->tmp_path = len > 0 ? malloc((size_t)len + 1) : NULL;
    f->sink = calloc(1, sizeof *f->sink);
    if (f->final_path == NULL || f->tmp_path == NULL || f->sink == NULL) {
        snprintf(err, errlen, "%s: out of memory", final_path);
        goto fail;
    }
    snprintf(f->tmp_path, (size_t)len + 1, "%s.tmp.%ld", final_path, pid);

    /* O_EXCL never follows a link at the name; O_NOFOLLOW says so. */
    int fd = open(f->tmp_path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd < 0) {
        int e = errno;
        snprintf(err, errlen, "%s: cannot create: %s%s", f->tmp_path, strerror(e),
                 errno_hint(e));
        goto fail;
    }
    f->sink->fd = fd;
    cookie_io_functions_t io = {.write = sink_write, .close = sink_close};
    f->fp = fopencookie(f->sink, "w", io);
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

bool afile_write(afile *f, const void *data, size_t n)
{
    if (f->fp == NULL || f->sink == NULL)
        return false;
    if (n && fwrite(data, 1, n, f->fp) != n)
        return false;
    return !ferror(f->fp) && f->sink->err == 0;
}

bool afile_commit(afile *f, char *err, size_t errlen)
{
    if (f->fp == NULL || f->tmp_path == NULL || f->final_path == NULL || f->sink == NULL) {
        snprintf(err, errlen, "bug: afile_commit on a file that is not open");
        afile_abort(f);
        return false;
    }
    afile_sink *k = f->sink;
    int e = 0;
    const char *what = "";

    /* The first error wins (a write's, kept by the sink); every step still runs so that
     * the stream is closed. */
    if (fflush(f->fp) != 0 || ferror(f->fp) || k->err) {
        e = k->err ? k->err : errno ? errno : EIO;
    } else if (fsync(k->fd) != 0) {
        e = errno;
        what = "fsync: ";
    } else {
        /* Every byte the writer gave is in the file, and nothing else. */
        struct stat st;
        if (fstat(k->fd, &st) != 0) {
            e = errno;
            what = "fstat: ";
        } else if ((uint64_t)st.st_size != k->written) {
            snprintf(err, errlen, "%s: %lld bytes on disk after writing %llu", f->final_path,
                     (long long)st.st_size, (unsigned long long)k->written);
            e = -1;
        }
    }
    if (fclose(f->fp) != 0 && !e) {
        e = k->err ? k->err : errno ? errno : EIO;
        what = "close: ";
    }
    f->fp = NULL;
    if (!e && f->set) {
        /* complete and on disk: the set renames it with the others */
        afile_set *s = f->set;
        if (s->n == AFILE_SET_MAX) {
            snprintf(err, errlen, "%s: bug: more than %d files in one set", f->final_path,
                     AFILE_SET_MAX);
            unlink(f->tmp_path);
            afile_clear(f);
            return false;
        }
        s->tmp[s->n] = f->tmp_path;
        s->final[s->n++] = f->final_path;
        f->tmp_path = f->final_path = NULL;
        afile_clear(f);
        return true;
    }
    if (!e && rename(f->tmp_path, f->final_path) != 0) {
        e = errno;
        snprintf(err, errlen, "%s: cannot rename %s: %s%s", f->final_path, f->tmp_path,
                 strerror(e), errno_hint(e));
        unlink(f->tmp_path);
        afile_clear(f);
        return false;
    }
    if (e) {
        /* Name the file the user knows; the temporary one is gone. */
        if (e > 0)
            snprintf(err, errlen, "%s: %s%s%s", f->final_path, what, strerror(e),
                     errno_hint(e));
        unlink(f->tmp_path);
    }
    afile_clear(f);
    return e == 0;
}

void afile_abort(afile *f)
{
    if (f == NULL)
        return;
    if (f->fp != NULL)
        fclose(f->fp);
    else if (f->sink != NULL && f->sink->fd > 0)
        close(f->sink->fd);
    if (f->tmp_path != NULL)
        unlink(f->tmp_path);
    afile_clear(f);
}

bool afile_set_commit(afile_set *s, char *err, size_t errlen)
{
    bool ok = true;
    for (size_t i = 0; i < s->n; i++) {
        if (ok && rename(s->tmp[i], s->final[i]) != 0) {
            int e = errno;
            snprintf(err, errlen, "%s: cannot rename %s: %s%s", s->final[i], s->tmp[i],
                     strerror(e), errno_hint(e));
            ok = false;
        }
        if (!ok)
            unlink(s->tmp[i]);
        free(s->tmp[i]);
        free(s->final[i]);
    }
    s->n = 0;
    return ok;
}

void afile_set_abort(afile_set *s)
{
    for (size_t i = 0; i < s->n; i++) {
        unlink(s->tmp[i]);
        free(s->tmp[i]);
        free(s->final[i]);
    }
    s->n = 0;
}

static bool is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

bool fs_mkdirs(const char *path, char *err, size_t errlen)
{
    return fs_mkdirs_tail(path, 0, err, errlen);
}

/* The number of components of p after offset at (empty ones skipped). */
static int components_after(const char *p, size_t at)
{
    int n = 0;
    for (size_t i = at; p[i]; i++)
        if (p[i] != '/' && (i == 0 || p[i - 1] == '/'))
            n++;
    return n;
}

bool fs_mkdirs_tail(const char *path, int tail, char *err, size_t errlen)
{
    if (path == NULL || path[0] == '\0') {
        snprintf(err, errlen, "cannot create directory: empty path");
        return false;
    }
    char *p = strdup(path);
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
            /* The last `tail` components: a link there is refused, never followed. */
            bool own = components_after(path, (size_t)(c - p)) < tail;
            struct stat st;
            if (mkdir(p, 0777) != 0 && !(errno == EEXIST && is_dir(p))) {
                int e = errno == EEXIST ? ENOTDIR : errno;
                snprintf(err, errlen, "%s: cannot create directory: %s", p, strerror(e));
                ok = false;
            } else if (own && (lstat(p, &st) != 0 || !S_ISDIR(st.st_mode))) {
                snprintf(err, errlen, "%s is a symbolic link: shadesweep never writes through "
                         "a link below its output folder (remove it)", p);
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

const char *fs_text_bom(const void *data, size_t len)
{
    static const struct {
        unsigned char bom[4];
        size_t len;
        const char *name;
    } boms[] = {
        {{0x00, 0x00, 0xfe, 0xff}, 4, "UTF-32 (big-endian)"},
        {{0xff, 0xfe, 0x00, 0x00}, 4, "UTF-32 (little-endian)"},
        {{0xfe, 0xff}, 2, "UTF-16 (big-endian)"},
        {{0xff, 0xfe}, 2, "UTF-16 (little-endian)"},
    };
    for (size_t i = 0; data && i < sizeof boms / sizeof boms[0]; i++)
        if (len >= boms[i].len && memcmp(data, boms[i].bom, boms[i].len) == 0)
            return boms[i].name;
    return NULL;
}
