#pragma once
/* The G-buffer layout (gbuffer_layout.c): attachments of slots, built from the options
 * and from what the scene's materials write, without GL; its bytes, its shader defines
 * and seed 002's G-buffer traffic. Shared by the deferred family (deferred_core.h and
 * what includes it) and by tests that need no context. Below every deferred renderer:
 * it includes no renderer of the family. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "renderers/gl/target.h"
#include "renderers/renderer.h"
#include "results/bandwidth.h"

#include "renderers/frame/bindings.h"

struct scene;

enum {
    DEFERRED_MAX_ATTACHMENTS = 6,
    DEFERRED_MAX_SLOTS = 4,         /* per attachment: one per channel at most */
    DEFERRED_FIRST_GBUFFER_UNIT = BIND_TEX_GBUFFER0,   /* attachment k at unit 4 + k */
    DEFERRED_DEPTH_UNIT = BIND_TEX_DEPTH,     /* the depth-stencil target (position from depth) */
    DEFERRED_SPECULAR_UNIT = BIND_TEX_SPECULAR,   /* the specular light target (compose) */
    DEFERRED_UNIFORM_LIGHT = LOC_RENDERER,    /* vec4 u_light[5] of deferred_light.frag */
};

/* A slot is one field of the surface (or a part of one) in one or more consecutive
 * channels of its attachment. Fields, with their channels:
 *   position.xy / position.z   view-space position (stored presets)
 *   depth                      linear view depth -z (curtis, spheremap: the position is
 *                              rebuilt as the pixel's view ray x depth)
 *   normal.xy / normal.z       view-space normal: xyz (float, or unorm x 0.5 + 0.5), or
 *                              normal.xy alone holding the spheremap code (seed 004)
 *   diffuse                    rgb
 *   gloss                      specular intensity x gloss map
 *   shininess                  the specular exponent (unorm attachments store n / 255)
 *   emissive                   rgb, or (fat, seed 000) one intensity e: emissive = e x diffuse */
typedef enum deferred_slot_kind {
    DEFERRED_SLOT_POSITION_XY,
    DEFERRED_SLOT_POSITION_Z,
    DEFERRED_SLOT_DEPTH,
    DEFERRED_SLOT_NORMAL_XY,
    DEFERRED_SLOT_NORMAL_Z,
    DEFERRED_SLOT_DIFFUSE,
    DEFERRED_SLOT_GLOSS,
    DEFERRED_SLOT_SHININESS,
    DEFERRED_SLOT_EMISSIVE,            /* rgb, or 1 channel when emissive_intensity */
    DEFERRED_SLOT_OCCLUSION,           /* pbr: the ambient occlusion */
    DEFERRED_SLOT_F0,                  /* pbr, deferred-lighting: the material's F0, rgb */
    DEFERRED_SLOT_COUNT
} deferred_slot_kind;

/* Where the light passes get the position from. */
typedef enum deferred_position_source {
    DEFERRED_POSITION_STORED,          /* position.xy + position.z slots */
    DEFERRED_POSITION_LINEAR_DEPTH,    /* depth slot x the pixel's view ray (seed 004) */
    DEFERRED_POSITION_DEPTH_BUFFER,    /* unprojected from the depth-stencil target */
} deferred_position_source;

typedef enum deferred_normal_encoding {
    DEFERRED_NORMAL_XYZ_FLOAT,         /* as it is */
    DEFERRED_NORMAL_XYZ_UNORM,         /* n x 0.5 + 0.5 (RGB10A2, RGBA8 / RG8 splits) */
    DEFERRED_NORMAL_SPHEREMAP,         /* Lambert azimuthal, two channels (seed 004) */
} deferred_normal_encoding;

typedef enum deferred_channel_type {
    DEFERRED_CHANNELS_FLOAT16,
    DEFERRED_CHANNELS_FLOAT32,
    DEFERRED_CHANNELS_UNORM8,
    DEFERRED_CHANNELS_UNORM10,
} deferred_channel_type;

typedef struct deferred_slot {
    deferred_slot_kind kind;
    uint8_t first, count;              /* channels first .. first + count - 1 */
} deferred_slot;

