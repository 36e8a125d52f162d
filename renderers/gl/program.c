/* GLSL programs in #define variants, built once each (program.h). */
#include "renderers/gl/program.h"

#include "renderers/gl/shaders.h"
#include "common/grow.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// >>errors

static const char *const err_text[] = {
#define GLP_ERR_TEXT(id, text) [id] = text,
    GLP_ERRORS(GLP_ERR_TEXT)
#undef GLP_ERR_TEXT
};

const char *gl_program_err_text(gl_program_err e)
{
    if ((size_t)e >= sizeof err_text / sizeof err_text[0])
        return "unknown error";
    return err_text[e];
}

// >>strings

/* A growing string; after a failed allocation it stays failed (oom) and empty. */
typedef struct strbuf {
    char *s;
    size_t len, cap;
    bool oom;
} strbuf;

static void sb_add(strbuf *b, const char *s, size_t n)
{
    if (b->oom)
        return;
    if (!GROW(b->s, b->cap, b->len + n + 1, 256)) {
        b->oom = true;
        return;
    }
    memcpy(b->s + b->len, s, n);
    b->len += n;
    b->s[b->len] = '\0';
}

static void sb_puts(strbuf *b, const char *s)
{
    sb_add(b, s, strlen(s));
}

static void sb_printf(strbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static void sb_printf(strbuf *b, const char *fmt, ...)
{
    char tmp[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n < 0)
        return;
    if ((size_t)n < sizeof tmp) {
        sb_add(b, tmp, (size_t)n);
        return;
    }
    char *big = malloc((size_t)n + 1);
    if (!big) {
        b->oom = true;
        return;
    }
    va_start(ap, fmt);
    vsnprintf(big, (size_t)n + 1, fmt, ap);
    va_end(ap);
    sb_add(b, big, (size_t)n);
    free(big);
}

static void sb_free(strbuf *b)
{
    free(b->s);
    *b = (strbuf){0};
}

static char *dup_string(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s, n);
    return d;
}

// >>defines

typedef struct define {
    char name[64];
    char value[192];   /* "" for a plain NAME */
} define;

static bool is_blank(char c)
{
    return c == ' ' || c == '\t';
}

