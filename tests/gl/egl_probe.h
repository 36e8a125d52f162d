#pragma once
/* Shared by the GL tests: whether Mesa's surfaceless EGL platform gives a display
 * here at all, and if not why (for the skip message). Independent of the code under
 * test. Like the contexts, it never terminates the display: eglTerminate would
 * unload Mesa's driver mid-process (see context_egl.c). */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

static inline bool egl_display_available(char *why, size_t len)
{
    const char *ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!ext || !strstr(ext, "EGL_MESA_platform_surfaceless")) {
        snprintf(why, len, "no EGL_MESA_platform_surfaceless among the EGL client extensions");
        return false;
    }
    PFNEGLGETPLATFORMDISPLAYEXTPROC get =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay d = get ? get(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL)
                       : EGL_NO_DISPLAY;
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, NULL, NULL)) {
        snprintf(why, len, "no surfaceless EGL display can be initialized (EGL error 0x%x)",
                 (unsigned)eglGetError());
        return false;
    }
    return true;
}
