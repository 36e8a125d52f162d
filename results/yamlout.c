/* A small structured YAML writer over libyaml's emitter. See yamlout.h.
 *
 * Every value reads back with the type it was written with, under YAML 1.1
 * (PyYAML, libyaml-based loaders) and YAML 1.2 core schema alike:
 *   - strings are plain only when no schema could take them for anything else
 *     (see plain_is_safe); otherwise double-quoted;
 *   - integers and booleans are plain; floats always carry a '.' (1.0, 2.5e-07 is
 *     written 2.5e-07, 1e+20 as 1.0e+20), so they never read back as integers;
 *   - NAN, +Inf and -Inf are .nan, .inf and -.inf; a NULL string is null.
 * Nesting is checked here (a key only where a mapping expects one, every value
 * after its key, every container closed), so misuse is reported by name. */
#include "results/yamlout.h"

#include <errno.h>
#include <limits.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

#include "common/fsutil.h"
#include "results/numfmt.h"

#define YO_MAX_DEPTH 64

typedef enum frame_kind { FRAME_MAP, FRAME_SEQ } frame_kind;

struct yaml_out {
    afile file;
    yaml_emitter_t emitter;
    bool emitter_ready;
    bool failed;          /* sticky */
    char msg[256];
    int write_errno;      /* set by the write handler */
    bool root_done;       /* the document's root node is complete */
    size_t depth;
    frame_kind kind[YO_MAX_DEPTH];
    bool want_value[YO_MAX_DEPTH]; /* FRAME_MAP: a key was given, its value comes next */
};

/* >>errors */

static void fail(yaml_out *y, const char *what)
{
    afile_fail_once(&y->file, "yaml", &y->failed, y->msg, sizeof y->msg, what);
}

static void fail_emitter(yaml_out *y)
{
    char m[200];
    if (y->write_errno != 0)
        snprintf(m, sizeof m, "write failed: %s", strerror(y->write_errno));
    else
        snprintf(m, sizeof m, "YAML emitter: %s",
                 y->emitter.problem ? y->emitter.problem : "unknown error");
    fail(y, m);
}

static int write_handler(void *data, unsigned char *buffer, size_t size)
{
    yaml_out *y = data;
    if (size > 0 && fwrite(buffer, 1, size, y->file.fp) != size) {
        y->write_errno = errno ? errno : EIO;
        return 0;
    }
    return 1;
}

static void emit(yaml_out *y, yaml_event_t *ev, bool init_ok)
{
    if (!init_ok) {
        fail(y, "YAML emitter: cannot create event (out of memory?)");
        return;
    }
    if (!yaml_emitter_emit(&y->emitter, ev)) /* consumes ev either way */
        fail_emitter(y);
}

/* >>structure */

/* Called before every node: checks that a node may come here. */
static bool node_allowed(yaml_out *y, const char *what)
{
    if (y->failed)
        return false;
    char m[128];
    if (y->depth == 0 && y->root_done) {
        snprintf(m, sizeof m, "bug: %s after the document's root node", what);
        fail(y, m);
        return false;
    }
    if (y->depth > 0 && y->kind[y->depth - 1] == FRAME_MAP && !y->want_value[y->depth - 1]) {
        snprintf(m, sizeof m, "bug: %s where a mapping expects a key", what);
        fail(y, m);
        return false;
    }
    return true;
}

/* Called after every complete node (a scalar, or a closed container). */
static void node_done(yaml_out *y)
{
    if (y->depth == 0)
        y->root_done = true;
    else if (y->kind[y->depth - 1] == FRAME_MAP)
        y->want_value[y->depth - 1] = false;
}

static void open_container(yaml_out *y, frame_kind k)
{
    const char *what = k == FRAME_MAP ? "a mapping" : "a sequence";
    if (!node_allowed(y, what))
        return;
    if (y->depth == YO_MAX_DEPTH) {
        fail(y, "bug: YAML nesting too deep");
        return;
    }
    yaml_event_t ev;
    int ok = k == FRAME_MAP
                 ? yaml_mapping_start_event_initialize(&ev, NULL, NULL, 1,
                                                       YAML_BLOCK_MAPPING_STYLE)
                 : yaml_sequence_start_event_initialize(&ev, NULL, NULL, 1,
                                                        YAML_BLOCK_SEQUENCE_STYLE);
    emit(y, &ev, ok);
    if (y->failed)
        return;
    y->kind[y->depth] = k;
    y->want_value[y->depth] = false;
    y->depth++;
}