static bool is_ident_start(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

static bool is_ident(char c)
{
    return is_ident_start(c) || (c >= '0' && c <= '9');
}

/* "NAME" or "NAME VALUE" -> d; false with the reason in why. */
static bool parse_define(const char *in, define *d, const char **why)
{
    const char *p = in;
    while (is_blank(*p))
        p++;
    const char *name = p;
    if (!is_ident_start(*p)) {
        *why = "does not start with a GLSL identifier";
        return false;
    }
    while (is_ident(*p))
        p++;
    size_t nlen = (size_t)(p - name);
    if (nlen >= sizeof d->name) {
        *why = "has a name longer than 63 characters";
        return false;
    }
    if (*p && !is_blank(*p)) {
        *why = "has a character after its name that is neither a blank nor an identifier's";
        return false;
    }
    while (is_blank(*p))
        p++;
    const char *value = p;
    const char *end = p + strlen(p);
    while (end > value && is_blank(end[-1]))
        end--;
    for (const char *c = value; c < end; c++)
        if (*c == '\n' || *c == '\r' || *c == '\\') {
            *why = "has a newline or a backslash in its value";
            return false;
        }
    size_t vlen = (size_t)(end - value);
    if (vlen >= sizeof d->value) {
        *why = "has a value longer than 191 characters";
        return false;
    }
    memcpy(d->name, name, nlen);
    d->name[nlen] = '\0';
    memcpy(d->value, value, vlen);
    d->value[vlen] = '\0';
    return true;
}

static int define_cmp(const void *a, const void *b)
{
    return strcmp(((const define *)a)->name, ((const define *)b)->name);
}

// >>cache

typedef struct variant {
    char *key;        /* vertex \n fragment \n compute \n then "NAME VALUE\n" per define */
    char *name;       /* "light_point+NORMAL_MAP" */
    GLuint program;
} variant;

struct gl_program_cache {
    variant *v;
    size_t n, cap;
    define common[GLP_MAX_COMMON_DEFINES];   /* sorted (gl_program_cache_set_common) */
    size_t ncommon;
};

gl_program_cache *gl_program_cache_create(void)
{
    return calloc(1, sizeof(gl_program_cache));
}

void gl_program_cache_destroy(gl_program_cache *c)
{
    if (!c)
        return;
    for (size_t i = 0; i < c->n; i++) {
        if (c->v[i].program && gl.DeleteProgram)
            gl.DeleteProgram(c->v[i].program);
        free(c->v[i].key);
        free(c->v[i].name);
    }
    free(c->v);
    free(c);
}

bool gl_program_cache_set_common(gl_program_cache *c, const char *const *defines, size_t n)
{
    define d[GLP_MAX_COMMON_DEFINES];
    const char *why = NULL;
    if (n > GLP_MAX_COMMON_DEFINES)
        return false;
    for (size_t i = 0; i < n; i++)
        if (!parse_define(defines[i], &d[i], &why))
            return false;
    qsort(d, n, sizeof d[0], define_cmp);
    for (size_t i = 1; i < n; i++)
        if (strcmp(d[i - 1].name, d[i].name) == 0)
            return false;
    memcpy(c->common, d, n * sizeof d[0]);
    c->ncommon = n;
    return true;
}

size_t gl_program_cache_count(const gl_program_cache *c)
{
    return c ? c->n : 0;
}

const char *gl_program_cache_variant(const gl_program_cache *c, size_t i)
{
    return c && i < c->n ? c->v[i].name : NULL;
}

GLuint gl_program_cache_program(const gl_program_cache *c, size_t i)
{
    return c && i < c->n ? c->v[i].program : 0;
}

void gl_program_cache_describe(const gl_program_cache *c, pass_plan *out)
{
    size_t cap = sizeof out->program / sizeof out->program[0];
    for (size_t i = 0; c && i < c->n && out->nprograms < cap; i++, out->nprograms++)
        snprintf(out->program[out->nprograms], sizeof out->program[0], "%s", c->v[i].name);
}

// >>sources

/* The files of one stage: [0] its own source, then includes in order of first inclusion. */
typedef struct stage_files {
    const char *name[GLP_MAX_FILES];
    size_t n;
} stage_files;

static int stage_file_index(const stage_files *f, const char *name)
{
    for (size_t i = 0; i < f->n; i++)
        if (strcmp(f->name[i], name) == 0)
            return (int)i;
    return -1;
}

/* If line (up to its end) is a preprocessor directive named word ("include",
 * "version"), returns a pointer just past the word; else NULL. */
static const char *directive(const char *line, const char *end, const char *word)
{
    const char *p = line;
    while (p < end && is_blank(*p))
        p++;
    if (p == end || *p != '#')
        return NULL;
    p++;
    while (p < end && is_blank(*p))
        p++;
    size_t n = strlen(word);
    if ((size_t)(end - p) < n || memcmp(p, word, n) != 0)
        return NULL;
    p += n;
    if (p < end && is_ident(*p))
        return NULL;
    return p;
}

/* Parses the rest of an #include line: blanks, "NAME", blanks, an optional //
 * comment. Copies NAME into name; false if the line is malformed. */
static bool include_name(const char *p, const char *end, char *name, size_t size)
{
    while (p < end && is_blank(*p))
        p++;
    if (p == end || *p != '"')
        return false;
    const char *start = ++p;
    while (p < end && *p != '"')
        p++;
    if (p == end || p == start || (size_t)(p - start) >= size)
        return false;
    memcpy(name, start, (size_t)(p - start));
    name[p - start] = '\0';
    p++;
    while (p < end && is_blank(*p))
        p++;
    return p == end || (end - p >= 2 && p[0] == '/' && p[1] == '/');
}

/* Appends source `name` (file number fileno of the stage) to out, expanding its
 * #includes. On failure returns the error and writes the reason to why. */
static gl_program_err expand(strbuf *out, stage_files *files, int fileno, int depth,
                             strbuf *why)
{
    const char *name = files->name[fileno];
    const char *src = gl_shader_source(name);
    if (!src) {
        sb_printf(why, "no embedded shader is called \"%s\"", name);
        return GLP_ERR_SOURCE;
    }
    unsigned lineno = 1;
    for (const char *line = src; *line; lineno++) {
        const char *end = strchr(line, '\n');
        const char *next = end ? end + 1 : line + strlen(line);
        if (!end)
            end = next;
        if (end > line && end[-1] == '\r')
            end--;
        if (directive(line, end, "version")) {
            sb_printf(why, "%s:%u: has #version (the program puts \"#version 450 core\" first)",
                      name, lineno);
            return GLP_ERR_DIRECTIVE;
        }
        const char *inc = directive(line, end, "include");
        if (!inc) {
            sb_add(out, line, (size_t)(next - line));
            if (next == end)   /* the last line had no newline */
                sb_puts(out, "\n");
            line = next;
            continue;
        }
        char incname[256];
        if (!include_name(inc, end, incname, sizeof incname)) {
            sb_printf(why, "%s:%u: malformed #include (expected #include \"NAME\" alone on its line)",
                      name, lineno);
            return GLP_ERR_DIRECTIVE;
        }
        if (stage_file_index(files, incname) >= 0) {
            sb_puts(out, "\n");   /* included already: keeps the line count */
        } else {
            if (!gl_shader_source(incname)) {
                sb_printf(why, "%s:%u: #include \"%s\": no embedded shader of that name", name,
                          lineno, incname);
                return GLP_ERR_SOURCE;
            }
            if (files->n == GLP_MAX_FILES || depth + 1 > GLP_MAX_INCLUDE_DEPTH) {
                sb_printf(why, "%s:%u: #include \"%s\": more than %d files or deeper than %d",
                          name, lineno, incname, GLP_MAX_FILES,
                          GLP_MAX_INCLUDE_DEPTH);
                return GLP_ERR_DIRECTIVE;
            }
            int k = (int)files->n;
            /* The name lives in the embedded table, which outlives everything. */
            for (size_t i = 0; i < gl_shader_count(); i++)
                if (strcmp(gl_shader_name(i), incname) == 0)
                    files->name[files->n++] = gl_shader_name(i);
            sb_printf(out, "#line 1 %d\n", k);
            gl_program_err e = expand(out, files, k, depth + 1, why);
            if (e != GLP_OK)
                return e;
            sb_printf(out, "#line %u %d\n", lineno + 1, fileno);
        }
        line = next;
    }
    return GLP_OK;
}

/* The full text of one stage: #version, defines, #line, the expanded source. */
static gl_program_err stage_text(const char *source, const define *defs, size_t ndefs,
                                 strbuf *out, stage_files *files, strbuf *why)
{
    sb_puts(out, "#version 450 core\n");
    for (size_t i = 0; i < ndefs; i++)
        sb_printf(out, "#define %s%s%s\n", defs[i].name, defs[i].value[0] ? " " : "",
                  defs[i].value);
    sb_puts(out, "#line 1 0\n");
    files->n = 0;
    files->name[files->n++] = source;
    gl_program_err e = expand(out, files, 0, 0, why);
    if (e == GLP_OK && out->oom)
        e = GLP_ERR_MEMORY;
    return e;
}

// >>building

typedef struct stage {
    GLenum type;
    const char *source;   /* embedded source name */
} stage;

static const char *stage_word(GLenum type)
{
    switch (type) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_COMPUTE_SHADER: return "compute";
    default: return "unknown";
    }
}

