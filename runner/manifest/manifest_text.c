/* Manifest messages: quoting what was found, what a parameter expects, lists. */
#include "runner/manifest/manifest_parse.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "renderers/renderer.h"
#include "runner/manifest/hash.h"
#include "runner/manifest/sweep_axis.h"
#include "scenes/scene.h"


/* Scalar text for a one-line message: escapes, truncated at a character boundary. */
void mf_escape_text(sbuf *b, const char *s, size_t len)
{
    size_t shown = len;
    if (shown > 60) {
        shown = 60;
        while (shown > 0 && ((unsigned char)s[shown] & 0xc0) == 0x80)
            shown--;
    }
    for (size_t i = 0; i < shown; i++) {
        unsigned char ch = (unsigned char)s[i];
        if (ch == '\'' || ch == '\\')
            mf_sb_add(b, "\\%c", ch);
        else if (ch == '\n')
            mf_sb_add(b, "\\n");
        else if (ch == '\t')
            mf_sb_add(b, "\\t");
        else if (ch < 0x20 || ch == 0x7f)
            mf_sb_add(b, "\\x%02x", ch);
        else
            mf_sb_add(b, "%c", ch);
    }
    if (shown < len)
        mf_sb_add(b, "...");
}

#define STR_TAG "tag:yaml.org,2002:str"
#define CORE_TAG_PREFIX "tag:yaml.org,2002:"

/* Explicit tags other than the string ones are not part of the schema. */
bool mf_tag_ok(const ynode *n)
{
    return !n->tag || strcmp(n->tag, "!") == 0 || strcmp(n->tag, STR_TAG) == 0;
}

/* What a node is, for "found ...": 'text' for a scalar (with `want_string` false a
 * quoted one is "a string 'text'", since its quotes are what makes it wrong),
 * "nothing" for an empty plain scalar, else the kind of node. */
const char *mf_found(const ynode *n, bool want_string, char *buf, size_t len)
{
    sbuf b = {buf, len, 0};
    buf[0] = '\0';
    if (!n) {
        mf_sb_add(&b, "nothing");
    } else if (n->kind == YNODE_MAPPING) {
        mf_sb_add(&b, n->n ? "a mapping" : "an empty mapping");
    } else if (n->kind == YNODE_SEQUENCE) {
        mf_sb_add(&b, n->n ? "a sequence" : "an empty sequence");
    } else if (!mf_tag_ok(n)) {
        const char *t = n->tag;
        bool core = strncmp(t, CORE_TAG_PREFIX, strlen(CORE_TAG_PREFIX)) == 0;
        mf_sb_add(&b, "'");
        mf_escape_text(&b, n->text, n->len);
        mf_sb_add(&b, "' tagged %s%s", core ? "!!" : "", core ? t + strlen(CORE_TAG_PREFIX) : t);
    } else if (ynode_empty(n)) {
        mf_sb_add(&b, "nothing");
    } else {
        bool quoted = n->style != YSTYLE_PLAIN || n->tag;
        mf_sb_add(&b, "%s'", quoted && !want_string ? "a string " : "");
        mf_escape_text(&b, n->text, n->len);
        mf_sb_add(&b, "'");
    }
    return buf;
}

/* "one of a, b, c" */
void mf_list_enum(sbuf *b, const char *const *names)
{
    mf_sb_add(b, "one of ");
    for (size_t i = 0; names[i]; i++)
        mf_sb_add(b, "%s%s", i ? ", " : "", names[i]);
}

void mf_list_scenes(sbuf *b)
{
    mf_sb_add(b, "one of ");
    for (size_t i = 0; i < scene_catalog_count(); i++)
        mf_sb_add(b, "%s%s", i ? ", " : "", scene_catalog_at(i)->name);
}

void mf_list_renderers(sbuf *b)
{
    mf_sb_add(b, "one of ");
    for (size_t i = 0; i < renderer_kind_count(); i++)
        mf_sb_add(b, "%s%s", i ? ", " : "", renderer_kind_at(i)->name);
}

void mf_range_number(sbuf *b, double min, double max, bool min_open)
{
    char lo[32], hi[32];
    params_fmt_double(min, lo, sizeof lo);
    mf_sb_add(b, "a number %s %s", min_open ? ">" : ">=", lo);
    if (isfinite(max)) {
        params_fmt_double(max, hi, sizeof hi);
        mf_sb_add(b, " and <= %s", hi);
    }
}

/* What a parameter expects, as the "expected ..." of its messages. */
const char *mf_expect(const param *pd, char *buf, size_t len)
{
    sbuf b = {buf, len, 0};
    buf[0] = '\0';
    switch (pd->type) {
    case PT_SCHEMA: mf_sb_add(&b, "1 or 2"); break;
    case PT_NAME: mf_sb_add(&b, "a name of 1..63 characters from a-z, 0-9 and -"); break;
    case PT_TEXT: mf_sb_add(&b, "a string"); break;
    case PT_SCENE:
        mf_list_scenes(&b);
        mf_sb_add(&b, ", or {file: PATH, scale, up, camera}");
        break;
    case PT_RENDERERS: mf_sb_add(&b, "a non-empty sequence of renderer names"); break;
    case PT_RENDERER: mf_list_renderers(&b); break;
    case PT_RESOLUTION: mf_sb_add(&b, "WxH with each side 1..%d", MAX_SIDE); break;
    case PT_UINT:
        mf_sb_add(&b, "an integer %.0f..%.0f%s", pd->min, pd->max,
               pd->flags & PF_AUTO ? ", or auto" : "");
        break;
    case PT_NUMBER:
        mf_range_number(&b, pd->min, pd->max, pd->flags & PF_MIN_OPEN);
        if (pd->flags & PF_SCENE_DEFAULT)
            mf_sb_add(&b, ", or scene");
        break;
    case PT_VEC3:
        mf_sb_add(&b, "[x, y, z] (finite numbers)");
        if (pd->flags & PF_SCENE_DEFAULT)
            mf_sb_add(&b, " or scene");
        break;
    case PT_ENUM: mf_list_enum(&b, pd->values); break;
    case PT_BOOL: mf_sb_add(&b, "true or false"); break;
    case PT_SPAN: mf_sb_add(&b, "{seconds: S} or {frames: N}"); break;
    case PT_COUNT:
        mf_sb_add(&b, "an integer 0..%u, all, or {start, step, every, max}", MAX_LIGHTS);
        break;
    case PT_TIMES: mf_sb_add(&b, "a sequence of at most %d times in seconds", MAX_SCREENSHOTS); break;
    case PT_GROUP:
        if (pd->shorthand) {
            mf_list_enum(&b, param_find(pd->shorthand)->values);
            mf_sb_add(&b, " or a mapping");
        } else {
            mf_sb_add(&b, "a mapping");
        }
        break;
    case PT_SWEEP:
        mf_sb_add(&b, "a mapping from parameters to sequences of values, or a sequence of "
                  "such mappings (blocks)");
        break;
    }
    return buf;
}

bool mf_wants_string(const param *pd)
{
    return pd->type == PT_NAME || pd->type == PT_TEXT || pd->type == PT_SCENE ||
           pd->type == PT_RESOLUTION || pd->type == PT_ENUM;
}

