/* File scenes, >>prescan: glTF JSON and GLB chunk lengths read before assimp sees them
 * (see scenes/file/file_assimp.c). */
#include "scenes/file/file_internal.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "common/grow.h"
#include "scenes/scene_fail.h"

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
                    if (!g->url[0] && file_is_url(buf))
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

// >>KHR_materials_emissive_strength

/* A JSON number at j (copied out: the bytes need not end in a NUL); false if none. */
static bool js_number(jscan *j, double *out)
{
    js_ws(j);
    char buf[64];
    size_t n = 0;
    while (j->p + n < j->end && n + 1 < sizeof buf && strchr("+-.0123456789eE", j->p[n]) &&
           j->p[n])
        n++;
    memcpy(buf, j->p, n);
    buf[n] = '\0';
    char *e;
    *out = strtod(buf, &e);
    if (n == 0 || e != buf + n)
        return j->bad = true, false;
    j->p += n;
    return true;
}

/* An object at j: fn called with each key, the value next (fn reads or skips it; false
 * stops). The callers' structure is fixed, so the calls nest at most four deep. */
typedef bool (*js_member_fn)(jscan *j, const char *k, size_t kn, void *ctx);
static bool js_object(jscan *j, js_member_fn fn, void *ctx)
{
    if (!js_lit(j, '{'))
        return false;
    if (js_lit(j, '}'))
        return true;
    do {
        const char *k;
        size_t kn;
        if (!js_string(j, &k, &kn) || !js_lit(j, ':') || !fn(j, k, kn, ctx))
            return false;
    } while (js_lit(j, ','));
    return js_lit(j, '}');
}

typedef struct strengths {
    float *v;                  /* per material: emissiveStrength, 1 without one */
    size_t n, cap;
    double bad;                /* the first value that is no finite number >= 0 */
    bool has_bad;
    bool deep;
} strengths;

static bool js_skip_member(jscan *j, bool *deep)
{
    return js_skip(j, 4, deep);
}

static bool strength_member(jscan *j, const char *k, size_t kn, void *ctx)
{
    strengths *st = ctx;
    if (!key_is(k, kn, "emissiveStrength"))
        return js_skip_member(j, &st->deep);
    double v;
    if (!js_number(j, &v))
        return false;
    if (!(isfinite(v) && v >= 0.0 && v <= 1e30) && !st->has_bad) {
        st->bad = v;
        st->has_bad = true;
    }
    st->v[st->n - 1] = (float)v;
    return true;
}

static bool extension_member(jscan *j, const char *k, size_t kn, void *ctx)
{
    strengths *st = ctx;
    if (!key_is(k, kn, "KHR_materials_emissive_strength"))
        return js_skip_member(j, &st->deep);
    return js_object(j, strength_member, ctx);
}

static bool material_member(jscan *j, const char *k, size_t kn, void *ctx)
{
    strengths *st = ctx;
    if (!key_is(k, kn, "extensions"))
        return js_skip_member(j, &st->deep);
    return js_object(j, extension_member, ctx);
}

static bool top_member(jscan *j, const char *k, size_t kn, void *ctx)
{
    strengths *st = ctx;
    if (!key_is(k, kn, "materials"))
        return js_skip_member(j, &st->deep);
    if (!js_lit(j, '['))
        return false;
    if (js_lit(j, ']'))
        return true;
    do {
        if (!GROW(st->v, st->cap, st->n + 1, 16))
            return false;
        st->v[st->n++] = 1.0f;
        if (!js_object(j, material_member, ctx))
            return false;
    } while (js_lit(j, ','));
    return js_lit(j, ']');
}

bool file_gltf_emissive_strengths(const char *path, const read_file *f, float **out, size_t *n,
                                  char *err, size_t errlen)
{
    *out = NULL;
    *n = 0;
    const char *json;
    size_t len;
    if (!gltf_json(f, &json, &len))
        return true;
    jscan j = {json, json + len, false};
    strengths st = {0};
    if (!js_object(&j, top_member, &st)) {   /* malformed: assimp reports it */
        free(st.v);
        return true;
    }
    if (st.has_bad) {
        free(st.v);
        return scene_fail(err, errlen, "%s: KHR_materials_emissive_strength: emissiveStrength "
                          "%g is not a finite number >= 0", path, st.bad);
    }
    *out = st.v;
    *n = st.n;
    return true;
}

/* False with a message naming the file when its glTF JSON asks for what would hurt. */
bool file_prescan_gltf(const char *path, const read_file *f, char *err, size_t errlen)
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

/* An OBJ's material libraries, read before assimp sees them. assimp 5.2's OBJ importer
 * rewrites an mtllib path that holds ":/" (a URL or a drive letter) before it opens it,
 * and one ending in "://" made it erase a negative length (scripts/fuzz.sh found it).
 * Such a path never names a file relative to the .obj's folder, which is all a scene
 * may reference, so any ':' in one is refused here, by name. A line is what assimp's
 * reader makes of it: it ends at CR, LF, NUL or FF, and a backslash before the line
 * break joins the next line to it. */
