#pragma once
/* Files that appear under their final name only when complete.
 *
 * afile_open() creates "<final>.tmp.<pid>" next to the final path; afile_commit()
 * flushes, fsyncs, checks the file's size against the bytes written, closes and renames
 * it over the final name; afile_abort() closes and unlinks it. Either of the two must be
 * called exactly once. Every file the program writes goes through here (images too:
 * common/image_io.cpp encodes in memory, then afile_write).
 *
 * fp is a stream whose every write(2) is checked: the first error's errno is kept (a
 * later fflush or ferror cannot lose it), and afile_commit fails with a message naming
 * the final path and that errno ("out/runs/ID/frames.csv: No space left on device (the
 * disk is full)"). Nothing appears under the final name unless every byte reached the
 * file. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct afile_sink afile_sink;

/* Files that must change together (a folder's summaries, which describe the same runs):
 * afile_commit of a file whose `set` is this one does everything but the rename and
 * hands its temporary over; afile_set_commit then renames them all, afile_set_abort
 * removes them all. One of the two must be called. */
enum { AFILE_SET_MAX = 8 };
typedef struct afile_set {
    size_t n;
    char *tmp[AFILE_SET_MAX], *final[AFILE_SET_MAX];
} afile_set;

typedef struct afile {
    FILE *fp;
    char *final_path;
    char *tmp_path;
    afile_sink *sink;          /* the descriptor, bytes written, first error */
    afile_set *set;            /* NULL: afile_commit renames at once; set after afile_open */
} afile;

bool afile_open(afile *f, const char *final_path, char *err, size_t errlen);
/* n bytes to the stream; false after any write error (afile_commit then says which). */
bool afile_write(afile *f, const void *data, size_t n);
bool afile_commit(afile *f, char *err, size_t errlen);
void afile_abort(afile *f);

/* Renames every file of the set in the order committed; false with a message naming the
 * first that failed (those before it are renamed, the rest removed). */
bool afile_set_commit(afile_set *s, char *err, size_t errlen);
void afile_set_abort(afile_set *s);

/* A writer's sticky failure: the first call sets *failed and writes "PATH: what" into msg
 * (PATH: f's final path, or `fallback` when it has none); later calls do nothing. */
void afile_fail_once(const afile *f, const char *fallback, bool *failed, char *msg,
                     size_t msglen, const char *what);

/* A writer's end: afile_commit, or when the writer failed, afile_abort with its message
 * msg in err (false). */
bool afile_finish(afile *f, bool failed, const char *msg, char *err, size_t errlen);

/* "path: <strerror(e)>", with what it means for the errors of a full or broken device:
 * ENOSPC "(the disk is full)", EDQUOT "(the disk quota is exhausted)", EROFS "(the file
 * system is read-only)", EIO "(the device reported an I/O error)", EFBIG "(over the
 * file-size limit, ulimit -f, or the file system's largest file)". */
void fs_error_message(char *err, size_t errlen, const char *path, int e);

/* The whole file into a NUL-terminated buffer the caller frees, its length (without the
 * NUL) in *len. NULL on failure with *err an errno value: the open's, EIO for a read
 * error, ENOMEM, or EFBIG when the file holds more than max bytes (max 0: no limit). */
char *fs_read_all(const char *path, size_t max, size_t *len, int *err);
/* As fs_read_all for a file a user names (a manifest): opened without blocking (a FIFO
 * must not hang the reader) and read only when it is a regular file; otherwise NULL
 * with *err 0 and *kind saying what it is ("a directory", "a FIFO", ...). */
char *fs_read_regular(const char *path, size_t max, size_t *len, int *err, const char **kind);

/* mkdir -p; true if the directory exists afterwards. */
bool fs_mkdirs(const char *path, char *err, size_t errlen);
/* mkdir -p whose last `tail` components must be directories of their own: one that is a
 * symbolic link is refused by name, never followed (what lies below an output folder;
 * the folder itself and what is above it may be links). */
bool fs_mkdirs_tail(const char *path, int tail, char *err, size_t errlen);
bool fs_exists(const char *path);
/* rm -rf of a directory this program created; false with a message on failure. */
bool fs_remove_tree(const char *path, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

/* The name of the UTF-16 or UTF-32 encoding whose byte-order mark `data` (len bytes)
 * starts with ("UTF-16 (little-endian)", ...), or NULL for none: text shadesweep reads
 * as UTF-8 (a manifest, an OBJ or glTF file) is refused by it, naming it. */
const char *fs_text_bom(const void *data, size_t len);
