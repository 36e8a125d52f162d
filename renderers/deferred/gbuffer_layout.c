/* The G-buffer layout logic of gbuffer_layout.h, apart from the renderer: layouts built from
 * the preset, the field overrides and what the scene's materials write, their bytes,
 * and their shader defines. No GL call (formats come from target.h's table), so the
 * deferred renderer, tiled-deferred and clustered deferred shading, and tests without
 * a context share it. */
#include "renderers/deferred/gbuffer_layout.h"

#include "renderers/gl/target.h"
#include "scenes/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const slot_names[DEFERRED_SLOT_COUNT] = {
    [DEFERRED_SLOT_POSITION_XY] = "position.xy", [DEFERRED_SLOT_POSITION_Z] = "position.z",
    [DEFERRED_SLOT_DEPTH] = "depth",             [DEFERRED_SLOT_NORMAL_XY] = "normal.xy",
    [DEFERRED_SLOT_NORMAL_Z] = "normal.z",       [DEFERRED_SLOT_DIFFUSE] = "diffuse",
    [DEFERRED_SLOT_GLOSS] = "gloss",             [DEFERRED_SLOT_SHININESS] = "shininess",
    [DEFERRED_SLOT_EMISSIVE] = "emissive",       [DEFERRED_SLOT_OCCLUSION] = "ao",
    [DEFERRED_SLOT_F0] = "f0",
};

const char *deferred_slot_name(deferred_slot_kind k)
{
    return (unsigned)k < DEFERRED_SLOT_COUNT ? slot_names[k] : "unknown";
}

/* >>presets: the seeds' layouts as data. Each attachment: its channel type, its format
 * and its slots in channel order (a zero count ends the list); then what the preset
 * itself stores, in the override enums' terms, so that an override asking for the same
 * leaves it alone. */
typedef struct preset_slot {
    deferred_slot_kind kind;
    uint8_t count;
} preset_slot;

typedef struct preset_att {
    deferred_channel_type channels;
    gl_format format;
    preset_slot slot[DEFERRED_MAX_SLOTS];
} preset_att;

typedef struct preset_def {
    const char *name;
    preset_att att[DEFERRED_MAX_ATTACHMENTS];   /* a zero format ends the list */
    gbuffer_position own_position;
    gbuffer_normal own_normal;
    bool spheremap, emissive_intensity;
} preset_def;

