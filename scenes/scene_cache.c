/* The scene cache (scene.h): a file scene as its builder made it (meshes, decoded
 * textures, materials, objects, authored lights, camera and bounds), written once by the
 * first trial that loads the file and read by the trials after it, each in its own
 * process. A file: a header (magic, format version, the layout of the structs written,
 * the key, the payload's size and FNV-1a 64 checksum), then the payload. Never trusted:
 * a file that fails any check (or lists files whose bytes changed) is not used, and every
 * count, size and index is checked before it is used, so any bytes are safe to read.
 * Structs go as their bytes (the layout word names their sizes): this is a cache on one
 * machine and one build (the key names the program's file), not an interchange format.
 * Animated scenes are not cached. */
#include "scenes/scene.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "common/fsutil.h"
#include "scenes/scene_build.h"
#include "scenes/scene_internal.h"

#define CACHE_MAGIC "SWSCENE\n"
#define CACHE_VERSION 1u
#define CACHE_MAX_BYTES ((size_t)1 << 35)
#define FNV_BASIS UINT64_C(0xcbf29ce484222325)

typedef struct cache_header {
    char magic[8];
    uint32_t version, layout;
    uint64_t key, payload_size, checksum;
} cache_header;

struct scene_cached {
    scene *s;
    scene_light *authored;
    uint32_t nauthored, ncoverage;
};

/* The sizes of what goes as bytes, and the byte order: a build whose structs differ
 * reads another layout and ignores the file. */
static uint32_t layout(void)
{
    const uint32_t sizes[] = {sizeof(scene), sizeof(mesh), sizeof(mesh_vertex),
                              sizeof(scene_material), sizeof(scene_object),
                              sizeof(scene_light), sizeof(scene_file_info), 0x01020304u};
    return (uint32_t)scene_fnv1a64_more(FNV_BASIS, sizes, sizeof sizes);
}

/* The program's own file (/proc/self/exe) as the file system names it: device, inode,
 * size and modification time. A loader changed without a new format version must not
 * read an older build's scene (a --resume with a rebuilt program, compare's two
 * programs), and every build writes a new file. Hashing the bytes instead costs 20 MB
 * a trial in a sanitizer build. 0 where it cannot be read. */
static uint64_t program_hash(void)
{
    static uint64_t h;
    static bool done;
    if (!done) {
        struct stat st;
        if (stat("/proc/self/exe", &st) == 0) {
            uint64_t id[6] = {(uint64_t)st.st_dev, (uint64_t)st.st_ino, (uint64_t)st.st_size,
                              (uint64_t)st.st_mtim.tv_sec, (uint64_t)st.st_mtim.tv_nsec,
                              (uint64_t)st.st_ctim.tv_nsec};
            h = scene_fnv1a64_more(FNV_BASIS, id, sizeof id);
        }
        done = true;
    }
    return h;
}

static uint64_t key_of(const scene_file_options *o, uint64_t content_hash, int width,
                       int height)
{
    char text[1024];
    snprintf(text, sizeof text,
             "v%u layout %08x program %016llx files %016llx %dx%d scale %a fit %d up %d "
             "camera %s outside %d around %d phong %d max %llu %llu %llu",
             CACHE_VERSION, layout(), (unsigned long long)program_hash(),
             (unsigned long long)content_hash, width, height,
             (double)o->scale, o->fit, (int)o->up, o->camera ? o->camera : "", o->allow_outside,
             o->lights_around, o->phong, (unsigned long long)o->max_image_bytes,
             (unsigned long long)o->max_triangles, (unsigned long long)o->max_vertices);
    return scene_fnv1a64_more(FNV_BASIS, text, strlen(text));
}

void scene_cache_name(const scene_file_options *o, uint64_t content_hash, int width,
                      int height, char out[SCENE_CACHE_NAME_LEN])
{
    snprintf(out, SCENE_CACHE_NAME_LEN, "%016llx.scene",
             (unsigned long long)key_of(o, content_hash, width, height));
}

// >>write

typedef struct writer {
    afile *f;                  /* NULL: the size and checksum only */
    uint64_t size, checksum;
    bool ok;
} writer;

static void put(writer *w, const void *data, size_t n)
{
    if (!n || !w->ok)
        return;
    if (w->f)
        w->ok = afile_write(w->f, data, n);
    w->size += n;
    w->checksum = scene_fnv1a64_more(w->checksum, data, n);
}

static void put_u32(writer *w, uint32_t v)
{
    put(w, &v, sizeof v);
}

