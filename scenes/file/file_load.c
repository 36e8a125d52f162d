/* File scenes, >>load: the import through assimp and everything checked on what it gives,
 * the referenced images decoded (see scenes/file/file_assimp.c). scene_file_check and the
 * builder share it, so what validate accepts is exactly what a run builds. */
#define _DEFAULT_SOURCE   /* realpath */
#include "scenes/file/file_internal.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "common/fsutil.h"
#include "common/grow.h"
#include "scenes/file/file_import.h"
#include "scenes/scene_fail.h"
#include "scenes/scene_internal.h"

void file_loaded_free(loaded *l)
{
    if (l->ai)
        aiReleaseImport(l->ai);
    for (uint32_t i = 0; i < l->nimages; i++) {
        free(l->images[i].ref);
        image_free(&l->images[i].img);
    }
    free(l->images);
    free(l->emissive_strength);
    file_set_free(&l->files);
    memset(l, 0, sizeof *l);
}

/* Percent-decodes a URI path (glTF image URIs may escape spaces and such). */
static void uri_decode(const char *in, char *out, size_t outlen)
{
    size_t k = 0;
    for (size_t i = 0; in[i] && k + 1 < outlen; i++) {
        unsigned v;
        if (in[i] == '%' && in[i + 1] && in[i + 2] && sscanf(in + i + 1, "%2x", &v) == 1) {
            out[k++] = (char)v;
            i += 2;
        } else {
            out[k++] = in[i];
        }
    }
    out[k] = '\0';
}

