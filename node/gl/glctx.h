/* glctx: an OpenGL 4.3+ core context behind one interface.
 *
 *   GLCTX_EGL     EGL surfaceless (Mesa) or device platform (NVIDIA); the headless default
 *   GLCTX_OSMESA  OSMesa, pure software, no display or driver needed
 *   GLCTX_GLFW    a window's context: the presentation module opens windows (present.h)
 *                 and hands their contexts over with glctx_adopt(); glctx_create() makes
 *                 only the headless two
 *
 * The renderer draws into its own framebuffers. The context is current on the creating
 * thread. glctx_gl() is the function table that every GL call must go through. */
#ifndef CAVELIGHT_GLCTX_H
#define CAVELIGHT_GLCTX_H

#include <stddef.h>
#include "gl_functions.h"

typedef enum glctx_backend {
    GLCTX_EGL = 0,
    GLCTX_OSMESA,
    GLCTX_GLFW,
} glctx_backend;

typedef struct glctx_desc {
    glctx_backend backend; /* GLCTX_EGL or GLCTX_OSMESA */
} glctx_desc;

typedef struct glctx glctx;

/* Returns NULL with one line in err: the backend, why it failed, what to install or do. */
glctx *glctx_create(const glctx_desc *desc, char *err, size_t errlen);
/* The context current on this thread, made by someone else (a window's): loads its
 * functions through load and checks it is 4.3 core. glctx_destroy() frees only the
 * wrapper; the owner ends the context. */
glctx *glctx_adopt(gl_functions_loader load, const char *describe, char *err, size_t errlen);
void glctx_destroy(glctx *ctx);
const gl_functions *glctx_gl(const glctx *ctx);
/* Any GL entry point of the context by name (an application's own drawing), or NULL. */
gl_functions_proc glctx_proc(const glctx *ctx, const char *name);
glctx_backend glctx_get_backend(const glctx *ctx);
/* Backend detail, e.g. "EGL surfaceless" or "OSMesa". */
const char *glctx_describe(const glctx *ctx);
/* GL_RENDERER string; glctx_is_software() is true for llvmpipe, softpipe and swrast. */
const char *glctx_renderer(const glctx *ctx);
int glctx_is_software(const glctx *ctx);
/* Parses "egl", "osmesa" or "glfw"; returns 0 or -1. */
int glctx_parse_backend(const char *name, glctx_backend *out);
const char *glctx_backend_name(glctx_backend backend);

#endif
