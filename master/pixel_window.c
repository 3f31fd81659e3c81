/* pixel_window: a GLFW window showing an RGB picture (pixel_window.h). */
#include "pixel_window.h"

#include <stdio.h>
#include <stdlib.h>
#include <GLFW/glfw3.h>

#include "base/xalloc.h"

/* The GL 1.x calls that put a picture in the window, looked up through GLFW. */
typedef void (*window_pos_fn)(GLint x, GLint y);
typedef void (*draw_pixels_fn)(GLsizei w, GLsizei h, GLenum format, GLenum type, const void *pixels);
typedef void (*pixel_zoom_fn)(GLfloat x, GLfloat y);
typedef void (*pixel_store_fn)(GLenum name, GLint value);
typedef void (*clear_color_fn)(GLfloat r, GLfloat g, GLfloat b, GLfloat a);
typedef void (*clear_fn)(GLbitfield mask);

struct pixel_window {
    GLFWwindow *win;
    window_pos_fn window_pos;
    draw_pixels_fn draw_pixels;
    pixel_zoom_fn pixel_zoom;
    pixel_store_fn pixel_store;
    clear_color_fn clear_color;
    clear_fn clear;
    int picture;
};

static int glfw_users; /* open windows: GLFW is terminated with the last one */

static void glfw_reason(const char *what, char *err, size_t errlen)
{
    const char *why = NULL;
    glfwGetError(&why);
    snprintf(err, errlen, "%s: %s", what, why ? why : "unknown GLFW error");
}

pixel_window *pixel_window_open(const pixel_window_desc *d, char *err, size_t errlen)
{
    if (glfw_users == 0 && !glfwInit()) {
        glfw_reason("no display (needs X or Xvfb)", err, errlen);
        return NULL;
    }
    pixel_window *w = xcalloc(1, sizeof *w);
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_RESIZABLE, d->resizable ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 1); /* any context that draws pixels will do */
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 4);
    w->win = glfwCreateWindow(d->width, d->height, d->title, NULL, NULL);
    if (w->win) {
        glfwMakeContextCurrent(w->win);
        glfwSwapInterval(0); /* never wait for the display: the master's frame loop draws here */
        w->window_pos = (window_pos_fn)glfwGetProcAddress("glWindowPos2i");
        w->draw_pixels = (draw_pixels_fn)glfwGetProcAddress("glDrawPixels");
        w->pixel_zoom = (pixel_zoom_fn)glfwGetProcAddress("glPixelZoom");
        w->pixel_store = (pixel_store_fn)glfwGetProcAddress("glPixelStorei");
        w->clear_color = (clear_color_fn)glfwGetProcAddress("glClearColor");
        w->clear = (clear_fn)glfwGetProcAddress("glClear");
        w->picture = w->window_pos && w->draw_pixels && w->pixel_zoom && w->pixel_store && w->clear_color &&
                     w->clear;
    }
    if (w->win && !w->picture) {
        /* No usable GL on this display: a window without a picture. */
        glfwDestroyWindow(w->win);
        glfwDefaultWindowHints();
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        glfwWindowHint(GLFW_RESIZABLE, d->resizable ? GLFW_TRUE : GLFW_FALSE);
        w->win = glfwCreateWindow(d->width, d->height, d->title, NULL, NULL);
    }
    if (!w->win) {
        glfw_reason("cannot create the window", err, errlen);
        if (glfw_users == 0)
            glfwTerminate();
        free(w);
        return NULL;
    }
    glfw_users++;
    return w;
}

int pixel_window_has_picture(const pixel_window *w)
{
    return w->picture;
}

void pixel_window_show(pixel_window *w, const uint8_t *rgb, int width, int height)
{
    if (!w->picture || width <= 0 || height <= 0)
        return;
    int fw, fh;
    glfwMakeContextCurrent(w->win);
    glfwGetFramebufferSize(w->win, &fw, &fh);
    float zx = (float)fw / width, zy = (float)fh / height, z = zx < zy ? zx : zy;
    w->clear_color(0, 0, 0, 1);
    w->clear(GL_COLOR_BUFFER_BIT);
    w->pixel_store(GL_UNPACK_ALIGNMENT, 1);
    /* Top row first: start at the top edge and zoom downwards. */
    w->pixel_zoom(z, -z);
    w->window_pos(0, fh);
    w->draw_pixels(width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb);
    glfwSwapBuffers(w->win);
}

int pixel_window_should_close(pixel_window *w)
{
    return glfwWindowShouldClose(w->win);
}

void *pixel_window_glfw(pixel_window *w)
{
    return w->win;
}

void pixel_window_close(pixel_window *w)
{
    if (!w)
        return;
    glfwDestroyWindow(w->win);
    if (--glfw_users == 0)
        glfwTerminate();
    free(w);
}
