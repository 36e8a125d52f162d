#pragma once
/* Images in memory, their files and their comparison. Encoding and decoding go through
 * OpenImageIO in the image module, loaded on the first such call (image_codec.h says
 * why); comparison is plain C. Images are tightly packed, row 0 at the TOP (callers flip
 * GL readbacks). */
#include <stdbool.h>
#include <stddef.h>

#include "common/image.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Writes by extension (.png, .exr, ...), under a temporary name then renamed. */
bool image_write(const char *path, const image *img, char *err, size_t errlen);
/* Reads any format OIIO knows; pixels malloc'ed, converted to `want` type. */
bool image_read(const char *path, image_type want, image *out, char *err, size_t errlen);
/* As image_read, from `size` bytes in memory (an embedded or already read file): `name`
 * (NULL: "embedded image") names it in messages, and its extension, or else the bytes'
 * PNG or JPEG signature, picks the format. */
bool image_decode(const void *data, size_t size, const char *name, image_type want, image *out,
                  char *err, size_t errlen);
/* The size image_decode would give, from the header alone (no pixel decoded): to refuse
 * an image too large before paying for it. *channels is the file's channel count and
 * *bytes what its pixels take decoded in the file's own format: width x height x
 * channels x bytes a channel (saturating at UINT64_MAX). */
bool image_probe(const void *data, size_t size, const char *name, int *width, int *height,
                 int *channels, unsigned long long *bytes, char *err, size_t errlen);
void image_free(image *img);

/* Loads the image module now (it is loaded on first use otherwise): a process that
 * forks workers which write images loads it once, before the fork. False with the
 * reason when it cannot be loaded (then every encode and decode fails with it). The
 * module is SHADESWEEP_IMAGE_MODULE when set, else shadesweep-image.so beside the program
 * (BINDIR/../LIBDIR/shadesweep), in the build folder, or at the install path. */
bool image_io_load(char *err, size_t errlen);

/* Non-finite values in a float image (0 for IMAGE_U8). */
size_t image_count_nonfinite(const image *img);

/* a and b must have equal size and channels. Computed in double precision.
 * Values non-finite in either image are left out of rmse and max_abs (they count in
 * `nonfinite`) and their pixel counts as differing. Alpha is never premultiplied:
 * images are written and read with oiio:UnassociatedAlpha. */
bool image_compare(const image *a, const image *b, image_error *out, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
