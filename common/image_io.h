#pragma once
/* The only door to OpenImageIO (image_io.cpp is a thin extern "C" shim).
 * Images are tightly packed, row 0 at the TOP (callers flip GL readbacks). */
#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum image_type { IMAGE_U8 = 0, IMAGE_F32 } image_type;

typedef struct image {
    int width, height, channels;
    image_type type;
    void *pixels;           /* width*height*channels of uint8_t or float */
} image;

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

/* Non-finite values in a float image (0 for IMAGE_U8). */
size_t image_count_nonfinite(const image *img);

typedef struct image_error {
    double rmse;            /* over all channels, values in [0,1] for U8 (v/255) */
    double psnr_db;         /* INFINITY when rmse == 0 */
    double max_abs;
    double frac_over_1_255; /* fraction of pixels with any channel off by more than 1/255 */
    size_t nonfinite;       /* non-finite values in either image */
    /* over the reference's edge pixels only: image_edge_rmse (image_ref.h) fills them,
     * image_compare leaves them as they are */
    double edge_rmse;       /* NAN when the reference has no edge */
    size_t edge_pixels;
} image_error;

/* a and b must have equal size and channels. Computed in double precision.
 * Values non-finite in either image are left out of rmse and max_abs (they count in
 * `nonfinite`) and their pixel counts as differing. Alpha is never premultiplied:
 * images are written and read with oiio:UnassociatedAlpha. */
bool image_compare(const image *a, const image *b, image_error *out, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