/* Short names of the channel types, here and in the overrides below. */
#define F16 DEFERRED_CHANNELS_FLOAT16
#define F32 DEFERRED_CHANNELS_FLOAT32
#define U8 DEFERRED_CHANNELS_UNORM8
#define S(kind, n) {DEFERRED_SLOT_##kind, n}
static const preset_def presets[] = {
    [GBUFFER_CURTIS] = {"curtis",
                        {{F16, GLT_FORMAT_RGBA16F, {S(NORMAL_XY, 2), S(NORMAL_Z, 1), S(DEPTH, 1)}},
                         {F16, GLT_FORMAT_RGBA16F, {S(DIFFUSE, 3), S(GLOSS, 1)}},
                         {F16, GLT_FORMAT_RGBA16F, {S(SHININESS, 1)}},
                         {F16, GLT_FORMAT_RGBA16F, {S(EMISSIVE, 3)}}},
                        GBUFFER_POSITION_PRESET, GBUFFER_NORMAL_FLOAT16, false, false},
    [GBUFFER_FAT] = {"fat",
                     {{F16, GLT_FORMAT_RGBA16F,
                       {S(POSITION_XY, 2), S(POSITION_Z, 1), S(SHININESS, 1)}},
                      {F16, GLT_FORMAT_RGBA16F, {S(NORMAL_XY, 2), S(NORMAL_Z, 1), S(EMISSIVE, 1)}},
                      {F16, GLT_FORMAT_RGBA16F, {S(DIFFUSE, 3), S(GLOSS, 1)}}},
                     GBUFFER_POSITION_STORED16, GBUFFER_NORMAL_FLOAT16, false, true},
    [GBUFFER_COMPACT] = {"compact",
                         {{F16, GLT_FORMAT_RG16F, {S(POSITION_XY, 2)}},
                          {F16, GLT_FORMAT_R16F, {S(POSITION_Z, 1)}},
                          {U8, GLT_FORMAT_RGBA8, {S(DIFFUSE, 3), S(NORMAL_Z, 1)}},
                          {U8, GLT_FORMAT_RG8, {S(NORMAL_XY, 2)}},
                          {U8, GLT_FORMAT_RG8, {S(GLOSS, 1), S(SHININESS, 1)}},
                          {U8, GLT_FORMAT_RGBA8, {S(EMISSIVE, 3)}}},
                         GBUFFER_POSITION_STORED16, GBUFFER_NORMAL_PRESET, false, false},
    [GBUFFER_SPHEREMAP] = {"spheremap",
                           {{U8, GLT_FORMAT_RG8, {S(NORMAL_XY, 2)}},
                            {F16, GLT_FORMAT_RGBA16F, {S(DEPTH, 1), S(GLOSS, 1), S(SHININESS, 1)}},
                            {U8, GLT_FORMAT_RGBA8, {S(DIFFUSE, 3)}},
                            {U8, GLT_FORMAT_RGBA8, {S(EMISSIVE, 3)}}},
                           GBUFFER_POSITION_PRESET, GBUFFER_NORMAL_SPHEREMAP8, true, false},
    [GBUFFER_REFERENCE] = {"reference",
                           {{F32, GLT_FORMAT_RGBA32F,
                             {S(POSITION_XY, 2), S(POSITION_Z, 1), S(SHININESS, 1)}},
                            {F32, GLT_FORMAT_RGBA32F,
                             {S(NORMAL_XY, 2), S(NORMAL_Z, 1), S(GLOSS, 1)}},
                            {F32, GLT_FORMAT_RGBA32F, {S(DIFFUSE, 3)}},
                            {F32, GLT_FORMAT_RGBA32F, {S(EMISSIVE, 3)}}},
                           GBUFFER_POSITION_STORED32, GBUFFER_NORMAL_FLOAT32, false, false},
};
#undef S

static const preset_def *preset_get(gbuffer_preset p)
{
    return (size_t)p < sizeof presets / sizeof presets[0] ? &presets[p] : NULL;
}

const char *deferred_preset_name(gbuffer_preset p)
{
    return (unsigned)p < sizeof presets / sizeof presets[0] ? presets[p].name : "unknown";
}

deferred_needs deferred_needs_of(const scene *s)
{
    deferred_needs n = {false, false, false, false};
    if (!s)
        return n;
    /* the metallic-roughness model: every surface has a specular lobe, its roughness
     * always needed (and the metallic factor beside it, as gloss is) */
    n.pbr = s->shading == SHADING_PBR;
    n.gloss = n.pbr;
    for (uint32_t i = 0; i < s->nobjects; i++) {
        uint32_t mi = s->objects[i].material;
        if (mi >= s->nmaterials)
            continue;
        const scene_material *m = &s->materials[mi];
        if (scene_material_translucent(m))
            continue;   /* forward, in the translucent pass: never in the G-buffer */
        if (m->specular > 0.0f)
            n.gloss = true;
        if (m->emissive[0] > 0.0f || m->emissive[1] > 0.0f || m->emissive[2] > 0.0f)
            n.emissive = true;
        if (n.pbr && m->gloss_map >= 0 && m->occlusion > 0.0f)
            n.occlusion = true;
    }
    return n;
}

/* A draft attachment: its slots in channel order, and whether an override took a
 * slot from it (then it is packed again and narrowed). */
enum { DRAFT_MAX_ATTACHMENTS = DEFERRED_MAX_ATTACHMENTS + 2 };   /* + the two overrides */

