/* File scenes through assimp's C API: glTF 2.0 (.gltf + .bin + images, .glb, embedded
 * data URIs), OBJ + MTL, and whatever else assimp reads. No GL in here; textures decode
 * through OpenImageIO (results/image_io.h).
 *
 * Every byte assimp reads goes through our own file callbacks (>>io), which read each
 * file whole, once, and feed it to the content hash; images the materials reference
 * are read the same way before they are decoded. scene_file_check and the builder share
 * one loader (>>load), so what validate accepts is exactly what a run builds.
 *
 * Mapping onto the Phong model (docs/architecture.md, "File scenes"):
 *   diffuse    base colour factor (glTF) or Kd (OBJ), times the base colour / diffuse map
 *   specular   metallic-roughness: F0 = mix(0.04, luminance(base colour), metallic);
 *              specular-glossiness and Phong: luminance of the specular colour
 *   shininess  glTF: from roughness (1 - glossiness) as the Blinn-Phong exponent that
 *              matches GGX's alpha = roughness^2, n = 2 / alpha^2 - 2, clamped to
 *              [1, 2048]; OBJ: Ns (0 counts as 1)
 *   normal map the normal texture, tangents from our own mesh_compute_tangents
 *   emissive   the emissive factor times the emissive map (mask alpha = 1)
 *   alpha      MASK -> MATERIAL_MASK with the cutoff; BLEND -> MATERIAL_BLEND (translucent,
 *              opacity: assimp's opacity, else the base colour's alpha)
 * Untrusted input: only regular files are opened, references stay in the scene file's
 * folder (unless allow_outside), and glTF JSON is pre-scanned before assimp (>>prescan).
 * Sections: >>io >>prescan >>load >>check >>materials >>nodes >>build */
#define _DEFAULT_SOURCE   /* realpath */
#include "scenes/scene.h"

#include <assimp/GltfMaterial.h>
#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "results/grow.h"
#include "results/image_io.h"
#include "scenes/scene_build.h"
#include "scenes/scene_fail.h"

/* Limits on what a file may ask for before anything is allocated for it. */
#define FILE_MAX_BYTES ((size_t)1 << 31)      /* one file, buffer or image: 2 GiB */
#define FILE_MAX_NODE_DEPTH 256u

// >>io

/* FNV-1a 64, the same function as runner/hash.h (scenes/ cannot reach runner/). */
/* assimp's aiGetMaterialFloat is a C99 `inline` function with no external definition: an
 * unoptimised build (the sanitizer suite's -O0) would not link. The array form is a real
 * export. */
static enum aiReturn mat_float(const struct aiMaterial *m, const char *key, unsigned type,
                               unsigned index, float *out)
{
    return aiGetMaterialFloatArray(m, key, type, index, out, NULL);
}

static uint64_t fnv1a64_more(uint64_t h, const void *data, size_t len)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < len; i++) {
        h ^= p[i];
        h *= UINT64_C(0x100000001b3);
    }
    return h;
}

typedef struct read_file {
    char *path;
    unsigned char *data;
    size_t size;
} read_file;

/* Every file read for one load, in first-read order, each once. */
typedef struct file_set {
    read_file *files;
    uint32_t n;
    size_t cap;
    char err[3 * PATH_MAX + 256]; /* the first read failure that is not "no such file" */
    char missing[PATH_MAX];         /* the first referenced file that does not exist */
    char root[PATH_MAX];       /* referenced files must resolve inside it; "" while the
                                * scene file itself is read */
    bool allow_outside;        /* scene.allow_outside: no containment */
    struct aiFile **open;      /* assimp's files not closed yet (an importer that
                                * throws forgets its streams) */
    uint32_t nopen;
    size_t cap_open;
} file_set;

static void file_set_free(file_set *fs)
{
    for (uint32_t i = 0; i < fs->n; i++) {
        free(fs->files[i].path);
        free(fs->files[i].data);
    }
    free(fs->files);
    for (uint32_t i = 0; i < fs->nopen; i++) {
        free(fs->open[i]->UserData);
        free(fs->open[i]);
    }
    free(fs->open);
    memset(fs, 0, sizeof *fs);
}

static const char *file_kind(mode_t m)
{
    return S_ISDIR(m) ? "a directory" : S_ISFIFO(m) ? "a FIFO" : S_ISSOCK(m) ? "a socket"
         : S_ISCHR(m) ? "a character device" : S_ISBLK(m) ? "a block device"
         : "not a regular file";
}

/* A reference that names a URL (scheme://...): only local files are read. */
static bool is_url(const char *p)
{
    const char *c = strstr(p, "://");
    if (!c || c == p)
        return false;
    for (const char *q = p; q < c; q++)
        if (!(isalnum((unsigned char)*q) || *q == '+' || *q == '-' || *q == '.'))
            return false;
    return true;
}

/* The file's bytes (read once, then served from memory), or NULL with fs->err set for
 * anything but a file that does not exist (errno ENOENT then). Only regular files are
 * opened (a FIFO would block, a device never end); a file the scene references must
 * resolve (symlinks, "..") inside fs->root unless fs->allow_outside. */
static const read_file *file_get(file_set *fs, const char *path)
{
    for (uint32_t i = 0; i < fs->n; i++)
        if (strcmp(fs->files[i].path, path) == 0)
            return &fs->files[i];
    const char *open_path = path;
    char real[PATH_MAX];
    if (fs->root[0]) {
        /* a URL inside a path: assimp prefixes the scene's folder */
        if (strstr(path, "://")) {
            snprintf(fs->err, sizeof fs->err, "%s: a URL: only local files are read", path);
            errno = EACCES;
            return NULL;
        }
        if (!realpath(path, real)) {
            if (errno != ENOENT) {
                snprintf(fs->err, sizeof fs->err, "%s: cannot open: %s", path, strerror(errno));
                errno = EIO;
            }
            return NULL;   /* errno ENOENT: a missing file */
        }
        size_t n = strlen(fs->root);
        if (!fs->allow_outside && !(strncmp(real, fs->root, n) == 0 &&
                                    (real[n] == '/' || (n == 1 && fs->root[0] == '/')))) {
            snprintf(fs->err, sizeof fs->err, "%s: resolves to %s, outside the scene file's "
                     "folder %s (scene.allow_outside: true permits it)", path, real, fs->root);
            errno = EACCES;
            return NULL;
        }
        open_path = real;
    }
    struct stat st, fst;
    if (stat(open_path, &st) != 0)
        return NULL;
    if (!S_ISREG(st.st_mode)) {
        snprintf(fs->err, sizeof fs->err, "%s: %s, not a regular file", path,
                 file_kind(st.st_mode));
        errno = EINVAL;
        return NULL;
    }
    int fd = open(open_path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC |
                                 (fs->root[0] ? O_NOFOLLOW : 0));
    if (fd < 0) {
        snprintf(fs->err, sizeof fs->err, "%s: cannot open: %s", path, strerror(errno));
        errno = EIO;
        return NULL;
    }
    if (fstat(fd, &fst) != 0 || !S_ISREG(fst.st_mode) || fst.st_dev != st.st_dev ||
        fst.st_ino != st.st_ino) {
        snprintf(fs->err, sizeof fs->err, "%s: changed while opened (now %s)", path,
                 file_kind(fst.st_mode));
        close(fd);
        errno = EIO;
        return NULL;
    }
    if ((uint64_t)fst.st_size > FILE_MAX_BYTES) {
        snprintf(fs->err, sizeof fs->err, "%s: %lld bytes, more than the 2 GiB a file may have",
                 path, (long long)fst.st_size);
        close(fd);
        errno = EFBIG;
        return NULL;
    }
    read_file r = {0};
    r.size = (size_t)fst.st_size;
    r.data = malloc(r.size + 1);   /* NUL-terminated: the JSON scan may use strtoul */
    r.path = strdup(path);
    if (!r.data || !r.path || !GROW(fs->files, fs->cap, (size_t)fs->n + 1, 8)) {
        snprintf(fs->err, sizeof fs->err, "%s: out of memory reading %zu bytes", path, r.size);
        free(r.data);
        free(r.path);
        close(fd);
        errno = ENOMEM;
        return NULL;
    }
    size_t got = 0;
    while (got < r.size) {
        ssize_t k = read(fd, r.data + got, r.size - got);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0) {
            snprintf(fs->err, sizeof fs->err, "%s: cannot read: %s", path,
                     k < 0 ? strerror(errno) : "file shrank while read");
            free(r.data);
            free(r.path);
            close(fd);
            errno = EIO;
            return NULL;
        }
        got += (size_t)k;
    }
    close(fd);
    r.data[r.size] = '\0';
    fs->files[fs->n] = r;
    return &fs->files[fs->n++];
}

