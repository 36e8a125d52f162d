#pragma once
/* Shared by the results tests: a scratch folder under /tmp and a count of what is
 * left in it (the tests assert that no temporary file outlives a commit or abort).
 * mkdtemp is POSIX 2008, which the build asks for. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Makes /tmp/<name>.XXXXXX into dir (at least 64 bytes); 0, or -1 on failure. */
static inline int temp_dir_make(char *dir, size_t len, const char *name)
{
    snprintf(dir, len, "/tmp/%s.XXXXXX", name);
    return mkdtemp(dir) ? 0 : -1;
}

/* Entries in dir other than . and ..; -1 if it cannot be read. */
static inline int count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (d == NULL)
        return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0)
            n++;
    }
    closedir(d);
    return n;
}
