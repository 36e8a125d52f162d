/* The light buffer (light_buffer.h). */
#include "renderers/frame/light_buffer.h"

#include <stdlib.h>
#include <string.h>

_Static_assert(sizeof(gpu_light) == 80, "gpu_light is 5 vec4s, as lighting.inc's Light");

bool light_buffer_create(light_buffer *lb, uint32_t capacity)
{
    memset(lb, 0, sizeof *lb);
    lb->staging = calloc(capacity, sizeof *lb->staging);
    if (!lb->staging)
        return false;
    lb->capacity = capacity;
    gl.CreateBuffers(1, &lb->buffer);
    gl.NamedBufferStorage(lb->buffer, (GLsizeiptr)((size_t)capacity * sizeof(gpu_light)), NULL,
                          GL_DYNAMIC_STORAGE_BIT);
    return true;
}

void light_buffer_release(light_buffer *lb)
{
    if (lb->buffer)
        gl.DeleteBuffers(1, &lb->buffer);
    free(lb->staging);
    memset(lb, 0, sizeof *lb);
}

uint32_t light_buffer_pack(light_buffer *lb, const scene *s, const frontend *fe)
{
    uint32_t n = fe->nlights < lb->capacity ? fe->nlights : lb->capacity;
    for (uint32_t k = 0; k < n; k++) {
        shading_pack_light(&s->lights[fe->lights[k]], s->view, &lb->staging[k]);
        shading_set_shadow_layer(&lb->staging[k], fe->shadow_layer[k]);
    }
    lb->count = n;
    return n;
}

void light_buffer_upload(const light_buffer *lb)
{
    if (lb->count)   /* only what is used */
        gl.NamedBufferSubData(lb->buffer, 0, (GLsizeiptr)(lb->count * sizeof(gpu_light)),
                              lb->staging);
}

uint32_t light_buffer_update(light_buffer *lb, const scene *s, const frontend *fe)
{
    light_buffer_pack(lb, s, fe);
    light_buffer_upload(lb);
    return lb->count;
}
