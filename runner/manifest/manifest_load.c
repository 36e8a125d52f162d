/* Loading a manifest: the file, the defaults, the checks, the diagnostics in
 * document order. */
#include "runner/manifest/manifest_parse.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/renderer.h"
#include "common/fsutil.h"
#include "runner/manifest/hash.h"
#include "runner/manifest/sweep_axis.h"
#include "scenes/scene.h"

/* >>load */

void experiment_free(experiment *e)
{
    if (!e)
        return;
    for (size_t i = 0; i < e->naxes; i++) {
        free(e->axes[i].values);
        free(e->axes[i].line);
        free(e->axes[i].col);
    }
    free(e->axes);
    free(e->block_first);
    for (size_t i = 0; i < e->nsets; i++)
        free(e->sets[i]);
    free(e->sets);
    free(e->renderer_filter);
    free(e->renderers);
    free(e->description);
    free(e->text);
    free(e->path);
    free(e);
}

static bool read_file(const char *path, unsigned char **out, size_t *outlen, diag_list *d)
{
    int e;
    const char *kind;
    /* a directory read as "Input/output error", and a FIFO hung the reader: only a
     * regular file is read, as for a scene file */
    *out = (unsigned char *)fs_read_regular(path, MANIFEST_MAX_BYTES, outlen, &e, &kind);
    if (*out)
        return true;
    if (kind)
        diag_add(d, path, 0, 0, "", "expected a manifest file, found %s, not a regular file",
                 kind);
    else if (e == EFBIG)
        diag_add(d, path, 0, 0, "", "expected a manifest of at most %u bytes, found more",
                 MANIFEST_MAX_BYTES);
    else if (e == ENOMEM)
        diag_add(d, path, 0, 0, "", "expected to load the manifest, found no memory left");
    else
        diag_add(d, path, 0, 0, "", "expected a readable file, found %s", strerror(e));
    return false;
}

typedef struct diag_seq {
    diag g;
    size_t seq;
} diag_seq;

static int diag_seq_cmp(const void *a, const void *b)
{
    const diag_seq *x = a, *y = b;
    if (x->g.line != y->g.line)
        return x->g.line < y->g.line ? -1 : 1;
    if (x->g.col != y->g.col)
        return x->g.col < y->g.col ? -1 : 1;
    return x->seq < y->seq ? -1 : x->seq > y->seq;
}

/* Document order (line, column), stable: required keys are found missing only
 * at the end, and belong where their mapping starts. */
static void sort_diags(diag_list *d, size_t from)
{
    size_t n = d->n - from;
    if (n < 2)
        return;
    diag_seq *t = malloc(n * sizeof *t);
    if (!t)
        return;   /* unsorted is still complete */
    for (size_t i = 0; i < n; i++)
        t[i] = (diag_seq){d->v[from + i], i};
    qsort(t, n, sizeof *t, diag_seq_cmp);
    for (size_t i = 0; i < n; i++)
        d->v[from + i] = t[i].g;
    free(t);
}

static bool load_mem(const char *name, const char *data, size_t len,
                     const manifest_overrides *ov, experiment **out, diag_list *diags)
{
    *out = NULL;
    size_t from = diags->n;
    ydoc *doc = NULL;
    bool ok = false;
    vctx c = {.file = name, .d = diags};

    experiment *e = calloc(1, sizeof *e);
    if (!e || !(e->path = strdup(name)) || !(e->description = strdup(""))) {
        diag_add(diags, name, 0, 0, "", "expected to load the manifest, found no memory left");
        goto done;
    }
    c.e = e;
    if (len > MANIFEST_MAX_BYTES) {
        diag_add(diags, name, 0, 0, "", "expected a manifest of at most %u bytes, found %zu bytes",
                 MANIFEST_MAX_BYTES, len);
        goto done;
    }
    if (!data)
        data = "";   /* libyaml wants a buffer even for no bytes */
    /* libyaml reads UTF-16 by its byte-order mark, but a run records the manifest's
     * bytes as written, and the YAML writer wants UTF-8 ("YAML emitter: cannot create
     * event", once the run was under way): refused here, as a scene file's are */
    const char *bom = fs_text_bom(data, len);
    if (bom) {
        diag_add(diags, name, 0, 0, "", "expected UTF-8 text, found %s (its byte-order mark "
                 "says so): save it as UTF-8 (iconv -f %.6s -t UTF-8)", bom, bom);
        goto done;
    }
    hash_hex(fnv1a64(data, len), 16, e->hash);
    if (!overrides_keep(&c, ov))
        goto done;
    if (!(e->text = malloc(len + 1))) {
        diag_add(diags, name, 0, 0, "", "expected to load the manifest, found no memory left");
        goto done;
    }
    memcpy(e->text, data, len);
    e->text[len] = '\0';
    e->scale = 1;
    if (!params_apply_defaults(&c, &e->base))
        goto done;
    if (!ydoc_load(name, data, len, &doc, diags))
        goto done;

    c.root = doc->root;
    if (doc->root->kind != YNODE_MAPPING) {
        char f[128];
        mf_err(&c, doc->root, "", "expected a mapping, found %s", mf_found(doc->root, false, f, sizeof f));
        goto done;
    }
    if (!overrides_apply(&c, doc))
        goto done;
    c.root = doc->root;
    e->schema = params_schema_of(doc->root);
    if (!params_apply_schema_defaults(&c, e->schema, &e->base))
        goto done;
    mf_parse_group(&c, "", doc->root, &e->base);
    manifest_check(&c);
    if (c.nerr == 0)
        overrides_filter(&c);
    ok = c.nerr == 0;

done:
    sort_diags(diags, from);
    ydoc_free(doc);
    if (ok)
        *out = e;
    else
        experiment_free(e);
    return ok;
}

bool manifest_load_mem(const char *name, const char *data, size_t len, experiment **out,
                       diag_list *diags)
{
    return load_mem(name, data, len, NULL, out, diags);
}

bool manifest_load(const char *path, experiment **out, diag_list *diags)
{
    return manifest_load_with(path, NULL, out, diags);
}

bool manifest_load_with(const char *path, const manifest_overrides *ov, experiment **out,
                        diag_list *diags)
{
    *out = NULL;
    unsigned char *buf = NULL;
    size_t len = 0;
    if (!read_file(path, &buf, &len, diags))
        return false;
    bool ok = load_mem(path, (const char *)buf, len, ov, out, diags);
    free(buf);
    return ok;
}
