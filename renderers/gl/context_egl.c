/* EGL backend: Mesa's surfaceless platform (device -1) or EGL device N
 * (EGL_EXT_device_enumeration + EGL_EXT_platform_device); a GL 4.5 core context
 * made current without a surface (EGL_KHR_surfaceless_context). */
#include "renderers/gl/context_internal.h"
#include "renderers/gl/loader.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct egl_state {
    EGLDisplay dpy;
    EGLContext ctx;
} egl_state;

// >>helpers

static const char *egl_error_name(EGLint e)
{
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    case EGL_BAD_DEVICE_EXT: return "EGL_BAD_DEVICE_EXT";
    default: return "unknown EGL error";
    }
}

/* "EGL: <call> failed (<error>)<: what>" with eglGetError() read now. */
static void egl_fail(char *err, size_t errlen, const char *call, const char *what)
{
    EGLint e = eglGetError();
    snprintf(err, errlen, "EGL: %s failed (%s)%s%s", call, egl_error_name(e),
             what ? ": " : "", what ? what : "");
}

/* Whether the space-separated extension list has `name` as a whole word. */
static bool has_ext(const char *list, const char *name)
{
    if (!list)
        return false;
    size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)) != NULL; p += n) {
        bool starts = p == list || p[-1] == ' ';
        bool ends = p[n] == '\0' || p[n] == ' ';
        if (starts && ends)
            return true;
    }
    return false;
}

/* eglGetProcAddress as a void * (gl_proc_pointer). */
static void *egl_getproc(const char *name)
{
    return gl_proc_pointer(eglGetProcAddress(name));
}

/* Client extensions (EGL_EXT_client_extensions); NULL when there are none. */
static const char *client_extensions(void)
{
    const char *s = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!s)
        (void)eglGetError();   /* EGL_BAD_DISPLAY: no client extensions; not an error of ours */
    return s;
}

static EGLDisplay get_platform_display(EGLenum platform, void *native, const char *client_ext,
                                       char *err, size_t errlen)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_ext = NULL;
    if (has_ext(client_ext, "EGL_EXT_platform_base")) {
        void *p = egl_getproc("eglGetPlatformDisplayEXT");
        memcpy(&get_ext, &p, sizeof p);
    }
    EGLDisplay dpy = EGL_NO_DISPLAY;
    if (get_ext) {
        dpy = get_ext(platform, native, NULL);
        if (dpy == EGL_NO_DISPLAY)
            egl_fail(err, errlen, "eglGetPlatformDisplayEXT", NULL);
        return dpy;
    }
    /* EGL 1.5 has it in core. */
    PFNEGLGETPLATFORMDISPLAYPROC get_core = NULL;
    void *p = egl_getproc("eglGetPlatformDisplay");
    memcpy(&get_core, &p, sizeof p);
    if (!get_core) {
        snprintf(err, errlen, "EGL: neither eglGetPlatformDisplayEXT (EGL_EXT_platform_base) "
                              "nor eglGetPlatformDisplay (EGL 1.5) is available");
        return EGL_NO_DISPLAY;
    }
    dpy = get_core(platform, native, NULL);
    if (dpy == EGL_NO_DISPLAY)
        egl_fail(err, errlen, "eglGetPlatformDisplay", NULL);
    return dpy;
}

// >>devices

typedef struct device_funcs {
    PFNEGLQUERYDEVICESEXTPROC query_devices;
    PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string;   /* NULL without EGL_EXT_device_query */
} device_funcs;

static bool load_device_funcs(const char *client_ext, device_funcs *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!has_ext(client_ext, "EGL_EXT_device_enumeration") &&
        !has_ext(client_ext, "EGL_EXT_device_base")) {
        snprintf(err, errlen, "EGL: EGL_EXT_device_enumeration is not available "
                              "(no EGL device can be listed)");
        return false;
    }
    void *p = egl_getproc("eglQueryDevicesEXT");
    memcpy(&out->query_devices, &p, sizeof p);
    if (!out->query_devices) {
        snprintf(err, errlen, "EGL: eglQueryDevicesEXT not found by eglGetProcAddress");
        return false;
    }
    if (has_ext(client_ext, "EGL_EXT_device_query") ||
        has_ext(client_ext, "EGL_EXT_device_base")) {
        p = egl_getproc("eglQueryDeviceStringEXT");
        memcpy(&out->query_device_string, &p, sizeof p);
    }
    return true;
}

