/* glctx: an OpenGL 4.3+ core context behind one interface, three backends.
 *
 *   GLCTX_EGL     EGL surfaceless (Mesa) or device platform (NVIDIA); the headless default
 *   GLCTX_OSMESA  OSMesa, pure software, no display or driver needed
 *   GLCTX_GLFW    a GLFW window, for a desk or a real display
 *
 * The renderer draws into its own framebuffers, so only the GLFW backend has a visible
 * default framebuffer (glctx_swap shows it). The context is current on the creating thread.
 * glctx_gl() is the function table that every GL call must go through. */
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
    glctx_backend backend;
    int width, height;    /* GLFW window size; 0 = 640x480 */
    const char *title;    /* GLFW window title; NULL = "cavelight" */
    int visible;          /* GLFW: show the window (0 = hidden) */
} glctx_desc;

typedef struct glctx glctx;

/* Returns NULL with one line in err: the backend, why it failed, what to install or do. */
glctx *glctx_create(const glctx_desc *desc, char *err, size_t errlen);
void glctx_destroy(glctx *ctx);
const gl_functions *glctx_gl(const glctx *ctx);
glctx_backend glctx_get_backend(const glctx *ctx);
/* Backend detail, e.g. "EGL surfaceless" or "OSMesa". */
const char *glctx_describe(const glctx *ctx);
/* GL_RENDERER string; glctx_is_software() is true for llvmpipe, softpipe and swrast. */
const char *glctx_renderer(const glctx *ctx);
int glctx_is_software(const glctx *ctx);
/* GLFW: present the default framebuffer, returns 0 once the window was asked to close. */
int glctx_swap(glctx *ctx);
/* Parses "egl", "osmesa" or "glfw"; returns 0 or -1. */
int glctx_parse_backend(const char *name, glctx_backend *out);
const char *glctx_backend_name(glctx_backend backend);

#endif
