#pragma once
/* The manifest changed from the command line (run, list, validate):
 *
 *   --set KEY=VALUE     KEY: VALUE as if written in the manifest (repeatable, applied
 *                       in order). VALUE is YAML (`--set 'lights.count={start: 0,
 *                       step: 8, every: 1, max: 64}'`); KEY is a dotted key of
 *                       docs/manifest.md, `sweep.KEY` (an axis) or `sweep`. The key is
 *                       replaced wherever the manifest has it: `--set lights.count=64`
 *                       on a manifest that sweeps lights.count makes it fixed (the axis
 *                       is gone), `--set 'sweep.lights.count=[16, 64]'` sweeps a key the
 *                       manifest sets in place, `--set 'sweep={...}'` replaces the
 *                       whole sweep (its keys removed in place). A value replaces
 *                       the whole key: `--set gbuffer=fat` drops the manifest's
 *                       gbuffer.normal, `--set gbuffer.preset=fat` keeps it.
 *   --renderer LIST     only the runs of these renderers (comma-separated), as if the
 *                       manifest's `renderers` listed only those of its own that LIST
 *                       names, in its order.
 *
 * Both go through the manifest's own validation (runner/overrides.c grafts each
 * --set's YAML onto the manifest's tree before it is read), so a bad value gets the
 * manifest's message, located at "MANIFEST: --set KEY=VALUE" instead of a line; the
 * run ids are those of the same manifest written out. Both are part of the manifest
 * hash (a folder resumes and merges only with the same ones) and meta.yaml records
 * them verbatim. */
#include <stdbool.h>
#include <stddef.h>

typedef struct manifest_overrides {
    size_t nsets;
    const char *const *sets;   /* "KEY=VALUE", verbatim, in command-line order */
    const char *renderers;     /* --renderer's list, verbatim; NULL: every renderer */
} manifest_overrides;

/* The command line's checks of one argument, before any manifest is read: a --set
 * without '=' or with an empty or malformed KEY; a --renderer list with a name that is
 * not a renderer or an empty name. False with a one-line message in err. */
bool override_check_set(const char *arg, char *err, size_t errlen);
bool override_check_renderers(const char *list, char *err, size_t errlen);
