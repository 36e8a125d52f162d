#pragma once
/* The frame's visible lights as the shaders read them (lighting.inc's Light: 5 vec4s,
 * 80 bytes, std140 and std430 alike): each of the frontend's lights, in its order,
 * packed in view space (shading_pack_light) with its shadow-map layer
 * (shading_set_shadow_layer) into a staging array, and the used part uploaded into
 * one buffer made with GL_DYNAMIC_STORAGE_BIT. The renderer binds it as it reads it:
 * a uniform block (forward-spml's FORWARD_LIGHTS_BINDING) or a storage buffer
 * (lights.inc's BIND_SSBO_LIGHTS: forward-spml's storage variant, forward-plus,
 * clustered, tiled-deferred, the translucent pass).
 *
 * Every renderer that uploads an array of lights uses this one; deferred's light
 * passes and forward-mpml set one light at a time as a uniform (shading_pack_light). */
#include <stdbool.h>
#include <stdint.h>

#include "renderers/frame/frontend.h"
#include "renderers/gl/loader.h"
#include "renderers/frame/shading.h"
#include "scenes/scene.h"

typedef struct light_buffer {
    GLuint buffer;                   /* capacity x gpu_light */
    gpu_light *staging;              /* capacity */
    uint32_t capacity;               /* lights it holds */
    uint32_t count;                  /* lights packed this frame (light_buffer_pack) */
} light_buffer;

/* The staging array, then the buffer, for capacity lights; false (nothing made) when
 * out of memory. */
bool light_buffer_create(light_buffer *lb, uint32_t capacity);
/* What create made; a zeroed buffer is fine. */
void light_buffer_release(light_buffer *lb);
/* The frame's visible lights into staging, at most capacity of them; returns (and
 * keeps in count) how many. */
uint32_t light_buffer_pack(light_buffer *lb, const scene *s, const frontend *fe);
/* The lights packed into the buffer (nothing when none). */
void light_buffer_upload(const light_buffer *lb);
/* pack, then upload: returns the count. */
uint32_t light_buffer_update(light_buffer *lb, const scene *s, const frontend *fe);