static void close_container(yaml_out *y, frame_kind k)
{
    if (y == NULL || y->failed)
        return;
    char m[128];
    const char *what = k == FRAME_MAP ? "yo_map_end" : "yo_seq_end";
    if (y->depth == 0 || y->kind[y->depth - 1] != k) {
        snprintf(m, sizeof m, "bug: %s without a matching begin", what);
        fail(y, m);
        return;
    }
    if (k == FRAME_MAP && y->want_value[y->depth - 1]) {
        snprintf(m, sizeof m, "bug: %s after a key with no value", what);
        fail(y, m);
        return;
    }
    yaml_event_t ev;
    int ok = k == FRAME_MAP ? yaml_mapping_end_event_initialize(&ev)
                            : yaml_sequence_end_event_initialize(&ev);
    emit(y, &ev, ok);
    if (y->failed)
        return;
    y->depth--;
    node_done(y);
}

/* >>scalars */

static bool ieq(const char *a, const char *b)
{
    for (; *a && *b; a++, b++) {
        char ca = *a >= 'A' && *a <= 'Z' ? (char)(*a - 'A' + 'a') : *a;
        if (ca != *b)
            return false;
    }
    return *a == '\0' && *b == '\0';
}

/* True when s, written as a plain scalar, reads back as this same string under any
 * common schema. Deliberately narrow: ASCII letters start it, only a safe set of
 * characters follows (no ':', '#', ',', quotes, brackets, control characters), no
 * trailing space, and it is none of the words that schemas resolve to bool, null,
 * inf or nan. Anything else is double-quoted, which is always exact. */
static bool plain_is_safe(const char *s)
{
    static const char *const reserved[] = {
        "y",   "n",    "yes",   "no",       "true", "false", "on", "off",
        "null", "inf", "nan",   "infinity", NULL,
    };
    char c = s[0];
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == '/'))
        return false;
    size_t n = 0;
    for (const char *p = s; *p; p++, n++) {
        c = *p;
        bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                  c == '_' || c == '-' || c == '.' || c == '/' || c == '+' || c == '(' ||
                  c == ')' || c == '=' || c == '@' || c == ' ';
        if (!ok)
            return false;
    }
    if (s[n - 1] == ' ')
        return false;
    for (size_t i = 0; reserved[i] != NULL; i++) {
        if (ieq(s, reserved[i]))
            return false;
    }
    return true;
}

static void emit_scalar(yaml_out *y, const char *text, bool plain)
{
    size_t len = strlen(text);
    if (len > INT_MAX) {
        fail(y, "bug: YAML scalar too long");
        return;
    }
    yaml_event_t ev;
    int ok = yaml_scalar_event_initialize(
        &ev, NULL, NULL, (const yaml_char_t *)text, (int)len, plain ? 1 : 0, plain ? 0 : 1,
        plain ? YAML_PLAIN_SCALAR_STYLE : YAML_DOUBLE_QUOTED_SCALAR_STYLE);
    emit(y, &ev, ok);
}

/* A scalar in value position (root, sequence item, mapping value). */
static void value_scalar(yaml_out *y, const char *what, const char *text, bool plain)
{
    if (y == NULL || !node_allowed(y, what))
        return;
    emit_scalar(y, text, plain);
    if (!y->failed)
        node_done(y);
}

/* >>api */

yaml_out *yo_open(const char *final_path, char *err, size_t errlen)
{
    yaml_out *y = calloc(1, sizeof *y);
    if (y == NULL) {
        snprintf(err, errlen, "%s: out of memory", final_path ? final_path : "yaml");
        return NULL;
    }
    if (!afile_open(&y->file, final_path, err, errlen)) {
        free(y);
        return NULL;
    }
    if (!yaml_emitter_initialize(&y->emitter)) {
        snprintf(err, errlen, "%s: cannot initialize the YAML emitter", final_path);
        afile_abort(&y->file);
        free(y);
        return NULL;
    }
    y->emitter_ready = true;
    yaml_emitter_set_output(&y->emitter, write_handler, y);
    yaml_emitter_set_unicode(&y->emitter, 1);
    yaml_emitter_set_width(&y->emitter, -1); /* never fold long strings */
    yaml_emitter_set_indent(&y->emitter, 2);

    yaml_event_t ev;
    emit(y, &ev, yaml_stream_start_event_initialize(&ev, YAML_UTF8_ENCODING));
    emit(y, &ev, !y->failed && yaml_document_start_event_initialize(&ev, NULL, NULL, NULL, 1));
    if (y->failed) {
        snprintf(err, errlen, "%s", y->msg);
        yo_abort(y);
        return NULL;
    }
    return y;
}

