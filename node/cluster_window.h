/* cluster_window: a GLFW window that shows finished RGB images (a node's display).
 *
 * Quad-buffered stereo is asked for with GLFW_STEREO when wanted; drivers without it give
 * an ordinary window and cluster_window_quad() says so. With `fullscreen` the window
 * covers the chosen monitor at its current video mode. Images are top row first. */
#ifndef CAVELIGHT_CLUSTER_WINDOW_H
#define CAVELIGHT_CLUSTER_WINDOW_H

#include <stddef.h>
#include <stdint.h>

#include "glctx.h"

typedef struct cluster_window cluster_window;

typedef struct cluster_window_desc {
    int width, height;
    const char *title;
    int want_quad;      /* ask for a quad-buffered (left/right back buffer) window */
    int monitor;        /* GLFW monitor index for fullscreen */
    int fullscreen;
} cluster_window_desc;

cluster_window *cluster_window_create(const cluster_window_desc *desc, char *err, size_t errlen);
void cluster_window_destroy(cluster_window *w);
glctx *cluster_window_context(cluster_window *w);
int cluster_window_quad(const cluster_window *w);
void cluster_window_make_current(cluster_window *w);
/* Shows left (and right in the right back buffer when quad-buffered). Returns 1 while the
 * window is open, 0 once it was asked to close, -1 on a GL error. */
int cluster_window_show(cluster_window *w, const uint8_t *left, const uint8_t *right, int width, int height);

#endif