static void put_payload(writer *w, const scene_cache_store *to, const scene_builder *b)
{
    const scene *s = b->s;
    put_u32(w, to->files->n);
    for (uint32_t i = 0; i < to->files->n; i++) {
        uint32_t n = (uint32_t)strlen(to->files->path[i]);
        put_u32(w, n);
        put(w, to->files->path[i], n);
    }
    put(w, to->info, sizeof *to->info);
    scene head = *s;
    head.meshes = NULL;
    head.textures = NULL;
    head.materials = NULL;
    head.objects = NULL;
    head.lights = NULL;
    head.anim = NULL;
    put(w, &head, sizeof head);
    for (uint32_t i = 0; i < s->nmeshes; i++) {
        mesh m = s->meshes[i];
        put_u32(w, (m.colors ? 1u : 0u) | (m.uv2 ? 2u : 0u));
        const mesh_vertex *v = m.vertices;
        const uint32_t *c = m.colors, *idx = m.indices;
        const float(*uv2)[2] = m.uv2;
        m.vertices = NULL;
        m.colors = NULL;
        m.uv2 = NULL;
        m.indices = NULL;
        put(w, &m, sizeof m);
        put(w, v, (size_t)m.nvertices * sizeof *v);
        if (c)
            put(w, c, (size_t)m.nvertices * sizeof *c);
        if (uv2)
            put(w, uv2, (size_t)m.nvertices * sizeof *uv2);
        put(w, idx, (size_t)m.nindices * sizeof *idx);
    }
    for (uint32_t i = 0; i < s->ntextures; i++) {
        const texture_image *t = &s->textures[i];
        const uint32_t dims[3] = {t->width, t->height, t->channels};
        put(w, dims, sizeof dims);
        put(w, t->data, (size_t)t->width * t->height * t->channels);
    }
    put(w, s->materials, (size_t)s->nmaterials * sizeof *s->materials);
    put(w, s->objects, (size_t)s->nobjects * sizeof *s->objects);
    const uint32_t lights[2] = {b->nauthored, b->ncoverage};
    put(w, lights, sizeof lights);
    put(w, b->authored, (size_t)b->nauthored * sizeof *b->authored);
}

static void write_file(scene_cache_store *to, const scene_builder *b);

void scene_cache_write(scene_cache_store *to, const scene_builder *b)
{
    double t0 = scene_now_s();
    write_file(to, b);
    to->write_s = scene_now_s() - t0;
}

static void write_file(scene_cache_store *to, const scene_builder *b)
{
    to->written = false;
    to->note[0] = '\0';
    if ((to->animated = b->s->anim != NULL))
        return;
    /* the payload twice: its size and checksum for the header, then its bytes */
    writer dry = {.checksum = FNV_BASIS, .ok = true};
    put_payload(&dry, to, b);
    cache_header h = {.version = CACHE_VERSION, .layout = layout(), .payload_size = dry.size,
                      .checksum = dry.checksum};
    memcpy(h.magic, CACHE_MAGIC, sizeof h.magic);
    h.key = key_of(to->o, to->content_hash, b->s->width, b->s->height);
    afile f;
    char why[512];
    if (!afile_open(&f, to->path, why, sizeof why)) {
        snprintf(to->note, sizeof to->note, "not cached: %s", why);
        return;
    }
    writer w = {.f = &f, .checksum = FNV_BASIS, .ok = afile_write(&f, &h, sizeof h)};
    put_payload(&w, to, b);
    /* afile_commit says why a write failed; a scene that changed between the passes
     * (it cannot) would leave a file whose checksum fails when read */
    if (!afile_commit(&f, why, sizeof why)) {
        snprintf(to->note, sizeof to->note, "not cached: %s", why);
        return;
    }
    to->written = true;
}

// >>read

typedef struct reader {
    const unsigned char *p;
    size_t left;
    bool bad;
} reader;

static bool take(reader *r, void *out, size_t n)
{
    if (r->bad || n > r->left) {
        r->bad = true;
        if (out && n)
            memset(out, 0, n);
        return false;
    }
    if (n)
        memcpy(out, r->p, n);
    r->p += n;
    r->left -= n;
    return true;
}

/* count items of size bytes, malloc'd (NULL for none; NULL and r->bad when the file holds
 * fewer bytes than that). */
static void *take_array(reader *r, uint64_t count, size_t size)
{
    if (r->bad || count == 0)
        return NULL;
    if (count > r->left / size) {
        r->bad = true;
        return NULL;
    }
    void *a = malloc((size_t)count * size);
    if (!a) {
        r->bad = true;
        return NULL;
    }
    take(r, a, (size_t)count * size);
    return a;
}

/* A bool read as bytes holds 0 or 1 (anything else is not a bool to load). */
static bool is_bool(const void *field)
{
    unsigned char c;
    memcpy(&c, field, 1);
    return c <= 1;
}

