#pragma once
/* Files that appear under their final name only when complete.
 *
 * afile_open() creates "<final>.tmp.<pid>" next to the final path; afile_commit()
 * flushes, fsyncs, checks the file's size against the bytes written, closes and renames
 * it over the final name; afile_abort() closes and unlinks it. Either of the two must be
 * called exactly once. Every file the program writes goes through here (images too:
 * results/image_io.cpp encodes in memory, then afile_write).
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

typedef struct afile {
    FILE *fp;
    char *final_path;
    char *tmp_path;
    afile_sink *sink;          /* the descriptor, bytes written, first error */
} afile;

bool afile_open(afile *f, const char *final_path, char *err, size_t errlen);
/* n bytes to the stream; false after any write error (afile_commit then says which). */
bool afile_write(afile *f, const void *data, size_t n);
bool afile_commit(afile *f, char *err, size_t errlen);
void afile_abort(afile *f);

/* A writer's sticky failure: the first call sets *failed and writes "PATH: what" into msg
 * (PATH: f's final path, or `fallback` when it has none); later calls do nothing. */
void afile_fail_once(const afile *f, const char *fallback, bool *failed, char *msg,
                     size_t msglen, const char *what);

/* A writer's end: afile_commit, or when the writer failed, afile_abort with its message
 * msg in err (false). */
bool afile_finish(afile *f, bool failed, const char *msg, char *err, size_t errlen);

/* "path: <strerror(e)>", with what it means for the errors of a full or broken device:
 * ENOSPC "(the disk is full)", EDQUOT "(the disk quota is exhausted)", EROFS "(the file
 * system is read-only)", EIO "(the device reported an I/O error)". */
void fs_error_message(char *err, size_t errlen, const char *path, int e);

/* The whole file into a NUL-terminated buffer the caller frees, its length (without the
 * NUL) in *len. NULL on failure with *err an errno value: the open's, EIO for a read
 * error, ENOMEM, or EFBIG when the file holds more than max bytes (max 0: no limit). */
char *fs_read_all(const char *path, size_t max, size_t *len, int *err);

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
