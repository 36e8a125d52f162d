/* I/O error injection for tests/cli/io_errors.sh (LD_PRELOAD), after SQLite's harness:
 * the Nth write-level call to a file under a chosen folder fails.
 *   IOFAULT_DIR=/abs/dir  only regular files under it count (not log.txt and lock)
 *   IOFAULT_COUNT=FILE    the count, shared by the sweep's processes (one at a time):
 *                         a byte appended to FILE per call
 *   IOFAULT_AT=N          call N (1-based) fails; 0 or unset: count only
 *   IOFAULT_PERSIST=1     every call after N fails too (a disk that stays full)
 *   IOFAULT_ERRNO=ENOSPC  or EIO, EDQUOT, EROFS
 *   IOFAULT_HIT=FILE      "N path" of each failed call, one line each
 *   IOFAULT_TRACE=FILE    "N kind path" of every counted call
 * Counted: write, writev, pwrite, pwrite64, fsync, fdatasync through the dynamic linker
 * (glibc's stdio inside libc is not seen, which is why common/fsutil.c's streams write
 * through write(2) of their own). */
#define _GNU_SOURCE
/* pwrite and pwrite64 are defined apart: neither may be renamed to the other */
#undef _FILE_OFFSET_BITS
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

typedef ssize_t (*write_fn)(int, const void *, size_t);
typedef ssize_t (*writev_fn)(int, const struct iovec *, int);
typedef ssize_t (*pwrite_fn)(int, const void *, size_t, off_t);
typedef int (*sync_fn)(int);

static write_fn real_write;

static write_fn get_write(void)
{
    if (!real_write)
        real_write = (write_fn)dlsym(RTLD_NEXT, "write");
    return real_write;
}

static int errno_of(const char *name)
{
    if (!name || strcmp(name, "ENOSPC") == 0)
        return ENOSPC;
    if (strcmp(name, "EIO") == 0)
        return EIO;
    if (strcmp(name, "EDQUOT") == 0)
        return EDQUOT;
    if (strcmp(name, "EROFS") == 0)
        return EROFS;
    return ENOSPC;
}

/* Whether fd is a regular file under IOFAULT_DIR (its path in *path). */
static int watched(int fd, char *path, size_t len)
{
    const char *dir = getenv("IOFAULT_DIR");
    if (!dir || !dir[0] || fd < 0)
        return 0;
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
        return 0;
    char link[64];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    ssize_t n = readlink(link, path, len - 1);
    if (n <= 0)
        return 0;
    path[n] = 0;
    size_t dl = strlen(dir);
    if (strncmp(path, dir, dl) != 0 || path[dl] != '/')
        return 0;
    const char *base = strrchr(path, '/') + 1;
    return strcmp(base, "log.txt") != 0 && strcmp(base, "lock") != 0;
}

/* Counts one call on fd; true when it must fail (errno is then set). */
static int fault(int fd, const char *kind)
{
    char path[PATH_MAX];
    const char *count = getenv("IOFAULT_COUNT");
    if (!count || !watched(fd, path, sizeof path))
        return 0;
    int saved = errno;
    int cfd = open(count, O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (cfd < 0)
        return 0;
    flock(cfd, LOCK_EX);
    get_write()(cfd, "x", 1);
    struct stat st;
    long long n = fstat(cfd, &st) == 0 ? (long long)st.st_size : 0;
    close(cfd);   /* releases the lock */
    const char *trace = getenv("IOFAULT_TRACE");
    if (trace) {
        int tfd = open(trace, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
        if (tfd >= 0) {
            char line[PATH_MAX + 48];
            int k = snprintf(line, sizeof line, "%lld %s %s\n", n, kind, path);
            get_write()(tfd, line, (size_t)k);
            close(tfd);
        }
    }
    const char *at_s = getenv("IOFAULT_AT");
    long long at = at_s ? atoll(at_s) : 0;
    const char *persist = getenv("IOFAULT_PERSIST");
    int hit = at > 0 && (n == at || (persist && persist[0] == '1' && n > at));
    if (!hit) {
        errno = saved;
        return 0;
    }
    const char *log = getenv("IOFAULT_HIT");
    if (log) {
        int lfd = open(log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
        if (lfd >= 0) {
            char line[PATH_MAX + 32];
            int k = snprintf(line, sizeof line, "%lld %s\n", n, path);
            get_write()(lfd, line, (size_t)k);
            close(lfd);
        }
    }
    errno = errno_of(getenv("IOFAULT_ERRNO"));
    return 1;
}

ssize_t write(int fd, const void *buf, size_t n)
{
    if (fault(fd, "write"))
        return -1;
    return get_write()(fd, buf, n);
}

ssize_t writev(int fd, const struct iovec *iov, int cnt)
{
    static writev_fn real;
    if (!real)
        real = (writev_fn)dlsym(RTLD_NEXT, "writev");
    if (fault(fd, "writev"))
        return -1;
    return real(fd, iov, cnt);
}

ssize_t pwrite(int fd, const void *buf, size_t n, off_t off)
{
    static pwrite_fn real;
    if (!real)
        real = (pwrite_fn)dlsym(RTLD_NEXT, "pwrite");
    if (fault(fd, "pwrite"))
        return -1;
    return real(fd, buf, n, off);
}

ssize_t pwrite64(int fd, const void *buf, size_t n, off_t off)
{
    static pwrite_fn real;
    if (!real)
        real = (pwrite_fn)dlsym(RTLD_NEXT, "pwrite64");
    if (fault(fd, "pwrite64"))
        return -1;
    return real(fd, buf, n, off);
}

int fsync(int fd)
{
    static sync_fn real;
    if (!real)
        real = (sync_fn)dlsym(RTLD_NEXT, "fsync");
    if (fault(fd, "fsync"))
        return -1;
    return real(fd);
}

int fdatasync(int fd)
{
    static sync_fn real;
    if (!real)
        real = (sync_fn)dlsym(RTLD_NEXT, "fdatasync");
    if (fault(fd, "fdatasync"))
        return -1;
    return real(fd);
}
