/* Shadow maps for spot and directional lights, shared by every renderer (shadow.h). */
#include "renderers/frame/shadow.h"

#include "renderers/gl/target.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// >>plan

void shadow_maps_plan(shadow_maps *sm, const scene *s, const renderer_options *o)
{
    memset(sm, 0, sizeof *sm);
    sm->size = o->shadow_map_size > 0 ? o->shadow_map_size : SHADOW_DEFAULT_SIZE;
    for (uint32_t i = 0; s && i < s->nlights_total; i++) {
        const scene_light *l = &s->lights[i];
        if (l->shadows && (unsigned)l->type < SHADOW_LIGHT_TYPES)
            sm->asking[l->type]++;
        if (frontend_light_casts_shadows(l))
            sm->layers++;
    }
    uint32_t spot = sm->asking[LIGHT_SPOT], dir = sm->asking[LIGHT_DIRECTIONAL],
             point = sm->asking[LIGHT_POINT];
    if (sm->layers == 0) {
        if (point)
            snprintf(sm->reason, sizeof sm->reason,
                     "%u point light%s ask%s for shadows: only spot and directional lights "
                     "cast them",
                     point, point == 1 ? "" : "s", point == 1 ? "s" : "");
        else
            snprintf(sm->reason, sizeof sm->reason, "no light casts shadows");
        return;
    }
    if (o->no_shadows) {
        snprintf(sm->reason, sizeof sm->reason, "shadows: off");
        sm->layers = 0;
        return;
    }
    sm->run = true;
    char what[64];
    if (spot && dir)
        snprintf(what, sizeof what, "%u spot and %u directional", spot, dir);
    else
        snprintf(what, sizeof what, "%u %s", spot ? spot : dir, spot ? "spot" : "directional");
    int n = snprintf(sm->reason, sizeof sm->reason, "%s light%s cast%s shadows", what,
                     sm->layers == 1 ? "" : "s", sm->layers == 1 ? "s" : "");
    if (point && n > 0 && (size_t)n < sizeof sm->reason)
        snprintf(sm->reason + n, sizeof sm->reason - (size_t)n,
                 " (%u point light%s ask%s: not drawn)", point, point == 1 ? "" : "s",
                 point == 1 ? "s" : "");
    snprintf(sm->max_define, sizeof sm->max_define, "MAX_SHADOWS %u", sm->layers);
}

bool shadow_maps_for_type(const shadow_maps *sm, int type)
{
    return sm->run && (type == LIGHT_SPOT || type == LIGHT_DIRECTIONAL) && sm->asking[type] > 0;
}

unsigned shadow_maps_defines(const shadow_maps *sm, const char *defs[2])
{
    if (!sm->run)
        return 0;
    defs[0] = "SHADOWS";
    defs[1] = sm->max_define;
    return 2;
}

// >>GL objects

