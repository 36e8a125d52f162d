#pragma once
/* >>import (file_import.cpp): assimp's import with only the importers of the file's
 * format registered. Shared by file_load.c and its C++ shim. */
#include <stddef.h>

#include <assimp/cfileio.h>
#include <assimp/scene.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Imports path (through io, with assimp's post-processing flags; drop_primitives, if
 * not 0, is AI_CONFIG_PP_SBP_REMOVE) with only the importers that claim its extension,
 * which must be .gltf, .glb or .obj (any case): no other importer sniffs the bytes of a
 * file its own importer declined. NULL with a one-line message (assimp's error, or the
 * extension refused); the scene is freed with aiReleaseImport. */
const struct aiScene *file_import(const char *path, unsigned flags, struct aiFileIO *io,
                                  int drop_primitives, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
