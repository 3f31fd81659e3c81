/* glctx_internal: what the backends share with glctx.c. Not for other modules. */
#ifndef CAVELIGHT_GLCTX_INTERNAL_H
#define CAVELIGHT_GLCTX_INTERNAL_H

#include "glctx.h"

struct glctx {
    glctx_backend backend;
    gl_functions gl;
    char describe[64];
    char renderer[128];
    void *native;                /* backend state */
    gl_functions_loader load;    /* the backend's GetProcAddress (glctx_proc()) */
    void (*destroy)(glctx *ctx);  /* NULL: adopted, its owner ends it */
};

/* Each fills ctx->native, describe, destroy and loads ctx->gl; 0 or -1 + err. */
int glctx_egl_open(glctx *ctx, const glctx_desc *desc, char *err, size_t errlen);
int glctx_osmesa_open(glctx *ctx, const glctx_desc *desc, char *err, size_t errlen);

#endif