/* The image a material references, decoded (once per reference), or -1 with a message. */
int file_load_image(loaded *l, const char *ref, char *err, size_t errlen)
{
    for (uint32_t i = 0; i < l->nimages; i++)
        if (strcmp(l->images[i].ref, ref) == 0)
            return (int)i;
    const struct aiScene *ai = l->ai;
    const void *bytes = NULL;
    size_t size = 0;
    char name[8300];
    const struct aiTexture *emb = NULL;
    if (ref[0] == '*') {
        char *end;
        unsigned long k = strtoul(ref + 1, &end, 10);
        if (*end || k >= ai->mNumTextures) {
            scene_fail(err, errlen, "%s: texture '%s': no such embedded image", l->path, ref);
            return -1;
        }
        emb = ai->mTextures[k];
    } else {
        for (unsigned k = 0; k < ai->mNumTextures && !emb; k++)
            if (strcmp(ai->mTextures[k]->mFilename.data, ref) == 0)
                emb = ai->mTextures[k];
    }
    image img = {0};
    char why[512] = "";
    if (emb && emb->mHeight != 0) {
        /* already decoded by assimp: BGRA texels */
        uint64_t n = (uint64_t)emb->mWidth * emb->mHeight;
        if (n > FILE_MAX_BYTES / 4) {
            scene_fail(err, errlen, "%s: embedded texture '%s' of %ux%u texels is too large",
                       l->path, ref, emb->mWidth, emb->mHeight);
            return -1;
        }
        img.width = (int)emb->mWidth;
        img.height = (int)emb->mHeight;
        img.channels = 4;
        img.type = IMAGE_U8;
        img.pixels = malloc((size_t)n * 4);
        if (!img.pixels) {
            scene_fail(err, errlen, "%s: out of memory for texture '%s'", l->path, ref);
            return -1;
        }
        unsigned char *p = img.pixels;
        for (uint64_t i = 0; i < n; i++) {
            p[4 * i + 0] = emb->pcData[i].r;
            p[4 * i + 1] = emb->pcData[i].g;
            p[4 * i + 2] = emb->pcData[i].b;
            p[4 * i + 3] = emb->pcData[i].a;
        }
        snprintf(name, sizeof name, "%s", ref);
    } else {
        if (emb) {
            bytes = emb->pcData;
            size = emb->mWidth;
            snprintf(name, sizeof name, "%s: embedded image %s", l->path, ref);
            /* embedded bytes are part of the file already hashed */
        } else {
            char rel[4096];
            uri_decode(ref, rel, sizeof rel);
            snprintf(name, sizeof name, "%s%s", rel[0] == '/' ? "" : l->dir, rel);
            errno = 0;
            const read_file *f = file_set_get(&l->files, name);
            if (!f && !l->files.err[0] && strchr(rel, '\\')) {
                /* a path written on Windows (an MTL's ".\wall.jpg"), where no file has
                 * that name: its backslashes are separators */
                for (char *c = rel; *c; c++)
                    if (*c == '\\')
                        *c = '/';
                snprintf(name, sizeof name, "%s%s", rel[0] == '/' ? "" : l->dir, rel);
                errno = 0;
                f = file_set_get(&l->files, name);
            }
            if (!f) {
                if (l->files.err[0])
                    scene_fail(err, errlen, "%s: %s", l->path, l->files.err);
                else
                    scene_fail(err, errlen, "%s: image '%s' is missing (%s: %s)", l->path, ref,
                               name, strerror(errno ? errno : ENOENT));
                return -1;
            }
            bytes = f->data;
            size = f->size;
        }
        int w = 0, h = 0, ch = 0;
        unsigned long long decoded = 0;
        if (!image_probe(bytes, size, name, &w, &h, &ch, &decoded, why, sizeof why)) {
            scene_fail(err, errlen, "%s: texture '%s' does not decode: %s", l->path, ref, why);
            return -1;
        }
        if (w > (int)TEXTURE_MAX_SIZE || h > (int)TEXTURE_MAX_SIZE) {
            scene_fail(err, errlen, "%s: texture '%s' is %dx%d, more than %u texels a side",
                       l->path, ref, w, h, TEXTURE_MAX_SIZE);
            return -1;
        }
        /* the sides pass, yet a header's channel count (or depth) can still ask for
         * gigabytes: the decoded size is bounded before decoding */
        if (decoded > l->max_image_bytes) {
            scene_fail(err, errlen, "%s: texture '%s' is %dx%d with %d channels, %llu bytes "
                       "decoded, more than scene.max_image_bytes %llu", l->path, ref, w, h, ch,
                       decoded, (unsigned long long)l->max_image_bytes);
            return -1;
        }
        image raw;
        if (!image_decode(bytes, size, name, IMAGE_U8, &raw, why, sizeof why)) {
            scene_fail(err, errlen, "%s: texture '%s' does not decode: %s", l->path, ref, why);
            return -1;
        }
        /* to RGBA: grey -> rgb, no alpha -> 255 */
        size_t n = (size_t)raw.width * (size_t)raw.height;
        img.width = raw.width;
        img.height = raw.height;
        img.channels = 4;
        img.type = IMAGE_U8;
        img.pixels = malloc(n * 4);
        if (!img.pixels) {
            image_free(&raw);
            scene_fail(err, errlen, "%s: out of memory for texture '%s'", l->path, ref);
            return -1;
        }
        const unsigned char *s = raw.pixels;
        unsigned char *d = img.pixels;
        int c = raw.channels;
        for (size_t i = 0; i < n; i++) {
            const unsigned char *t = s + i * (size_t)c;
            d[4 * i + 0] = t[0];
            d[4 * i + 1] = c >= 3 ? t[1] : t[0];
            d[4 * i + 2] = c >= 3 ? t[2] : t[0];
            d[4 * i + 3] = c == 4 ? t[3] : c == 2 ? t[1] : 255;
        }
        image_free(&raw);
    }
    if (img.width > (int)TEXTURE_MAX_SIZE || img.height > (int)TEXTURE_MAX_SIZE) {
        scene_fail(err, errlen, "%s: texture '%s' is %dx%d, more than %u texels a side", l->path,
                   ref, img.width, img.height, TEXTURE_MAX_SIZE);
        image_free(&img);
        return -1;
    }
    if (!GROW(l->images, l->cap_images, (size_t)l->nimages + 1, 8)) {
        image_free(&img);
        scene_fail(err, errlen, "%s: out of memory", l->path);
        return -1;
    }
    l->images[l->nimages].ref = strdup(ref);
    l->images[l->nimages].img = img;
    if (!l->images[l->nimages].ref) {
        image_free(&img);
        scene_fail(err, errlen, "%s: out of memory", l->path);
        return -1;
    }
    return (int)l->nimages++;
}