/* The info log of a shader (is_program false) or program, appended to b. */
static void append_log(strbuf *b, GLuint obj, bool is_program)
{
    GLint len = 0;
    if (is_program)
        gl.GetProgramiv(obj, GL_INFO_LOG_LENGTH, &len);
    else
        gl.GetShaderiv(obj, GL_INFO_LOG_LENGTH, &len);
    if (len <= 1) {
        sb_puts(b, "(the driver gave no log)");
        return;
    }
    char *log = malloc((size_t)len);
    if (!log) {
        b->oom = true;
        return;
    }
    GLsizei got = 0;
    if (is_program)
        gl.GetProgramInfoLog(obj, len, &got, log);
    else
        gl.GetShaderInfoLog(obj, len, &got, log);
    while (got > 0 && (log[got - 1] == '\n' || log[got - 1] == ' '))
        got--;
    sb_add(b, log, (size_t)got);
    free(log);
}

/* Compiles one stage; 0 on failure, with the stage and its log appended to why. */
static GLuint compile(GLenum type, const char *text, const stage_files *files, strbuf *why)
{
    GLuint sh = gl.CreateShader(type);
    const GLchar *strings[1] = {text};
    gl.ShaderSource(sh, 1, strings, NULL);
    gl.CompileShader(sh);
    GLint ok = GL_FALSE;
    gl.GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (ok)
        return sh;
    sb_printf(why, "the %s shader does not compile (source strings:", stage_word(type));
    for (size_t i = 0; i < files->n; i++)
        sb_printf(why, " %zu %s%s", i, files->name[i], i + 1 < files->n ? "," : "");
    sb_puts(why, "):\n");
    append_log(why, sh, false);
    gl.DeleteShader(sh);
    return 0;
}

