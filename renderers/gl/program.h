#pragma once
/* GLSL programs from the embedded sources (shaders.h), compiled in #define
 * variants, each variant once.
 *
 * Use, what a stage is compiled from line by line, #include, the cache and its variant
 * names: the comment above the types below. Needs GL 4.5 (the shaders are #version 450)
 * and a current context whose GL table is loaded. */
#include "renderers/gl/loader.h"
#include "renderers/gl/stats.h"

#include <stdbool.h>
#include <stddef.h>

enum {
    GLP_MAX_DEFINES = 16,
    GLP_MAX_FILES = 16,          /* per stage, the stage's own file included */
    GLP_MAX_INCLUDE_DEPTH = 8,
};

/* Zero value: nothing (refused as GLP_ERR_DESC). Give vertex + fragment, or
 * compute alone. */
/*     gl_program_cache *pc = gl_program_cache_create();
 *     GLuint prog;
 *     gl_program_err e = gl_program_get(pc, &(gl_program_desc){
 *             .name = "light_point",
 *             .vertex = "light_volume.vert", .fragment = "light_point.frag",
 *             .defines = {"NORMAL_MAP", "MAX_LIGHTS 64"}},
 *         &prog, err, sizeof err);
 *     ... gl_state_program(state, prog) ...
 *     gl_program_cache_destroy(pc);      // deletes every program it made
 *
 * What a stage is compiled from, line by line:
 *
 *     #version 450 core
 *     #define MAX_LIGHTS 64               the defines, sorted by name
 *     #define NORMAL_MAP
 *     #line 1 0
 *     <the source, with each #include "NAME" replaced by that embedded source
 *      between "#line 1 K" and "#line N+1 0" (K = 1, 2, ... in order of first
 *      inclusion), so compiler messages read "K:LINE(COL)" with K 0 for the file
 *      itself and LINE the line in that file>
 *
 * - #include "NAME" must stand alone on its line (blanks and a // comment may
 *   follow); it is expanded before the GLSL preprocessor runs, so also inside a
 *   false #if; a file already included into the stage is not included again (an
 *   empty line stands in its place). Up to GLP_MAX_FILES files per stage,
 *   nested up to GLP_MAX_INCLUDE_DEPTH.
 * - A source with a #version line is refused (the program adds it).
 * - Binding points belong in the shaders: layout(location = N) for inputs,
 *   outputs and plain uniforms, layout(binding = N) for samplers and blocks, so
 *   that nothing has to be looked up or bound per program after linking.
 *
 * The cache: a variant is identified by (vertex, fragment, compute source names,
 * the set of defines): the order of defines does not matter, "A 1" and "A  1" are
 * the same define, the display name is not part of it (a second desc naming the
 * same variant under another name gets the first one's program and name). Failed
 * builds are not cached. Each variant built is listed for renderer_describe under
 * its variant name: the display name, then "+NAME" or "+NAME=VALUE" per define in
 * sorted order ("light_point+MAX_LIGHTS=64+NORMAL_MAP").
 *
 * Needs GL 4.5 (the shaders are #version 450) and a current context whose GL table
 * is loaded; every GL object is made and deleted in that context. */
typedef struct gl_program_desc {
    const char *name;        /* display name; NULL: the fragment (or compute) source
                                name up to its first '.' ("light_point.frag" -> "light_point") */
    const char *vertex;      /* embedded source names (shaders.h) */
    const char *fragment;
    const char *compute;
    /* "NAME" or "NAME VALUE" (NAME a GLSL identifier; VALUE the rest of the line,
     * blanks around it dropped); the list ends at the first NULL. */
    const char *defines[GLP_MAX_DEFINES];
} gl_program_desc;

/* Error ids and their descriptions, one list (sokol style). */
#define GLP_ERRORS(X)                                                                     \
    X(GLP_OK, "ok")                                                                       \
    X(GLP_ERR_DESC, "the description names neither vertex+fragment nor compute alone")   \
    X(GLP_ERR_SOURCE, "a source (or an #include) names no embedded shader")               \
    X(GLP_ERR_DEFINE, "a define is malformed or repeated")                                \
    X(GLP_ERR_DIRECTIVE, "a source has #version, a malformed #include or too many files") \
    X(GLP_ERR_COMPILE, "a stage does not compile")                                        \
    X(GLP_ERR_LINK, "the program does not link")                                          \
    X(GLP_ERR_MEMORY, "out of memory")

typedef enum gl_program_err {
#define GLP_ERR_ENUM(id, text) id,
    GLP_ERRORS(GLP_ERR_ENUM)
#undef GLP_ERR_ENUM
} gl_program_err;

const char *gl_program_err_text(gl_program_err e);

typedef struct gl_program_cache gl_program_cache;

gl_program_cache *gl_program_cache_create(void);    /* NULL when memory runs out */
void gl_program_cache_destroy(gl_program_cache *c); /* deletes its programs; NULL is fine */

/* The program of desc's variant in *program, built now if it is not in the cache
 * yet. On failure *program is 0, nothing is cached, and err holds one message
 * naming the variant, its sources and defines, and for GLP_ERR_COMPILE /
 * GLP_ERR_LINK the stage, which file each source string number is, and the
 * driver's info log:
 *
 *     program test_color+TEST_COMPILE_ERROR (vertex fullscreen.vert, fragment
 *     test_color.frag, defines TEST_COMPILE_ERROR): the fragment shader does not
 *     compile (source strings: 0 test_color.frag, 1 test_common.inc):
 *     0:32(6): error: `this_is_not_declared' undeclared
 *
 * Note that Mesa (22.3) also reports a failed compile, though not a failed link,
 * through KHR_debug as a GL_DEBUG_TYPE_ERROR message, which a debug context counts
 * as a GL error. */
gl_program_err gl_program_get(gl_program_cache *c, const gl_program_desc *desc,
                              GLuint *program, char *err, size_t errlen);

/* Defines that every program of this cache is compiled with besides its desc's (at most
 * GLP_MAX_COMMON_DEFINES; none replaces the last list): renderer_base_scene sets the
 * light features of the scene's lights (lighting.inc's LIGHT_TYPES and
 * LIGHT_ATTENUATIONS) before the renderer builds its programs. They are part of each
 * variant's identity (a program built under other common defines is not reused) but
 * not of its name: the variant names stay what the renderer asked for, and the pass
 * plan says once what the common defines left out. A desc naming a common define is
 * refused as GLP_ERR_DEFINE. False, and the cache unchanged, when one is malformed or
 * repeated, or there are too many. */
/* renderer_base_scene's are at most 7: LIGHT_TYPES, LIGHT_ATTENUATIONS, VERTEX_COLOR,
 * UV2, SKINNING, SHADING_PBR, ENVIRONMENT (renderers/frame/base.c) */
enum { GLP_MAX_COMMON_DEFINES = 8 };
bool gl_program_cache_set_common(gl_program_cache *c, const char *const *defines, size_t n);

/* Variants built so far (each compiled and linked once), in order of building. */
size_t gl_program_cache_count(const gl_program_cache *c);
const char *gl_program_cache_variant(const gl_program_cache *c, size_t i);   /* NULL past the end */
GLuint gl_program_cache_program(const gl_program_cache *c, size_t i);        /* 0 past the end */

/* Appends the variant names to out->program[] from out->nprograms on, as many as
 * fit (RENDERER_MAX_PASSES; each cut to its 63 characters), for renderer_describe. */
void gl_program_cache_describe(const gl_program_cache *c, pass_plan *out);