typedef struct draft {
    int nattachments;
    deferred_attachment att[DRAFT_MAX_ATTACHMENTS];
    bool touched[DRAFT_MAX_ATTACHMENTS];
    bool emissive_intensity;
} draft;

static int draft_att(draft *d, deferred_channel_type ch, gl_format fmt, bool touched)
{
    int a = d->nattachments++;
    deferred_attachment *at = &d->att[a];
    memset(at, 0, sizeof *at);
    at->channels = ch;
    at->format = fmt;
    d->touched[a] = touched;
    return a;
}

static void draft_slot(draft *d, int a, deferred_slot_kind k, uint8_t count)
{
    deferred_attachment *at = &d->att[a];
    uint8_t first = 0;
    for (int i = 0; i < at->nslots; i++)
        first = (uint8_t)(first + at->slot[i].count);
    at->slot[at->nslots++] = (deferred_slot){.kind = k, .first = first, .count = count};
}

/* Removes every slot of kind k; marks the attachments it was in as touched if `touch`. */
static void draft_remove(draft *d, deferred_slot_kind k, bool touch)
{
    for (int a = 0; a < d->nattachments; a++) {
        deferred_attachment *at = &d->att[a];
        int n = 0;
        for (int i = 0; i < at->nslots; i++) {
            if (at->slot[i].kind == k) {
                if (touch)
                    d->touched[a] = true;
                continue;
            }
            at->slot[n++] = at->slot[i];
        }
        at->nslots = n;
    }
}

static gl_format narrowest(deferred_channel_type ch, unsigned channels)
{
    switch (ch) {
    case DEFERRED_CHANNELS_FLOAT16:
        return channels <= 1 ? GLT_FORMAT_R16F
                             : channels == 2 ? GLT_FORMAT_RG16F : GLT_FORMAT_RGBA16F;
    case DEFERRED_CHANNELS_FLOAT32:
        return channels <= 1 ? GLT_FORMAT_R32F : GLT_FORMAT_RGBA32F;
    case DEFERRED_CHANNELS_UNORM8:
        return channels <= 2 ? GLT_FORMAT_RG8 : GLT_FORMAT_RGBA8;
    case DEFERRED_CHANNELS_UNORM10:
        return GLT_FORMAT_RGB10A2;
    }
    return GLT_FORMAT_NONE;
}

/* The channels a preset's format offers a slot (RGB10A2's 2-bit alpha: none). */
static unsigned format_channels(gl_format f)
{
    switch (f) {
    case GLT_FORMAT_R16F:
    case GLT_FORMAT_R32F:
        return 1;
    case GLT_FORMAT_RG16F:
    case GLT_FORMAT_RG8:
        return 2;
    case GLT_FORMAT_RGB10A2:
        return 3;
    case GLT_FORMAT_RGBA16F:
    case GLT_FORMAT_RGBA32F:
    case GLT_FORMAT_RGBA8:
        return 4;
    default:
        return 0;
    }
}

/* A slot's field name; under pbr gloss and shininess hold metallic and roughness. Short,
 * as "ao": the longest name, spheremap's "gbuffer.depth+metal+rough+ao", fits the 31
 * characters of a target's name. */
static const char *slot_label(deferred_slot_kind k, bool pbr)
{
    if (pbr && k == DEFERRED_SLOT_GLOSS)
        return "metal";
    if (pbr && k == DEFERRED_SLOT_SHININESS)
        return "rough";
    return deferred_slot_name(k);
}

/* "gbuffer." + the slots' field names joined by '+' (position.xy + position.z is
 * "position", and so the normal). The longest a layout makes is 29 characters. */
