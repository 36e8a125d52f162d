/* A scene's meshes and textures on the GPU and the draws every renderer makes of
 * them (scene_gpu.h). Everything is made with direct state access, so creation
 * binds nothing the state cache keeps. */
#include "renderers/frame/bindings.h"
#include "renderers/frame/scene_gpu.h"

#include "renderers/frame/frontend.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/target.h"
#include "renderers/frame/environment.h"
#include "renderers/frame/shading.h"
#include "scenes/scene_anim.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct gpu_mesh {
    GLuint vao, vbo, ibo;
    GLuint cbo;                /* the vertex colours (attribute 4), or 0 */
    GLuint uvbo;               /* the second uv set (attribute 5), or 0 */
    GLuint skbo;               /* a skin's joints, then its weights (attributes 6, 7), or 0 */
    GLsizei count;             /* indices */
} gpu_mesh;

struct scene_gpu {
    gpu_mesh *meshes;
    uint32_t nmeshes;
    GLuint *textures;
    uint32_t ntextures;
    gpu_mesh sphere, cone;     /* the light volumes (frontend.h) */
    GLuint frame_ubo;
    size_t frame_bytes;        /* of gpu_frame: shading_frame_bytes */
    GLuint joints_buffer, joints_texture;   /* the joint palette (skin.inc), or 0 */
    GLuint environment;        /* the prefiltered sky (environment.inc), or 0 */
    uint32_t njoints;
    gl_program_cache *programs;
    GLuint sky_program, resolve_program;
    bool unclipped;            /* the programs are FULLSCREEN_UNCLIPPED variants */
    bool uv2;                  /* the scene uses a second uv set: LOC_UV1_MAPS is set */
    int width, height;         /* the scene's size (the sky's target) */
    scene_display display;     /* the resolve's variant (at create) and exposure (per frame) */
    uint64_t bytes;
};

// >>meshes

/* A skinned mesh's joints (attribute 6, 4 x uint16, integer) and weights (attribute 7,
 * 4 floats) from one buffer, the weights after the joints; the others read the generic
 * joint 0 and weights 0, which skin.inc takes for no skin. */
static void skin_upload(gpu_mesh *out, const mesh *m, uint64_t *bytes)
{
    GLsizeiptr jbytes = (GLsizeiptr)((size_t)m->nvertices * sizeof *m->joints);
    GLsizeiptr wbytes = (GLsizeiptr)((size_t)m->nvertices * sizeof *m->weights);
    gl.CreateBuffers(1, &out->skbo);
    gl.NamedBufferStorage(out->skbo, jbytes + wbytes, NULL, GL_DYNAMIC_STORAGE_BIT);
    gl.NamedBufferSubData(out->skbo, 0, jbytes, m->joints);
    gl.NamedBufferSubData(out->skbo, jbytes, wbytes, m->weights);
    gl.VertexArrayVertexBuffer(out->vao, 3, out->skbo, 0, (GLsizei)sizeof *m->joints);
    gl.VertexArrayVertexBuffer(out->vao, 4, out->skbo, jbytes, (GLsizei)sizeof *m->weights);
    gl.EnableVertexArrayAttrib(out->vao, SCENE_GPU_JOINTS_ATTRIB);
    gl.VertexArrayAttribIFormat(out->vao, SCENE_GPU_JOINTS_ATTRIB, 4, GL_UNSIGNED_SHORT, 0);
    gl.VertexArrayAttribBinding(out->vao, SCENE_GPU_JOINTS_ATTRIB, 3);
    gl.EnableVertexArrayAttrib(out->vao, SCENE_GPU_WEIGHTS_ATTRIB);
    gl.VertexArrayAttribFormat(out->vao, SCENE_GPU_WEIGHTS_ATTRIB, 4, GL_FLOAT, GL_FALSE, 0);
    gl.VertexArrayAttribBinding(out->vao, SCENE_GPU_WEIGHTS_ATTRIB, 4);
    *bytes += (uint64_t)(jbytes + wbytes);
}

