/* OSMesa backend: Mesa's software renderer into a small client buffer. The renderer
 * draws into its own framebuffer objects, so the client buffer only anchors the context.
 * libOSMesa (and the LLVM it pulls in) is loaded when this backend is asked for
 * (dynlib.h), so a node that uses EGL or GLFW never maps it. */
#include <stdio.h>
#include <stdlib.h>

#include <GL/osmesa.h>

#include "base/dynlib.h"
#include "glctx_internal.h"
#include "base/xalloc.h"

static OSMesaContext (*create_context)(const int *attribs, OSMesaContext share);
static GLboolean (*make_current)(OSMesaContext c, void *buffer, GLenum type, GLsizei w, GLsizei h);
static void (*destroy_context)(OSMesaContext c);
static OSMESAproc (*get_proc_address)(const char *name);

static const dynlib_symbol osmesa_symbols[] = {
    {"OSMesaCreateContextAttribs", &create_context},
    {"OSMesaMakeCurrent", &make_current},
    {"OSMesaDestroyContext", &destroy_context},
    {"OSMesaGetProcAddress", &get_proc_address},
};
static const char *const osmesa_files[] = {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so", NULL};
static const dynlib osmesa_lib = {.what = "OSMesa", .files = osmesa_files, .package = "libosmesa6",
                                  .symbols = osmesa_symbols,
                                  .symbol_count = sizeof osmesa_symbols / sizeof *osmesa_symbols};

typedef struct osmesa_state {
    OSMesaContext context;
    unsigned char buffer[4 * 4 * 4];
} osmesa_state;

static gl_functions_proc osmesa_load(const char *name)
{
    return (gl_functions_proc)get_proc_address(name);
}

static void osmesa_destroy(glctx *ctx)
{
    osmesa_state *s = ctx->native;
    destroy_context(s->context);
    free(s);
}

int glctx_osmesa_open(glctx *ctx, const glctx_desc *desc, char *err, size_t errlen)
{
    if (dynlib_load(&osmesa_lib, err, errlen) != 0)
        return -1;
    const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 3, 0,
    };
    osmesa_state *s = xcalloc(1, sizeof *s);
    s->context = create_context(attribs, NULL);
    if (!s->context) {
        free(s);
        snprintf(err, errlen, "OSMesa: cannot create an OpenGL 4.3 core context "
                 "(install libosmesa6 from Mesa 20 or later)");
        return -1;
    }
    if (!make_current(s->context, s->buffer, GL_UNSIGNED_BYTE, 4, 4)) {
        destroy_context(s->context);
        free(s);
        snprintf(err, errlen, "OSMesa: cannot make the context current (reinstall libosmesa6)");
        return -1;
    }
    ctx->native = s;
    ctx->destroy = osmesa_destroy;
    snprintf(ctx->describe, sizeof ctx->describe, "OSMesa");
    ctx->load = osmesa_load;
    if (gl_functions_load(&ctx->gl, osmesa_load, err, errlen) != 0) {
        osmesa_destroy(ctx);
        return -1;
    }
    return 0;
}
