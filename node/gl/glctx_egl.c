/* EGL backend: Mesa's surfaceless platform first, then the device platform (NVIDIA). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "glctx_internal.h"
#include "base/xalloc.h"

typedef struct egl_state {
    EGLDisplay display;
    EGLContext context;
} egl_state;

static gl_functions_proc egl_load(const char *name)
{
    return (gl_functions_proc)eglGetProcAddress(name);
}

static void egl_destroy(glctx *ctx)
{
    egl_state *s = ctx->native;
    eglMakeCurrent(s->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(s->display, s->context);
    eglTerminate(s->display);
    free(s);
}

static int has_extension(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return 1;
    return 0;
}

static EGLDisplay open_display(const char **platform)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display)
        return EGL_NO_DISPLAY;
    if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay d = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
        if (d != EGL_NO_DISPLAY && eglInitialize(d, NULL, NULL)) {
            *platform = "EGL surfaceless";
            return d;
        }
    }
    PFNEGLQUERYDEVICESEXTPROC query_devices =
        (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    if (has_extension(client, "EGL_EXT_platform_device") && query_devices) {
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        if (query_devices(8, devices, &count))
            for (EGLint i = 0; i < count; i++) {
                EGLDisplay d = get_display(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
                if (d != EGL_NO_DISPLAY && eglInitialize(d, NULL, NULL)) {
                    *platform = "EGL device";
                    return d;
                }
            }
    }
    return EGL_NO_DISPLAY;
}

int glctx_egl_open(glctx *ctx, const glctx_desc *desc, char *err, size_t errlen)
{
    const char *platform = "EGL";
    EGLDisplay display = open_display(&platform);
    if (display == EGL_NO_DISPLAY) {
        snprintf(err, errlen, "EGL: no surfaceless or device platform could be opened "
                 "(install libegl-mesa0 and mesa drivers, or try --gl osmesa)");
        return -1;
    }
    if (!has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context") ||
        !eglBindAPI(EGL_OPENGL_API)) {
        eglTerminate(display);
        snprintf(err, errlen, "%s: no surfaceless desktop OpenGL (update Mesa or the driver, "
                 "or try --gl osmesa)", platform);
        return -1;
    }
    const EGLint attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE,
    };
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (context == EGL_NO_CONTEXT ||
        !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        EGLint code = eglGetError();
        if (context != EGL_NO_CONTEXT)
            eglDestroyContext(display, context);
        eglTerminate(display);
        snprintf(err, errlen, "%s: cannot create an OpenGL 4.3 core context (EGL error 0x%x; "
                 "update Mesa or the GPU driver, or try --gl osmesa)", platform, (unsigned)code);
        return -1;
    }
    egl_state *s = xmalloc(sizeof *s);
    s->display = display;
    s->context = context;
    ctx->native = s;
    ctx->destroy = egl_destroy;
    snprintf(ctx->describe, sizeof ctx->describe, "%s", platform);
    ctx->load = egl_load;
    if (gl_functions_load(&ctx->gl, egl_load, err, errlen) != 0) {
        egl_destroy(ctx);
        return -1;
    }
    return 0;
}
