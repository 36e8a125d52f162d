#pragma once
/* The manifest keys the renderers read, declared by each family in a table beside its
 * code (renderers/keys.def lists them). runner/manifest/params.def includes them in place, so the
 * central key table stays one ordered list; this header makes their C enums. A table
 * holds, in any order:
 *   KEY_ENUM(type, names, V("text", ENUMERATOR) ...)   an enum key's values: the C enum
 *       `type`, whose ENUMERATOR is the value's index (what run_params stores), and the
 *       NULL-terminated `names` (runner/manifest/params.c); VX(ENUMERATOR): a value the renderers
 *       know that no manifest names
 *   PARAM(...), PARAM_META(...)   the keys, in runner/manifest/params.def's format: type, default
 *       text, limits, description, and `apply`, the statement that sets the options
 *   KEY_OPTION(type, member, dims)   a renderer_options member the key before it sets
 * A default is written once, as the key's text: the runner parses it like any value, and
 * renderer_options_default() (renderers/renderer.c) makes options of it by its C type. */

/* each enum, and its names (defined once, renderers/renderer.c) */
#define KEY_ENUM(type, names, values)                                                         \
    typedef enum type { values } type;                                                        \
    _Static_assert(sizeof(type) == sizeof(int), "enum size");                                 \
    extern const char *const names[];
#define V(text, e) e,
#define VX(e) e,
#define PARAM_META(...)
#define PARAM(...)
#define KEY_OPTION(type, member, dims)
#include "renderers/keys.def"
#undef KEY_ENUM
#undef V
#undef VX
#undef PARAM_META
#undef PARAM
#undef KEY_OPTION