/* Fills name (the variant name), key and who ("NAME (vertex V, fragment F, defines
 * A, B=1)"). */
static void describe_variant(const gl_program_desc *d, const define *defs, size_t ndefs,
                             strbuf *name, strbuf *key, strbuf *who)
{
    if (d->name) {
        sb_puts(name, d->name);
    } else {
        const char *base = d->fragment ? d->fragment : d->compute ? d->compute : "program";
        const char *dot = strchr(base, '.');
        sb_add(name, base, dot ? (size_t)(dot - base) : strlen(base));
    }
    for (size_t i = 0; i < ndefs; i++)
        sb_printf(name, "+%s%s%s", defs[i].name, defs[i].value[0] ? "=" : "", defs[i].value);

    sb_printf(key, "%s\n%s\n%s\n", d->vertex ? d->vertex : "", d->fragment ? d->fragment : "",
              d->compute ? d->compute : "");
    for (size_t i = 0; i < ndefs; i++)
        sb_printf(key, "%s %s\n", defs[i].name, defs[i].value);

    sb_printf(who, "program %s (", name->oom ? "?" : name->s);
    const char *sep = "";
    if (d->vertex) {
        sb_printf(who, "vertex %s", d->vertex);
        sep = ", ";
    }
    if (d->fragment) {
        sb_printf(who, "%sfragment %s", sep, d->fragment);
        sep = ", ";
    }
    if (d->compute) {
        sb_printf(who, "%scompute %s", sep, d->compute);
        sep = ", ";
    }
    if (ndefs) {
        sb_printf(who, "%sdefines ", sep);
        for (size_t i = 0; i < ndefs; i++)
            sb_printf(who, "%s%s%s%s", i ? ", " : "", defs[i].name, defs[i].value[0] ? "=" : "",
                      defs[i].value);
    } else if (!*sep) {
        sb_puts(who, "no stages");
    }
    sb_puts(who, ")");
}