static bool mesh_upload(gpu_mesh *out, const mesh *m, const char *what, uint64_t *bytes,
                        char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!m->nvertices || !m->nindices || m->nindices > (uint32_t)INT32_MAX) {
        snprintf(err, errlen, "scene_gpu: %s has %u vertices and %u indices: nothing to draw",
                 what, m->nvertices, m->nindices);
        return false;
    }
    GLsizeiptr vbytes = (GLsizeiptr)((size_t)m->nvertices * sizeof *m->vertices);
    GLsizeiptr ibytes = (GLsizeiptr)((size_t)m->nindices * sizeof *m->indices);
    gl.CreateVertexArrays(1, &out->vao);
    gl.CreateBuffers(1, &out->vbo);
    gl.CreateBuffers(1, &out->ibo);
    /* a deforming mesh's vertices are uploaded again every frame (scene_gpu_frame) */
    gl.NamedBufferStorage(out->vbo, vbytes, m->vertices, m->deforms ? GL_DYNAMIC_STORAGE_BIT : 0);
    gl.NamedBufferStorage(out->ibo, ibytes, m->indices, 0);
    gl.VertexArrayVertexBuffer(out->vao, 0, out->vbo, 0, (GLsizei)sizeof(mesh_vertex));
    gl.VertexArrayElementBuffer(out->vao, out->ibo);
    static const struct {
        GLint size;
        GLuint offset;
    } attrs[4] = {
        {3, (GLuint)offsetof(mesh_vertex, position)},
        {3, (GLuint)offsetof(mesh_vertex, normal)},
        {4, (GLuint)offsetof(mesh_vertex, tangent)},
        {2, (GLuint)offsetof(mesh_vertex, uv)},
    };
    for (GLuint i = 0; i < 4; i++) {
        gl.EnableVertexArrayAttrib(out->vao, i);
        gl.VertexArrayAttribFormat(out->vao, i, attrs[i].size, GL_FLOAT, GL_FALSE, attrs[i].offset);
        gl.VertexArrayAttribBinding(out->vao, i, 0);
    }
    if (m->colors) {   /* attribute 4 from its own buffer; else the generic white */
        GLsizeiptr cbytes = (GLsizeiptr)((size_t)m->nvertices * sizeof *m->colors);
        gl.CreateBuffers(1, &out->cbo);
        gl.NamedBufferStorage(out->cbo, cbytes, m->colors, 0);
        gl.VertexArrayVertexBuffer(out->vao, 1, out->cbo, 0, (GLsizei)sizeof *m->colors);
        gl.EnableVertexArrayAttrib(out->vao, SCENE_GPU_COLOR_ATTRIB);
        gl.VertexArrayAttribFormat(out->vao, SCENE_GPU_COLOR_ATTRIB, 4, GL_UNSIGNED_BYTE,
                                   GL_TRUE, 0);
        gl.VertexArrayAttribBinding(out->vao, SCENE_GPU_COLOR_ATTRIB, 1);
        *bytes += (uint64_t)cbytes;
    }
    if (m->uv2) {   /* attribute 5 from its own buffer; else the generic (0, 0) */
        GLsizeiptr ubytes = (GLsizeiptr)((size_t)m->nvertices * sizeof *m->uv2);
        gl.CreateBuffers(1, &out->uvbo);
        gl.NamedBufferStorage(out->uvbo, ubytes, m->uv2, 0);
        gl.VertexArrayVertexBuffer(out->vao, 2, out->uvbo, 0, (GLsizei)sizeof *m->uv2);
        gl.EnableVertexArrayAttrib(out->vao, SCENE_GPU_UV2_ATTRIB);
        gl.VertexArrayAttribFormat(out->vao, SCENE_GPU_UV2_ATTRIB, 2, GL_FLOAT, GL_FALSE, 0);
        gl.VertexArrayAttribBinding(out->vao, SCENE_GPU_UV2_ATTRIB, 2);
        *bytes += (uint64_t)ubytes;
    }
    if (m->joints && m->weights)
        skin_upload(out, m, bytes);
    out->count = (GLsizei)m->nindices;
    *bytes += (uint64_t)vbytes + (uint64_t)ibytes;
    return true;
}