/* Lists the EGL devices into a malloc'd array (*devices, free it) of *count. */
static bool list_devices(const device_funcs *f, EGLDeviceEXT **devices, EGLint *count,
                         char *err, size_t errlen)
{
    *devices = NULL;
    *count = 0;
    EGLint n = 0;
    if (!f->query_devices(0, NULL, &n)) {
        egl_fail(err, errlen, "eglQueryDevicesEXT", "cannot count the EGL devices");
        return false;
    }
    if (n <= 0)
        return true;
    EGLDeviceEXT *d = calloc((size_t)n, sizeof *d);
    if (!d) {
        snprintf(err, errlen, "out of memory listing %d EGL devices", (int)n);
        return false;
    }
    EGLint got = 0;
    if (!f->query_devices(n, d, &got)) {
        egl_fail(err, errlen, "eglQueryDevicesEXT", "cannot list the EGL devices");
        free(d);
        return false;
    }
    *devices = d;
    *count = got;
    return true;
}

/* The DRM device file where the device has one (EGL_EXT_device_drm), else its
 * render node (EGL_EXT_device_drm_render_node), else its extension string
 * (e.g. "EGL_MESA_device_software" for llvmpipe). */
static void device_name(const device_funcs *f, EGLDeviceEXT dev, char *out, size_t outlen)
{
    out[0] = '\0';
    if (!f->query_device_string)
        return;
    const char *ext = f->query_device_string(dev, EGL_EXTENSIONS);
    const char *name = NULL;
    if (has_ext(ext, "EGL_EXT_device_drm"))
        name = f->query_device_string(dev, EGL_DRM_DEVICE_FILE_EXT);
    if (!name && has_ext(ext, "EGL_EXT_device_drm_render_node"))
        name = f->query_device_string(dev, EGL_DRM_RENDER_NODE_FILE_EXT);
    if (!name)
        name = ext;
    (void)eglGetError();   /* a NULL answer above is not an error of ours */
    snprintf(out, outlen, "%s", name ? name : "");
}

int gl_egl_device_count(char *err, size_t errlen)
{
    device_funcs f;
    if (!load_device_funcs(client_extensions(), &f, err, errlen))
        return -1;
    EGLint n = 0;
    if (!f.query_devices(0, NULL, &n)) {
        egl_fail(err, errlen, "eglQueryDevicesEXT", "cannot count the EGL devices");
        return -1;
    }
    return (int)n;
}

// >>display

/* Opens the display the caller asked for: surfaceless (device < 0) or device N. */
static bool open_display(gl_context *ctx, int device, EGLDisplay *out, char *err, size_t errlen)
{
    const char *client_ext = client_extensions();
    *out = EGL_NO_DISPLAY;
    if (device < 0) {
        if (!has_ext(client_ext, "EGL_MESA_platform_surfaceless")) {
            snprintf(err, errlen, "EGL: the Mesa surfaceless platform "
                                  "(EGL_MESA_platform_surfaceless) is not available");
            return false;
        }
        *out = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY,
                                    client_ext, err, errlen);
        ctx->info.backend = "egl-surfaceless";
        ctx->info.device[0] = '\0';
        return *out != EGL_NO_DISPLAY;
    }

    device_funcs f;
    if (!load_device_funcs(client_ext, &f, err, errlen))
        return false;
    if (!has_ext(client_ext, "EGL_EXT_platform_device")) {
        snprintf(err, errlen, "EGL: EGL_EXT_platform_device is not available "
                              "(no display can be opened on an EGL device)");
        return false;
    }
    EGLDeviceEXT *devices;
    EGLint count;
    if (!list_devices(&f, &devices, &count, err, errlen))
        return false;
    if (device >= count) {
        snprintf(err, errlen, "EGL device %d requested, but %d found", device, (int)count);
        free(devices);
        return false;
    }
    device_name(&f, devices[device], ctx->info.device, sizeof ctx->info.device);
    *out = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[device], client_ext,
                                err, errlen);
    free(devices);
    ctx->info.backend = "egl-device";
    return *out != EGL_NO_DISPLAY;
}

// >>context