gl_program_err gl_program_get(gl_program_cache *c, const gl_program_desc *desc,
                              GLuint *program, char *err, size_t errlen)
{
    *program = 0;
    if (errlen)
        err[0] = '\0';

    /* Defines: parsed, sorted, no name twice; then the cache's common ones (in the
     * key and the text, not in the name). */
    define defs[GLP_MAX_DEFINES + GLP_MAX_COMMON_DEFINES];
    size_t ndefs = 0;
    gl_program_err e = GLP_OK;
    strbuf name = {0}, key = {0}, who = {0}, why = {0}, text = {0};
    GLuint shaders[2] = {0, 0};
    size_t nshaders = 0;
    GLuint prog = 0;

    const char *reason = NULL;
    for (size_t i = 0; i < GLP_MAX_DEFINES && desc->defines[i]; i++) {
        if (!parse_define(desc->defines[i], &defs[ndefs], &reason)) {
            sb_printf(&why, "define \"%s\" %s", desc->defines[i], reason);
            e = GLP_ERR_DEFINE;
            break;
        }
        ndefs++;
    }
    qsort(defs, ndefs, sizeof defs[0], define_cmp);
    for (size_t i = 1; i < ndefs && e == GLP_OK; i++)
        if (strcmp(defs[i - 1].name, defs[i].name) == 0) {
            sb_printf(&why, "%s is defined twice", defs[i].name);
            e = GLP_ERR_DEFINE;
        }

    for (size_t i = 0; i < c->ncommon && e == GLP_OK; i++)
        for (size_t j = 0; j < ndefs; j++)
            if (strcmp(defs[j].name, c->common[i].name) == 0) {
                sb_printf(&why, "%s is one of the cache's common defines", defs[j].name);
                e = GLP_ERR_DEFINE;
            }

    describe_variant(desc, defs, e == GLP_OK ? ndefs : 0, &name, &key, &who);
    if (e == GLP_OK) {
        for (size_t i = 0; i < c->ncommon; i++) {
            sb_printf(&key, "common %s %s\n", c->common[i].name, c->common[i].value);
            defs[ndefs + i] = c->common[i];
        }
        ndefs += c->ncommon;
    }
    if (name.oom || key.oom || who.oom) {
        e = GLP_ERR_MEMORY;
        goto out;
    }
    if (e != GLP_OK)
        goto out;

    bool graphics = desc->vertex || desc->fragment;
    if ((graphics && desc->compute) || (!graphics && !desc->compute) ||
        (graphics && !(desc->vertex && desc->fragment))) {
        sb_puts(&why, "give a vertex and a fragment source, or a compute source alone");
        e = GLP_ERR_DESC;
        goto out;
    }

    for (size_t i = 0; i < c->n; i++)
        if (strcmp(c->v[i].key, key.s) == 0) {
            *program = c->v[i].program;
            goto out;
        }

    stage stages[2];
    size_t nstages = 0;
    if (desc->compute) {
        stages[nstages++] = (stage){GL_COMPUTE_SHADER, desc->compute};
    } else {
        stages[nstages++] = (stage){GL_VERTEX_SHADER, desc->vertex};
        stages[nstages++] = (stage){GL_FRAGMENT_SHADER, desc->fragment};
    }
    /* Every source is checked before anything is compiled. */
    for (size_t s = 0; s < nstages; s++)
        if (!gl_shader_source(stages[s].source)) {
            sb_printf(&why, "no embedded shader is called \"%s\"", stages[s].source);
            e = GLP_ERR_SOURCE;
            goto out;
        }

    for (size_t s = 0; s < nstages; s++) {
        stage_files files;
        text.len = 0;
        if (text.s)
            text.s[0] = '\0';
        e = stage_text(stages[s].source, defs, ndefs, &text, &files, &why);
        if (e != GLP_OK)
            goto out;
        GLuint sh = compile(stages[s].type, text.s, &files, &why);
        if (!sh) {
            e = GLP_ERR_COMPILE;
            goto out;
        }
        shaders[nshaders++] = sh;
    }

    prog = gl.CreateProgram();
    for (size_t s = 0; s < nshaders; s++)
        gl.AttachShader(prog, shaders[s]);
    gl.LinkProgram(prog);
    for (size_t s = 0; s < nshaders; s++)
        gl.DetachShader(prog, shaders[s]);
    GLint linked = GL_FALSE;
    gl.GetProgramiv(prog, GL_LINK_STATUS, &linked);
    if (!linked) {
        sb_puts(&why, "the program does not link:\n");
        append_log(&why, prog, true);
        e = GLP_ERR_LINK;
        goto out;
    }

    if (!GROW(c->v, c->cap, c->n + 1, 16)) {
        e = GLP_ERR_MEMORY;
        goto out;
    }
    variant v = {dup_string(key.s), dup_string(name.s), prog};
    if (!v.key || !v.name) {
        free(v.key);
        free(v.name);
        e = GLP_ERR_MEMORY;
        goto out;
    }
    {
        /* Labels are limited (GL_MAX_LABEL_LENGTH, at least 256 with the terminator);
         * a variant with many defines has a longer name: the label is its start. */
        GLint max_label = 0;
        gl.GetIntegerv(GL_MAX_LABEL_LENGTH, &max_label);
        size_t len = strlen(v.name);
        if (max_label > 0 && len >= (size_t)max_label)
            len = (size_t)max_label - 1;
        gl.ObjectLabel(GL_PROGRAM, prog, (GLsizei)len, v.name);
    }
    c->v[c->n++] = v;
    *program = prog;
    prog = 0;   /* the cache owns it now */

out:
    for (size_t s = 0; s < nshaders; s++)
        gl.DeleteShader(shaders[s]);
    if (prog)
        gl.DeleteProgram(prog);
    if (e == GLP_ERR_MEMORY || why.oom)
        snprintf(err, errlen, "program: out of memory");
    else if (e != GLP_OK)
        snprintf(err, errlen, "%s: %s", who.oom || !who.s ? "program" : who.s,
                 why.s ? why.s : gl_program_err_text(e));
    sb_free(&name);
    sb_free(&key);
    sb_free(&who);
    sb_free(&why);
    sb_free(&text);
    return e;
}
