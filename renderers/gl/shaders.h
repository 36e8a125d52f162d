#pragma once
/* GLSL sources embedded into the binary at build time.
 *
 * Every renderers/shaders/NAME.glsl listed in renderers/meson.build (explicitly:
 * no globbing) is turned into C data by renderers/gl/embed.c when the project is
 * built; nothing is read from disk at run time. A source is found by its file
 * name without ".glsl".
 *
 * The conventions for the files (program.h relies on them): the comment above
 * gl_shader_source below. */
#include <stddef.h>

/* Conventions for the files (program.h relies on them):
 * - One shader stage per file; the stage is in the name:
 *       NAME.vert.glsl   vertex shader
 *       NAME.frag.glsl   fragment shader
 *       NAME.comp.glsl   compute shader
 *       NAME.inc.glsl    code shared by several shaders, pulled in with
 *                        #include "NAME.inc" (program.h expands it)
 *   The program's stages are named when it is built (gl_program_desc), so the
 *   suffix is for people; the lookup does not care.
 * - No #version line: program.h puts "#version 450 core" and the variant's
 *   #defines in front of the source, then "#line 1 0", so that a compiler
 *   message's line numbers are those of the file.
 * - Text ending in a newline, no NUL byte (the build refuses anything else). */

/* The embedded source called name ("fullscreen.vert"), NUL-terminated, or NULL
 * when there is none of that name (NULL too). */
const char *gl_shader_source(const char *name);

/* Number of embedded sources, and their names in strcmp order (NULL past the end). */
size_t gl_shader_count(void);
const char *gl_shader_name(size_t i);