/* assimp's view of one open file: a cursor over the bytes in the file_set. */
typedef struct open_file {
    const read_file *f;
    size_t pos;
} open_file;

static size_t io_read(struct aiFile *af, char *buf, size_t size, size_t count)
{
    open_file *o = (open_file *)af->UserData;
    if (size == 0 || o->pos >= o->f->size)
        return 0;
    size_t n = (o->f->size - o->pos) / size;
    if (n > count)
        n = count;
    memcpy(buf, o->f->data + o->pos, n * size);
    o->pos += n * size;
    return n;
}

static size_t io_write(struct aiFile *af, const char *buf, size_t size, size_t count)
{
    return 0;   /* loading never writes */
}

static size_t io_tell(struct aiFile *af) { return ((open_file *)af->UserData)->pos; }

static size_t io_size(struct aiFile *af) { return ((open_file *)af->UserData)->f->size; }

static void io_flush(struct aiFile *af) {}

static enum aiReturn io_seek(struct aiFile *af, size_t off, enum aiOrigin origin)
{
    open_file *o = (open_file *)af->UserData;
    size_t base = origin == aiOrigin_SET ? 0 : origin == aiOrigin_CUR ? o->pos : o->f->size;
    if (off > o->f->size || base > o->f->size - off)
        return aiReturn_FAILURE;
    o->pos = base + off;
    return aiReturn_SUCCESS;
}

static struct aiFile *io_open(struct aiFileIO *io, const char *path, const char *mode)
{
    file_set *fs = (file_set *)io->UserData;
    if (strchr(mode, 'w') || strchr(mode, 'a'))
        return NULL;
    errno = 0;
    const read_file *f = file_get(fs, path);
    if (!f) {
        if (!fs->err[0] && !fs->missing[0] && fs->n > 0)
            snprintf(fs->missing, sizeof fs->missing, "%s", path);
        return NULL;
    }
    if (!GROW(fs->open, fs->cap_open, (size_t)fs->nopen + 1, 8))
        return NULL;
    struct aiFile *af = calloc(1, sizeof *af);
    open_file *o = calloc(1, sizeof *o);
    if (!af || !o) {
        free(af);
        free(o);
        return NULL;
    }
    o->f = f;
    af->ReadProc = io_read;
    af->WriteProc = io_write;
    af->TellProc = io_tell;
    af->FileSizeProc = io_size;
    af->SeekProc = io_seek;
    af->FlushProc = io_flush;
    af->UserData = (char *)o;
    fs->open[fs->nopen++] = af;
    return af;
}

static void io_close(struct aiFileIO *io, struct aiFile *af)
{
    file_set *fs = (file_set *)io->UserData;
    if (!af)
        return;
    for (uint32_t i = 0; i < fs->nopen; i++)
        if (fs->open[i] == af) {
            fs->open[i] = fs->open[--fs->nopen];
            break;
        }
    free(af->UserData);
    free(af);
}

// >>prescan


/* glTF's JSON read before assimp sees it, for what would hurt inside the importer:
 * nesting deeper than its recursive parser's stack (JSON_MAX_NESTING), a node hierarchy
 * deeper than FILE_MAX_NODE_DEPTH or recursing (assimp recurses per level before our
 * check_nodes could run), and URLs as buffer or image uris (assimp would read a local
 * file of the same name). Malformed JSON is left to assimp to report. Iterative: no
 * input can make this recurse. */
#define JSON_MAX_NESTING 64u

typedef struct jscan {
    const char *p, *end;
    bool bad;                  /* malformed: stop, assimp reports it */
} jscan;

static void js_ws(jscan *j)
{
    while (j->p < j->end && (*j->p == ' ' || *j->p == '\t' || *j->p == '\n' || *j->p == '\r'))
        j->p++;
}

static bool js_lit(jscan *j, char c)
{
    js_ws(j);
    if (j->p < j->end && *j->p == c) {
        j->p++;
        return true;
    }
    return false;
}

/* A string's raw bytes (escapes left in), *s and *n; false if not a string. */
static bool js_string(jscan *j, const char **s, size_t *n)
{
    js_ws(j);
    if (j->p >= j->end || *j->p != '"')
        return j->bad = true, false;
    const char *b = ++j->p;
    while (j->p < j->end && *j->p != '"')
        j->p += *j->p == '\\' ? 2 : 1;
    if (j->p >= j->end)
        return j->bad = true, false;
    *s = b;
    *n = (size_t)(j->p - b);
    j->p++;
    return true;
}

/* Skips one value of any kind; false when malformed or nested too deep (*deep). */
static bool js_skip(jscan *j, unsigned depth, bool *deep)
{
    js_ws(j);
    unsigned d = 0;
    do {
        js_ws(j);
        if (j->p >= j->end)
            return j->bad = true, false;
        char c = *j->p;
        if (c == '"') {
            const char *s;
            size_t n;
            if (!js_string(j, &s, &n))
                return false;
        } else if (c == '{' || c == '[') {
            if (depth + ++d > JSON_MAX_NESTING)
                return *deep = true, false;
            j->p++;
            continue;
        } else if (c == '}' || c == ']') {
            if (d == 0)
                return j->bad = true, false;
            d--;
            j->p++;
        } else if (c == ',' || c == ':') {
            j->p++;
            continue;
        } else {
            const char *b = j->p;
            while (j->p < j->end && !strchr(",:]}\" \t\r\n{[", *j->p))
                j->p++;
            if (j->p == b)
                return j->bad = true, false;
        }
        /* a complete value at level d: inside a container, go on with its next item */
    } while (d > 0);
    return true;
}

