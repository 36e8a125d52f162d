/* Images: the image module's loader (image_codec.h), and what needs no codec (free,
 * non-finite count, comparison), in C. */
#include "common/image_io.h"
#include "common/image_codec.h"

#include <dlfcn.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "config.h"

static pthread_once_t load_once = PTHREAD_ONCE_INIT;
static const image_codec *codec;
static char load_err[1024];

static bool is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* Where the module is, as image_io_load says; false with the places looked in. */
static bool find_module(char *out, size_t len, char *looked, size_t looklen)
{
    const char *env = getenv("SHADESWEEP_IMAGE_MODULE");
    if (env && *env) {
        snprintf(out, len, "%s", env);
        snprintf(looked, looklen, "SHADESWEEP_IMAGE_MODULE=%s", env);
        return true;   /* dlopen says what is wrong with it */
    }
    char places[3][2048];
    int n = 0;
    char exe[1024];
    ssize_t k = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (k > 0) {
        exe[k] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';   /* BINDIR */
            snprintf(places[n++], sizeof places[0], "%s/../%s", exe, SHADESWEEP_IMAGE_MODULE_REL);
        }
    }
    snprintf(places[n++], sizeof places[0], "%s", SHADESWEEP_IMAGE_MODULE_BUILD);
    snprintf(places[n++], sizeof places[0], "%s", SHADESWEEP_IMAGE_MODULE_INSTALLED);
    looked[0] = '\0';
    for (int i = 0; i < n; i++) {
        if (is_file(places[i])) {
            snprintf(out, len, "%s", places[i]);
            return true;
        }
        size_t used = strlen(looked);
        snprintf(looked + used, looklen - used, "%s%s", i ? ", " : "", places[i]);
    }
    return false;
}

static void load(void)
{
    char path[2048], looked[3 * 2048 + 64];
    if (!find_module(path, sizeof path, looked, sizeof looked)) {
        snprintf(load_err, sizeof load_err,
                 "the image module (shadesweep-image.so) is not installed: looked in %.900s",
                 looked);
        return;
    }
    /* RTLD_LOCAL: OpenImageIO's libraries stay out of the global scope (image_codec.h) */
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        snprintf(load_err, sizeof load_err, "cannot load the image module: %.900s", dlerror());
        return;
    }
    const image_codec *(*entry)(void);
    *(void **)&entry = dlsym(h, IMAGE_CODEC_SYMBOL);
    const image_codec *c = entry ? entry() : NULL;
    if (!c || c->abi != IMAGE_CODEC_ABI) {
        snprintf(load_err, sizeof load_err,
                 "%.900s is not this build's image module (%s)", path,
                 c ? "another interface version" : "no " IMAGE_CODEC_SYMBOL);
        dlclose(h);
        return;
    }
    codec = c;
}

bool image_io_load(char *err, size_t errlen)
{
    pthread_once(&load_once, load);
    if (!codec && err && errlen)
        snprintf(err, errlen, "%s", load_err);
    return codec != NULL;
}

/* The codec, or NULL with "WHAT: cannot VERB image: why" in err. */
static const image_codec *need(const char *what, const char *verb, char *err, size_t errlen)
{
    if (image_io_load(NULL, 0))
        return codec;
    if (err && errlen)
        snprintf(err, errlen, "%s: cannot %s image: %s", what, verb, load_err);
    return NULL;
}

bool image_write(const char *path, const image *img, char *err, size_t errlen)
{
    const image_codec *c = need(path ? path : "image", "write", err, errlen);
    return c && c->write(path, img, err, errlen);
}

bool image_read(const char *path, image_type want, image *out, char *err, size_t errlen)
{
    if (out)
        memset(out, 0, sizeof *out);   /* safe to image_free() on failure */
    const image_codec *c = need(path ? path : "image", "read", err, errlen);
    return c && c->read(path, want, out, err, errlen);
}

bool image_decode(const void *data, size_t size, const char *name, image_type want, image *out,
                  char *err, size_t errlen)
{
    if (out)
        memset(out, 0, sizeof *out);
    const image_codec *c = need(name && name[0] ? name : "embedded image", "read", err, errlen);
    return c && c->decode(data, size, name, want, out, err, errlen);
}

