/* Diagnostics for bad input (diag.h): collected, never fatal, one line each. */
#include "runner/manifest/diag.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "common/grow.h"

/* Diagnostics are what tells the user why nothing ran: losing one to a failed
 * allocation would turn a bad manifest into a silent one, so that aborts. */
static char *xstrdup(const char *s)
{
    char *c = strdup(s ? s : "");
    if (!c) {
        fputs("shadesweep: out of memory while reporting an error\n", stderr);
        abort();
    }
    return c;
}

void diag_add(diag_list *d, const char *file, int line, int col, const char *key,
              const char *fmt, ...)
{
    if (!GROW(d->v, d->cap, d->n + 1, 16)) {
        fputs("shadesweep: out of memory while reporting an error\n", stderr);
        abort();
    }

    va_list ap;
    va_start(ap, fmt);
    va_list ap2;
    va_copy(ap2, ap);
    int len = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *msg = malloc(len > 0 ? (size_t)len + 1 : 1);
    if (!msg) {
        va_end(ap2);
        fputs("shadesweep: out of memory while reporting an error\n", stderr);
        abort();
    }
    if (len > 0)
        vsnprintf(msg, (size_t)len + 1, fmt, ap2);
    else
        msg[0] = '\0';
    va_end(ap2);

    diag *g = &d->v[d->n++];
    g->file = xstrdup(file);
    g->line = line;
    g->col = col;
    g->key = xstrdup(key);
    g->msg = msg;
}

/* "FILE:LINE:COL: KEY: msg"; without "KEY: " for the document itself (key ""),
 * and without ":LINE:COL" where no position applies (line 0: unreadable file). */
void diag_print(const diag_list *d, FILE *out)
{
    for (size_t i = 0; i < d->n; i++) {
        const diag *g = &d->v[i];
        fputs(g->file, out);
        if (g->line > 0)
            fprintf(out, ":%d:%d", g->line, g->col);
        fputs(": ", out);
        if (g->key[0] != '\0')
            fprintf(out, "%s: ", g->key);
        fputs(g->msg, out);
        fputc('\n', out);
    }
}

void diag_free(diag_list *d)
{
    if (!d)
        return;
    for (size_t i = 0; i < d->n; i++) {
        free(d->v[i].file);
        free(d->v[i].key);
        free(d->v[i].msg);
    }
    free(d->v);
    d->v = NULL;
    d->n = d->cap = 0;
}