static void name_attachment(deferred_attachment *at, bool spheremap, bool pbr)
{
    char *out = at->name;
    const size_t cap = sizeof at->name;
    size_t len = (size_t)snprintf(out, cap, "gbuffer.");
    for (int i = 0; i < at->nslots && len < cap; i++) {
        deferred_slot_kind k = at->slot[i].kind;
        const char *nm = slot_label(k, pbr);
        if (k == DEFERRED_SLOT_POSITION_XY && i + 1 < at->nslots &&
            at->slot[i + 1].kind == DEFERRED_SLOT_POSITION_Z) {
            nm = "position";
            i++;
        } else if (k == DEFERRED_SLOT_NORMAL_XY &&
                   ((i + 1 < at->nslots && at->slot[i + 1].kind == DEFERRED_SLOT_NORMAL_Z) ||
                    spheremap)) {
            nm = "normal";
            if (!spheremap)
                i++;
        }
        int n = snprintf(out + len, cap - len, "%s%s", len > strlen("gbuffer.") ? "+" : "", nm);
        if (n < 0)
            break;
        len += (size_t)n;
    }
}

bool deferred_layout_build(const renderer_options *o, deferred_needs needs,
                           deferred_layout *out, char *err, size_t errlen)
{
    draft d;
    memset(&d, 0, sizeof d);
    int a;

    const preset_def *pd = preset_get(o->gbuffer);
    if (!pd) {
        snprintf(err, errlen, "deferred: unknown G-buffer preset %d", (int)o->gbuffer);
        return false;
    }
    for (int i = 0; i < DEFERRED_MAX_ATTACHMENTS && pd->att[i].format != GLT_FORMAT_NONE; i++) {
        const preset_att *pa = &pd->att[i];
        a = draft_att(&d, pa->channels, pa->format, false);
        for (int k = 0; k < DEFERRED_MAX_SLOTS && pa->slot[k].count; k++)
            draft_slot(&d, a, pa->slot[k].kind, pa->slot[k].count);
    }
    gbuffer_position own_position = pd->own_position;
    gbuffer_normal own_normal = pd->own_normal;
    bool spheremap = pd->spheremap;
    d.emissive_intensity = pd->emissive_intensity;

    /* >>overrides: the field gets an attachment of its own */
    gbuffer_position pos = o->gbuffer_position;
    bool depth_buffer = false;
    if (pos != GBUFFER_POSITION_PRESET && pos != own_position) {
        draft_remove(&d, DEFERRED_SLOT_POSITION_XY, true);
        draft_remove(&d, DEFERRED_SLOT_POSITION_Z, true);
        draft_remove(&d, DEFERRED_SLOT_DEPTH, true);
        switch (pos) {
        case GBUFFER_POSITION_STORED16:
        case GBUFFER_POSITION_STORED32:
            a = draft_att(&d, pos == GBUFFER_POSITION_STORED16 ? F16 : F32, GLT_FORMAT_NONE,
                          true);
            draft_slot(&d, a, DEFERRED_SLOT_POSITION_XY, 2);
            draft_slot(&d, a, DEFERRED_SLOT_POSITION_Z, 1);
            break;
        case GBUFFER_POSITION_DEPTH:
            depth_buffer = true;
            break;
        default:
            snprintf(err, errlen, "deferred: unknown G-buffer position %d", (int)pos);
            return false;
        }
    }
    gbuffer_normal nrm = o->gbuffer_normal;
    if (nrm != GBUFFER_NORMAL_PRESET && nrm != own_normal) {
        draft_remove(&d, DEFERRED_SLOT_NORMAL_XY, true);
        draft_remove(&d, DEFERRED_SLOT_NORMAL_Z, true);
        spheremap = false;
        switch (nrm) {
        case GBUFFER_NORMAL_FLOAT16:
        case GBUFFER_NORMAL_FLOAT32:
        case GBUFFER_NORMAL_UNORM10:
            a = draft_att(&d,
                          nrm == GBUFFER_NORMAL_FLOAT16   ? F16
                          : nrm == GBUFFER_NORMAL_FLOAT32 ? F32
                                                          : DEFERRED_CHANNELS_UNORM10,
                          GLT_FORMAT_NONE, true);
            draft_slot(&d, a, DEFERRED_SLOT_NORMAL_XY, 2);
            draft_slot(&d, a, DEFERRED_SLOT_NORMAL_Z, 1);
            break;
        case GBUFFER_NORMAL_SPHEREMAP8:
        case GBUFFER_NORMAL_SPHEREMAP16:
            a = draft_att(&d, nrm == GBUFFER_NORMAL_SPHEREMAP8 ? U8 : F16, GLT_FORMAT_NONE, true);
            draft_slot(&d, a, DEFERRED_SLOT_NORMAL_XY, 2);
            spheremap = true;
            break;
        default:
            snprintf(err, errlen, "deferred: unknown G-buffer normal %d", (int)nrm);
            return false;
        }
    }

    /* >>what the scene does not need: the slot goes, its channels stay where they were */
    if (!needs.gloss) {
        draft_remove(&d, DEFERRED_SLOT_GLOSS, false);
        draft_remove(&d, DEFERRED_SLOT_SHININESS, false);
    }
    if (!needs.emissive)
        draft_remove(&d, DEFERRED_SLOT_EMISSIVE, false);
    /* >>pbr's occlusion: no preset has it; the first attachment with a channel to spare
     * takes it, else one of its own in the preset's first channel type */
    if (needs.occlusion) {
        int at = -1;
        for (int i = 0; i < d.nattachments && at < 0; i++) {
            unsigned used = 0;
            for (int k = 0; k < d.att[i].nslots; k++)
                used += d.att[i].slot[k].count;
            if (!d.touched[i] && used < format_channels(d.att[i].format) && d.att[i].nslots > 0)
                at = i;
        }
        if (at < 0)
            at = draft_att(&d, d.att[0].channels, GLT_FORMAT_NONE, true);
        draft_slot(&d, at, DEFERRED_SLOT_OCCLUSION, 1);
    }

    /* >>the attachments that remain, packed again where an override took a slot */
    memset(out, 0, sizeof *out);
    for (int i = 0; i < d.nattachments; i++) {
        deferred_attachment at = d.att[i];
        if (at.nslots == 0)
            continue;
        if (out->nattachments >= DEFERRED_MAX_ATTACHMENTS) {
            snprintf(err, errlen, "bug: deferred: more than %d G-buffer attachments",
                     DEFERRED_MAX_ATTACHMENTS);
            return false;
        }
        if (d.touched[i]) {
            uint8_t first = 0;
            for (int k = 0; k < at.nslots; k++) {
                at.slot[k].first = first;
                first = (uint8_t)(first + at.slot[k].count);
            }
            at.format = narrowest(at.channels, first);
        }
        name_attachment(&at, spheremap, needs.pbr);
        for (int k = 0; k < at.nslots; k++)
            out->has[at.slot[k].kind] = true;
        out->att[out->nattachments++] = at;
    }
    out->pbr = needs.pbr;
    out->emissive_intensity = d.emissive_intensity && out->has[DEFERRED_SLOT_EMISSIVE];
    out->position = out->has[DEFERRED_SLOT_POSITION_XY]  ? DEFERRED_POSITION_STORED
                    : out->has[DEFERRED_SLOT_DEPTH] && !depth_buffer ? DEFERRED_POSITION_LINEAR_DEPTH
                                                                     : DEFERRED_POSITION_DEPTH_BUFFER;
    out->normal = DEFERRED_NORMAL_XYZ_FLOAT;
    if (spheremap) {
        out->normal = DEFERRED_NORMAL_SPHEREMAP;
    } else {
        for (int i = 0; i < out->nattachments; i++)
            for (int k = 0; k < out->att[i].nslots; k++)
                if (out->att[i].slot[k].kind == DEFERRED_SLOT_NORMAL_XY &&
                    (out->att[i].channels == DEFERRED_CHANNELS_UNORM8 ||
                     out->att[i].channels == DEFERRED_CHANNELS_UNORM10))
                    out->normal = DEFERRED_NORMAL_XYZ_UNORM;
    }
    return true;
}

