// The image module (shadesweep-image.so): the only door to OpenImageIO, loaded by
// common/image_io.c on the first encode or decode; see image_codec.h for why.
//
// No C++ exception crosses into C: every entry point catches everything and turns
// it into false with a message.
#include "common/image_codec.h"
#include "common/fsutil.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace {

void set_err(char *err, size_t errlen, const std::string &msg)
{
    if (err != nullptr && errlen > 0)
        std::snprintf(err, errlen, "%s", msg.c_str());
}

// OIIO error strings may span lines; one line reads better in our logs.
std::string one_line(std::string s)
{
    while (!s.empty() && (s.back() == '\n' || s.back() == ' '))
        s.pop_back();
    for (char &c : s)
        if (c == '\n')
            c = ' ';
    return s.empty() ? std::string("unknown error") : s;
}

size_t type_size(image_type t)
{
    return t == IMAGE_F32 ? sizeof(float) : sizeof(uint8_t);
}

TypeDesc type_desc(image_type t)
{
    return t == IMAGE_F32 ? TypeDesc(TypeDesc::FLOAT) : TypeDesc(TypeDesc::UINT8);
}

// Number of channel values, or false when the dimensions are not a sane image.
bool value_count(int w, int h, int c, size_t *out)
{
    if (w <= 0 || h <= 0 || c <= 0)
        return false;
    size_t n = (size_t)w;
    if (n > std::numeric_limits<size_t>::max() / (size_t)h)
        return false;
    n *= (size_t)h;
    if (n > std::numeric_limits<size_t>::max() / (size_t)c / sizeof(float))
        return false;
    *out = n * (size_t)c;
    return true;
}

bool valid_image(const image *img, const char *what, char *err, size_t errlen)
{
    size_t n;
    if (img == nullptr || img->pixels == nullptr ||
        (img->type != IMAGE_U8 && img->type != IMAGE_F32) ||
        !value_count(img->width, img->height, img->channels, &n)) {
        set_err(err, errlen, std::string(what) + ": not a valid image (no pixels or bad size)");
        return false;
    }
    return true;
}

// Lower-case extension without the dot ("" when there is none).
std::string extension_of(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    size_t base = slash == std::string::npos ? 0 : slash + 1;
    size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || dot <= base)
        return std::string();
    std::string ext = path.substr(dot + 1);
    for (char &c : ext)
        if (c >= 'A' && c <= 'Z')
            c = (char)(c - 'A' + 'a');
    return ext;
}

// Formats that store floats as they are; everything else gets 8-bit pixels.
bool stores_float(const std::string &ext)
{
    return ext == "exr" || ext == "sxr" || ext == "mxr" || ext == "tif" || ext == "tiff" ||
           ext == "pfm" || ext == "hdr";
}

// The image encoded into bytes in memory (IOVecOutput): OIIO's writers then never touch
// the disk, and the bytes go through afile (common/fsutil.h), which checks every write,
// the flush, fsync and the file's size before the rename. A format whose writer cannot
// write to a proxy is refused (PNG and EXR, what this program writes, can).
bool encode(const std::string &final_path, const std::string &ext, const image *img,
            std::vector<unsigned char> &bytes, std::string &why)
{
    auto out = ImageOutput::create(final_path);
    if (!out) {
        why = "cannot write ." + ext + " images: " + one_line(OIIO::geterror());
        return false;
    }
    if (!out->supports("ioproxy")) {
        why = std::string("OpenImageIO's ") + out->format_name() +
              " writer cannot write to memory, so its writes could not be checked";
        return false;
    }
    TypeDesc file_type = type_desc(img->type);
    if (img->type == IMAGE_F32 && !stores_float(ext))
        file_type = TypeDesc::UINT8; // OIIO converts: clamp to [0,1], scale, round
    ImageSpec spec(img->width, img->height, img->channels, file_type);
    // Pixels are written as they are: an alpha channel is never (un)premultiplied.
    spec.attribute("oiio:UnassociatedAlpha", 1);

    OIIO::Filesystem::IOVecOutput vec(bytes);
    bool ok = out->set_ioproxy(&vec) && out->open(final_path, spec);
    if (!ok) {
        why = one_line(out->geterror());
    } else {
        ok = out->write_image(type_desc(img->type), img->pixels);
        if (!ok)
            why = one_line(out->geterror());
        // close() writes the rest of the file; it must succeed too.
        if (!out->close() && ok) {
            ok = false;
            why = one_line(out->geterror());
        }
    }
    if (ok && bytes.empty()) {
        why = "the encoder produced no bytes";
        ok = false;
    }
    return ok;
}

