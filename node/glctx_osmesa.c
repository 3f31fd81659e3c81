/* OSMesa backend: Mesa's software renderer into a small client buffer. The renderer
 * draws into its own framebuffer objects, so the client buffer only anchors the context. */
#include <stdio.h>
#include <stdlib.h>

#include <GL/osmesa.h>

#include "glctx_internal.h"
#include "base/xalloc.h"

typedef struct osmesa_state {
    OSMesaContext context;
    unsigned char buffer[4 * 4 * 4];
} osmesa_state;

static gl_functions_proc osmesa_load(const char *name)
{
    return (gl_functions_proc)OSMesaGetProcAddress(name);
}

static void osmesa_destroy(glctx *ctx)
{
    osmesa_state *s = ctx->native;
    OSMesaDestroyContext(s->context);
    free(s);
}

int glctx_osmesa_open(glctx *ctx, const glctx_desc *desc, char *err, size_t errlen)
{
    const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 3, 0,
    };
    osmesa_state *s = xcalloc(1, sizeof *s);
    s->context = OSMesaCreateContextAttribs(attribs, NULL);
    if (!s->context) {
        free(s);
        snprintf(err, errlen, "OSMesa: cannot create an OpenGL 4.3 core context "
                 "(install libosmesa6 from Mesa 20 or later)");
        return -1;
    }
    if (!OSMesaMakeCurrent(s->context, s->buffer, GL_UNSIGNED_BYTE, 4, 4)) {
        OSMesaDestroyContext(s->context);
        free(s);
        snprintf(err, errlen, "OSMesa: cannot make the context current (reinstall libosmesa6)");
        return -1;
    }
    ctx->native = s;
    ctx->destroy = osmesa_destroy;
    snprintf(ctx->describe, sizeof ctx->describe, "OSMesa");
    if (gl_functions_load(&ctx->gl, osmesa_load, err, errlen) != 0) {
        osmesa_destroy(ctx);
        return -1;
    }
    return 0;
}
