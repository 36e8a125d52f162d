#pragma once
/* The two JSON values shadesweep writes by hand (summary.json, `shadesweep ratios`): a
 * string, escaped (quotes, backslashes, control characters as \u00XX; other bytes as
 * they are: our strings are UTF-8), and a number, %.9g, or null when not finite (JSON has
 * no NaN). */
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

void json_string(FILE *fp, const char *s);
/* The n bytes at s as json_string writes a string; where yaml, a control character as
 * \xXX instead (a YAML double-quoted scalar: meta.yaml's trial status, runner/folder/trials.c). */
void json_quoted(FILE *fp, const char *s, size_t n, bool yaml);
/* Space-separated words (a list of names) as an array of strings; "" is []. */
void json_words(FILE *fp, const char *words);
void json_number(FILE *fp, double v);

/* A text as the JSON value it reads as: a number when the whole text is one (finite),
 * true or false, else a string. For parameters written as text (plan.csv, meta.yaml). */
void json_typed(FILE *fp, const char *s);

/* Members of an object: `"key": ` (after ", " unless *first, which it clears), then the
 * value; a NULL string is null. */
void json_key(FILE *fp, bool *first, const char *key);
void json_member_string(FILE *fp, bool *first, const char *key, const char *v);
void json_member_number(FILE *fp, bool *first, const char *key, double v);
