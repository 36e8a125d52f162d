#pragma once
/* Number text that never depends on the locale, shared by the CSV and YAML writers
 * and by the manifest's canonical parameter text. */
#include <stdbool.h>
#include <stddef.h>

/* Shortest "%.*g" (precision 1..17) of a finite v that reads back as v; where %g
 * picks the exponent form (100 -> "1e+02"), the plain form when it is no longer
 * ("100"). The decimal separator is always '.'. cap >= 32. */
void num_shortest(double v, char *s, size_t cap);

/* The same digits as num_shortest (the shortest text that reads back as v), never in
 * exponent form: 1e+06 -> "1000000", 2.5e-05 -> "0.000025". For tables that scripts
 * and spreadsheets read as plain decimals. cap >= 340 holds any finite double
 * (5e-324 has 323 zeros after the point); a smaller cap truncates. */
void num_plain(double v, char *s, size_t cap);
/* The same for a float: the shortest digits that read back (strtof) as v, so that
 * 0.1f prints as "0.1", not as the double it widens to; 10 as "10", not "1e+01". */
void num_plain_float(float v, char *s, size_t cap);

/* The fewest significant digits (1 to 16 for a double, 1 to 8 for a float) whose
 * decimal form reads back as the finite v (strtod, or strtof when single); 17 or 9
 * when none does. The digits of the three above. */
int num_fewest_digits(double v, bool single);

/* Replaces a locale decimal separator other than '.' in s by '.'. */
void num_c_decimal_point(char *s);