static bool key_is(const char *s, size_t n, const char *k)
{
    return n == strlen(k) && memcmp(s, k, n) == 0;
}

typedef struct node_graph {
    uint32_t nnodes;
    uint32_t *edge_from, *edge_to;
    size_t nedges, cap_from, cap_to;
    char url[256];             /* the first buffer or image uri that is a URL */
    char absolute[256];        /* the first that is an absolute path */
    bool deep;                 /* JSON nested deeper than JSON_MAX_NESTING */
} node_graph;

static bool ng_edge(node_graph *g, uint32_t from, uint32_t to)
{
    if (!GROW(g->edge_from, g->cap_from, g->nedges + 1, 64) ||
        !GROW(g->edge_to, g->cap_to, g->nedges + 1, 64))
        return false;
    g->edge_from[g->nedges] = from;
    g->edge_to[g->nedges++] = to;
    return true;
}

/* Top-level "nodes" (children lists), "buffers" and "images" (uris); the rest skipped. */
static bool js_gltf(jscan *j, node_graph *g)
{
    if (!js_lit(j, '{'))
        return false;
    if (js_lit(j, '}'))
        return true;
    do {
        const char *k;
        size_t kn;
        if (!js_string(j, &k, &kn) || !js_lit(j, ':'))
            return false;
        bool nodes = key_is(k, kn, "nodes");
        bool uris = key_is(k, kn, "buffers") || key_is(k, kn, "images");
        if (!nodes && !uris) {
            if (!js_skip(j, 1, &g->deep))
                return false;
            continue;
        }
        if (!js_lit(j, '['))
            return false;
        if (js_lit(j, ']'))
            continue;
        do {   /* one node, buffer or image */
            uint32_t self = g->nnodes;
            if (nodes)
                g->nnodes++;
            if (!js_lit(j, '{'))
                return false;
            if (js_lit(j, '}'))
                continue;
            do {
                const char *f;
                size_t fn;
                if (!js_string(j, &f, &fn) || !js_lit(j, ':'))
                    return false;
                if (nodes && key_is(f, fn, "children")) {
                    if (!js_lit(j, '['))
                        return false;
                    if (js_lit(j, ']'))
                        continue;
                    do {
                        js_ws(j);
                        char *e;
                        unsigned long c = strtoul(j->p, &e, 10);
                        if (e == j->p || e > j->end || c > UINT32_MAX)
                            return false;   /* assimp says what is wrong */
                        j->p = e;
                        if (!ng_edge(g, self, (uint32_t)c))
                            return false;
                    } while (js_lit(j, ','));
                    if (!js_lit(j, ']'))
                        return false;
                } else if (uris && key_is(f, fn, "uri")) {
                    const char *u;
                    size_t un;
                    if (!js_string(j, &u, &un))
                        return false;
                    char buf[256];
                    snprintf(buf, sizeof buf, "%.*s", (int)(un < 255 ? un : 255), u);
                    if (!g->url[0] && is_url(buf))
                        snprintf(g->url, sizeof g->url, "%s", buf);
                    if (!g->absolute[0] && buf[0] == '/')
                        snprintf(g->absolute, sizeof g->absolute, "%s", buf);
                } else if (!js_skip(j, 3, &g->deep)) {
                    return false;
                }
            } while (js_lit(j, ','));
            if (!js_lit(j, '}'))
                return false;
        } while (js_lit(j, ','));
        if (!js_lit(j, ']'))
            return false;
    } while (js_lit(j, ','));
    return js_lit(j, '}');
}

/* Longest chain of nodes below any node (1 for a leaf), iteratively; UINT32_MAX if the
 * hierarchy recurses (*cycle: a node on it). */
static uint32_t ng_height(const node_graph *g, uint32_t *cycle, bool *oom)
{
    uint32_t n = g->nnodes, best = 0;
    uint32_t *first = calloc((size_t)n + 1, sizeof *first);
    uint32_t *adj = malloc((g->nedges ? g->nedges : 1) * sizeof *adj);
    uint32_t *height = calloc(n ? n : 1, sizeof *height);
    unsigned char *state = calloc(n ? n : 1, 1);   /* 0 new, 1 on the path, 2 done */
    uint32_t *stack = malloc((n ? n : 1) * sizeof *stack);
    uint32_t *next = malloc((n ? n : 1) * sizeof *next);
    if (!first || !adj || !height || !state || !stack || !next) {
        *oom = true;
        goto out;
    }
    for (size_t e = 0; e < g->nedges; e++)
        if (g->edge_from[e] < n && g->edge_to[e] < n)
            first[g->edge_from[e] + 1]++;
    for (uint32_t i = 0; i < n; i++)
        first[i + 1] += first[i];
    uint32_t *fill = calloc(n ? n : 1, sizeof *fill);
    if (!fill) {
        *oom = true;
        goto out;
    }
    for (size_t e = 0; e < g->nedges; e++) {
        uint32_t a = g->edge_from[e], b = g->edge_to[e];
        if (a < n && b < n)
            adj[first[a] + fill[a]++] = b;
    }
    free(fill);
    for (uint32_t r = 0; r < n && best != UINT32_MAX; r++) {
        if (state[r])
            continue;
        uint32_t sp = 0;
        stack[sp] = r;
        next[sp++] = first[r];
        state[r] = 1;
        while (sp > 0) {
            uint32_t v = stack[sp - 1];
            if (next[sp - 1] < first[v + 1]) {
                uint32_t c = adj[next[sp - 1]++];
                if (state[c] == 1) {
                    *cycle = c;
                    best = UINT32_MAX;
                    break;
                }
                if (state[c] == 0) {
                    state[c] = 1;
                    stack[sp] = c;
                    next[sp++] = first[c];
                }
                continue;
            }
            uint32_t h = 0;
            for (uint32_t e = first[v]; e < first[v + 1]; e++)
                if (height[adj[e]] > h)
                    h = height[adj[e]];
            height[v] = h + 1;
            if (height[v] > best)
                best = height[v];
            state[v] = 2;
            sp--;
        }
    }
out:
    free(first);
    free(adj);
    free(height);
    free(state);
    free(stack);
    free(next);
    return best;
}

/* The deepest nesting of arrays and objects anywhere in the JSON, whatever its shape
 * (js_gltf stops at the first thing it does not expect; assimp's parser would go on). */