static bool fail(char *err, size_t errlen, const char *who, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static bool fail(char *err, size_t errlen, const char *who, const char *fmt, ...)
{
    char why[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    snprintf(err, errlen, "%s: %s", who, why);
    return false;
}

bool shadow_maps_create(shadow_maps *sm, gl_program_cache *pc, const char *who, char *err,
                        size_t errlen)
{
    if (!sm->run)
        return true;
    GLint max_size = 0, max_layers = 0, max_block = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    gl.GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    gl.GetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &max_block);
    if (sm->size <= 0 || sm->size > max_size)
        return fail(err, errlen, who, "shadow maps of %d x %d texels: the context allows 1 to %d "
                    "(GL_MAX_TEXTURE_SIZE)", sm->size, sm->size, (int)max_size);
    uint32_t most = (uint32_t)(max_layers > 0 ? max_layers : 0);
    uint32_t by_block = (uint32_t)(max_block > 0 ? max_block : 0) / 64u;
    if (by_block < most)
        most = by_block;
    if (sm->layers > most)
        return fail(err, errlen, who, "%u lights cast shadows, this context allows at most %u "
                    "shadow maps (GL_MAX_ARRAY_TEXTURE_LAYERS %d, GL_MAX_UNIFORM_BLOCK_SIZE %d "
                    "/ 64 bytes)", sm->layers, most, (int)max_layers, (int)max_block);

    sm->fbo = calloc(sm->layers, sizeof *sm->fbo);
    sm->staging = calloc(sm->layers, sizeof *sm->staging);
    if (!sm->fbo || !sm->staging) {
        shadow_maps_destroy(sm);
        return fail(err, errlen, who, "out of memory for %u shadow maps", sm->layers);
    }
    gl.CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &sm->texture);
    gl.TextureStorage3D(sm->texture, 1, GL_DEPTH_COMPONENT32F, sm->size, sm->size,
                        (GLsizei)sm->layers);
    gl.TextureParameteri(sm->texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TextureParameteri(sm->texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TextureParameteri(sm->texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(sm->texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(sm->texture, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl.TextureParameteri(sm->texture, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl.ObjectLabel(GL_TEXTURE, sm->texture, -1, "shadow.maps");
    sm->bytes = (uint64_t)sm->size * (uint64_t)sm->size * 4u * sm->layers;
    static const GLenum none = GL_NONE;
    for (uint32_t i = 0; i < sm->layers; i++) {
        gl.CreateFramebuffers(1, &sm->fbo[i]);
        gl.NamedFramebufferTextureLayer(sm->fbo[i], GL_DEPTH_ATTACHMENT, sm->texture, 0,
                                        (GLint)i);
        gl.NamedFramebufferDrawBuffers(sm->fbo[i], 1, &none);
        gl.NamedFramebufferReadBuffer(sm->fbo[i], GL_NONE);
        GLenum status = gl.CheckNamedFramebufferStatus(sm->fbo[i], GL_DRAW_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            shadow_maps_destroy(sm);
            return fail(err, errlen, who, "the framebuffer of shadow map %u (depth32f %d x %d, "
                        "layer %u) is not complete (status 0x%x)", i, sm->size, sm->size, i,
                        (unsigned)status);
        }
    }
    gl.CreateBuffers(1, &sm->ubo);
    gl.NamedBufferStorage(sm->ubo, (GLsizeiptr)(sm->layers * sizeof *sm->staging), NULL,
                          GL_DYNAMIC_STORAGE_BIT);

    char why[4096] = "";
    if (gl_program_get(pc, &(gl_program_desc){.name = "shadow_depth", .vertex = "shadow.vert",
                                               .fragment = "shadow.frag"},
                       &sm->program, why, sizeof why) != GLP_OK) {
        shadow_maps_destroy(sm);
        return fail(err, errlen, who, "%s", why);
    }
    return true;
}

void shadow_maps_destroy(shadow_maps *sm)
{
    if (!sm)
        return;
    if (sm->fbo) {
        for (uint32_t i = 0; i < sm->layers; i++)
            if (sm->fbo[i])
                gl.DeleteFramebuffers(1, &sm->fbo[i]);
    }
    GL_OBJECTS_DELETE(GLO_TEXTURE, &sm->texture);
    GL_OBJECTS_DELETE(GLO_BUFFER, &sm->ubo);
    free(sm->fbo);
    free(sm->staging);
    memset(sm, 0, sizeof *sm);
}

// >>per frame

/* Light clip space [-1, 1]^3 to map coordinates [0, 1]^3. */
static const sm_mat4 TO_MAP = {
    {0.5f, 0.0f, 0.0f, 0.0f},
    {0.0f, 0.5f, 0.0f, 0.0f},
    {0.0f, 0.0f, 0.5f, 0.0f},
    {0.5f, 0.5f, 0.5f, 1.0f},
};

uint64_t shadow_maps_draw(shadow_maps *sm, gl_state *st, scene_gpu *gpu, const frontend *fe,
                          const scene *s)
{
    if (!sm->run || !sm->texture)
        return 0;
    uint64_t draws = 0;
    uint32_t used = 0;
    sm_mat4 inv_view, m;
    sm_mat4_inv(s->view, inv_view);

    gl_state_program(st, sm->program);
    gl_state_blend(st, NULL);
    gl_state_stencil(st, NULL);
    gl_state_cull(st, GLS_CULL_FRONT);
    gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(SHADOW_OFFSET_FACTOR, SHADOW_OFFSET_UNITS);
    for (uint32_t k = 0; k < fe->nlights; k++) {
        uint32_t layer = fe->shadow_layer[k];
        if (layer == FRONTEND_NO_SHADOW)
            continue;
        if (layer >= sm->layers) {
            fprintf(stderr, "bug: shadow map layer %u of a pool of %u\n", layer, sm->layers);
            continue;
        }
        gl_state_framebuffer(st, sm->fbo[layer]);
        gl_state_viewport(st, 0, 0, sm->size, sm->size);
        gl_state_clear(st, GL_DEPTH_BUFFER_BIT, NULL, 1.0, 0);
        for (uint32_t e = fe->shadow_start[k]; e < fe->shadow_start[k + 1]; e++) {
            scene_gpu_draw_object_depth(gpu, st, s, fe->shadow[e], fe->shadow_viewproj[k]);
            draws++;
        }
        sm_mat4_mul(fe->shadow_viewproj[k], inv_view, m);
        sm_mat4_mul(TO_MAP, m, m);
        memcpy(sm->staging[layer], m, sizeof m);
        if (layer + 1 > used)
            used = layer + 1;
    }
    gl.Disable(GL_POLYGON_OFFSET_FILL);
    if (used)
        gl.NamedBufferSubData(sm->ubo, 0, (GLsizeiptr)(used * sizeof *sm->staging), sm->staging);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, SHADOW_UBO_BINDING, sm->ubo);
    /* The passes after this one count as in a frame without shadow maps (shadow.h). */
    gl_state_invalidate(st);
    return draws;
}

void shadow_maps_bind(const shadow_maps *sm, gl_state *st)
{
    if (sm->run && sm->texture)
        gl_state_texture(st, SHADOW_TEXTURE_UNIT, sm->texture);
}

void shadow_maps_describe(const shadow_maps *sm, pass_plan *out)
{
    if (!sm->run || !sm->texture || out->ntargets >= sizeof out->target / sizeof out->target[0])
        return;
    target_plan_entry *t = &out->target[out->ntargets++];
    memset(t, 0, sizeof *t);
    snprintf(t->name, sizeof t->name, "shadow.maps[%u]", sm->layers);
    snprintf(t->format, sizeof t->format, "depth32f");
    t->width = t->height = sm->size;
    t->bytes = sm->bytes;
    out->target_bytes += sm->bytes;
}
