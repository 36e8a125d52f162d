#include "results/numfmt.h"

#include <locale.h>
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

void num_shortest_float(float v, char *s, size_t cap)
{
    for (int prec = 1; prec <= 9; prec++) {
        snprintf(s, cap, "%.*g", prec, (double)v);
        if (strtof(s, NULL) == v)
            break;
    }
    num_c_decimal_point(s);
}