static uint32_t js_max_nesting(const char *p, size_t n)
{
    uint32_t d = 0, best = 0;
    bool str = false;
    for (size_t i = 0; i < n; i++) {
        char c = p[i];
        if (str) {
            if (c == '\\')
                i++;
            else if (c == '"')
                str = false;
        } else if (c == '"') {
            str = true;
        } else if (c == '{' || c == '[') {
            if (++d > best)
                best = d;
        } else if ((c == '}' || c == ']') && d > 0) {
            d--;
        }
    }
    return best;
}

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The JSON of a .gltf, or of a .glb's first chunk; false if the bytes are neither. */
static bool gltf_json(const read_file *f, const char **json, size_t *n)
{
    const unsigned char *d = f->data;
    if (f->size >= 20 && memcmp(d, "glTF", 4) == 0) {
        uint32_t len = le32(d + 12);
        if (memcmp(d + 16, "JSON", 4) != 0)
            return false;
        *json = (const char *)d + 20;
        *n = len < f->size - 20 ? len : f->size - 20;
        return true;
    }
    size_t i = 0;
    if (f->size >= 3 && memcmp(d, "\xEF\xBB\xBF", 3) == 0)
        i = 3;   /* a UTF-8 byte order mark */
    while (i < f->size && strchr(" \t\r\n", d[i]) && d[i])
        i++;
    if (i >= f->size || d[i] != '{')
        return false;
    *json = (const char *)d + i;
    *n = f->size - i;
    return true;
}

/* A .glb's header and chunk lengths against the file's size: assimp allocates (and
 * clears) what they claim before it finds the file shorter. */
static bool glb_lengths(const char *path, const read_file *f, char *err, size_t errlen)
{
    const unsigned char *d = f->data;
    if (f->size < 12 || memcmp(d, "glTF", 4) != 0)
        return true;
    uint32_t total = le32(d + 8);
    if (total > f->size)
        return scene_fail(err, errlen, "%s: the GLB header claims %u bytes, the file has %zu", path,
                          total, f->size);
    size_t at = 12;
    for (int k = 0; k < 2 && at + 8 <= f->size; k++) {
        uint64_t len = le32(d + at);
        if (len > f->size - at - 8)
            return scene_fail(err, errlen, "%s: GLB chunk %d claims %llu bytes, %zu follow it",
                              path, k, (unsigned long long)len, f->size - at - 8);
        at += 8 + (size_t)((len + 3) & ~(uint64_t)3);
    }
    return true;
}

/* False with a message naming the file when its glTF JSON asks for what would hurt. */
static bool prescan_gltf(const char *path, const read_file *f, char *err, size_t errlen)
{
    const char *json;
    size_t n;
    if (!glb_lengths(path, f, err, errlen))
        return false;
    if (!gltf_json(f, &json, &n))
        return true;
    jscan j = {json, json + n, false};
    node_graph g = {0};
    bool deep = js_max_nesting(json, n) > JSON_MAX_NESTING;
    bool parsed = !deep && js_gltf(&j, &g);
    bool ok = true;
    if (deep || g.deep) {
        ok = scene_fail(err, errlen, "%s: JSON nested more than %u deep", path, JSON_MAX_NESTING);
    } else if (g.url[0]) {
        ok = scene_fail(err, errlen, "%s: uri '%s' is a URL: only local files are read", path,
                        g.url);
    } else if (g.absolute[0]) {
        ok = scene_fail(err, errlen, "%s: uri '%s' is an absolute path: a uri is relative to the "
                        "file's folder", path, g.absolute);
    } else if (parsed) {
        uint32_t cycle = 0;
        bool oom = false;
        uint32_t h = ng_height(&g, &cycle, &oom);
        if (oom)
            ok = scene_fail(err, errlen, "%s: out of memory checking %u nodes", path, g.nnodes);
        else if (h == UINT32_MAX)
            ok = scene_fail(err, errlen, "%s: node %u contains itself: the hierarchy recurses",
                            path, cycle);
        else if (h >= FILE_MAX_NODE_DEPTH)
            ok = scene_fail(err, errlen, "%s: the node hierarchy is %u deep, more than %u", path, h,
                            FILE_MAX_NODE_DEPTH - 1);
    }
    free(g.edge_from);
    free(g.edge_to);
    return ok;
}

// >>load

/* One loaded file: assimp's scene, the files read, the decoded images (one per distinct
 * texture reference, in first-use order) and the world transforms of the mesh nodes. */
typedef struct loaded_image {
    char *ref;                 /* the material's texture path ("*N": embedded) */
    image img;                 /* RGBA8 */
} loaded_image;

typedef struct loaded {
    const struct aiScene *ai;
    file_set files;
    loaded_image *images;
    uint32_t nimages;
    size_t cap_images;
    char dir[4096];            /* the file's folder, with a trailing '/', or "" */
    const char *path;
} loaded;

