/* present_window: the presentation's GLFW windows, the node's only window code.
 *
 * A window with an OpenGL 4.3 core context (glctx_adopt()), placed on a monitor chosen by
 * index or by its output's name, fullscreen at the monitor's current video mode or at a
 * position and size, quad-buffered when asked and offered (else an ordinary window, quad
 * 0), swapping every swap_interval-th refresh, and in an NVIDIA swap group and barrier
 * when asked (GLX_NV_swap_group, present_swap_group.c: one line says joined, or not and
 * why). present_window_report() says in one line what the window became. GLFW starts
 * with the first window and ends with the last. Draws nothing (present.c does). */
#ifndef CAVELIGHT_PRESENT_WINDOW_H
#define CAVELIGHT_PRESENT_WINDOW_H

#include <stddef.h>

#include "gl/glctx.h"

typedef struct present_window_desc {
    const char *title;
    int width, height;        /* the window's size (fullscreen: the monitor's mode instead) */
    int want_quad;            /* a left and a right back buffer */
    int width_without_quad;   /* the width when the driver offers none; 0: width */
    const char *monitor_name; /* the output's name ("DP-1"); NULL or "": by index */
    int monitor;
    int fullscreen;
    int have_position, position[2];
    int swap_interval;        /* 0: no vsync */
    int swap_group, swap_barrier;
    const char *log_name;     /* what the lines start with: "cavelight-node n01" */
    int quiet;                /* only the swap group line, and only when asked */
} present_window_desc;

typedef struct present_window {
    void *handle;             /* GLFWwindow */
    void *monitor;            /* GLFWmonitor it went to, or NULL */
    char monitor_note[200];   /* why not the asked monitor, or "" */
    glctx *ctx;
    int quad;                 /* quad buffers were offered */
    int fullscreen;           /* it covers its monitor */
} present_window;

/* 0, or -1 with err (no display, no 4.3 context). */
int present_window_open(present_window *w, const present_window_desc *d, char *err, size_t errlen);
void present_window_close(present_window *w);
/* One line: size, place, monitor, vsync, quad buffers (and the asked monitor when missing). */
void present_window_report(present_window *w, const present_window_desc *d);
void present_window_make_current(present_window *w);
void present_window_framebuffer(present_window *w, int *width, int *height);
/* Swaps and handles events; 0 once the window was asked to close, else 1. */
int present_window_swap(present_window *w);

/* GLX_NV_swap_group on the window's drawable (present_swap_group.c): 1 joined (and bound
 * to barrier when not 0), 0 not, with the reason in why. */
int present_swap_group_join(void *glfw_window, int group, int barrier, char *why, size_t whylen);

#endif
