#pragma once
/* Private to renderer.c and renderer_base.c: the renderer handle renderer.h hands out. */
#include <stdbool.h>

#include "renderers/renderer.h"

struct renderer {
    const renderer_impl *impl;   /* the design whose entry points serve self */
    const char *kind;            /* the registry's name ("clustered" for its variants) */
    void *self;
    bool prepared;               /* the last prepare succeeded: draw may run */
};
