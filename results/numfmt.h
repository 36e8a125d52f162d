#pragma once
/* Number text that never depends on the locale, shared by the CSV and YAML writers
 * and by the manifest's canonical parameter text. */
#include <stddef.h>

/* Shortest "%.*g" (precision 1..17) of a finite v that reads back as v; where %g
 * picks the exponent form (100 -> "1e+02"), the plain form when it is no longer
 * ("100"). The decimal separator is always '.'. cap >= 32. */
void num_shortest(double v, char *s, size_t cap);

/* The same for a float: the shortest text that reads back (strtof) as v, so that
 * 1e-4f prints as "0.0001", not as the double it widens to. */
void num_shortest_float(float v, char *s, size_t cap);

/* Replaces a locale decimal separator other than '.' in s by '.'. */
void num_c_decimal_point(char *s);
