#pragma once
/* Between common/image_io.c and the image module (image_codec.cpp, built as
 * shadesweep-image.so): the four calls that need OpenImageIO, as one table the module
 * exports under IMAGE_CODEC_SYMBOL.
 *
 * Why a module: OpenImageIO brings some 260 shared libraries (codecs, GDAL, FFmpeg,
 * GStreamer). Linked into the program, the dynamic loader resolved them at every start
 * (0.55 s on the 2-core CI machine, for `shadesweep version` too) and each later dlopen
 * of Mesa's driver searched all of them. Loaded on first use with RTLD_LOCAL, a command
 * that writes no image never pays, and Mesa's lookups see a short global scope. */
#include <stdbool.h>
#include <stddef.h>

#include "common/image.h"

#ifdef __cplusplus
extern "C" {
#endif

#define IMAGE_CODEC_ABI 1
#define IMAGE_CODEC_SYMBOL "shadesweep_image_codec"

typedef struct image_codec {
    int abi;   /* IMAGE_CODEC_ABI: a module of another build is refused */
    bool (*write)(const char *path, const image *img, char *err, size_t errlen);
    bool (*read)(const char *path, image_type want, image *out, char *err, size_t errlen);
    bool (*decode)(const void *data, size_t size, const char *name, image_type want,
                   image *out, char *err, size_t errlen);
    bool (*probe)(const void *data, size_t size, const char *name, int *width, int *height,
                  int *channels, unsigned long long *bytes, char *err, size_t errlen);
} image_codec;

const image_codec *shadesweep_image_codec(void);

#ifdef __cplusplus
}
#endif