/* The texture types a material may use, as scene_material's maps take them. */
static const enum aiTextureType base_types[] = {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE};
static const enum aiTextureType mr_types[] = {aiTextureType_UNKNOWN, aiTextureType_METALNESS};
static const enum aiTextureType occlusion_types[] = {aiTextureType_LIGHTMAP,
                                                     aiTextureType_AMBIENT_OCCLUSION};

static bool material_texture(const struct aiMaterial *m, enum aiTextureType t, char *out,
                             size_t outlen, unsigned *uv_set)
{
    struct aiString p;
    unsigned uv = 0;
    if (aiGetMaterialTextureCount(m, t) == 0 ||
        aiGetMaterialTexture(m, t, 0, &p, NULL, &uv, NULL, NULL, NULL, NULL) != aiReturn_SUCCESS)
        return false;
    snprintf(out, outlen, "%s", p.data);
    *uv_set = uv;
    return out[0] != '\0';
}

void file_material_refs(const struct aiMaterial *m, material_refs *r)
{
    r->diffuse[0] = r->normal[0] = r->emissive[0] = r->mr[0] = r->occlusion[0] = '\0';
    r->diffuse_uv = r->normal_uv = r->emissive_uv = r->mr_uv = r->occlusion_uv = 0;
    for (size_t k = 0; k < 2; k++)
        if (material_texture(m, base_types[k], r->diffuse, sizeof r->diffuse, &r->diffuse_uv))
            break;
    if (!material_texture(m, aiTextureType_NORMALS, r->normal, sizeof r->normal, &r->normal_uv))
        r->normal[0] = '\0';
    if (!material_texture(m, aiTextureType_EMISSIVE, r->emissive, sizeof r->emissive,
                          &r->emissive_uv))
        r->emissive[0] = '\0';
    /* assimp 5.2's glTF importer: metallicRoughnessTexture under UNKNOWN (and METALNESS),
     * occlusionTexture under LIGHTMAP */
    for (size_t k = 0; k < sizeof mr_types / sizeof mr_types[0]; k++)
        if (material_texture(m, mr_types[k], r->mr, sizeof r->mr, &r->mr_uv))
            break;
    for (size_t k = 0; k < sizeof occlusion_types / sizeof occlusion_types[0]; k++)
        if (material_texture(m, occlusion_types[k], r->occlusion, sizeof r->occlusion,
                             &r->occlusion_uv))
            break;
}

/* Node hierarchy: depth bounded and no node met twice (a hierarchy that recurses). */
static bool check_nodes(const loaded *l, const struct aiNode *n, unsigned depth,
                        const struct aiNode **path, char *err, size_t errlen)
{
    if (depth >= FILE_MAX_NODE_DEPTH)
        return scene_fail(err, errlen, "%s: the node hierarchy is more than %u deep (recursive?)",
                          l->path, FILE_MAX_NODE_DEPTH);
    for (unsigned i = 0; i < depth; i++)
        if (path[i] == n)
            return scene_fail(err, errlen, "%s: node '%s' contains itself: the hierarchy recurses",
                              l->path, n->mName.data);
    path[depth] = n;
    for (unsigned i = 0; i < n->mNumMeshes; i++)
        if (n->mMeshes[i] >= l->ai->mNumMeshes)
            return scene_fail(err, errlen, "%s: node '%s' names mesh %u of %u", l->path,
                              n->mName.data, n->mMeshes[i], l->ai->mNumMeshes);
    for (unsigned i = 0; i < n->mNumChildren; i++)
        if (!check_nodes(l, n->mChildren[i], depth + 1, path, err, errlen))
            return false;
    return true;
}