static void loaded_free(loaded *l)
{
    if (l->ai)
        aiReleaseImport(l->ai);
    for (uint32_t i = 0; i < l->nimages; i++) {
        free(l->images[i].ref);
        image_free(&l->images[i].img);
    }
    free(l->images);
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
static int load_image(loaded *l, const char *ref, char *err, size_t errlen)
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
            const read_file *f = file_get(&l->files, name);
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
        int w = 0, h = 0;
        if (!image_probe(bytes, size, name, &w, &h, why, sizeof why)) {
            scene_fail(err, errlen, "%s: texture '%s' does not decode: %s", l->path, ref, why);
            return -1;
        }
        if (w > (int)TEXTURE_MAX_SIZE || h > (int)TEXTURE_MAX_SIZE) {
            scene_fail(err, errlen, "%s: texture '%s' is %dx%d, more than %u texels a side",
                       l->path, ref, w, h, TEXTURE_MAX_SIZE);
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

static bool material_texture(const struct aiMaterial *m, enum aiTextureType t, char *out,
                             size_t outlen)
{
    struct aiString p;
    if (aiGetMaterialTextureCount(m, t) == 0 ||
        aiGetMaterialTexture(m, t, 0, &p, NULL, NULL, NULL, NULL, NULL, NULL) != aiReturn_SUCCESS)
        return false;
    snprintf(out, outlen, "%s", p.data);
    return out[0] != '\0';
}

/* Which of a material's maps exist: diffuse, normal, emissive references, "" if none. */
typedef struct material_refs {
    char diffuse[1024], normal[1024], emissive[1024];
} material_refs;

static void material_refs_of(const struct aiMaterial *m, material_refs *r)
{
    r->diffuse[0] = r->normal[0] = r->emissive[0] = '\0';
    for (size_t k = 0; k < 2; k++)
        if (material_texture(m, base_types[k], r->diffuse, sizeof r->diffuse))
            break;
    if (!material_texture(m, aiTextureType_NORMALS, r->normal, sizeof r->normal))
        r->normal[0] = '\0';
    if (!material_texture(m, aiTextureType_EMISSIVE, r->emissive, sizeof r->emissive))
        r->emissive[0] = '\0';
}

static bool finite3(const struct aiVector3D *v)
{
    return isfinite(v->x) && isfinite(v->y) && isfinite(v->z);
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

/* Imports and checks everything; on success l holds the scene and every texture. */
static bool load(const scene_file_options *o, loaded *l, char *err, size_t errlen)
{
    memset(l, 0, sizeof *l);
    if (!o || !o->path || !o->path[0])
        return scene_fail(err, errlen, "scene file: no path");
    l->path = o->path;
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
    if (!file_get(&l->files, o->path)) {
        if (l->files.err[0])
            scene_fail(err, errlen, "%s", l->files.err);
        else
            scene_fail(err, errlen, "%s: cannot open: %s", o->path,
                       strerror(errno ? errno : ENOENT));
        loaded_free(l);
        return false;
    }
    /* what the file references is read from inside its folder */
    if (!realpath(l->dir[0] ? l->dir : ".", l->files.root)) {
        scene_fail(err, errlen, "%s: cannot resolve its folder: %s", o->path, strerror(errno));
        loaded_free(l);
        return false;
    }
    l->files.allow_outside = o->allow_outside;
    if (!prescan_gltf(o->path, &l->files.files[0], err, errlen)) {
        loaded_free(l);
        return false;
    }
    struct aiFileIO io = {io_open, io_close, (char *)&l->files};
    struct aiPropertyStore *props = aiCreatePropertyStore();
    /* drop points and lines after triangulation: shadesweep draws triangles */
    aiSetImportPropertyInteger(props, AI_CONFIG_PP_SBP_REMOVE,
                               aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                     aiProcess_GenSmoothNormals | aiProcess_SortByPType |
                     aiProcess_ValidateDataStructure | aiProcess_FindDegenerates;
    import_warning[0] = '\0';
    struct aiLogStream stream = {log_fn, NULL};
    aiAttachLogStream(&stream);
    l->ai = aiImportFileExWithProperties(o->path, flags, &io, props);
    aiDetachLogStream(&stream);
    aiReleasePropertyStore(props);
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
    if (!ai) {
        const char *why = aiGetErrorString();
        if (l->files.err[0])
            scene_fail(err, errlen, "%s", l->files.err);
        else
            scene_fail(err, errlen, "%s: cannot load: %s", o->path,
                       why && why[0] ? why : "unknown error");
        goto out;
    }
    if (ai->mFlags & AI_SCENE_FLAGS_INCOMPLETE) {
        scene_fail(err, errlen, "%s: incomplete scene (assimp could not read all of it)", o->path);
        goto out;
    }
    if (!ai->mRootNode || ai->mNumMeshes == 0) {
        scene_fail(err, errlen, "%s: empty scene: no triangle meshes", o->path);
        goto out;
    }
    const struct aiNode *path[FILE_MAX_NODE_DEPTH];
    if (!check_nodes(l, ai->mRootNode, 0, path, err, errlen))
        goto out;
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
        for (unsigned v = 0; v < m->mNumVertices; v++)
            if (!finite3(&m->mVertices[v])) {
                scene_fail(err, errlen, "%s: mesh %u ('%s'): vertex %u has a position that is not "
                           "finite (%g, %g, %g)", o->path, i, m->mName.data, v,
                           (double)m->mVertices[v].x, (double)m->mVertices[v].y,
                           (double)m->mVertices[v].z);
                goto out;
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
    for (unsigned i = 0; i < ai->mNumMaterials; i++) {
        material_refs r;
        material_refs_of(ai->mMaterials[i], &r);
        const char *refs[3] = {r.diffuse, r.normal, r.emissive};
        for (int k = 0; k < 3; k++)
            if (refs[k][0] && load_image(l, refs[k], err, errlen) < 0)
                goto out;
    }
    if (o->camera && o->camera[0] && strcmp(o->camera, "orbit") != 0) {
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
        loaded_free(l);
    return ok;
}

// >>nodes

/* Our matrix (column-major, m[col][row]) from assimp's row-major one. */
static void from_ai(const struct aiMatrix4x4 *a, sm_mat4 m)
{
    const float r[4][4] = {{a->a1, a->a2, a->a3, a->a4},
                           {a->b1, a->b2, a->b3, a->b4},
                           {a->c1, a->c2, a->c3, a->c4},
                           {a->d1, a->d2, a->d3, a->d4}};
    for (int c = 0; c < 4; c++)
        for (int k = 0; k < 4; k++)
            m[c][k] = r[k][c];
}

/* The root transform: the file's scale, and z-up turned to y-up ((x, y, z) -> (x, z, -y)). */
static void root_transform(const scene_file_options *o, sm_mat4 m)
{
    float s = o->scale > 0.0f ? o->scale : 1.0f;
    sm_mat4_identity(m);
    if (o->up == SCENE_UP_Z) {
        m[1][1] = 0.0f;
        m[1][2] = -s;
        m[2][1] = s;
        m[2][2] = 0.0f;
        m[0][0] = s;
    } else {
        m[0][0] = m[1][1] = m[2][2] = s;
    }
}

typedef void (*node_fn)(const struct aiNode *n, const sm_mat4 world, void *user);

static void walk(const struct aiNode *n, const sm_mat4 parent, node_fn fn, void *user,
                 unsigned depth)
{
    sm_mat4 local, world;
    from_ai(&n->mTransformation, local);
    sm_mat4_mul(parent, local, world);
    fn(n, world, user);
    if (depth + 1 < FILE_MAX_NODE_DEPTH)
        for (unsigned i = 0; i < n->mNumChildren; i++)
            walk(n->mChildren[i], world, fn, user, depth + 1);
}

/* The world transform of the node named `name` (lights, cameras), false if none. */
typedef struct find_node {
    const char *name;
    bool found;
    sm_mat4 world;
    const struct aiNode *node;
} find_node;

static void find_fn(const struct aiNode *n, const sm_mat4 world, void *user)
{
    find_node *f = user;
    if (!f->found && strcmp(n->mName.data, f->name) == 0) {
        f->found = true;
        f->node = n;
        sm_mat4_copy(world, f->world);
    }
}

/* A float of a node's metadata (assimp keeps KHR_lights_punctual's range there as
 * "PBR_LightRange"); false if the node has none. */
static bool node_float(const struct aiNode *n, const char *key, float *out)
{
    const struct aiMetadata *m = n ? n->mMetaData : NULL;
    for (unsigned k = 0; m && k < m->mNumProperties; k++)
        if (strcmp(m->mKeys[k].data, key) == 0) {
            if (m->mValues[k].mType == AI_FLOAT && m->mValues[k].mData) {
                *out = *(const float *)m->mValues[k].mData;
                return true;
            }
            if (m->mValues[k].mType == AI_DOUBLE && m->mValues[k].mData) {
                *out = (float)*(const double *)m->mValues[k].mData;
                return true;
            }
        }
    return false;
}

/* glTF by its extension: assimp's glTF importer gives cameras its own way (below). */
static bool is_gltf(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && (strcasecmp(dot, ".gltf") == 0 || strcasecmp(dot, ".glb") == 0);
}

/* Counts and bounds over every mesh instance. */
typedef struct count_nodes {
    const struct aiScene *ai;
    uint32_t objects;
    uint64_t triangles;
    sm_vec3 lo, hi;
} count_nodes;

static void count_fn(const struct aiNode *n, const sm_mat4 world, void *user)
{
    count_nodes *c = user;
    for (unsigned i = 0; i < n->mNumMeshes; i++) {
        const struct aiMesh *m = c->ai->mMeshes[n->mMeshes[i]];
        c->objects++;
        c->triangles += m->mNumFaces;
        for (unsigned v = 0; v < m->mNumVertices; v++) {
            sm_vec3 p = {m->mVertices[v].x, m->mVertices[v].y, m->mVertices[v].z}, w;
            sm_mat4_mulv3(world, p, 1.0f, w);
            for (int k = 0; k < 3; k++) {
                c->lo[k] = fminf(c->lo[k], w[k]);
                c->hi[k] = fmaxf(c->hi[k], w[k]);
            }
        }
    }
}

static void counts_of(const scene_file_options *o, const loaded *l, count_nodes *c)
{
    memset(c, 0, sizeof *c);
    c->ai = l->ai;
    for (int k = 0; k < 3; k++) {
        c->lo[k] = INFINITY;
        c->hi[k] = -INFINITY;
    }
    sm_mat4 root;
    root_transform(o, root);
    walk(l->ai->mRootNode, root, count_fn, c, 0);
}

// >>check

/* A material's alpha mode (glTF alphaMode; OBJ: d < 1 is translucent) and cutoff. */
static material_alpha alpha_mode(const struct aiMaterial *am, float *cutoff)
{
    struct aiString mode;
    float opacity = 1.0f;
    if (aiGetMaterialString(am, AI_MATKEY_GLTF_ALPHAMODE, &mode) == aiReturn_SUCCESS) {
        if (strcmp(mode.data, "MASK") == 0) {
            float c = 0.5f;
            mat_float(am, AI_MATKEY_GLTF_ALPHACUTOFF, &c);
            if (cutoff)
                *cutoff = c;
            return MATERIAL_MASK;
        }
        return strcmp(mode.data, "BLEND") == 0 ? MATERIAL_BLEND : MATERIAL_OPAQUE;
    }
    mat_float(am, AI_MATKEY_OPACITY, &opacity);
    return opacity < 1.0f ? MATERIAL_BLEND : MATERIAL_OPAQUE;
}

bool scene_file_check(const scene_file_options *o, scene_file_info *info, char *err,
                      size_t errlen)
{
    loaded l;
    if (!load(o, &l, err, errlen))
        return false;
    count_nodes c;
    counts_of(o, &l, &c);
    bool ok = true;
    if (c.objects == 0 || !(c.lo[0] <= c.hi[0])) {
        ok = scene_fail(err, errlen, "%s: empty scene: no node draws a mesh", o->path);
    } else if (!(isfinite(c.lo[0]) && isfinite(c.lo[1]) && isfinite(c.lo[2]) &&
                 isfinite(c.hi[0]) && isfinite(c.hi[1]) && isfinite(c.hi[2]))) {
        ok = scene_fail(err, errlen, "%s: node transforms put vertices at non-finite positions",
                        o->path);
    }
    if (ok && info) {
        memset(info, 0, sizeof *info);
        info->meshes = l.ai->mNumMeshes;
        info->triangles = c.triangles;
        info->objects = c.objects;
        info->materials = l.ai->mNumMaterials;
        info->textures = l.nimages;
        info->lights = l.ai->mNumLights;
        info->cameras = l.ai->mNumCameras;
        for (unsigned i = 0; i < l.ai->mNumMaterials; i++) {
            material_alpha a = alpha_mode(l.ai->mMaterials[i], NULL);
            info->materials_mask += a == MATERIAL_MASK;
            info->materials_blend += a == MATERIAL_BLEND;
        }
        info->files = l.files.n;
        uint64_t h = UINT64_C(0xcbf29ce484222325);
        for (uint32_t i = 0; i < l.files.n; i++) {
            /* each file's length, then its bytes: names do not count */
            uint64_t n = l.files.files[i].size;
            unsigned char len[8];
            for (int k = 0; k < 8; k++)
                len[k] = (unsigned char)(n >> (8 * k));
            h = fnv1a64_more(h, len, sizeof len);
            h = fnv1a64_more(h, l.files.files[i].data, l.files.files[i].size);
        }
        info->hash = h;
        sm_vec3_copy(c.lo, info->bounds_min);
        sm_vec3_copy(c.hi, info->bounds_max);
    }
    loaded_free(&l);
    return ok;
}

// >>materials

static float luminance(const struct aiColor4D *c)
{
    return 0.2126f * c->r + 0.7152f * c->g + 0.0722f * c->b;
}

/* Blinn-Phong exponent for a roughness: GGX alpha = r^2, n = 2 / alpha^2 - 2. */
static float shininess_of_roughness(float r)
{
    r = sm_clamp(r, 0.0f, 1.0f);
    float a = r * r;
    float n = a > 0.0f ? 2.0f / (a * a) - 2.0f : 2048.0f;
    return sm_clamp(n, 1.0f, 2048.0f);
}

/* A texture of the file as a scene texture; its index, or -1 for none. */
static int scene_texture(scene_builder *b, loaded *l, const char *ref, int *map, bool emissive)
{
    if (!ref[0] || b->failed)
        return -1;
    int i = load_image(l, ref, b->err, b->errlen);
    if (i < 0) {
        b->failed = true;
        return -1;
    }
    if (map[i] >= 0 && !emissive)
        return map[i];
    scene *s = b->s;
    if (!sb_reserve(b, (void **)&s->textures, &b->cap_textures, s->ntextures, 1,
                    sizeof *s->textures, "textures"))
        return -1;
    const image *img = &l->images[i].img;
    texture_image *t = &s->textures[s->ntextures];
    size_t n = (size_t)img->width * (size_t)img->height * 4;
    t->data = malloc(n);
    if (!t->data) {
        sb_fail(b, "%s: out of memory for a %dx%d texture", l->path, img->width, img->height);
        return -1;
    }
    memcpy(t->data, img->pixels, n);
    t->width = (uint32_t)img->width;
    t->height = (uint32_t)img->height;
    t->channels = 4;
    if (emissive)   /* the emissive mask: the whole texel */
        for (size_t k = 3; k < n; k += 4)
            t->data[k] = 255;
    else
        map[i] = (int)s->ntextures;
    return (int)s->ntextures++;
}

static void add_material(scene_builder *b, loaded *l, const struct aiMaterial *am, int *map)
{
    struct aiColor4D base = {1, 1, 1, 1}, spec = {0, 0, 0, 1}, emis = {0, 0, 0, 1};
    if (aiGetMaterialColor(am, AI_MATKEY_BASE_COLOR, &base) != aiReturn_SUCCESS)
        aiGetMaterialColor(am, AI_MATKEY_COLOR_DIFFUSE, &base);
    aiGetMaterialColor(am, AI_MATKEY_COLOR_EMISSIVE, &emis);
    float metallic = 0.0f, roughness = 1.0f, gloss = 0.0f, shininess = 0.0f;
    float specular, exponent;
    if (mat_float(am, AI_MATKEY_ROUGHNESS_FACTOR, &roughness) == aiReturn_SUCCESS &&
        mat_float(am, AI_MATKEY_GLOSSINESS_FACTOR, &gloss) != aiReturn_SUCCESS) {
        mat_float(am, AI_MATKEY_METALLIC_FACTOR, &metallic);
        metallic = sm_clamp(metallic, 0.0f, 1.0f);
        specular = 0.04f * (1.0f - metallic) + luminance(&base) * metallic;
        exponent = shininess_of_roughness(roughness);
    } else if (mat_float(am, AI_MATKEY_GLOSSINESS_FACTOR, &gloss) == aiReturn_SUCCESS) {
        aiGetMaterialColor(am, AI_MATKEY_COLOR_SPECULAR, &spec);
        specular = luminance(&spec);
        exponent = shininess_of_roughness(1.0f - gloss);
    } else {
        aiGetMaterialColor(am, AI_MATKEY_COLOR_SPECULAR, &spec);
        mat_float(am, AI_MATKEY_SHININESS, &shininess);
        specular = luminance(&spec);
        exponent = sm_clamp(shininess, 1.0f, 2048.0f);
    }
    uint32_t mi = sb_material(b, base.r, base.g, base.b, sm_clamp(specular, 0.0f, 1.0f),
                              exponent);
    if (b->failed)
        return;
    material_refs r;
    material_refs_of(am, &r);
    int d = scene_texture(b, l, r.diffuse, map, false);
    int nm = scene_texture(b, l, r.normal, map, false);
    int em = scene_texture(b, l, r.emissive, map, true);
    if (b->failed)
        return;
    scene_material *m = &b->s->materials[mi];
    m->diffuse_map = d;
    m->normal_map = nm;
    m->emissive_map = em;
    sm_vec3_make(emis.r, emis.g, emis.b, m->emissive);
    if (em >= 0 && emis.r == 0.0f && emis.g == 0.0f && emis.b == 0.0f)
        sm_vec3_make(1.0f, 1.0f, 1.0f, m->emissive);   /* OBJ: map_Ke without Ke */
    float cutoff = 0.5f;
    m->alpha = alpha_mode(am, &cutoff);
    if (m->alpha == MATERIAL_MASK)
        m->alpha_cutoff = cutoff;
    if (m->alpha == MATERIAL_BLEND) {
        /* glTF: the base colour factor's alpha (the map's alpha multiplies it in the
         * shader); OBJ: d (assimp's opacity) */
        float opacity = base.a;
        if (mat_float(am, AI_MATKEY_OPACITY, &opacity) != aiReturn_SUCCESS)
            opacity = base.a;
        m->opacity = isfinite(opacity) ? sm_clamp(opacity, 0.0f, 1.0f) : 1.0f;
    }
}

// >>build

typedef struct build_nodes {
    scene_builder *b;
    const struct aiScene *ai;
    const uint32_t *mesh_index;    /* file mesh -> scene mesh */
    const uint32_t *mesh_mirror;   /* file mesh -> its mirrored copy, made on demand */
    uint32_t *mirror;
} build_nodes;

/* A mesh of the file as a scene mesh: uv v flipped (assimp gives GL's bottom-up v; ours
 * is the image's first row at v = 0), tangents computed. Index or -1. */
static int add_mesh(scene_builder *b, const char *path, const struct aiMesh *am)
{
    scene *s = b->s;
    if (!sb_reserve(b, (void **)&s->meshes, &b->cap_meshes, s->nmeshes, 1, sizeof *s->meshes,
                    "meshes"))
        return -1;
    mesh *m = &s->meshes[s->nmeshes];
    memset(m, 0, sizeof *m);
    m->vertices = calloc(am->mNumVertices, sizeof *m->vertices);
    m->indices = malloc((size_t)am->mNumFaces * 3 * sizeof *m->indices);
    if (!m->vertices || !m->indices) {
        mesh_free(m);
        sb_fail(b, "%s: out of memory for a mesh of %u vertices", path, am->mNumVertices);
        return -1;
    }
    m->nvertices = am->mNumVertices;
    m->nindices = am->mNumFaces * 3;
    for (unsigned v = 0; v < am->mNumVertices; v++) {
        mesh_vertex *mv = &m->vertices[v];
        mv->position[0] = am->mVertices[v].x;
        mv->position[1] = am->mVertices[v].y;
        mv->position[2] = am->mVertices[v].z;
        sm_vec3 n = {0.0f, 1.0f, 0.0f};
        if (am->mNormals && finite3(&am->mNormals[v])) {
            sm_vec3_make(am->mNormals[v].x, am->mNormals[v].y, am->mNormals[v].z, n);
            if (sm_vec3_norm(n) > 0.0f)
                sm_vec3_normalize(n);
            else
                sm_vec3_make(0.0f, 1.0f, 0.0f, n);
        }
        sm_vec3_copy(n, mv->normal);
        if (am->mTextureCoords[0]) {
            mv->uv[0] = am->mTextureCoords[0][v].x;
            mv->uv[1] = 1.0f - am->mTextureCoords[0][v].y;
            if (!isfinite(mv->uv[0]) || !isfinite(mv->uv[1]))
                mv->uv[0] = mv->uv[1] = 0.0f;
        }
    }
    for (unsigned f = 0; f < am->mNumFaces; f++)
        for (unsigned k = 0; k < 3; k++)
            m->indices[3 * f + k] = am->mFaces[f].mIndices[k];
    if (!mesh_compute_tangents(m)) {
        mesh_free(m);
        sb_fail(b, "%s: out of memory computing tangents", path);
        return -1;
    }
    mesh_compute_bounds(m);
    return (int)s->nmeshes++;
}

static void object_fn(const struct aiNode *n, const sm_mat4 world, void *user)
{
    build_nodes *bn = user;
    scene_builder *b = bn->b;
    for (unsigned i = 0; i < n->mNumMeshes && !b->failed; i++) {
        unsigned fm = n->mMeshes[i];
        const struct aiMesh *am = bn->ai->mMeshes[fm];
        uint32_t me = bn->mesh_index[fm];
        sm_mat4 t;
        sm_mat4_copy(world, t);
        if (sm_mat4_det(world) < 0.0f) {
            /* a mirroring node: renderers cull back faces by winding, so bake the mirror
             * into a copy of the mesh (mesh_transform flips its winding) */
            if (bn->mirror[fm] == UINT32_MAX) {
                scene *s = b->s;
                if (!sb_reserve(b, (void **)&s->meshes, &b->cap_meshes, s->nmeshes, 1,
                                sizeof *s->meshes, "meshes") ||
                    !mesh_append(&s->meshes[s->nmeshes], &s->meshes[me], NULL, b->err,
                                 b->errlen)) {
                    b->failed = true;
                    return;
                }
                sm_mat4 flip;
                sm_mat4_identity(flip);
                flip[0][0] = -1.0f;
                if (!mesh_transform(&s->meshes[s->nmeshes], flip, b->err, b->errlen)) {
                    b->failed = true;
                    return;
                }
                bn->mirror[fm] = s->nmeshes++;
            }
            me = bn->mirror[fm];
            sm_mat4 flip;
            sm_mat4_identity(flip);
            flip[0][0] = -1.0f;
            sm_mat4_mul(world, flip, t);
        }
        scene_object *o = sb_object(b, (int)me, am->mMaterialIndex, 0.0f, 0.0f, 0.0f, 1.0f);
        sm_mat4_copy(t, o->transform);
    }
}

/* The light of a KHR_lights_punctual (or any assimp) light, in world space; range: the
 * file's (KHR_lights_punctual range), or NAN for none. */
static void add_light(scene_builder *b, const struct aiLight *al, const sm_mat4 world,
                      float file_range)
{
    sm_vec3 p = {al->mPosition.x, al->mPosition.y, al->mPosition.z}, wp;
    sm_vec3 d = {al->mDirection.x, al->mDirection.y, al->mDirection.z}, wd;
    sm_mat4_mulv3(world, p, 1.0f, wp);
    sm_mat4_mulv3(world, d, 0.0f, wd);
    if (sm_vec3_norm(wd) > 0.0f)
        sm_vec3_normalize(wd);
    else
        sm_vec3_make(0.0f, 0.0f, -1.0f, wd);
    sm_vec3 color = {al->mColorDiffuse.r, al->mColorDiffuse.g, al->mColorDiffuse.b};
    /* glTF lights are inverse-square, cut off at their range; a light without one
     * reaches where 1 / d^2 falls to 1/256 of its brightest channel (a light volume
     * needs a range) */
    float peak = fmaxf(color[0], fmaxf(color[1], color[2]));
    float range = isfinite(file_range) && file_range > 0.0f
                      ? file_range : sqrtf(fmaxf(peak, 1e-6f) * 256.0f);
    scene_light *l;
    switch (al->mType) {
    case aiLightSource_DIRECTIONAL:
        l = sb_directional(b, wd, color, false);
        return;
    case aiLightSource_SPOT: {
        sm_vec3 at;
        sm_vec3_add(wp, wd, at);
        l = sb_spot(b, wp, at, sm_rad2deg(al->mAngleOuterCone), 1.0f, range, color, false);
        l->spot_angle = al->mAngleOuterCone;   /* exactly the file's, not via degrees */
        break;
    }
    default:
        l = sb_point(b, wp[0], wp[1], wp[2], range, color[0], color[1], color[2]);
        break;
    }
    l->attenuation = ATTENUATION_INVERSE_SQUARE;
}

bool scene_build_file(scene_builder *b, const void *arg)
{
    const scene_file_options *o = arg;
    loaded l;
    if (!load(o, &l, b->err, b->errlen)) {
        b->failed = true;
        return false;
    }
    const struct aiScene *ai = l.ai;
    count_nodes c;
    counts_of(o, &l, &c);
    uint32_t *mesh_index = calloc(ai->mNumMeshes, sizeof *mesh_index);
    uint32_t *mirror = malloc(ai->mNumMeshes * sizeof *mirror);
    int *map = malloc((l.nimages ? l.nimages : 1) * sizeof *map);
    if (!mesh_index || !mirror || !map) {
        sb_fail(b, "%s: out of memory", o->path);
        goto out;
    }
    for (uint32_t i = 0; i < l.nimages; i++)
        map[i] = -1;
    for (unsigned i = 0; i < ai->mNumMeshes; i++)
        mirror[i] = UINT32_MAX;
    if (!sb_begin(b, c.objects))
        goto out;
    for (unsigned i = 0; i < ai->mNumMaterials && !b->failed; i++)
        add_material(b, &l, ai->mMaterials[i], map);
    for (unsigned i = 0; i < ai->mNumMeshes && !b->failed; i++) {
        int m = add_mesh(b, o->path, ai->mMeshes[i]);
        mesh_index[i] = m < 0 ? 0 : (uint32_t)m;
    }
    sm_mat4 root;
    root_transform(o, root);
    build_nodes bn = {b, ai, mesh_index, NULL, mirror};
    if (!b->failed)
        walk(ai->mRootNode, root, object_fn, &bn, 0);
    for (unsigned i = 0; i < ai->mNumLights && !b->failed; i++) {
        find_node f = {ai->mLights[i]->mName.data, false, {{0}}, NULL};
        walk(ai->mRootNode, root, find_fn, &f, 0);
        if (!f.found)
            sm_mat4_copy(root, f.world);
        float range = NAN;
        node_float(f.node, "PBR_LightRange", &range);
        add_light(b, ai->mLights[i], f.world, range);
    }
    if (b->failed)
        goto out;

    /* bounds, camera and projection from the scene's extent */
    scene *s = b->s;
    sm_vec3 centre, ext;
    for (int k = 0; k < 3; k++) {
        centre[k] = 0.5f * (c.lo[k] + c.hi[k]);
        ext[k] = c.hi[k] - c.lo[k];
    }
    float size = fmaxf(sm_vec3_norm(ext), 1e-3f);
    sb_set_bounds(b, c.lo[0], c.lo[1], c.lo[2], c.hi[0], c.hi[1], c.hi[2]);
    sm_vec3_make(0.1f, 0.1f, 0.1f, s->ambient);
    sb_set_projection(b, 60.0f, size * 1e-3f, size * 10.0f);
    sb_set_orbit(b, centre[0], centre[1], centre[2], size, 0.35f * size, 60.0f);
    if (o->camera && o->camera[0] && strcmp(o->camera, "orbit") != 0) {
        for (unsigned i = 0; i < ai->mNumCameras; i++) {
            const struct aiCamera *cam = ai->mCameras[i];
            if (strcmp(cam->mName.data, o->camera) != 0)
                continue;
            find_node f = {cam->mName.data, false, {{0}}, NULL};
            walk(ai->mRootNode, root, find_fn, &f, 0);
            if (!f.found)
                sm_mat4_copy(root, f.world);
            bool gltf = is_gltf(o->path);
            /* glTF: the camera sits at its node's origin looking down -Z (assimp also
             * copies the node's translation into mPosition, which would count it twice) */
            sm_vec3 p = {cam->mPosition.x, cam->mPosition.y, cam->mPosition.z};
            if (gltf)
                sm_vec3_make(0.0f, 0.0f, 0.0f, p);
            sm_vec3 at = {p[0] + cam->mLookAt.x, p[1] + cam->mLookAt.y, p[2] + cam->mLookAt.z};
            float eye[1][3], target[1][3];
            sm_mat4_mulv3(f.world, p, 1.0f, eye[0]);
            sm_mat4_mulv3(f.world, at, 1.0f, target[0]);
            sb_set_keys(b, 1, (const float (*)[3])eye, (const float (*)[3])target, 60.0f);
            /* assimp documents mHorizontalFOV as half the horizontal angle; its glTF
             * importer stores yfov x aspect instead */
            float aspect = cam->mAspect > 0.0f ? cam->mAspect : 1.0f;
            float fovy = gltf ? cam->mHorizontalFOV / aspect
                              : 2.0f * atanf(tanf(cam->mHorizontalFOV) / aspect);
            float zn = cam->mClipPlaneNear > 0.0f ? cam->mClipPlaneNear : size * 1e-3f;
            float zf = cam->mClipPlaneFar > zn ? cam->mClipPlaneFar : size * 10.0f;
            sb_set_projection(b, sm_rad2deg(fovy), zn, zf);
            s->fovy = fovy;   /* exactly, not through degrees */
            break;
        }
    }
out:
    free(mesh_index);
    free(mirror);
    free(map);
    loaded_free(&l);
    return !b->failed;
}