static void mesh_release(gpu_mesh *m)
{
    GL_OBJECTS_DELETE(GLO_VERTEX_ARRAY, &m->vao);
    GL_OBJECTS_DELETE(GLO_BUFFER, &m->vbo, &m->cbo, &m->uvbo, &m->skbo, &m->ibo);
    memset(m, 0, sizeof *m);
}

// >>textures

/* Half way from a to b as llvmpipe's 8-bit linear filter has it: a + (b - a + 1) / 2,
 * rounded down (to -inf). */
static unsigned lerp_half(unsigned a, unsigned b)
{
    int d = (int)b - (int)a + 1;
    return (unsigned)((int)a + (d >= 0 ? d / 2 : -((1 - d) / 2)));
}

/* The level below src (sw x sh texels of ch 8-bit channels) into dst, GL's size rule
 * (max(1, floor(n / 2)) a side). Each texel filters its 2x2 block as glGenerateMipmap
 * does on llvmpipe (a bilinear sample at the block's centre: the two rows' texel pairs,
 * then the two results, each by lerp_half), so llvmpipe's mip levels, and its images, are
 * the same bytes; a GPU's own filter may differ from it by a unit. Sides are powers of
 * two (texture_upload leaves the others to glGenerateMipmap, whose sample points then
 * fall between blocks). Why on the CPU: glGenerateMipmap cost llvmpipe 0.33 s a trial (a
 * blit per level per map, each through its shader pipeline), more than most trials'
 * measured frames; this takes a millisecond. */
static void mip_down(const uint8_t *src, uint32_t sw, uint32_t sh, uint32_t ch, uint8_t *dst)
{
    uint32_t dw = sw > 1 ? sw / 2 : 1, dh = sh > 1 ? sh / 2 : 1;
    for (uint32_t y = 0; y < dh; y++) {
        const uint8_t *r0 = src + (size_t)(sh > 1 ? 2 * y : 0) * sw * ch;   /* a side of 1 */
        const uint8_t *r1 = src + (size_t)(sh > 1 ? 2 * y + 1 : 0) * sw * ch;
        for (uint32_t x = 0; x < dw; x++) {
            size_t x0 = (size_t)(sw > 1 ? 2 * x : 0) * ch, x1 = (size_t)(sw > 1 ? 2 * x + 1 : 0) * ch;
            for (uint32_t c = 0; c < ch; c++)
                dst[((size_t)y * dw + x) * ch + c] =
                    (uint8_t)lerp_half(lerp_half(r0[x0 + c], r0[x1 + c]),
                                       lerp_half(r1[x0 + c], r1[x1 + c]));
        }
    }
}