void deferred_layout_light_prepass(deferred_needs needs, deferred_layout *out)
{
    /* Engel 2008's minimal G-buffer: the normal and the specular power beside the depth
     * buffer (the position is unprojected from it); no albedo, which the material pass
     * reads from the material. 16-bit floats: the normal as deferred's curtis stores it. */
    draft d = {0};
    int a = draft_att(&d, DEFERRED_CHANNELS_FLOAT16, GLT_FORMAT_NONE, false);
    draft_slot(&d, a, DEFERRED_SLOT_NORMAL_XY, 2);
    draft_slot(&d, a, DEFERRED_SLOT_NORMAL_Z, 1);
    if (needs.gloss)   /* no specular material: no highlight to shape */
        draft_slot(&d, a, DEFERRED_SLOT_SHININESS, 1);
    /* the metallic-roughness model's specular light depends on F0 per channel (Schlick's
     * Fresnel does not factor out of the sum over the lights as Phong's gloss does):
     * the light pre-pass reads it here, in 16-bit floats as the rest */
    if (needs.pbr)
        draft_slot(&d, draft_att(&d, DEFERRED_CHANNELS_FLOAT16, GLT_FORMAT_NONE, false),
                   DEFERRED_SLOT_F0, 3);
    memset(out, 0, sizeof *out);
    for (int i = 0; i < d.nattachments; i++) {
        deferred_attachment at = d.att[i];
        unsigned channels = 0;
        for (int k = 0; k < at.nslots; k++)
            channels += at.slot[k].count;
        at.format = narrowest(at.channels, channels);
        name_attachment(&at, false, needs.pbr);
        for (int k = 0; k < at.nslots; k++)
            out->has[at.slot[k].kind] = true;
        out->att[out->nattachments++] = at;
    }
    out->position = DEFERRED_POSITION_DEPTH_BUFFER;
    out->normal = DEFERRED_NORMAL_XYZ_FLOAT;
    out->pbr = needs.pbr;
}

