/* pixel_window: a GLFW window that shows an RGB picture, scaled to fit. The desk
 * simulator's window (input_desk.h) and the master's live preview (preview.h) are each
 * one.
 *
 * The picture goes in with glDrawPixels and glPixelZoom, GL 1.x calls looked up through
 * GLFW so that the master links no GL library. Where the display offers no OpenGL the
 * window still opens, without a picture (pixel_window_has_picture() says so). GLFW is
 * initialised by the first window opened and terminated when the last one closes, so that
 * several windows live in one process. The master's main thread only. */
#ifndef CAVELIGHT_PIXEL_WINDOW_H
#define CAVELIGHT_PIXEL_WINDOW_H

#include <stddef.h>
#include <stdint.h>

typedef struct pixel_window pixel_window;

typedef struct pixel_window_desc {
    const char *title;
    int width, height;  /* the window's size in screen pixels (required) */
    int resizable;      /* 1: the user may resize it; the picture follows */
} pixel_window_desc;

/* Returns NULL with GLFW's reason in err (no display, no window) and nothing left open. */
pixel_window *pixel_window_open(const pixel_window_desc *desc, char *err, size_t errlen);
/* 1 when the window can show pictures (it has OpenGL). */
int pixel_window_has_picture(const pixel_window *w);
/* Shows rgb (width x height, 3 bytes a pixel, top row first) scaled to fit the window,
 * aspect kept, black around it; nothing without a picture. */
void pixel_window_show(pixel_window *w, const uint8_t *rgb, int width, int height);
/* 1 once the user asked to close it (events are polled with glfwPollEvents()). */
int pixel_window_should_close(pixel_window *w);
/* The GLFWwindow, for input callbacks and tests. */
void *pixel_window_glfw(pixel_window *w);
void pixel_window_close(pixel_window *w);

#endif
