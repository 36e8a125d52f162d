#pragma once
/* Diagnostics for bad input: every problem is collected, none stops the parse,
 * and each prints as one line
 *     FILE:LINE:COL: KEY: expected ..., found ...
 * (line and column 1-based; KEY is the dotted path, e.g. "lights.count.max"). */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

typedef struct diag {
    char *file;
    int line, col;
    char *key;                 /* dotted path; "" for the document itself */
    char *msg;                 /* "expected ..., found ..." */
} diag;

typedef struct diag_list {
    diag *v;
    size_t n, cap;
} diag_list;

void diag_add(diag_list *d, const char *file, int line, int col, const char *key,
              const char *fmt, ...) __attribute__((format(printf, 6, 7)));
void diag_print(const diag_list *d, FILE *out);
void diag_free(diag_list *d);