static bool read_meshes(reader *r, scene *s)
{
    if (s->nmeshes == 0 || s->nmeshes > r->left / sizeof(mesh) ||
        !(s->meshes = calloc(s->nmeshes, sizeof *s->meshes)))
        return false;
    for (uint32_t i = 0; i < s->nmeshes; i++) {
        uint32_t flags;
        mesh m;
        if (!take(r, &flags, sizeof flags) || flags > 3 || !take(r, &m, sizeof m) ||
            !is_bool(&m.deforms) || m.nvertices == 0 || m.nvertices > MESH_MAX_VERTICES ||
            m.nindices == 0 || m.nindices % 3 || m.nindices > MESH_MAX_INDICES)
            return false;
        mesh *d = &s->meshes[i];
        *d = m;
        d->vertices = NULL;   /* the pointers read are not ours */
        d->colors = NULL;
        d->uv2 = NULL;
        d->joints = NULL;
        d->weights = NULL;
        d->indices = NULL;
        d->vertices = take_array(r, m.nvertices, sizeof *d->vertices);
        if (flags & 1)
            d->colors = take_array(r, m.nvertices, sizeof *d->colors);
        if (flags & 2)
            d->uv2 = take_array(r, m.nvertices, sizeof *d->uv2);
        d->indices = take_array(r, m.nindices, sizeof *d->indices);
        if (r->bad)
            return false;
        for (uint32_t k = 0; k < m.nindices; k++)
            if (d->indices[k] >= m.nvertices)
                return false;
    }
    return true;
}

static bool read_textures(reader *r, scene *s)
{
    if (s->ntextures > r->left / 12 ||
        (s->ntextures && !(s->textures = calloc(s->ntextures, sizeof *s->textures))))
        return false;
    for (uint32_t i = 0; i < s->ntextures; i++) {
        uint32_t d[3];
        if (!take(r, d, sizeof d) || d[0] == 0 || d[1] == 0 || d[0] > 65536 || d[1] > 65536 ||
            (d[2] != 1 && d[2] != 4))
            return false;
        texture_image *t = &s->textures[i];
        t->data = take_array(r, (uint64_t)d[0] * d[1] * d[2], 1);
        if (r->bad)
            return false;
        t->width = d[0];
        t->height = d[1];
        t->channels = d[2];
    }
    return true;
}

static bool map_ok(int m, uint32_t n)
{
    return m >= -1 && (m < 0 || (uint32_t)m < n);
}

static bool read_tables(reader *r, scene_cached *c)
{
    scene *s = c->s;
    s->materials = take_array(r, s->nmaterials, sizeof *s->materials);
    s->objects = take_array(r, s->nobjects, sizeof *s->objects);
    uint32_t lights[2];
    take(r, lights, sizeof lights);
    c->authored = take_array(r, lights[0], sizeof *c->authored);
    if (r->bad || !s->nmaterials || !s->nobjects || lights[1] > lights[0])
        return false;
    c->nauthored = lights[0];
    c->ncoverage = lights[1];
    for (uint32_t i = 0; i < s->nmaterials; i++) {
        const scene_material *m = &s->materials[i];
        if (!map_ok(m->diffuse_map, s->ntextures) || !map_ok(m->gloss_map, s->ntextures) ||
            !map_ok(m->normal_map, s->ntextures) || !map_ok(m->emissive_map, s->ntextures) ||
            !map_ok(m->orm_map, s->ntextures) || (unsigned)m->alpha > MATERIAL_BLEND ||
            m->uv1_maps > 15 || !is_bool(&m->double_sided))
            return false;
    }
    for (uint32_t i = 0; i < s->nobjects; i++) {
        const scene_object *o = &s->objects[i];
        if (o->mesh >= s->nmeshes || o->material >= s->nmaterials || o->anim_node != 0 ||
            !is_bool(&o->anim_mirror))
            return false;
    }
    for (uint32_t i = 0; i < c->nauthored; i++) {
        const scene_light *l = &c->authored[i];
        if ((unsigned)l->type > LIGHT_DIRECTIONAL ||
            (unsigned)l->attenuation > ATTENUATION_WINDOWED || !is_bool(&l->shadows))
            return false;
    }
    return r->left == 0;
}