unsigned deferred_layout_bytes_per_pixel(const deferred_layout *l)
{
    unsigned b = 0;
    for (int i = 0; i < l->nattachments; i++) {
        const gl_format_info *fi = gl_format_get(l->att[i].format);
        b += fi ? fi->bytes_per_pixel : 0;
    }
    return b;
}

unsigned deferred_gbuffer_bytes_per_pixel(const renderer_options *o, deferred_needs needs)
{
    deferred_layout l;
    char err[160];
    return o && deferred_layout_build(o, needs, &l, err, sizeof err)
               ? deferred_layout_bytes_per_pixel(&l) : 0;
}

gbuffer_traffic deferred_gbuffer_traffic(unsigned bytes_per_pixel, int width, int height,
                                         const frame_stats *fs)
{
    gbuffer_traffic t = {NAN, NAN};
    if (bytes_per_pixel == 0 || !fs)
        return t;
    /* deferred.c's pass names: what writes the G-buffer (with msaa, every sample it
     * passes is stored), what reads it per sample */
    static const char *const readers[] = {"ambient", "directional", "point", "spot"};
    double written = 0.0, shaded = 0.0;
    for (size_t i = 0; i < fs->npasses; i++) {
        const pass_stats *ps = &fs->pass[i];
        if (!ps->name)
            continue;
        if (strcmp(ps->name, "gbuffer") == 0)
            written += ps->samples;
        else if (strcmp(ps->name, "tiled") == 0)
            shaded += (double)width * (double)height;
        else if (strcmp(ps->name, "edges") == 0)   /* msaa: every sample of every pixel */
            shaded += (double)width * (double)height * (double)fs->msaa;
        else
            for (size_t k = 0; k < sizeof readers / sizeof readers[0]; k++)
                if (strcmp(ps->name, readers[k]) == 0)
                    /* msaa: a pixel shaded once reads one sample (samples_shaded) */
                    shaded += fs->msaa > 1 ? ps->samples_shaded : ps->samples;
    }
    t.write_bytes = s002_mrt_write_bytes((double)bytes_per_pixel, written);
    t.read_bytes = s002_mrt_read_bytes((double)bytes_per_pixel, shaded);
    return t;
}


