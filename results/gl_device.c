/* Software rasterizers by their GL strings (results/gl_device.h). */
#include "results/gl_device.h"

#include <ctype.h>
#include <stdbool.h>

/* Whether `needle` (lower case) occurs in s, ignoring case. */
static bool has(const char *s, const char *needle)
{
    for (; s && *s; s++) {
        size_t i = 0;
        while (needle[i] && s[i] && tolower((unsigned char)s[i]) == needle[i])
            i++;
        if (!needle[i])
            return true;
    }
    return false;
}

/* Words of GL_RENDERER (or, for the last, GL_VENDOR) that name a software rasterizer,
 * and its name. Mesa prints "llvmpipe (LLVM 15.0.6, 256 bits)", "softpipe", and
 * "zink (lavapipe)" over Vulkan's; its old classic rasterizer "Software Rasterizer"
 * (vendor "Mesa Project") and, under OSMesa, "Mesa OffScreen"; the DRI loader's
 * "swrast". Google's SwiftShader names itself (alone and inside ANGLE's strings);
 * Windows' WARP is the "Microsoft Basic Render Driver" (ANGLE's D3D11 and Mesa's
 * D3D12 over it); Apple's is the "Apple Software Renderer". */
static const struct {
    const char *word, *name;
} soft[] = {
    {"llvmpipe", "llvmpipe"},         {"softpipe", "softpipe"},
    {"lavapipe", "lavapipe"},         {"swiftshader", "SwiftShader"},
    {"basic render driver", "WARP"},  {"mesa offscreen", "OSMesa"},
    {"osmesa", "OSMesa"},             {"swrast", "swrast"},
    {"software rasterizer", "swrast"}, {"software renderer", "a software renderer"},
};

const char *gl_software_rasterizer(const char *renderer, const char *vendor,
                                   const char *version)
{
    (void)version;   /* no version string alone names a rasterizer */
    for (size_t i = 0; i < sizeof soft / sizeof *soft; i++)
        if (has(renderer, soft[i].word))
            return soft[i].name;
    if (has(vendor, "swiftshader"))
        return "SwiftShader";
    return NULL;
}
