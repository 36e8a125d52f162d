#include "results/numfmt.h"

#include <locale.h>
#include <stdbool.h>
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

/* Whether v's decimal form with prec significant digits reads back as v (strtof for a
 * float, strtod for a double). */
static bool reads_back(double v, int prec, bool single)
{
    char e[40];
    snprintf(e, sizeof e, "%.*e", prec - 1, v);
    return single ? strtof(e, NULL) == (float)v : strtod(e, NULL) == v;
}

/* printf rounds correctly, so the nearest (p+1)-digit decimal is at least as near v as
 * the nearest p-digit one (which is one of them): where v's rounding interval is
 * symmetric, p digits reading back means p+1 do too, and a bisection finds the fewest
 * in 4 or 5 conversions instead of up to 17 (lights.csv of 65,536 lights: 2 s a run).
 * Below a power of two the interval is half as wide as above, which can break that
 * order: those are scanned from 1 digit up. */
int num_fewest_digits(double v, bool single)
{
    const int max = single ? 9 : 17;
    int exp;
    double m = frexp(v, &exp);
    int lo = 1, hi = max;
    if (m == 0.5 || m == -0.5 || m == 0) {
        while (lo < hi && !reads_back(v, lo, single))
            lo++;
        return lo;
    }
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (reads_back(v, mid, single))
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

void num_shortest(double v, char *s, size_t cap)
{
    int prec = isfinite(v) ? num_fewest_digits(v, false) : 17;
    snprintf(s, cap, "%.*g", prec, v);
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
    plain_digits(v, isfinite(v) ? num_fewest_digits(v, false) : 17, s, cap);
}

void num_plain_float(float v, char *s, size_t cap)
{
    plain_digits(v, isfinite(v) ? num_fewest_digits(v, true) : 9, s, cap);
}
