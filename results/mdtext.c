/* Markdown escaping of values copied from result files (mdtext.h). */
#include "results/mdtext.h"

void md_put(FILE *fp, const char *s)
{
    for (; s && *s; s++) {
        switch (*s) {
        case '\\': fputs("\\\\", fp); break;
        case '|': fputs("\\|", fp); break;
        case '`': fputs("\\`", fp); break;
        case '&': fputs("&amp;", fp); break;
        case '<': fputs("&lt;", fp); break;
        case '>': fputs("&gt;", fp); break;
        case '\n':
        case '\r': fputc(' ', fp); break;
        default: fputc(*s, fp);
        }
    }
}
