/* File scenes, >>io: every byte assimp reads goes through these callbacks, which read each
 * file whole, once, into the load's file_set (see scenes/file/file_assimp.c). Only regular
 * files are opened; references stay inside the scene file's folder unless allowed out. */
#define _DEFAULT_SOURCE   /* realpath */
#include "scenes/file/file_internal.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/grow.h"

void file_set_free(file_set *fs)
{
    for (uint32_t i = 0; i < fs->n; i++) {
        free(fs->files[i].path);
        free(fs->files[i].data);
    }
    free(fs->files);
    for (uint32_t i = 0; i < fs->nopen; i++) {
        free(fs->open[i]->UserData);
        free(fs->open[i]);
    }
    free(fs->open);
    memset(fs, 0, sizeof *fs);
}

static const char *file_kind(mode_t m)
{
    return S_ISDIR(m) ? "a directory" : S_ISFIFO(m) ? "a FIFO" : S_ISSOCK(m) ? "a socket"
         : S_ISCHR(m) ? "a character device" : S_ISBLK(m) ? "a block device"
         : "not a regular file";
}

/* A reference that names a URL (scheme://...): only local files are read. */
bool file_is_url(const char *p)
{
    const char *c = strstr(p, "://");
    if (!c || c == p)
        return false;
    for (const char *q = p; q < c; q++)
        if (!(isalnum((unsigned char)*q) || *q == '+' || *q == '-' || *q == '.'))
            return false;
    return true;
}

/* The file's bytes (read once, then served from memory), or NULL with fs->err set for
 * anything but a file that does not exist (errno ENOENT then). Only regular files are
 * opened (a FIFO would block, a device never end); a file the scene references must
 * resolve (symlinks, "..") inside fs->root unless fs->allow_outside. */
const read_file *file_set_get(file_set *fs, const char *path)
{
    for (uint32_t i = 0; i < fs->n; i++)
        if (strcmp(fs->files[i].path, path) == 0)
            return &fs->files[i];
    const char *open_path = path;
    char real[PATH_MAX];
    if (fs->root[0]) {
        /* a URL inside a path: assimp prefixes the scene's folder */
        if (strstr(path, "://")) {
            snprintf(fs->err, sizeof fs->err, "%s: a URL: only local files are read", path);
            errno = EACCES;
            return NULL;
        }
        if (!realpath(path, real)) {
            if (errno != ENOENT) {
                snprintf(fs->err, sizeof fs->err, "%s: cannot open: %s", path, strerror(errno));
                errno = EIO;
            }
            return NULL;   /* errno ENOENT: a missing file */
        }
        size_t n = strlen(fs->root);
        if (!fs->allow_outside && !(strncmp(real, fs->root, n) == 0 &&
                                    (real[n] == '/' || (n == 1 && fs->root[0] == '/')))) {
            snprintf(fs->err, sizeof fs->err, "%s: resolves to %s, outside the scene file's "
                     "folder %s (scene.allow_outside: true permits it)", path, real, fs->root);
            errno = EACCES;
            return NULL;
        }
        open_path = real;
    }
    struct stat st, fst;
    if (stat(open_path, &st) != 0)
        return NULL;
    if (!S_ISREG(st.st_mode)) {
        snprintf(fs->err, sizeof fs->err, "%s: %s, not a regular file", path,
                 file_kind(st.st_mode));
        errno = EINVAL;
        return NULL;
    }
    int fd = open(open_path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC |
                                 (fs->root[0] ? O_NOFOLLOW : 0));
    if (fd < 0) {
        snprintf(fs->err, sizeof fs->err, "%s: cannot open: %s", path, strerror(errno));
        errno = EIO;
        return NULL;
    }
    if (fstat(fd, &fst) != 0 || !S_ISREG(fst.st_mode) || fst.st_dev != st.st_dev ||
        fst.st_ino != st.st_ino) {
        snprintf(fs->err, sizeof fs->err, "%s: changed while opened (now %s)", path,
                 file_kind(fst.st_mode));
        close(fd);
        errno = EIO;
        return NULL;
    }
    if ((uint64_t)fst.st_size > FILE_MAX_BYTES) {
        snprintf(fs->err, sizeof fs->err, "%s: %lld bytes, more than the 2 GiB a file may have",
                 path, (long long)fst.st_size);
        close(fd);
        errno = EFBIG;
        return NULL;
    }
    read_file r = {0};
    r.size = (size_t)fst.st_size;
    r.data = malloc(r.size + 1);   /* NUL-terminated: the JSON scan may use strtoul */
    r.path = strdup(path);
    if (!r.data || !r.path || !GROW(fs->files, fs->cap, (size_t)fs->n + 1, 8)) {
        snprintf(fs->err, sizeof fs->err, "%s: out of memory reading %zu bytes", path, r.size);
        free(r.data);
        free(r.path);
        close(fd);
        errno = ENOMEM;
        return NULL;
    }
    size_t got = 0;
    while (got < r.size) {
        ssize_t k = read(fd, r.data + got, r.size - got);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0) {
            snprintf(fs->err, sizeof fs->err, "%s: cannot read: %s", path,
                     k < 0 ? strerror(errno) : "file shrank while read");
            free(r.data);
            free(r.path);
            close(fd);
            errno = EIO;
            return NULL;
        }
        got += (size_t)k;
    }
    close(fd);
    r.data[r.size] = '\0';
    fs->files[fs->n] = r;
    return &fs->files[fs->n++];
}