static GLuint texture_upload(const texture_image *img, uint32_t index, uint64_t *bytes,
                             char *err, size_t errlen)
{
    GLenum ifmt, fmt;
    if (img->channels == 4) {
        ifmt = GL_RGBA8;
        fmt = GL_RGBA;
    } else if (img->channels == 1) {
        ifmt = GL_R8;
        fmt = GL_RED;
    } else {
        snprintf(err, errlen, "scene_gpu: texture %u has %u channels (1 or 4 expected)", index,
                 img->channels);
        return 0;
    }
    GLint max_size = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (!img->data || img->width == 0 || img->height == 0 ||
        img->width > (uint32_t)max_size || img->height > (uint32_t)max_size) {
        snprintf(err, errlen, "scene_gpu: texture %u is %ux%u (1..%d per side expected)", index,
                 img->width, img->height, (int)max_size);
        return 0;
    }
    GLsizei levels = 1;
    for (uint32_t m = img->width > img->height ? img->width : img->height; m > 1; m >>= 1)
        levels++;
    /* levels below the first: mip_down's where both sides are powers of two */
    bool pot = (img->width & (img->width - 1)) == 0 && (img->height & (img->height - 1)) == 0;
    size_t below = (size_t)(img->width > 1 ? img->width / 2 : 1) *
                   (img->height > 1 ? img->height / 2 : 1) * img->channels;
    uint8_t *mip[2] = {pot ? malloc(below) : NULL, pot ? malloc(below) : NULL};
    if (pot && (!mip[0] || !mip[1])) {
        free(mip[0]);
        free(mip[1]);
        snprintf(err, errlen, "scene_gpu: out of memory for texture %u's levels", index);
        return 0;
    }
    GLuint t = 0;
    GLint align = 4;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &t);
    gl.TextureStorage2D(t, levels, ifmt, (GLsizei)img->width, (GLsizei)img->height);
    gl.GetIntegerv(GL_UNPACK_ALIGNMENT, &align);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);   /* rows are tightly packed */
    const uint8_t *level = img->data;
    uint32_t w = img->width, h = img->height;
    for (GLsizei l = 0; l < levels; l++) {
        if (l > 0) {
            if (pot) {
                mip_down(level, w, h, img->channels, mip[l & 1]);
                level = mip[l & 1];
            }
            w = w > 1 ? w / 2 : 1;
            h = h > 1 ? h / 2 : 1;
        }
        if (l == 0 || pot)
            gl.TextureSubImage2D(t, l, 0, 0, (GLsizei)w, (GLsizei)h, fmt, GL_UNSIGNED_BYTE,
                                 level);
        *bytes += (uint64_t)w * h * img->channels;
    }
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, align);
    if (!pot)
        gl.GenerateTextureMipmap(t);
    free(mip[0]);
    free(mip[1]);
    gl.TextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl.TextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TextureParameteri(t, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl.TextureParameteri(t, GL_TEXTURE_WRAP_T, GL_REPEAT);
    return t;
}

// >>create and destroy

/* The joint palette (scene_anim.h) as a texture buffer of RGBA32F texels, a matrix's 4
 * columns each, which the vertex stage of every pass (and visibility's compute) reads
 * with texelFetch (skin.inc). Why a texture buffer: a storage block in the vertex stage
 * may be refused (GL's minimum MAX_VERTEX_SHADER_STORAGE_BLOCKS is 0), a uniform block's
 * minimum size (16 KiB) holds only 256 matrices and would be bound again per skin, a
 * texture buffer's minimum (65536 texels) holds every skin's joints at once
 * (SCENE_ANIM_MAX_JOINTS), bound once a frame. */
static bool joints_create(scene_gpu *g, const scene *s, char *err, size_t errlen)
{
    uint32_t n = s->anim ? s->anim->njoints : 0;
    if (!n)
        return true;
    GLint max_texels = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    if ((uint64_t)n * 4 > (uint64_t)max_texels) {
        snprintf(err, errlen, "scene_gpu: the scene's skins have %u joints; a texture buffer "
                 "of this GL holds %d", n, max_texels / 4);
        return false;
    }
    GLsizeiptr bytes = (GLsizeiptr)((size_t)n * sizeof(sm_mat4));
    gl.CreateBuffers(1, &g->joints_buffer);
    gl.NamedBufferStorage(g->joints_buffer, bytes, s->anim->joints, GL_DYNAMIC_STORAGE_BIT);
    gl.CreateTextures(GL_TEXTURE_BUFFER, 1, &g->joints_texture);
    gl.TextureBuffer(g->joints_texture, GL_RGBA32F, g->joints_buffer);
    g->njoints = n;
    g->bytes += (uint64_t)bytes;
    return true;
}

/* The environment's cube map (environment.h): RGBA16F, its mips the prefiltered levels,
 * trilinear, seamless across faces. */