bool image_probe(const void *data, size_t size, const char *name, int *width, int *height,
                 int *channels, unsigned long long *bytes, char *err, size_t errlen)
{
    const image_codec *c = need(name && name[0] ? name : "embedded image", "read", err, errlen);
    return c && c->probe(data, size, name, width, height, channels, bytes, err, errlen);
}

void image_free(image *img)
{
    if (img == NULL)
        return;
    free(img->pixels);
    img->pixels = NULL;
    img->width = img->height = img->channels = 0;
}

/* The number of channel values, or false when the dimensions are not a sane image. */
static bool value_count(int w, int h, int c, size_t *out)
{
    if (w <= 0 || h <= 0 || c <= 0)
        return false;
    size_t n = (size_t)w;
    if (n > SIZE_MAX / (size_t)h)
        return false;
    n *= (size_t)h;
    if (n > SIZE_MAX / (size_t)c / sizeof(float))
        return false;
    *out = n * (size_t)c;
    return true;
}

static bool valid_image(const image *img, const char *what, char *err, size_t errlen)
{
    size_t n;
    if (img == NULL || img->pixels == NULL || (img->type != IMAGE_U8 && img->type != IMAGE_F32) ||
        !value_count(img->width, img->height, img->channels, &n)) {
        snprintf(err, errlen, "%s: not a valid image (no pixels or bad size)", what);
        return false;
    }
    return true;
}

size_t image_count_nonfinite(const image *img)
{
    size_t n;
    if (img == NULL || img->type != IMAGE_F32 || img->pixels == NULL ||
        !value_count(img->width, img->height, img->channels, &n))
        return 0;
    const float *p = img->pixels;
    size_t bad = 0;
    for (size_t i = 0; i < n; i++)
        bad += isfinite(p[i]) ? 0 : 1;
    return bad;
}

/* Channel value i of img as a number in the [0,1] scale (U8 as v/255). */
static double value_at(const image *img, size_t i)
{
    if (img->type == IMAGE_U8)
        return (double)((const uint8_t *)img->pixels)[i] / 255.0;
    return (double)((const float *)img->pixels)[i];
}

/* In double precision (OpenImageIO's ImageBufAlgo::compare works in float): U8
 * differences come out exact (3/255 is 3/255). */
bool image_compare(const image *a, const image *b, image_error *out, char *err, size_t errlen)
{
    if (!valid_image(a, "image compare (first image)", err, errlen) ||
        !valid_image(b, "image compare (second image)", err, errlen))
        return false;
    if (a->width != b->width || a->height != b->height || a->channels != b->channels) {
        snprintf(err, errlen,
                 "image compare: sizes differ: %dx%d with %d channels vs %dx%d with %d channels",
                 a->width, a->height, a->channels, b->width, b->height, b->channels);
        return false;
    }
    const size_t pixels = (size_t)a->width * (size_t)a->height;
    const size_t ch = (size_t)a->channels;
    const bool both_u8 = a->type == IMAGE_U8 && b->type == IMAGE_U8;
    const uint8_t *a8 = a->pixels, *b8 = b->pixels;

    double sum_sq = 0.0, max_abs = 0.0;
    size_t finite_values = 0, over = 0;
    for (size_t p = 0; p < pixels; p++) {
        bool differs = false;
        for (size_t c = 0; c < ch; c++) {
            size_t i = p * ch + c;
            double d;
            if (both_u8) {
                int di = (int)a8[i] - (int)b8[i];
                differs = differs || di > 1 || di < -1;
                d = (double)di / 255.0;
            } else {
                double va = value_at(a, i), vb = value_at(b, i);
                if (!isfinite(va) || !isfinite(vb)) {
                    differs = true;
                    continue;
                }
                d = va - vb;
                differs = differs || fabs(d) > 1.0 / 255.0;
            }
            double ad = fabs(d);
            sum_sq += d * d;
            max_abs = ad > max_abs ? ad : max_abs;
            finite_values++;
        }
        over += differs ? 1 : 0;
    }
    out->rmse = finite_values > 0 ? sqrt(sum_sq / (double)finite_values) : NAN;
    out->psnr_db = out->rmse == 0.0 ? INFINITY : 20.0 * log10(1.0 / out->rmse);
    out->max_abs = finite_values > 0 ? max_abs : NAN;
    out->frac_over_1_255 = (double)over / (double)pixels;
    out->nonfinite = image_count_nonfinite(a) + image_count_nonfinite(b);
    return true;
}
