#pragma once
/* Text from result files (renderer, scene, experiment names, parameter values, statuses)
 * as Markdown shows it: never markup. */
#include <stdio.h>

/* s with `\` `|` and backticks escaped by a backslash, `&` `<` `>` as entities, and
 * line ends as spaces: it can neither end a table cell or row, open a code span, nor
 * pass HTML through. */
void md_put(FILE *fp, const char *s);
