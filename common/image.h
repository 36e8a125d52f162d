#pragma once
/* An image in memory and the error between two (common/image_io.h makes and compares
 * them; common/image_codec.h passes them to the image module). */
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

#ifdef __cplusplus
}
#endif
