#pragma once
/* The scenes code's one way to report a failure into a caller's buffer; not part of the
 * scenes interface (nothing outside scenes/ includes it). */
#include <stdbool.h>
#include <stddef.h>

/* Writes the printf-style message into err (when err and errlen); false, so that a
 * failing path can `return scene_fail(...)`. */
bool scene_fail(char *err, size_t errlen, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