/* assimp reports some defects only as warnings and repairs them (faces with indices out
 * of range are dropped): a log stream catches those during an import. */
static char import_warning[512];

static void log_fn(const char *msg, char *user)
{
    if (!import_warning[0] && strstr(msg, "out-of-range indices")) {
        const char *m = strstr(msg, ": ");
        snprintf(import_warning, sizeof import_warning, "%s", m ? m + 2 : msg);
        size_t n = strlen(import_warning);
        while (n && (import_warning[n - 1] == '\n' || import_warning[n - 1] == ' '))
            import_warning[--n] = '\0';
    }
}

/* Why an import gave no triangle mesh, where the cause can be named (issue 25): a text
 * encoding assimp does not read (it reads text formats as ASCII or UTF-8), or a file whose
 * primitives are only points and lines (shadesweep draws triangles). The main file is
 * read again, where assimp's error is about meshes (error; NULL: a scene without any),
 * without the post-processing that drops points and lines. false: neither. */
/* Whether some triangle of some mesh has an area (assimp's FindDegenerates removes
 * repeated corners, not corners on a line). Indices are checked already. */
static bool any_area(const struct aiScene *ai)
{
    for (unsigned i = 0; i < ai->mNumMeshes; i++) {
        const struct aiMesh *m = ai->mMeshes[i];
        for (unsigned f = 0; f < m->mNumFaces; f++) {
            const unsigned *x = m->mFaces[f].mIndices;
            const struct aiVector3D *a = &m->mVertices[x[0]], *b = &m->mVertices[x[1]],
                                    *c = &m->mVertices[x[2]];
            /* in double: float differences of large coordinates overflow */
            double e1[3] = {(double)b->x - a->x, (double)b->y - a->y, (double)b->z - a->z};
            double e2[3] = {(double)c->x - a->x, (double)c->y - a->y, (double)c->z - a->z};
            double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                           e1[0] * e2[1] - e1[1] * e2[0]};
            if (n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0.0)
                return true;
        }
    }
    return false;
}

static bool why_no_triangles(loaded *l, const char *path, struct aiFileIO *io,
                             const char *error, char *why, size_t n)
{
    const read_file *f = l->files.n ? &l->files.files[0] : NULL;
    const char *bom = f ? fs_text_bom(f->data, f->size) : NULL;
    if (bom) {
        snprintf(why, n, "the file is %s text (its byte-order mark says so), which assimp "
                 "does not read: save it as UTF-8 (iconv -f %.6s -t UTF-8)", bom, bom);
        return true;
    }
    /* only where assimp's error is about meshes: "No meshes remaining", "Mesh contains
     * no faces", "mNumMeshes is 0" (NULL: the import gave a scene without meshes) */
    if (error && !strstr(error, "esh"))
        return false;
    char ignored[256];
    const struct aiScene *raw = file_import(path, 0, io, 0, ignored, sizeof ignored);
    if (!raw)
        return false;
    unsigned points = 0, lines = 0, triangles = 0;
    for (unsigned i = 0; raw->mMeshes && i < raw->mNumMeshes; i++) {
        const struct aiMesh *m = raw->mMeshes[i];
        if (!m)
            continue;
        unsigned t = m->mPrimitiveTypes;
        if (t & (aiPrimitiveType_TRIANGLE | aiPrimitiveType_POLYGON))
            triangles++;
        else if (t & aiPrimitiveType_LINE)
            lines++;
        else if (m->mNumVertices > 0)
            points++;   /* points, or vertices with no face at all */
    }
    aiReleaseImport(raw);
    if (triangles || points + lines == 0)
        return false;
    snprintf(why, n, "it has only points and lines (%u mesh%s of points, %u of lines), and "
             "shadesweep draws triangles", points, points == 1 ? "" : "es", lines);
    return true;
}

uint64_t scene_file_hash_more(uint64_t h, const void *data, size_t len)
{
    unsigned char n[8];
    for (int k = 0; k < 8; k++)
        n[k] = (unsigned char)((uint64_t)len >> (8 * k));
    h = scene_fnv1a64_more(h, n, sizeof n);
    return scene_fnv1a64_more(h, data, len);
}

