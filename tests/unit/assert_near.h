#pragma once
/* cmocka 1.1 compares only floats; doubles need their own check. Equal values
 * (infinities included) always pass. Include after <cmocka.h>. */
#include <math.h>

static inline void check_near(double a, double b, double eps, const char *file, int line)
{
    if (a == b || fabs(a - b) <= eps)
        return;
    print_error("%.17g != %.17g (tolerance %g)\n", a, b, eps);
    _fail(file, line);
}
#define assert_near(a, b, eps) check_near((a), (b), (eps), __FILE__, __LINE__)
