#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glctx_internal.h"
#include "base/xalloc.h"

static const char *const backend_names[] = {"egl", "osmesa", "glfw"};

int glctx_parse_backend(const char *name, glctx_backend *out)
{
    for (int i = 0; i < 3; i++)
        if (strcmp(name, backend_names[i]) == 0) {
            *out = (glctx_backend)i;
            return 0;
        }
    return -1;
}

const char *glctx_backend_name(glctx_backend backend)
{
    return (unsigned)backend < 3 ? backend_names[backend] : "?";
}

/* What every context must offer: 4.3 core. Ends ctx on failure. */
static glctx *check_version(glctx *ctx, char *err, size_t errlen)
{
    const char *r = (const char *)ctx->gl.GetString(GL_RENDERER);
    snprintf(ctx->renderer, sizeof ctx->renderer, "%s", r ? r : "unknown");
    GLint major = 0, minor = 0;
    ctx->gl.GetIntegerv(GL_MAJOR_VERSION, &major);
    ctx->gl.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major < 4 || (major == 4 && minor < 3)) {
        snprintf(err, errlen, "%s: OpenGL %d.%d on %s, cavelight needs 4.3 core "
                 "(update Mesa or the GPU driver)", ctx->describe, major, minor, ctx->renderer);
        glctx_destroy(ctx);
        return NULL;
    }
    return ctx;
}

glctx *glctx_create(const glctx_desc *desc, char *err, size_t errlen)
{
    glctx *ctx = xcalloc(1, sizeof *ctx);
    ctx->backend = desc->backend;
    int rc;
    switch (desc->backend) {
    case GLCTX_EGL: rc = glctx_egl_open(ctx, desc, err, errlen); break;
    case GLCTX_OSMESA: rc = glctx_osmesa_open(ctx, desc, err, errlen); break;
    default:
        snprintf(err, errlen, "GL context: glctx_create makes egl or osmesa contexts; a window's "
                 "comes from present_create()");
        rc = -1;
    }
    if (rc != 0) {
        free(ctx);
        return NULL;
    }
    return check_version(ctx, err, errlen);
}

glctx *glctx_adopt(gl_functions_loader load, const char *describe, char *err, size_t errlen)
{
    glctx *ctx = xcalloc(1, sizeof *ctx);
    ctx->backend = GLCTX_GLFW;
    snprintf(ctx->describe, sizeof ctx->describe, "%s", describe);
    ctx->load = load;
    if (gl_functions_load(&ctx->gl, load, err, errlen) != 0) {
        free(ctx);
        return NULL;
    }
    return check_version(ctx, err, errlen);
}

void glctx_destroy(glctx *ctx)
{
    if (!ctx)
        return;
    if (ctx->destroy)
        ctx->destroy(ctx);
    free(ctx);
}

gl_functions_proc glctx_proc(const glctx *ctx, const char *name)
{
    return ctx->load ? ctx->load(name) : NULL;
}

const gl_functions *glctx_gl(const glctx *ctx) { return &ctx->gl; }

glctx_backend glctx_get_backend(const glctx *ctx) { return ctx->backend; }
const char *glctx_describe(const glctx *ctx) { return ctx->describe; }
const char *glctx_renderer(const glctx *ctx) { return ctx->renderer; }

int glctx_is_software(const glctx *ctx)
{
    return strstr(ctx->renderer, "llvmpipe") || strstr(ctx->renderer, "softpipe") ||
           strstr(ctx->renderer, "swrast");
}
