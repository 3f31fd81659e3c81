/* present_window: see present_window.h. */
#include "present_window.h"

#include <stdio.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

static int glfw_users; /* open windows: GLFW ends with the last */

static gl_functions_proc glfw_load(const char *name)
{
    return (gl_functions_proc)glfwGetProcAddress(name);
}

static const char *glfw_reason(void)
{
    const char *why = NULL;
    glfwGetError(&why);
    return why ? why : "unknown reason";
}

/* The monitor the desc names, or NULL with why (not found: the connected ones listed). */
static GLFWmonitor *pick_monitor(const present_window_desc *d, char *why, size_t whylen)
{
    int count = 0;
    GLFWmonitor **mons = glfwGetMonitors(&count);
    if (d->monitor_name && *d->monitor_name) {
        char names[160] = "";
        for (int i = 0; i < count; i++) {
            const char *n = glfwGetMonitorName(mons[i]);
            if (n && strcmp(n, d->monitor_name) == 0)
                return mons[i];
            size_t used = strlen(names);
            snprintf(names + used, sizeof names - used, "%s'%s'", i ? ", " : "", n ? n : "?");
        }
        snprintf(why, whylen, "monitor '%s' not found (connected: %s)", d->monitor_name, count ? names : "none");
        return NULL;
    }
    if (d->monitor < count)
        return mons[d->monitor];
    snprintf(why, whylen, "monitor %d not found (%d connected)", d->monitor, count);
    return NULL;
}

static void window_hints(const present_window_desc *d, int stereo, const GLFWvidmode *mode)
{
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE); /* shown once placed */
    glfwWindowHint(GLFW_STEREO, stereo ? GLFW_TRUE : GLFW_FALSE);
    if (d->fullscreen && mode)
        glfwWindowHint(GLFW_REFRESH_RATE, mode->refreshRate);
}

/* Quad buffers are a hard constraint in GLFW: without them the window fails, and the
 * ordinary one is tried. */
static GLFWwindow *create(present_window *w, const present_window_desc *d, GLFWmonitor *mon)
{
    const GLFWvidmode *mode = mon ? glfwGetVideoMode(mon) : NULL;
    int fullscreen = d->fullscreen && mode;
    int width = fullscreen ? mode->width : d->width, height = fullscreen ? mode->height : d->height;
    GLFWwindow *win = NULL;
    for (int stereo = d->want_quad; !win && stereo >= 0; stereo--) {
        window_hints(d, stereo, mode);
        int w_now = !fullscreen && d->want_quad && !stereo && d->width_without_quad ? d->width_without_quad : width;
        win = glfwCreateWindow(w_now, height, d->title, fullscreen ? mon : NULL, NULL);
        w->quad = win && stereo;
    }
    if (!win)
        return NULL;
    int x = 0, y = 0;
    if (d->have_position)
        glfwSetWindowPos(win, d->position[0], d->position[1]);
    else if (mon && !fullscreen) {
        glfwGetMonitorPos(mon, &x, &y);
        glfwSetWindowPos(win, x, y);
    }
    glfwShowWindow(win);
    return win;
}

/* An asked swap group: joined, or not and why, in one line. */
static void join_swap_group(present_window *w, const present_window_desc *d)
{
    if (d->swap_group <= 0)
        return;
    char why[200];
    int joined = present_swap_group_join(w->handle, d->swap_group, d->swap_barrier, why, sizeof why);
    fprintf(stderr, "%s: swap group %d: %s: %s%s\n", d->log_name, d->swap_group, joined ? "joined" : "not joined",
            why, joined ? "" : "; frames are released by the software barrier alone");
}

void present_window_report(present_window *w, const present_window_desc *d)
{
    GLFWwindow *win = w->handle;
    if (w->monitor_note[0] && (d->fullscreen || (d->monitor_name && *d->monitor_name)))
        fprintf(stderr, "%s: %s: %s\n", d->log_name, w->monitor_note,
                d->fullscreen ? "staying windowed" : "placed by the window manager");
    if (d->quiet)
        return;
    int fw, fh, x, y;
    glfwGetFramebufferSize(win, &fw, &fh);
    glfwGetWindowPos(win, &x, &y);
    GLFWmonitor *mon = w->monitor;
    const char *name = mon ? glfwGetMonitorName(mon) : NULL;
    fprintf(stderr, "%s: window %dx%d at (%d, %d)%s%s%s%s, vsync %s (swap interval %d)%s\n", d->log_name, fw, fh, x,
            y, mon ? " on monitor '" : "", mon && name ? name : "", mon ? "'" : "",
            w->fullscreen ? " fullscreen" : "", d->swap_interval ? "on" : "off", d->swap_interval,
            w->quad ? ", quad-buffered" : "");
}

int present_window_open(present_window *w, const present_window_desc *d, char *err, size_t errlen)
{
    memset(w, 0, sizeof *w);
    if (glfw_users == 0 && !glfwInit()) {
        snprintf(err, errlen, "GLFW: cannot start (%s; set DISPLAY or WAYLAND_DISPLAY to a running display "
                 "server)", glfw_reason());
        return -1;
    }
    glfw_users++;
    GLFWmonitor *mon = pick_monitor(d, w->monitor_note, sizeof w->monitor_note);
    w->monitor = mon;
    GLFWwindow *win = create(w, d, mon);
    if (!win) {
        snprintf(err, errlen, "GLFW: no OpenGL 4.3 core window (%s; update the GPU driver)", glfw_reason());
        present_window_close(w);
        return -1;
    }
    w->handle = win;
    w->fullscreen = glfwGetWindowMonitor(win) != NULL;
    glfwMakeContextCurrent(win);
    glfwSwapInterval(d->swap_interval);
    if (!(w->ctx = glctx_adopt(glfw_load, "GLFW window", err, errlen))) {
        present_window_close(w);
        return -1;
    }
    join_swap_group(w, d);
    return 0;
}

void present_window_close(present_window *w)
{
    if (w->ctx)
        glctx_destroy(w->ctx);
    if (w->handle)
        glfwDestroyWindow(w->handle);
    if (glfw_users > 0 && --glfw_users == 0)
        glfwTerminate();
    memset(w, 0, sizeof *w);
}

void present_window_make_current(present_window *w)
{
    if (glfwGetCurrentContext() != w->handle)
        glfwMakeContextCurrent(w->handle);
}

void present_window_framebuffer(present_window *w, int *width, int *height)
{
    glfwGetFramebufferSize(w->handle, width, height);
}

int present_window_swap(present_window *w)
{
    glfwSwapBuffers(w->handle);
    glfwPollEvents();
    return !glfwWindowShouldClose(w->handle);
}