static bool create_context(egl_state *s, bool debug, EGLint egl_major, EGLint egl_minor,
                           char *err, size_t errlen)
{
    const char *ext = eglQueryString(s->dpy, EGL_EXTENSIONS);
    bool egl15 = egl_major > 1 || (egl_major == 1 && egl_minor >= 5);
    if (!egl15 && !has_ext(ext, "EGL_KHR_create_context")) {
        snprintf(err, errlen, "EGL: the display has neither EGL 1.5 nor EGL_KHR_create_context "
                              "(cannot ask for GL 4.5 core), only EGL %d.%d",
                 (int)egl_major, (int)egl_minor);
        return false;
    }
    if (!has_ext(ext, "EGL_KHR_surfaceless_context")) {
        snprintf(err, errlen, "EGL: the display lacks EGL_KHR_surfaceless_context "
                              "(needed to render off-screen without a surface)");
        return false;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        egl_fail(err, errlen, "eglBindAPI", "desktop OpenGL not supported");
        return false;
    }

    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_ext(ext, "EGL_KHR_no_config_context")) {
        const EGLint want[] = {
            EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
            EGL_SURFACE_TYPE, 0,   /* no surface: any config will do */
            EGL_NONE,
        };
        EGLint n = 0;
        if (!eglChooseConfig(s->dpy, want, &config, 1, &n)) {
            egl_fail(err, errlen, "eglChooseConfig", NULL);
            return false;
        }
        if (n < 1) {
            snprintf(err, errlen, "EGL: eglChooseConfig found no config with EGL_OPENGL_BIT");
            return false;
        }
    }

    /* EGL 1.5 names; EGL_KHR_create_context has the same values for all but the
     * debug flag, which it sets through EGL_CONTEXT_FLAGS_KHR. */
    EGLint attribs[16];
    size_t n = 0;
    attribs[n++] = EGL_CONTEXT_MAJOR_VERSION;
    attribs[n++] = 4;
    attribs[n++] = EGL_CONTEXT_MINOR_VERSION;
    attribs[n++] = 5;
    attribs[n++] = EGL_CONTEXT_OPENGL_PROFILE_MASK;
    attribs[n++] = EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT;
    if (debug && egl15) {
        attribs[n++] = EGL_CONTEXT_OPENGL_DEBUG;
        attribs[n++] = EGL_TRUE;
    } else if (debug) {
        attribs[n++] = EGL_CONTEXT_FLAGS_KHR;
        attribs[n++] = EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR;
    }
    attribs[n++] = EGL_NONE;

    s->ctx = eglCreateContext(s->dpy, config, EGL_NO_CONTEXT, attribs);
    if (s->ctx == EGL_NO_CONTEXT) {
        egl_fail(err, errlen, "eglCreateContext",
                 debug ? "GL 4.5 core debug context not available" : "GL 4.5 core not available");
        return false;
    }
    if (!eglMakeCurrent(s->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, s->ctx)) {
        egl_fail(err, errlen, "eglMakeCurrent", "cannot make the context current without a surface");
        return false;
    }
    return true;
}

void gl_egl_close(void *native)
{
    egl_state *s = native;
    if (!s)
        return;
    /* Only what is ours: a creation that failed early must not unbind (through
     * eglReleaseThread) a context that someone else has current. */
    bool was_current = s->ctx != EGL_NO_CONTEXT && eglGetCurrentContext() == s->ctx;
    if (was_current)
        eglMakeCurrent(s->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (s->ctx != EGL_NO_CONTEXT)
        eglDestroyContext(s->dpy, s->ctx);
    if (was_current)
        eglReleaseThread();
    free(s);
}

bool gl_egl_open(gl_context *ctx, int device, char *err, size_t errlen)
{
    egl_state *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(err, errlen, "out of memory");
        return false;
    }
    s->dpy = EGL_NO_DISPLAY;
    s->ctx = EGL_NO_CONTEXT;

    if (!open_display(ctx, device, &s->dpy, err, errlen))
        goto fail;

    /* An EGL display lives as long as the process: it is initialized by the first
     * context on it and never terminated here. eglInitialize is not reference
     * counted, so terminating would end the display for every other context on it;
     * and eglTerminate unloads Mesa's driver (LLVM included), which a sweep would
     * then reload for every run, and whose allocations the leak checker could no
     * longer name. Initializing an initialized display is allowed and cheap. */
    EGLint major = 0, minor = 0;
    if (!eglInitialize(s->dpy, &major, &minor)) {
        egl_fail(err, errlen, "eglInitialize",
                 device < 0 ? "no Mesa surfaceless display" : "cannot open the EGL device");
        goto fail;
    }
    if (!create_context(s, ctx->debug_requested, major, minor, err, errlen))
        goto fail;

    ctx->native = s;
    ctx->native_close = gl_egl_close;
    ctx->getproc = egl_getproc;
    return true;

fail:
    gl_egl_close(s);
    return false;
}