static bool environment_create(scene_gpu *g, char *err, size_t errlen)
{
    const environment_maps *m = environment_get();
    if (!m) {
        snprintf(err, errlen, "scene_gpu: out of memory for the environment's maps");
        return false;
    }
    gl.CreateTextures(GL_TEXTURE_CUBE_MAP, 1, &g->environment);
    gl.TextureStorage2D(g->environment, ENVIRONMENT_LEVELS, GL_RGBA16F, ENVIRONMENT_FACE,
                        ENVIRONMENT_FACE);
    for (int k = 0; k < ENVIRONMENT_LEVELS; k++) {
        int size = ENVIRONMENT_FACE >> k;
        /* a cube map's faces are layers 0..5 of TextureSubImage3D (DSA) */
        gl.TextureSubImage3D(g->environment, k, 0, 0, 0, size, size, 6, GL_RGB, GL_FLOAT,
                             m->level[k]);
        g->bytes += (uint64_t)size * (uint64_t)size * 6u * 8u;
    }
    gl.TextureParameteri(g->environment, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl.TextureParameteri(g->environment, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TextureParameteri(g->environment, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(g->environment, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(g->environment, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    /* context state; no other cube map is sampled (the shadow maps are 2D arrays) */
    gl.Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    return true;
}

static bool build_program(scene_gpu *g, const char *fragment, GLuint *out, char *err,
                          size_t errlen)
{
    gl_program_desc d = {.vertex = "fullscreen.vert", .fragment = fragment};
    int n = 0;
    if (g->unclipped)
        d.defines[n++] = "FULLSCREEN_UNCLIPPED";
    if (strcmp(fragment, "sky.frag") == 0) {
        d.defines[n++] = "FULLSCREEN_FAR";   /* z = w: the sky lies on the far plane */
        if (g->environment)
            d.defines[n++] = "ENVIRONMENT";   /* the sky is the environment's */
    }
    if (strcmp(fragment, "resolve.frag") == 0) {
        if (g->display.exposed)
            d.defines[n++] = "EXPOSURE";
        if (g->display.tonemap == TONEMAP_PBR_NEUTRAL)
            d.defines[n++] = "TONEMAP_PBR_NEUTRAL";
    }
    char why[2048];
    if (gl_program_get(g->programs, &d, out, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "scene_gpu: %s", why);
        return false;
    }
    return true;
}

static double upload_total_s;   /* this process's scene_gpu_create uploads */

static double mono_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

double scene_gpu_upload_s(void) { return upload_total_s; }

scene_gpu *scene_gpu_create(const scene *s, char *err, size_t errlen)
{
    double t0 = mono_s();
    scene_gpu *g = calloc(1, sizeof *g);
    if (!g)
        goto oom;
    g->width = s->width;
    g->height = s->height;
    g->display = s->display;
    g->meshes = calloc(s->nmeshes ? s->nmeshes : 1, sizeof *g->meshes);
    g->textures = calloc(s->ntextures ? s->ntextures : 1, sizeof *g->textures);
    g->programs = gl_program_cache_create();
    if (!g->meshes || !g->textures || !g->programs)
        goto oom;

    /* what a mesh without colours reads from attribute 4 (context state, set once) */
    gl.VertexAttrib4f(SCENE_GPU_COLOR_ATTRIB, 1.0f, 1.0f, 1.0f, 1.0f);
    gl.VertexAttrib4f(SCENE_GPU_UV2_ATTRIB, 0.0f, 0.0f, 0.0f, 1.0f);
    gl.VertexAttribI4ui(SCENE_GPU_JOINTS_ATTRIB, 0, 0, 0, 0);
    gl.VertexAttrib4f(SCENE_GPU_WEIGHTS_ATTRIB, 0.0f, 0.0f, 0.0f, 0.0f);   /* no skin */
    if (!joints_create(g, s, err, errlen))
        goto fail;
    if (s->environment != ENVIRONMENT_NONE && !environment_create(g, err, errlen))
        goto fail;
    g->uv2 = scene_uses_uv2(s);
    for (uint32_t i = 0; i < s->nmeshes; i++) {
        char what[32];
        snprintf(what, sizeof what, "mesh %u", i);
        if (!mesh_upload(&g->meshes[i], &s->meshes[i], what, &g->bytes, err, errlen))
            goto fail;
        g->nmeshes = i + 1;
    }
    for (uint32_t i = 0; i < s->ntextures; i++) {
        g->textures[i] = texture_upload(&s->textures[i], i, &g->bytes, err, errlen);
        if (!g->textures[i])
            goto fail;
        g->ntextures = i + 1;
    }

    mesh sphere, cone;
    if (!frontend_volume_meshes(&sphere, &cone, err, errlen))
        goto fail;
    bool ok = mesh_upload(&g->sphere, &sphere, "the light sphere", &g->bytes, err, errlen) &&
              mesh_upload(&g->cone, &cone, "the light cone", &g->bytes, err, errlen);
    mesh_free(&sphere);
    mesh_free(&cone);
    if (!ok)
        goto fail;

    g->frame_bytes = shading_frame_bytes(s);
    gl.CreateBuffers(1, &g->frame_ubo);
    gl.NamedBufferStorage(g->frame_ubo, (GLsizeiptr)g->frame_bytes, NULL,
                          GL_DYNAMIC_STORAGE_BIT);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, 0, g->frame_ubo);
    g->bytes += g->frame_bytes;
    gl.Finish();   /* the copies done, so that the time is theirs: once, before any frame */
    upload_total_s += mono_s() - t0;

    GLint dims[2] = {0, 0};
    gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
    g->unclipped = (int64_t)2 * s->width <= dims[0] && (int64_t)2 * s->height <= dims[1];
    if (s->sky && !build_program(g, "sky.frag", &g->sky_program, err, errlen))
        goto fail;
    if (!build_program(g, "resolve.frag", &g->resolve_program, err, errlen))
        goto fail;
    return g;

oom:
    snprintf(err, errlen, "scene_gpu: out of memory for scene '%s'", s->name);
fail:
    scene_gpu_destroy(g);
    return NULL;
}

unsigned scene_gpu_texture(const scene_gpu *g, int index)
{
    return g && index >= 0 && (uint32_t)index < g->ntextures ? g->textures[index] : 0u;
}

void scene_gpu_destroy(scene_gpu *g)
{
    if (!g)
        return;
    for (uint32_t i = 0; i < g->nmeshes; i++)
        mesh_release(&g->meshes[i]);
    if (g->ntextures)
        gl.DeleteTextures((GLsizei)g->ntextures, g->textures);
    mesh_release(&g->sphere);
    mesh_release(&g->cone);
    GL_OBJECTS_DELETE(GLO_BUFFER, &g->frame_ubo, &g->joints_buffer);
    GL_OBJECTS_DELETE(GLO_TEXTURE, &g->joints_texture, &g->environment);
    gl_program_cache_destroy(g->programs);
    free(g->meshes);
    free(g->textures);
    free(g);
}

// >>per frame

void scene_gpu_frame(scene_gpu *g, const scene *s)
{
    gpu_frame f;
    g->display.exposure = s->display.exposure;
    shading_pack_frame(s, &f);
    gl.NamedBufferSubData(g->frame_ubo, 0, (GLsizeiptr)g->frame_bytes, &f);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, 0, g->frame_ubo);
    for (uint32_t i = 0; i < g->nmeshes && i < s->nmeshes; i++)   /* morph targets */
        if (s->meshes[i].deforms)
            gl.NamedBufferSubData(g->meshes[i].vbo, 0,
                                  (GLsizeiptr)((size_t)s->meshes[i].nvertices *
                                               sizeof(mesh_vertex)),
                                  s->meshes[i].vertices);
    if (g->joints_texture && s->anim && s->anim->njoints == g->njoints) {
        /* the frame's joints, for every pass (bound outside the cache, as the Frame) */
        gl.NamedBufferSubData(g->joints_buffer, 0,
                              (GLsizeiptr)((size_t)g->njoints * sizeof(sm_mat4)),
                              s->anim->joints);
        gl.BindTextureUnit(BIND_TEX_JOINTS, g->joints_texture);
    }
    if (g->environment)   /* as the joints: outside the cache, for every pass */
        gl.BindTextureUnit(BIND_TEX_ENVIRONMENT, g->environment);
}

/* The object's mesh, or NULL (with a message) for a bad object. */
static const gpu_mesh *object_mesh(const scene_gpu *g, const scene *s, uint32_t object,
                                   const char *fn)
{
    if (object >= s->nobjects) {
        fprintf(stderr, "bug: %s: object %u of %u\n", fn, object, s->nobjects);
        return NULL;
    }
    const scene_object *o = &s->objects[object];
    if (o->mesh >= g->nmeshes || o->material >= s->nmaterials) {
        fprintf(stderr, "bug: %s: object %u has mesh %u of %u, material %u of %u\n", fn,
                object, o->mesh, g->nmeshes, o->material, s->nmaterials);
        return NULL;
    }
    return &g->meshes[o->mesh];
}

/* Locations 0, 1, 2 of mesh.vert for object o. */
static void set_transform(const scene *s, const scene_object *o)
{
    sm_mat4 mv;
    sm_mat3 nm;
    sm_mat4_mul(s->view, o->model, mv);
    sm_mat4_normal(mv, nm);
    gl.UniformMatrix4fv(0, 1, GL_FALSE, &mv[0][0]);
    gl.UniformMatrix4fv(1, 1, GL_FALSE, &s->proj[0][0]);
    gl.UniformMatrix3fv(2, 1, GL_FALSE, &nm[0][0]);
}

/* The object's mesh drawn: a double-sided material's without culling, whatever the pass
 * culls (the pass's culling set back after it: two state changes a double-sided object). */
static void draw_mesh(gl_state *st, const scene *s, uint32_t object, const gpu_mesh *gm)
{
    gls_cull pass = gl_state_cull_current(st);
    bool both = s->materials[s->objects[object].material].double_sided &&
                pass != GLS_CULL_NONE;
    if (both)
        gl_state_cull(st, GLS_CULL_NONE);
    gl_state_vertex_array(st, gm->vao);
    gl_state_draw_elements(st, GL_TRIANGLES, gm->count, GL_UNSIGNED_INT, 0);
    if (both)
        gl_state_cull(st, pass);
}

void scene_gpu_draw_object(scene_gpu *g, gl_state *st, const scene *s, uint32_t object)
{
    const gpu_mesh *gm = object_mesh(g, s, object, "scene_gpu_draw_object");
    if (!gm)
        return;
    const scene_object *o = &s->objects[object];
    const scene_material *m = &s->materials[o->material];
    const int maps[4] = {m->diffuse_map, m->gloss_map, m->normal_map, m->emissive_map};
    for (unsigned unit = 0; unit < 4; unit++)
        if (maps[unit] >= 0 && (uint32_t)maps[unit] >= g->ntextures) {
            fprintf(stderr, "bug: scene_gpu_draw_object: material %u has texture %d of %u\n",
                    o->material, maps[unit], g->ntextures);
            return;
        }
    for (unsigned unit = 0; unit < 4; unit++)
        if (maps[unit] >= 0)
            gl_state_texture(st, unit, g->textures[maps[unit]]);

    set_transform(s, o);
    gl.Uniform3fv(8, 1, m->diffuse);
    gl.Uniform1f(9, m->specular);
    gl.Uniform1f(10, m->shininess);
    gl.Uniform3fv(11, 1, m->emissive);
    if (m->alpha == MATERIAL_MASK)   /* only the ALPHA_TEST variant has it */
        gl.Uniform1f(LOC_ALPHA_CUTOFF, m->alpha_cutoff);
    if (m->alpha == MATERIAL_BLEND)   /* only the TRANSLUCENT variant has it */
        gl.Uniform1f(LOC_OPACITY, m->opacity);
    if (g->uv2)   /* every surface.inc program has it then (UV2) */
        gl.Uniform1i(LOC_UV1_MAPS, (GLint)m->uv1_maps);
    if (s->shading == SHADING_PBR && m->gloss_map >= 0)   /* the ORM map's (surface.inc) */
        gl.Uniform1f(LOC_OCCLUSION, m->occlusion);
    draw_mesh(st, s, object, gm);
}

void scene_gpu_draw_object_geometry(scene_gpu *g, gl_state *st, const scene *s,
                                    uint32_t object)
{
    const gpu_mesh *gm = object_mesh(g, s, object, "scene_gpu_draw_object_geometry");
    if (!gm)
        return;
    set_transform(s, &s->objects[object]);
    draw_mesh(st, s, object, gm);
}

void scene_gpu_draw_object_depth(scene_gpu *g, gl_state *st, const scene *s, uint32_t object,
                                 const sm_mat4 viewproj)
{
    const gpu_mesh *gm = object_mesh(g, s, object, "scene_gpu_draw_object_depth");
    if (!gm)
        return;
    sm_mat4 mvp;
    sm_mat4_mul(viewproj, s->objects[object].model, mvp);
    gl.UniformMatrix4fv(0, 1, GL_FALSE, &mvp[0][0]);
    draw_mesh(st, s, object, gm);
}

void scene_gpu_draw_light_volume(scene_gpu *g, gl_state *st, const scene *s, uint32_t light)
{
    if (light >= s->nlights_total) {
        fprintf(stderr, "bug: scene_gpu_draw_light_volume: light %u of %u\n", light,
                s->nlights_total);
        return;
    }
    const scene_light *l = &s->lights[light];
    const gpu_mesh *gm;
    if (l->type == LIGHT_POINT)
        gm = &g->sphere;
    else if (l->type == LIGHT_SPOT)
        gm = &g->cone;
    else {
        fprintf(stderr, "bug: scene_gpu_draw_light_volume: light %u is directional: it has "
                "no volume\n", light);
        return;
    }
    sm_mat4 model, mv;
    frontend_light_volume_model(l, model);
    sm_mat4_mul(s->view, model, mv);
    gl.UniformMatrix4fv(0, 1, GL_FALSE, &mv[0][0]);
    gl.UniformMatrix4fv(1, 1, GL_FALSE, &s->proj[0][0]);
    gl_state_vertex_array(st, gm->vao);
    gl_state_draw_elements(st, GL_TRIANGLES, gm->count, GL_UNSIGNED_INT, 0);
}

/* What the fullscreen passes set besides their program. */
static void fullscreen_state(gl_state *st, const gls_depth *depth)
{
    gl_state_depth(st, depth);
    gl_state_blend(st, NULL);
    gl_state_stencil(st, NULL);
    gl_state_cull(st, GLS_CULL_NONE);
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
}

void scene_gpu_draw_sky(scene_gpu *g, gl_state *st)
{
    if (!g->sky_program) {
        fprintf(stderr, "bug: scene_gpu_draw_sky: the scene has no sky\n");
        return;
    }
    gl_state_program(st, g->sky_program);
    fullscreen_state(st, &(gls_depth){.compare = GLS_COMPARE_LEQUAL, .write = false});
    gl_state_draw_fullscreen(st, g->width, g->height, g->unclipped);
}

void scene_gpu_resolve(scene_gpu *g, gl_state *st, unsigned hdr_texture, unsigned output_fbo,
                       int width, int height)
{
    gl_state_framebuffer(st, output_fbo);
    gl_state_program(st, g->resolve_program);
    if (g->display.exposed)   /* DSA: whatever program the state cache has bound */
        gl.ProgramUniform1f(g->resolve_program, 0, g->display.exposure);
    gl_state_texture(st, 0, hdr_texture);
    fullscreen_state(st, NULL);
    gl_state_draw_fullscreen(st, width, height, g->unclipped);
}

uint64_t scene_gpu_bytes(const scene_gpu *g)
{
    return g ? g->bytes : 0;
}

void scene_gpu_describe(const scene_gpu *g, pass_plan *out)
{
    if (g)
        gl_program_cache_describe(g->programs, out);
}