/* assimp's view of one open file: a cursor over the bytes in the file_set. */
typedef struct open_file {
    const read_file *f;
    size_t pos;
} open_file;

static size_t io_read(struct aiFile *af, char *buf, size_t size, size_t count)
{
    open_file *o = (open_file *)af->UserData;
    if (size == 0 || o->pos >= o->f->size)
        return 0;
    size_t n = (o->f->size - o->pos) / size;
    if (n > count)
        n = count;
    memcpy(buf, o->f->data + o->pos, n * size);
    o->pos += n * size;
    return n;
}

static size_t io_write(struct aiFile *af, const char *buf, size_t size, size_t count)
{
    return 0;   /* loading never writes */
}

static size_t io_tell(struct aiFile *af) { return ((open_file *)af->UserData)->pos; }

static size_t io_size(struct aiFile *af) { return ((open_file *)af->UserData)->f->size; }

static void io_flush(struct aiFile *af) {}

static enum aiReturn io_seek(struct aiFile *af, size_t off, enum aiOrigin origin)
{
    open_file *o = (open_file *)af->UserData;
    size_t base = origin == aiOrigin_SET ? 0 : origin == aiOrigin_CUR ? o->pos : o->f->size;
    if (off > o->f->size || base > o->f->size - off)
        return aiReturn_FAILURE;
    o->pos = base + off;
    return aiReturn_SUCCESS;
}

struct aiFile *file_io_open(struct aiFileIO *io, const char *path, const char *mode)
{
    file_set *fs = (file_set *)io->UserData;
    if (strchr(mode, 'w') || strchr(mode, 'a'))
        return NULL;
    errno = 0;
    const read_file *f = file_set_get(fs, path);
    if (!f) {
        if (!fs->err[0] && !fs->missing[0] && fs->n > 0)
            snprintf(fs->missing, sizeof fs->missing, "%s", path);
        return NULL;
    }
    /* the OBJ importer opens nothing but the .obj and its material libraries */
    if (fs->obj && f != &fs->files[0] && !file_prescan_mtl(path, f, fs->err, sizeof fs->err))
        return NULL;
    if (!GROW(fs->open, fs->cap_open, (size_t)fs->nopen + 1, 8))
        return NULL;
    struct aiFile *af = calloc(1, sizeof *af);
    open_file *o = calloc(1, sizeof *o);
    if (!af || !o) {
        free(af);
        free(o);
        return NULL;
    }
    o->f = f;
    af->ReadProc = io_read;
    af->WriteProc = io_write;
    af->TellProc = io_tell;
    af->FileSizeProc = io_size;
    af->SeekProc = io_seek;
    af->FlushProc = io_flush;
    af->UserData = (char *)o;
    fs->open[fs->nopen++] = af;
    return af;
}

void file_io_close(struct aiFileIO *io, struct aiFile *af)
{
    file_set *fs = (file_set *)io->UserData;
    if (!af)
        return;
    for (uint32_t i = 0; i < fs->nopen; i++)
        if (fs->open[i] == af) {
            fs->open[i] = fs->open[--fs->nopen];
            break;
        }
    free(af->UserData);
    free(af);
}