/* An attachment: a colour target of the G-buffer pass. Its name is made from its slots
 * ("gbuffer.position+shininess"), so a name says what it holds. */
typedef struct deferred_attachment {
    char name[32];                     /* "gbuffer.diffuse+gloss" */
    gl_format format;
    deferred_channel_type channels;
    int nslots;
    deferred_slot slot[DEFERRED_MAX_SLOTS];
} deferred_attachment;

/* A G-buffer layout: its attachments. With no position slot at all (the position rebuilt
 * from the depth buffer) the position comes from the shared depth-stencil target. */
typedef struct deferred_layout {
    int nattachments;
    deferred_attachment att[DEFERRED_MAX_ATTACHMENTS];
    deferred_position_source position;
    deferred_normal_encoding normal;
    bool emissive_intensity;           /* fat: emissive = e x diffuse */
    bool pbr;                          /* gloss and shininess are metallic and roughness
                                          (deferred_needs.pbr): their slots are named so */
    bool has[DEFERRED_SLOT_COUNT];     /* a slot of that kind is in some attachment */
} deferred_layout;

/* The slot kind's field name as attachment names use it: "position.xy", ... */
const char *deferred_slot_name(deferred_slot_kind k);
/* "fat", "curtis", "compact", "spheremap", "reference"; "unknown" out of range. */
const char *deferred_preset_name(gbuffer_preset p);

/* The layout of preset (with the field-by-field overrides of o) for a scene that needs
 * `needs`: the preset's attachments as seed 000/002/003/004 give them, each allocated
 * only when one of its slots is needed; an override (position, normal) that differs
 * from what the preset stores removes the preset's slots for that field and adds an
 * attachment of its own; an attachment that lost a slot to an override is packed
 * again into the narrowest format of its channel type. False with a message on a bad
 * option value. */
bool deferred_layout_build(const renderer_options *o, deferred_needs needs,
                           deferred_layout *out, char *err, size_t errlen);

/* deferred-lighting's G-buffer (Engel 2008's light pre-pass), whatever the gbuffer keys
 * say: one RGBA16F attachment, normal.xy + normal.z + shininess (RGBA16F, shininess
 * left out when no material has specular), the position from the depth buffer. */
void deferred_layout_light_prepass(deferred_needs needs, deferred_layout *out);

/* Bytes per pixel of the layout's attachments. */
unsigned deferred_layout_bytes_per_pixel(const deferred_layout *l);

/* The layout as gbuffer.inc.glsl's defines ("GB_DIFFUSE gb2.xyz", "GB_NORMAL_ENC 2",
 * ...), what every program reading or writing the G-buffer is compiled with. */
enum { DEFERRED_MAX_LAYOUT_DEFS = 14 };
typedef struct deferred_layout_defs {
    int n;
    char text[DEFERRED_MAX_LAYOUT_DEFS][40];
} deferred_layout_defs;
void deferred_layout_defines(const deferred_layout *l, deferred_layout_defs *d);

/* The G-buffer models the renderers and tests ask without making a renderer. */

/* The bytes per pixel of the G-buffer of o's preset and overrides for a scene that needs
 * `needs` (as renderer_prepare builds it); 0 for a layout that does not build. */
unsigned deferred_gbuffer_bytes_per_pixel(const renderer_options *o, deferred_needs needs);
/* seed 002's G-buffer traffic (results/bandwidth.h, equations 4 and 5's MRT terms) of one
 * collected frame of such a renderer at width x height: writes = bytes_per_pixel x
 * the samples of the pass named "gbuffer"; reads = bytes_per_pixel x (the samples of
 * "ambient", "directional", "point" and "spot", the passes that fetch the G-buffer per
 * shaded sample, + width x height for each "tiled" pass: a compute pass counts no
 * samples, and tiled_deferred.comp loads the surface of every pixel of the screen once).
 * Other passes (shadows, compose, sky, resolve) touch no G-buffer attachment. NAN for
 * both when bytes_per_pixel is 0 (no G-buffer), NAN for one whose samples are NAN. */
gbuffer_traffic deferred_gbuffer_traffic(unsigned bytes_per_pixel, int width, int height,
                                         const frame_stats *fs);