bool file_prescan_obj(const char *path, const read_file *f, uint64_t max_triangles,
                      uint64_t max_vertices, char *err, size_t errlen)
{
    const char *dot = strrchr(path, '.');
    if (!dot || strcasecmp(dot, ".obj") != 0)
        return true;
    const char *d = (const char *)f->data, *end = d + f->size;
    /* what assimp would build, counted before it builds anything: a face of n corners
     * is n - 2 triangles, a `v` line one position */
    uint64_t triangles = 0, vertices = 0;
    for (const char *p = d; p < end;) {
        while (p < end && (*p == ' ' || *p == '\t'))
            p++;
        bool mtllib = end - p > 6 && memcmp(p, "mtllib", 6) == 0 && (p[6] == ' ' || p[6] == '\t');
        bool face = end - p > 1 && p[0] == 'f' && (p[1] == ' ' || p[1] == '\t');
        vertices += end - p > 1 && p[0] == 'v' && (p[1] == ' ' || p[1] == '\t');
        const char *name = mtllib ? p + 7 : NULL, *colon = NULL;
        uint64_t corners = 0;
        bool in_word = false;
        for (p += face; p < end; p++) {
            if (*p == '\\' && p + 1 < end && (p[1] == '\n' || p[1] == '\r')) {
                p += p + 2 < end && p[1] == '\r' && p[2] == '\n' ? 2 : 1;
                in_word = false;
                continue;   /* a continued line */
            }
            if (*p == '\r' || *p == '\n' || *p == '\0' || *p == '\f')
                break;
            if (name && *p == ':' && !colon)
                colon = p;
            bool space = *p == ' ' || *p == '\t';
            corners += face && !space && !in_word;
            in_word = !space;
        }
        triangles += corners > 2 ? corners - 2 : 0;
        if (colon) {
            while (*name == ' ' || *name == '\t')
                name++;
            char shown[128];   /* one line, printable: a continued line shows as "?" */
            size_t n = 0;
            for (; name < p && n + 1 < sizeof shown; name++)
                shown[n++] = (unsigned char)*name < 0x20 || *name == 0x7f ? '?' : *name;
            shown[n] = '\0';
            return scene_fail(err, errlen, "%s: mtllib '%s' has a ':' (a URL or a drive letter): "
                              "a material library is named relative to the .obj's folder", path,
                              shown);
        }
        p++;
    }
    if (triangles > max_triangles)
        return scene_fail(err, errlen, "%s: %" PRIu64 " triangles, more than scene.max_triangles %"
                          PRIu64, path, triangles, max_triangles);
    if (vertices > max_vertices)
        return scene_fail(err, errlen, "%s: %" PRIu64 " vertices, more than scene.max_vertices %"
                          PRIu64, path, vertices, max_vertices);
    return true;
}

/* An OBJ's material library. assimp 5.2's MTL reader keeps a "current material" that
 * only newmtl sets, and a statement before the first one writes through it while it is
 * still null for some keywords (an "a..." line, any texture map: scripts/fuzz.sh found
 * the first; assimp fixed it after 5.2.5, pull requests 4647 and 5119). Only blank and
 * '#' lines may come before the first newmtl, which the reader takes from any line
 * starting "ne" (either case of the n). Lines end where assimp's do (CR, LF, NUL, FF)
 * and leading blanks are skipped, a stricter reading than assimp's, which skips them on
 * the second line on. A file with a UTF-16 or UTF-32 byte-order mark (assimp converts
 * it) is refused: its bytes are not the text checked here. */
bool file_prescan_mtl(const char *path, const read_file *f, char *err, size_t errlen)
{
    const unsigned char *d = f->data, *end = d + f->size;
    if (f->size >= 2 && ((d[0] == 0xff && d[1] == 0xfe) || (d[0] == 0xfe && d[1] == 0xff) ||
                         (f->size >= 4 && d[0] == 0 && d[1] == 0 && d[2] == 0xfe && d[3] == 0xff)))
        return scene_fail(err, errlen, "%s: a material library in UTF-16 or UTF-32: write it "
                          "as UTF-8", path);
    if (f->size >= 3 && d[0] == 0xef && d[1] == 0xbb && d[2] == 0xbf)
        d += 3;   /* UTF-8's mark: assimp drops it */
    unsigned line = 1;
    for (const unsigned char *p = d; p < end; line++) {
        while (p < end && (*p == ' ' || *p == '\t'))
            p++;
        const unsigned char *start = p;
        while (p < end && *p != '\r' && *p != '\n' && *p != '\0' && *p != '\f')
            p++;
        if (start < p && *start != '#') {
            if (p - start >= 2 && (start[0] == 'n' || start[0] == 'N') && start[1] == 'e')
                return true;   /* the first material: what follows has one */
            char shown[48];
            size_t n = 0;
            for (const unsigned char *q = start; q < p && n + 1 < sizeof shown; q++)
                shown[n++] = *q < 0x20 || *q >= 0x7f ? '?' : (char)*q;
            shown[n] = '\0';
            return scene_fail(err, errlen, "%s: line %u '%s' comes before the first newmtl: "
                              "a material statement needs a material", path, line, shown);
        }
        if (p < end)
            p++;
    }
    return true;
}
