#pragma once
/* The line every answer made on a software rasterizer carries (summary.md, summary.json,
 * run's terminal verdict, compare, the report through `shadesweep ratios`): which
 * device measured a folder's runs, as their meta.yaml `gl` block names it, when that
 * device is a CPU (results/gl_device.h) or when the runs mix devices (a merge of shards
 * run on different machines). A folder measured on one GPU gets no line. Why:
 * docs/notes/answer.md "Software rasterizers". */
#include <stdbool.h>
#include <stddef.h>
#include "runner/answer/run_model.h"

typedef struct device_note {
    size_t ndevices;           /* distinct GL renderers among the runs' meta.yaml */
    size_t nsoftware;          /* of them, software rasterizers */
    char line[1400];           /* one line, no line end; "" when there is nothing to say */
} device_note;

/* The note of the runs of output folder DIR (runs/<id>/meta.yaml; a run without one, or
 * without a context, counts for no device). */
void device_note_of(const char *dir, const run_result *runs, size_t n, device_note *out);