bool write_impl(const char *path, const image *img, char *err, size_t errlen)
{
    if (path == nullptr || path[0] == '\0') {
        set_err(err, errlen, "image write: empty path");
        return false;
    }
    if (!valid_image(img, path, err, errlen))
        return false;
    const std::string final_path(path);
    const std::string ext = extension_of(final_path);
    if (ext.empty()) {
        set_err(err, errlen, final_path + ": no extension to choose an image format by");
        return false;
    }
    std::vector<unsigned char> bytes;
    std::string why;
    if (!encode(final_path, ext, img, bytes, why)) {
        set_err(err, errlen, final_path + ": cannot write image: " + why);
        return false;
    }
    afile f;
    if (!afile_open(&f, path, err, errlen))
        return false;
    afile_write(&f, bytes.data(), bytes.size()); // afile_commit reports its error
    return afile_commit(&f, err, errlen);
}

// Whether a PNG's chunks are all there, up to IEND; else why not. libpng meets the end
// of a cut-off file inside its decoder, prints a line of its own to stderr and longjmps
// out of OpenImageIO's reader, which loses an allocation on the way (31 bytes under
// LeakSanitizer): a file cut short is refused here, before libpng sees it.
bool png_complete(const unsigned char *b, size_t size, std::string &why)
{
    size_t at = 8;
    while (size - at >= 12) {
        uint32_t len = (uint32_t)b[at] << 24 | (uint32_t)b[at + 1] << 16 |
                       (uint32_t)b[at + 2] << 8 | b[at + 3];
        std::string type(reinterpret_cast<const char *>(b + at + 4), 4);
        if (len > size - at - 12) {
            why = "cut off: its " + type + " chunk claims " + std::to_string(len) +
                  " bytes, " + std::to_string(size - at - 12) + " follow";
            return false;
        }
        if (type == "IEND")
            return true;
        at += 12 + (size_t)len;
    }
    why = "cut off: it ends after " + std::to_string(size) + " bytes without its IEND chunk";
    return false;
}

// From a file (mem == nullptr) or from size bytes at mem, which `path` names in messages
// (its extension, or else the bytes' signature, picks the format).
bool read_impl(const char *path, image_type want, image *out, char *err, size_t errlen,
               const void *mem = nullptr, size_t size = 0)
{
    if (out == nullptr) {
        set_err(err, errlen, "image read: bug: no output image");
        return false;
    }
    *out = image{}; // safe to image_free() on failure
    if (path == nullptr || path[0] == '\0') {
        set_err(err, errlen, "image read: empty path");
        return false;
    }
    if (want != IMAGE_U8 && want != IMAGE_F32) {
        set_err(err, errlen, std::string(path) + ": bug: unknown image type requested");
        return false;
    }
    // As written: PNG color is not premultiplied by its alpha on the way in.
    ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    errno = 0;
    std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy;
    std::string name = path;
    if (mem != nullptr) {
        proxy.reset(new OIIO::Filesystem::IOMemReader(mem, size));
        const unsigned char *b = static_cast<const unsigned char *>(mem);
        if (size >= 8 && std::memcmp(b, "\x89PNG", 4) == 0)
            name = "embedded.png";
        else if (size >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF)
            name = "embedded.jpg";
        std::string why;
        if (size >= 8 && std::memcmp(b, "\x89PNG", 4) == 0 && !png_complete(b, size, why)) {
            set_err(err, errlen, std::string(path) + ": cannot read image: " + why);
            return false;
        }
        // readers look for the proxy in the configuration (OIIO 2.4 drops it otherwise)
        void *ptr = proxy.get();
        config.attribute("oiio:ioproxy", TypeDesc::PTR, &ptr);
    }
    auto in = ImageInput::open(name, &config, proxy.get());
    if (!in) {
        int e = errno;
        std::string why = one_line(OIIO::geterror());
        if (e != 0 && why.find(std::strerror(e)) == std::string::npos)
            why += std::string(" (") + std::strerror(e) + ")";
        set_err(err, errlen, std::string(path) + ": cannot read image: " + why);
        return false;
    }
    const ImageSpec &spec = in->spec();
    size_t n;
    if (spec.deep || spec.depth > 1 || !value_count(spec.width, spec.height, spec.nchannels, &n)) {
        set_err(err, errlen, std::string(path) + ": unsupported image (deep, volume or empty)");
        return false;
    }
    std::unique_ptr<void, void (*)(void *)> pixels(std::malloc(n * type_size(want)), std::free);
    if (!pixels) {
        set_err(err, errlen, std::string(path) + ": out of memory");
        return false;
    }
    if (!in->read_image(0, 0, 0, spec.nchannels, type_desc(want), pixels.get())) {
        set_err(err, errlen, std::string(path) + ": cannot read image: " +
                                 one_line(in->geterror()));
        return false;
    }
    in->close();
    out->width = spec.width;
    out->height = spec.height;
    out->channels = spec.nchannels;
    out->type = want;
    out->pixels = pixels.release();
    return true;
}

