/* GLFW backend: a window with an OpenGL 4.3 core context, for a desk or a real display. */
#include <stdio.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "glctx_internal.h"

static gl_functions_proc glfw_load(const char *name)
{
    return (gl_functions_proc)glfwGetProcAddress(name);
}

static void glfw_destroy(glctx *ctx)
{
    glfwDestroyWindow(ctx->native);
    glfwTerminate();
}

static int glfw_swap(glctx *ctx)
{
    glfwSwapBuffers(ctx->native);
    glfwPollEvents();
    return !glfwWindowShouldClose(ctx->native);
}

int glctx_glfw_open(glctx *ctx, const glctx_desc *desc, char *err, size_t errlen)
{
    if (!glfwInit()) {
        const char *why = NULL;
        glfwGetError(&why);
        snprintf(err, errlen, "GLFW: cannot start (%s; set DISPLAY or WAYLAND_DISPLAY to a "
                 "running display server)", why ? why : "no display");
        return -1;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, desc->visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow *w = glfwCreateWindow(desc->width > 0 ? desc->width : 640,
                                     desc->height > 0 ? desc->height : 480,
                                     desc->title ? desc->title : "cavelight", NULL, NULL);
    if (!w) {
        const char *why = NULL;
        glfwGetError(&why);
        glfwTerminate();
        snprintf(err, errlen, "GLFW: no OpenGL 4.3 core window (%s; update the GPU driver)",
                 why ? why : "unknown reason");
        return -1;
    }
    glfwMakeContextCurrent(w);
    ctx->native = w;
    ctx->destroy = glfw_destroy;
    ctx->swap = glfw_swap;
    snprintf(ctx->describe, sizeof ctx->describe, "GLFW window");
    if (gl_functions_load(&ctx->gl, glfw_load, err, errlen) != 0) {
        glfw_destroy(ctx);
        return -1;
    }
    return 0;
}
