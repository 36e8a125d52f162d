#pragma once
/* What a test means by a renderer option it leaves unset (zero): runner/params.def's
 * default, which tests/unit/test_params.c checks these are. The renderers refuse an
 * unset option (renderer_create), so the tests complete theirs here before making one;
 * a test that wants another value sets the field. */
#include "renderers/renderer.h"

static inline void test_options_complete(renderer_options *o)
{
    if (o->gbuffer == GBUFFER_UNSET)
        o->gbuffer = GBUFFER_CURTIS;
    if (o->light_volumes == LIGHT_VOLUMES_UNSET)
        o->light_volumes = LIGHT_VOLUMES_STENCIL;
    if (o->light_buffer == LIGHT_BUFFER_UNSET)
        o->light_buffer = LIGHT_BUFFER_UNIFORM;
    if (o->tile_size == 0)
        o->tile_size = 16;
    if (o->clustered_slices == 0)
        o->clustered_slices = 24;
    if (o->hdr == HDR_UNSET)
        o->hdr = HDR_RGBA16F;
    if (o->aa == AA_UNSET)
        o->aa = AA_NONE;
    if (o->lpp_light_buffer == LPP_LIGHT_BUFFER_UNSET)
        o->lpp_light_buffer = LPP_LIGHT_BUFFER_RGBA16F;
}

/* renderer_create with o's unset options completed. */
static inline renderer *test_renderer_create(const char *kind, const renderer_options *o,
                                             char *err, size_t errlen)
{
    renderer_options c = *o;
    test_options_complete(&c);
    return renderer_create(kind, &c, err, errlen);
}