void scene_file_list_free(scene_file_list *f)
{
    for (uint32_t i = 0; f && i < f->n; i++)
        free(f->path[i]);
    if (f)
        free(f->path);
    if (f)
        *f = (scene_file_list){0};
}

bool file_loaded_list(const loaded *l, scene_file_list *out, char *err, size_t errlen)
{
    *out = (scene_file_list){0};
    if (!(out->path = calloc(l->files.n ? l->files.n : 1, sizeof *out->path)))
        return scene_fail(err, errlen, "%s: out of memory", l->path);
    for (; out->n < l->files.n; out->n++)
        if (!(out->path[out->n] = strdup(l->files.files[out->n].path))) {
            scene_file_list_free(out);
            return scene_fail(err, errlen, "%s: out of memory", l->path);
        }
    return true;
}

/* What this thread's loads spent since scene_file_times_take last took it. */
static _Thread_local scene_file_times load_times;

double scene_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void scene_file_times_take(scene_file_times *t)
{
    *t = load_times;
    load_times = (scene_file_times){0};
}

static bool file_load_checked(const scene_file_options *o, loaded *l, double *decode_s,
                              char *err, size_t errlen);

/* Imports and checks everything; on success l holds the scene and every texture. */
bool file_load(const scene_file_options *o, loaded *l, char *err, size_t errlen)
{
    double t0 = scene_now_s(), decode_s = 0.0;
    bool ok = file_load_checked(o, l, &decode_s, err, errlen);
    load_times.import_s += scene_now_s() - t0 - decode_s;
    load_times.decode_s += decode_s;
    load_times.loads++;
    return ok;
}

