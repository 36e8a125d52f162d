#pragma once
/* What runner/folder/folder.c and runner/folder/folder_files.c share. */
#include <stdbool.h>
#include <stddef.h>

/* dst = dir/name; false when it does not fit in n bytes. */
bool folder_path_join(char *dst, size_t n, const char *dir, const char *name);
/* A name a run's folder may hold (a temporary of one too: *temp says so). */
bool folder_is_run_file(const char *name, bool *temp);
