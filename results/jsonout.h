#pragma once
/* The two JSON values shadesweep writes by hand (summary.json, `shadesweep ratios`): a
 * string, escaped (quotes, backslashes, control characters as \u00XX; other bytes as
 * they are: our strings are UTF-8), and a number, %.9g, or null when not finite (JSON has
 * no NaN). */
#include <stdio.h>

void json_string(FILE *fp, const char *s);
void json_number(FILE *fp, double v);