static bool file_load_checked(const scene_file_options *o, loaded *l, double *decode_s,
                              char *err, size_t errlen)
{
    memset(l, 0, sizeof *l);
    if (!o || !o->path || !o->path[0])
        return scene_fail(err, errlen, "scene file: no path");
    l->path = o->path;
    l->max_image_bytes = o->max_image_bytes ? o->max_image_bytes : SCENE_FILE_MAX_IMAGE_BYTES;
    l->max_triangles = o->max_triangles ? o->max_triangles : SCENE_FILE_MAX_TRIANGLES;
    l->max_vertices = o->max_vertices ? o->max_vertices : SCENE_FILE_MAX_VERTICES;
    if (!(o->scale == 0.0f || (isfinite(o->scale) && o->scale > 0.0f)))
        return scene_fail(err, errlen, "%s: scale %g: expected a finite number > 0", o->path,
                          (double)o->scale);
    const char *slash = strrchr(o->path, '/');
    if (slash) {
        size_t n = (size_t)(slash - o->path) + 1;
        if (n >= sizeof l->dir)
            return scene_fail(err, errlen, "%s: path too long", o->path);
        memcpy(l->dir, o->path, n);
        l->dir[n] = '\0';
    }
    errno = 0;
    if (!file_set_get(&l->files, o->path)) {
        if (l->files.err[0])
            scene_fail(err, errlen, "%s", l->files.err);
        else
            scene_fail(err, errlen, "%s: cannot open: %s", o->path,
                       strerror(errno ? errno : ENOENT));
        file_loaded_free(l);
        return false;
    }
    /* what the file references is read from inside its folder */
    if (!realpath(l->dir[0] ? l->dir : ".", l->files.root)) {
        scene_fail(err, errlen, "%s: cannot resolve its folder: %s", o->path, strerror(errno));
        file_loaded_free(l);
        return false;
    }
    l->files.allow_outside = o->allow_outside;
    const char *dot = strrchr(o->path, '.');
    l->files.obj = dot && strcasecmp(dot, ".obj") == 0;   /* file_import.cpp: by extension */
    if (!file_prescan_gltf(o->path, &l->files.files[0], err, errlen) ||
        !file_prescan_obj(o->path, &l->files.files[0], l->max_triangles, l->max_vertices, err,
                          errlen) ||
        !file_gltf_emissive_strengths(o->path, &l->files.files[0], &l->emissive_strength,
                                      &l->nemissive_strength, err, errlen)) {
        file_loaded_free(l);
        return false;
    }
    struct aiFileIO io = {file_io_open, file_io_close, (char *)&l->files};
    unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                     aiProcess_GenSmoothNormals | aiProcess_SortByPType |
                     aiProcess_ValidateDataStructure | aiProcess_FindDegenerates;
    import_warning[0] = '\0';
    struct aiLogStream stream = {log_fn, NULL};
    aiAttachLogStream(&stream);
    /* drop points and lines after triangulation: shadesweep draws triangles */
    char why[512];
    l->ai = file_import(o->path, flags, &io, aiPrimitiveType_POINT | aiPrimitiveType_LINE, why,
                        sizeof why);
    aiDetachLogStream(&stream);
    bool ok = false;
    const struct aiScene *ai = l->ai;
    if (l->files.err[0]) {   /* a refused file, even where the importer went on */
        scene_fail(err, errlen, "%s: %s", o->path, l->files.err);
        goto out;
    }
    if (l->files.missing[0]) {
        scene_fail(err, errlen, "%s: references %s, which does not exist", o->path,
                   l->files.missing);
        goto out;
    }
    if (ai && import_warning[0]) {
        scene_fail(err, errlen, "%s: indices out of range: %s", o->path, import_warning);
        goto out;
    }
    char cause[256];
    if (!ai) {
        if (why_no_triangles(l, o->path, &io, why, cause, sizeof cause))
            scene_fail(err, errlen, "%s: cannot load: %s", o->path, cause);
        else
            scene_fail(err, errlen, "%s: cannot load: %s", o->path, why);
        goto out;
    }
    if (ai->mFlags & AI_SCENE_FLAGS_INCOMPLETE) {
        scene_fail(err, errlen, "%s: incomplete scene (assimp could not read all of it)", o->path);
        goto out;
    }
    if (!ai->mRootNode || ai->mNumMeshes == 0) {
        if (why_no_triangles(l, o->path, &io, NULL, cause, sizeof cause))
            scene_fail(err, errlen, "%s: cannot load: %s", o->path, cause);
        else
            scene_fail(err, errlen, "%s: empty scene: no triangle meshes", o->path);
        goto out;
    }
    const struct aiNode *path[FILE_MAX_NODE_DEPTH];
    if (!check_nodes(l, ai->mRootNode, 0, path, err, errlen))
        goto out;
    /* the whole file's, for what the pre-scan cannot count (a glTF's accessors) */
    uint64_t total_vertices = 0, total_triangles = 0;
    for (unsigned i = 0; i < ai->mNumMeshes; i++) {
        total_vertices += ai->mMeshes[i]->mNumVertices;
        total_triangles += ai->mMeshes[i]->mNumFaces;
    }
    if (total_triangles > l->max_triangles || total_vertices > l->max_vertices) {
        bool tri = total_triangles > l->max_triangles;
        scene_fail(err, errlen, "%s: %llu %s, more than scene.max_%s %llu", o->path,
                   (unsigned long long)(tri ? total_triangles : total_vertices),
                   tri ? "triangles" : "vertices", tri ? "triangles" : "vertices",
                   (unsigned long long)(tri ? l->max_triangles : l->max_vertices));
        goto out;
    }
    for (unsigned i = 0; i < ai->mNumMeshes; i++) {
        const struct aiMesh *m = ai->mMeshes[i];
        if (!m->mVertices || m->mNumVertices == 0 || m->mNumFaces == 0) {
            scene_fail(err, errlen, "%s: mesh %u ('%s') has no triangles", o->path, i,
                       m->mName.data);
            goto out;
        }
        if (m->mNumVertices > MESH_MAX_VERTICES || m->mNumFaces > MESH_MAX_INDICES / 3) {
            scene_fail(err, errlen,
                       "%s: mesh %u has %u vertices and %u triangles (at most %u and %u)", o->path,
                       i, m->mNumVertices, m->mNumFaces, MESH_MAX_VERTICES, MESH_MAX_INDICES / 3);
            goto out;
        }
        for (unsigned v = 0; v < m->mNumVertices; v++) {
            const struct aiVector3D *q = &m->mVertices[v];
            if (!file_finite3(q)) {
                scene_fail(err, errlen, "%s: mesh %u ('%s'): vertex %u has a position that is not "
                           "finite (%g, %g, %g)", o->path, i, m->mName.data, v, (double)q->x,
                           (double)q->y, (double)q->z);
                goto out;
            }
            /* finite, but past what 32-bit float arithmetic on it survives: the bounds'
             * diagonal (fit's scale) and squared distances overflow to inf or NaN (3e38
             * passed as "zero area" before) */
            if (fabsf(q->x) > FILE_MAX_COORD || fabsf(q->y) > FILE_MAX_COORD ||
                fabsf(q->z) > FILE_MAX_COORD) {
                scene_fail(err, errlen, "%s: mesh %u ('%s'): vertex %u has a position too large "
                           "for 32-bit float arithmetic (%g, %g, %g): at most %g a coordinate",
                           o->path, i, m->mName.data, v, (double)q->x, (double)q->y,
                           (double)q->z, FILE_MAX_COORD);
                goto out;
            }
        }
        for (unsigned f = 0; f < m->mNumFaces; f++) {
            const struct aiFace *fc = &m->mFaces[f];
            if (fc->mNumIndices != 3) {
                scene_fail(err, errlen, "%s: mesh %u: face %u has %u corners after triangulation",
                           o->path, i, f, fc->mNumIndices);
                goto out;
            }
            for (unsigned k = 0; k < 3; k++)
                if (fc->mIndices[k] >= m->mNumVertices) {
                    scene_fail(err, errlen, "%s: mesh %u: index %u out of range (%u vertices)",
                               o->path, i, fc->mIndices[k], m->mNumVertices);
                    goto out;
                }
        }
        if (m->mMaterialIndex >= ai->mNumMaterials) {
            scene_fail(err, errlen, "%s: mesh %u uses material %u of %u", o->path, i,
                       m->mMaterialIndex, ai->mNumMaterials);
            goto out;
        }
    }
    if (!any_area(ai)) {
        scene_fail(err, errlen, "%s: every triangle has zero area (its corners coincide or lie "
                   "on a line): nothing to draw", o->path);
        goto out;
    }
    double t_decode = scene_now_s();
    for (unsigned i = 0; i < ai->mNumMaterials; i++) {
        material_refs r;
        file_material_refs(ai->mMaterials[i], &r);
        const char *refs[5] = {r.diffuse, r.normal, r.emissive, r.mr, r.occlusion};
        for (int k = 0; k < 5; k++)
            if (refs[k][0] && file_load_image(l, refs[k], err, errlen) < 0) {
                *decode_s = scene_now_s() - t_decode;
                goto out;
            }
    }
    *decode_s = scene_now_s() - t_decode;
    if (!file_camera_is(o->camera, "orbit") && !file_camera_is(o->camera, "auto")) {
        bool found = false;
        for (unsigned i = 0; i < ai->mNumCameras && !found; i++)
            found = strcmp(ai->mCameras[i]->mName.data, o->camera) == 0;
        if (!found) {
            char names[512] = "";
            size_t k = 0;
            for (unsigned i = 0; i < ai->mNumCameras && k + 4 < sizeof names; i++)
                k += (size_t)snprintf(names + k, sizeof names - k, "%s'%s'", i ? ", " : "",
                                      ai->mCameras[i]->mName.data);
            scene_fail(err, errlen, "%s: no camera named '%s' (the file has %s%s)", o->path,
                       o->camera, ai->mNumCameras ? "" : "none", names);
            goto out;
        }
    }
    ok = true;
out:
    if (!ok)
        file_loaded_free(l);
    return ok;
}