/* The payload's scene after its file list and info; false for anything out of range. */
static bool read_scene(reader *r, scene_cached *c)
{
    scene head;
    if (!take(r, &head, sizeof head))
        return false;
    if (!is_bool(&head.from_file) || !is_bool(&head.lights_outside) || !is_bool(&head.sky) ||
        !is_bool(&head.file_camera) || !is_bool(&head.display.exposed) ||
        !is_bool(&head.count.growth) || (unsigned)head.shading > SHADING_PBR ||
        (unsigned)head.environment > ENVIRONMENT_SKY || (unsigned)head.path > CAMERA_SCRIPTED ||
        (unsigned)head.display.tonemap > TONEMAP_PBR_NEUTRAL || head.nkeys > 8)
        return false;
    if (!(c->s = calloc(1, sizeof *c->s)))
        return false;
    *c->s = head;
    scene *s = c->s;
    s->meshes = NULL;
    s->textures = NULL;
    s->materials = NULL;
    s->objects = NULL;
    s->lights = NULL;
    s->anim = NULL;
    s->name[sizeof s->name - 1] = '\0';
    s->nlights_total = 0;
    /* scene_destroy frees what was allocated when a check fails half-way */
    return read_meshes(r, s) && read_textures(r, s) && read_tables(r, c);
}

/* Whether the files listed (each path's bytes read again) hash to content_hash. */
static bool files_hold(reader *r, uint64_t content_hash, char *note, size_t notelen)
{
    uint32_t n;
    if (!take(r, &n, sizeof n) || n == 0 || n > r->left / 4)
        return false;
    uint64_t h = FNV_BASIS;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t len;
        char path[4200];
        if (!take(r, &len, sizeof len) || len == 0 || len >= sizeof path ||
            !take(r, path, len))
            return false;
        path[len] = '\0';
        size_t size;
        int e;
        const char *kind = NULL;
        char *data = fs_read_regular(path, (size_t)1 << 31, &size, &e, &kind);
        if (!data) {
            snprintf(note, notelen, "%.400s, which it was made from, cannot be read", path);
            return false;
        }
        h = scene_file_hash_more(h, data, size);
        free(data);
    }
    if (h != content_hash) {
        snprintf(note, notelen, "the files it was made from have changed");
        return false;
    }
    return true;
}

scene_cached *scene_cache_read(const char *path, const scene_file_options *o,
                               uint64_t content_hash, int width, int height,
                               scene_file_info *info, char *note, size_t notelen)
{
    note[0] = '\0';
    size_t size;
    int e;
    const char *kind = NULL;
    unsigned char *data = (unsigned char *)fs_read_regular(path, CACHE_MAX_BYTES, &size, &e,
                                                           &kind);
    if (!data) {
        if (kind || e != ENOENT)
            snprintf(note, notelen, "%s: ignored: %s", path,
                     kind ? kind : "cannot be read");
        return NULL;
    }
    cache_header h;
    reader r = {data, size, false};
    const char *why = NULL;
    char what[512] = "";
    scene_cached *c = NULL;
    if (!take(&r, &h, sizeof h) || memcmp(h.magic, CACHE_MAGIC, sizeof h.magic) != 0)
        why = "not a shadesweep scene cache (bad magic)";
    else if (h.version != CACHE_VERSION || h.layout != layout())
        why = "written by another version of shadesweep";
    else if (h.payload_size != r.left)
        why = "truncated or grown (its size is not the header's)";
    else if (h.checksum != scene_fnv1a64_more(FNV_BASIS, r.p, r.left))
        why = "corrupt (its checksum does not match)";
    else if (h.key != key_of(o, content_hash, width, height))
        why = "made for another scene or options (its key does not match)";
    else if (!files_hold(&r, content_hash, what, sizeof what))
        why = what[0] ? what : "its list of files is malformed";
    else if (!take(&r, info, sizeof *info) || info->hash != content_hash)
        why = "its scene information is malformed";
    else if (!(c = calloc(1, sizeof *c)) || !read_scene(&r, c))
        why = "its scene is malformed";
    free(data);
    if (why) {
        scene_cached_free(c);
        snprintf(note, notelen, "%s: ignored: %s", path, why);
        return NULL;
    }
    info->view[sizeof info->view - 1] = '\0';
    if (info->nnot_rendered > SCENE_FILE_MAX_NOT_RENDERED)
        info->nnot_rendered = SCENE_FILE_MAX_NOT_RENDERED;
    for (uint32_t i = 0; i < SCENE_FILE_MAX_NOT_RENDERED; i++)
        info->not_rendered[i][sizeof info->not_rendered[i] - 1] = '\0';
    return c;
}

void scene_cached_free(scene_cached *c)
{
    if (!c)
        return;
    scene_destroy(c->s);
    free(c->authored);
    free(c);
}

scene_builder *scene_cached_take(scene_cached *c, char *err, size_t errlen)
{
    scene_builder *b = calloc(1, sizeof *b);
    if (!b) {
        snprintf(err, errlen, "out of memory building scene '%s'", c->s->name);
        scene_cached_free(c);
        return NULL;
    }
    b->s = c->s;
    b->authored = c->authored;
    b->nauthored = c->nauthored;
    b->ncoverage = c->ncoverage;
    free(c);
    return b;
}
