/* JSON strings and numbers (results/jsonout.h). */
#include "results/jsonout.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void json_quoted(FILE *fp, const char *s, size_t n, bool yaml)
{
    fputc('"', fp);
    for (const char *e = s + n; s < e; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\')
            fprintf(fp, "\\%c", ch);
        else if (ch < 0x20)
            fprintf(fp, yaml ? "\\x%02x" : "\\u%04x", ch);
        else
            fputc(ch, fp);
    }
    fputc('"', fp);
}

void json_string(FILE *fp, const char *s)
{
    json_quoted(fp, s, strlen(s), false);
}

void json_words(FILE *fp, const char *words)
{
    fputc('[', fp);
    bool first = true;
    for (const char *w = words + strspn(words, " "); *w; w += strspn(w, " ")) {
        size_t n = strcspn(w, " ");
        fputs(first ? "" : ", ", fp);
        first = false;
        json_quoted(fp, w, n, false);
        w += n;
    }
    fputc(']', fp);
}

void json_number(FILE *fp, double v)
{
    if (isfinite(v))
        fprintf(fp, "%.9g", v);
    else
        fputs("null", fp);
}

void json_key(FILE *fp, bool *first, const char *key)
{
    fputs(*first ? "" : ", ", fp);
    *first = false;
    json_string(fp, key);
    fputs(": ", fp);
}

void json_member_string(FILE *fp, bool *first, const char *key, const char *v)
{
    json_key(fp, first, key);
    if (v)
        json_string(fp, v);
    else
        fputs("null", fp);
}

void json_member_number(FILE *fp, bool *first, const char *key, double v)
{
    json_key(fp, first, key);
    json_number(fp, v);
}

void json_typed(FILE *fp, const char *s)
{
    if (strcmp(s, "true") == 0 || strcmp(s, "false") == 0) {
        fputs(s, fp);
        return;
    }
    char *end;
    double v = strtod(s, &end);
    if (*s && end != s && *end == '\0' && isfinite(v))
        json_number(fp, v);
    else
        json_string(fp, s);
}
