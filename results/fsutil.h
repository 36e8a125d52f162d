#pragma once
/* Files that appear under their final name only when complete.
 *
 * afile_open() creates "<final>.tmp.<pid>" next to the final path; afile_commit()
 * flushes, fsyncs, closes and renames it over the final name; afile_abort()
 * closes and unlinks it. Either of the two must be called exactly once. */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

typedef struct afile {
    FILE *fp;
    char *final_path;
    char *tmp_path;
} afile;

bool afile_open(afile *f, const char *final_path, char *err, size_t errlen);
bool afile_commit(afile *f, char *err, size_t errlen);
void afile_abort(afile *f);

/* The whole file into a NUL-terminated buffer the caller frees, its length (without the
 * NUL) in *len. NULL on failure with *err an errno value: the open's, EIO for a read
 * error, ENOMEM, or EFBIG when the file holds more than max bytes (max 0: no limit). */
char *fs_read_all(const char *path, size_t max, size_t *len, int *err);

/* mkdir -p; true if the directory exists afterwards. */
bool fs_mkdirs(const char *path, char *err, size_t errlen);
bool fs_exists(const char *path);
/* rm -rf of a directory this program created; false with a message on failure. */
bool fs_remove_tree(const char *path, char *err, size_t errlen);
