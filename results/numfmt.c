#include "results/numfmt.h"

#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void num_c_decimal_point(char *s)
{
    const char *dp = localeconv()->decimal_point;
    if (dp == NULL || dp[0] == '\0' || strcmp(dp, ".") == 0)
        return;
    char *hit = strstr(s, dp);
    if (hit == NULL)
        return;
    size_t dl = strlen(dp);
    *hit = '.';
    memmove(hit + 1, hit + dl, strlen(hit + dl) + 1);
}

void num_shortest(double v, char *s, size_t cap)
{
    int prec = 1;
    for (; prec <= 17; prec++) {
        snprintf(s, cap, "%.*g", prec, v);
        if (strtod(s, NULL) == v)
            break;
    }
    const char *e = strchr(s, 'e');
    if (e != NULL) {
        int x = atoi(e + 1);
        if (x >= prec && x <= 16) { /* "%.{x+1}g" is the fixed form, and round-trips */
            char fixed[40];
            snprintf(fixed, sizeof fixed, "%.*g", x + 1, v);
            if (strlen(fixed) <= strlen(s) && strtod(fixed, NULL) == v)
                snprintf(s, cap, "%s", fixed);
        }
    }
    num_c_decimal_point(s);
}

/* v with `prec` significant digits, in %f form: %f to the place of the last digit
 * rounds the exact binary value to that place, as %e to prec digits does: the same
 * digits. */
static void plain_digits(double v, int prec, char *s, size_t cap)
{
    if (!isfinite(v)) {
        snprintf(s, cap, "%s", isnan(v) ? "nan" : v > 0 ? "inf" : "-inf");
        return;
    }
    char e[40];
    snprintf(e, sizeof e, "%.*e", prec - 1, v);
    int decimals = prec - 1 - atoi(strchr(e, 'e') + 1);
    snprintf(s, cap, "%.*f", decimals > 0 ? decimals : 0, v);
    num_c_decimal_point(s);
}

void num_plain(double v, char *s, size_t cap)
{
    char e[40];
    int prec = 1;
    for (; prec < 17; prec++) {
        snprintf(e, sizeof e, "%.*e", prec - 1, v);
        if (strtod(e, NULL) == v)
            break;
    }
    plain_digits(v, prec, s, cap);
}

void num_plain_float(float v, char *s, size_t cap)
{
    char e[40];
    int prec = 1;
    for (; prec < 9; prec++) {
        snprintf(e, sizeof e, "%.*e", prec - 1, (double)v);
        if (strtof(e, NULL) == v)
            break;
    }
    plain_digits(v, prec, s, cap);
}