static bool slot_where(const deferred_layout *l, deferred_slot_kind k, char *buf, size_t len,
                       deferred_channel_type *ch)
{
    static const char swz[] = "xyzw";
    for (int i = 0; i < l->nattachments; i++)
        for (int s = 0; s < l->att[i].nslots; s++) {
            const deferred_slot *sl = &l->att[i].slot[s];
            if (sl->kind != k)
                continue;
            char sw[5] = "";
            for (int c = 0; c < sl->count && sl->first + c < 4; c++)
                sw[c] = swz[sl->first + c];
            snprintf(buf, len, "gb%d.%s", i, sw);
            if (ch)
                *ch = l->att[i].channels;
            return true;
        }
    return false;
}

static void add_define(deferred_layout_defs *d, const char *name, deferred_slot_kind k,
                       const deferred_layout *l)
{
    char where[16];
    if (d->n < DEFERRED_MAX_LAYOUT_DEFS && slot_where(l, k, where, sizeof where, NULL))
        snprintf(d->text[d->n++], sizeof d->text[0], "%s %s", name, where);
}

void deferred_layout_defines(const deferred_layout *l, deferred_layout_defs *d)
{
    memset(d, 0, sizeof *d);
    if (l->position == DEFERRED_POSITION_STORED) {
        add_define(d, "GB_POSITION_XY", DEFERRED_SLOT_POSITION_XY, l);
        add_define(d, "GB_POSITION_Z", DEFERRED_SLOT_POSITION_Z, l);
    } else if (l->position == DEFERRED_POSITION_LINEAR_DEPTH) {
        add_define(d, "GB_DEPTH", DEFERRED_SLOT_DEPTH, l);
    }
    snprintf(d->text[d->n++], sizeof d->text[0], "GB_NORMAL_ENC %d",
             l->normal == DEFERRED_NORMAL_SPHEREMAP   ? 2
             : l->normal == DEFERRED_NORMAL_XYZ_UNORM ? 1
                                                      : 0);
    add_define(d, "GB_NORMAL_XY", DEFERRED_SLOT_NORMAL_XY, l);
    if (l->normal != DEFERRED_NORMAL_SPHEREMAP)
        add_define(d, "GB_NORMAL_Z", DEFERRED_SLOT_NORMAL_Z, l);
    add_define(d, "GB_DIFFUSE", DEFERRED_SLOT_DIFFUSE, l);
    add_define(d, "GB_GLOSS", DEFERRED_SLOT_GLOSS, l);
    add_define(d, "GB_SHININESS", DEFERRED_SLOT_SHININESS, l);
    char where[16];
    deferred_channel_type ch;
    if (!l->pbr && slot_where(l, DEFERRED_SLOT_SHININESS, where, sizeof where, &ch) &&
        (ch == DEFERRED_CHANNELS_UNORM8 || ch == DEFERRED_CHANNELS_UNORM10))
        snprintf(d->text[d->n++], sizeof d->text[0], "GB_SHININESS_UNORM");
    add_define(d, l->emissive_intensity ? "GB_EMISSIVE_INTENSITY" : "GB_EMISSIVE",
               DEFERRED_SLOT_EMISSIVE, l);
    add_define(d, "GB_OCCLUSION", DEFERRED_SLOT_OCCLUSION, l);
    add_define(d, "GB_F0", DEFERRED_SLOT_F0, l);
}