// body() for the C interface: an exception becomes "WHAT: cannot VERB image: why" and false.
template <typename Body>
bool guarded(const char *what, const char *verb, char *err, size_t errlen, Body body)
{
    try {
        return body();
    } catch (const std::exception &e) {
        set_err(err, errlen, std::string(what) + ": cannot " + verb + " image: " + e.what());
    } catch (...) {
        set_err(err, errlen,
                std::string(what) + ": cannot " + verb + " image: unknown exception");
    }
    return false;
}

bool codec_write(const char *path, const image *img, char *err, size_t errlen)
{
    return guarded(path ? path : "image", "write", err, errlen,
                   [&] { return write_impl(path, img, err, errlen); });
}

bool codec_read(const char *path, image_type want, image *out, char *err, size_t errlen)
{
    return guarded(path ? path : "image", "read", err, errlen,
                   [&] { return read_impl(path, want, out, err, errlen); });
}

bool codec_decode(const void *data, size_t size, const char *name, image_type want, image *out,
                  char *err, size_t errlen)
{
    const char *what = name && name[0] ? name : "embedded image";
    return guarded(what, "read", err, errlen, [&] {
        if (data == nullptr || size == 0) {
            if (out != nullptr)
                *out = image{};
            set_err(err, errlen, std::string(what) + ": cannot read image: no bytes");
            return false;
        }
        return read_impl(what, want, out, err, errlen, data, size);
    });
}

bool codec_probe(const void *data, size_t size, const char *name, int *width, int *height,
                 int *channels, unsigned long long *bytes, char *err, size_t errlen)
{
    const char *what = name && name[0] ? name : "embedded image";
    try {
        if (data == nullptr || size == 0) {
            set_err(err, errlen, std::string(what) + ": cannot read image: no bytes");
            return false;
        }
        // the format as read_impl picks it, the header only: no pixel is decoded
        OIIO::Filesystem::IOMemReader proxy(data, size);
        std::string fmt = what;
        const unsigned char *b = static_cast<const unsigned char *>(data);
        if (size >= 8 && std::memcmp(b, "\x89PNG", 4) == 0)
            fmt = "embedded.png";
        else if (size >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF)
            fmt = "embedded.jpg";
        ImageSpec config;
        void *ptr = &proxy;
        config.attribute("oiio:ioproxy", TypeDesc::PTR, &ptr);
        auto in = ImageInput::open(fmt, &config, &proxy);
        if (!in) {
            set_err(err, errlen, std::string(what) + ": cannot read image: " +
                                     one_line(OIIO::geterror()));
            return false;
        }
        const ImageSpec &spec = in->spec();
        *width = spec.width;
        *height = spec.height;
        *channels = spec.nchannels;
        // a header may claim any of the four: the product saturates rather than wraps
        unsigned long long total = spec.format.size();
        for (long long f : {(long long)spec.width, (long long)spec.height,
                            (long long)spec.nchannels}) {
            unsigned long long u = f > 0 ? (unsigned long long)f : 0;
            total = u && total > ULLONG_MAX / u ? ULLONG_MAX : total * u;
        }
        *bytes = total;
        in->close();
        return true;
    } catch (const std::exception &e) {
        set_err(err, errlen, std::string(what) + ": cannot read image: " + e.what());
    } catch (...) {
        set_err(err, errlen, std::string(what) + ": cannot read image: unknown exception");
    }
    return false;
}

const image_codec codec = {IMAGE_CODEC_ABI, codec_write, codec_read, codec_decode, codec_probe};

} // namespace

extern "C" __attribute__((visibility("default"))) const image_codec *shadesweep_image_codec(void)
{
    return &codec;
}
