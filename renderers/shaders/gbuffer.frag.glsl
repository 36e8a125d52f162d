// The deferred renderer's geometry pass (seed 000 4.5.2): the surface of each
// fragment, exactly as the forward passes see it (surface.inc), stored into the
// G-buffer's attachments as the layout defines say (gbuffer.inc). Vertex shader:
// mesh.vert. Depth is written by the fixed function (depth test LESS).
#include "frame.inc"
#include "surface.inc"
#define GBUFFER_WRITE
#include "gbuffer.inc"

void main()
{
    gbuffer_store(surface_get());
}
