#pragma once
/* `shadesweep probe` and the device profile of an output folder (issue 38): the probe
 * measures the device (renderers/probe/probe.h), writes device.yaml into the cache
 * (results/device_profile.h: one file per device and driver) and prints it; `run`
 * copies the cached profile of the device its runs were measured on into its folder
 * as device.yaml, and never probes. docs/notes/device-profile.md. */
#include <stdbool.h>

#include "renderers/gl/context.h"
#include "runner/manifest/manifest.h"

/* The command: 0, or 2 with the reason on stderr (no such device, no context, a
 * benchmark that failed, a cache that cannot be written). */
int probe_main(gl_backend backend, int device, bool json, bool quick);

/* OUT/device.yaml from the cache, for the device that the plan's first run with a
 * meta.yaml names; with no cached profile, one line on stderr says how to make one.
 * Never fails the sweep: a copy that fails is said on stderr. */
void probe_copy_to_folder(const char *out_dir, const plan *p);
