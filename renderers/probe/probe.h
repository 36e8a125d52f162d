#pragma once
/* `shadesweep probe`'s microbenchmarks (issue 38): fill rate per target format, with
 * and without blending, at 1 and 4 samples; memory bandwidth (a compute copy, a
 * full-screen texture read); arithmetic rate in the fragment and compute stages; the
 * cost of a draw, a state change and a dispatch; the timer's resolution. Each figure is
 * the median of repeats with its spread (results/device_profile.h). The runner calls
 * this one function; what each figure measures: docs/notes/device-profile.md. */
#include <stdbool.h>
#include <stddef.h>

#include "renderers/gl/context.h"
#include "results/device_profile.h"

/* Measures ctx's device into out (its GL strings, software rasterizer and figures; the
 * host, version and date are the caller's). quick: the smallest sizes that still give
 * finite, positive figures (CI); else about a minute on llvmpipe. False with a
 * message (an incomplete framebuffer, a program that does not build, a GL error). */
bool gl_probe_run(gl_context *ctx, bool quick, device_profile *out, char *err, size_t errlen);