void yo_map_begin(yaml_out *y)
{
    if (y != NULL)
        open_container(y, FRAME_MAP);
}

void yo_map_end(yaml_out *y)
{
    close_container(y, FRAME_MAP);
}

void yo_seq_begin(yaml_out *y)
{
    if (y != NULL)
        open_container(y, FRAME_SEQ);
}

void yo_seq_end(yaml_out *y)
{
    close_container(y, FRAME_SEQ);
}

void yo_key(yaml_out *y, const char *key)
{
    if (y == NULL || y->failed)
        return;
    if (y->depth == 0 || y->kind[y->depth - 1] != FRAME_MAP || y->want_value[y->depth - 1]) {
        fail(y, y->depth > 0 && y->kind[y->depth - 1] == FRAME_MAP
                    ? "bug: yo_key where a mapping expects a value"
                    : "bug: yo_key outside a mapping");
        return;
    }
    if (key == NULL) {
        fail(y, "bug: yo_key(NULL)");
        return;
    }
    emit_scalar(y, key, key[0] != '\0' && plain_is_safe(key));
    if (!y->failed)
        y->want_value[y->depth - 1] = true;
}

void yo_str(yaml_out *y, const char *v)
{
    if (v == NULL)
        value_scalar(y, "yo_str", "null", true);
    else
        value_scalar(y, "yo_str", v, v[0] != '\0' && plain_is_safe(v));
}

void yo_i64(yaml_out *y, int64_t v)
{
    char s[24];
    snprintf(s, sizeof s, "%lld", (long long)v);
    value_scalar(y, "yo_i64", s, true);
}

/* The shortest form, with ".0" added to a mantissa without a point so that the
 * text is a float under YAML 1.1 and 1.2 (1 -> 1.0, 1e+20 -> 1.0e+20). */
static void format_float(double v, char *s, size_t cap)
{
    char g[40];
    num_shortest(v, g, sizeof g);
    char *e = strchr(g, 'e');
    if (strchr(g, '.') != NULL)
        snprintf(s, cap, "%s", g);
    else if (e != NULL)
        snprintf(s, cap, "%.*s.0%s", (int)(e - g), g, e);
    else
        snprintf(s, cap, "%s.0", g);
}

void yo_f64(yaml_out *y, double v)
{
    char s[48];
    if (isnan(v))
        snprintf(s, sizeof s, ".nan");
    else if (isinf(v))
        snprintf(s, sizeof s, "%s", v > 0 ? ".inf" : "-.inf");
    else
        format_float(v, s, sizeof s);
    value_scalar(y, "yo_f64", s, true);
}

void yo_bool(yaml_out *y, bool v)
{
    value_scalar(y, "yo_bool", v ? "true" : "false", true);
}

bool yo_commit(yaml_out *y, char *err, size_t errlen)
{
    if (y == NULL) {
        snprintf(err, errlen, "bug: yo_commit(NULL)");
        return false;
    }
    if (!y->failed && y->depth != 0)
        fail(y, "bug: a mapping or sequence was not closed");
    if (!y->failed && !y->root_done)
        fail(y, "bug: empty document");
    if (!y->failed) {
        yaml_event_t ev;
        emit(y, &ev, yaml_document_end_event_initialize(&ev, 1));
        if (!y->failed)
            emit(y, &ev, yaml_stream_end_event_initialize(&ev));
        if (!y->failed && !yaml_emitter_flush(&y->emitter))
            fail_emitter(y);
    }
    yaml_emitter_delete(&y->emitter);
    bool ok = afile_finish(&y->file, y->failed, y->msg, err, errlen);
    free(y);
    return ok;
}

void yo_abort(yaml_out *y)
{
    if (y == NULL)
        return;
    if (y->emitter_ready)
        yaml_emitter_delete(&y->emitter);
    afile_abort(&y->file);
    free(y);
}
