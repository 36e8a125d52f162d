#pragma once
/* Whether the GL strings a run recorded (meta.yaml's gl: renderer, vendor, version)
 * name a software rasterizer: a CPU doing the GPU's work, whose rankings measure that
 * CPU, and whose per-pass times are not the passes' own (llvmpipe runs the work where
 * it flushes, not in the pass that issued it: docs/notes/answer.md "Software
 * rasterizers"). The runner (measure.metric auto, passes.csv), the answers (summary.md,
 * summary.json, the terminal, compare) and the report (through `shadesweep ratios`)
 * all ask here. */
#include <stddef.h>

/* The rasterizer's short name ("llvmpipe", "softpipe", "lavapipe", "swrast",
 * "SwiftShader", "WARP", "OSMesa", "a software renderer") when the strings name a
 * software rasterizer; NULL for a GPU, and for strings too empty to tell (NULLs are
 * empty). Mesa's GPU drivers are not flagged though their strings say "Mesa" or
 * "LLVM" (radeonsi's shader compiler). */
const char *gl_software_rasterizer(const char *renderer, const char *vendor,
                                   const char *version);
