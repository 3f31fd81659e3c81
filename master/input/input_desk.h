/* input_desk: a desk simulator for the CAVE's tracking and wand, from a small GLFW window.
 *
 *   W/A/S/D          move the head (1 m/s) in the CAVE's floor plane
 *   PageUp/PageDown  raise and lower the head
 *   mouse position   points the wand: left-right = yaw (+-90 deg), up-down = pitch (+-45)
 *   mouse wheel      wand distance in front of the head (0.1..1.0 m: sets the fly speed)
 *   left mouse / 4   C (fly, flashlight, GI method)      1 L   2 M   3 or Tab R   5 AUX
 *   arrow keys       axes: left/right = X, down/up = Y
 * The head starts at (0, 1.7, 0) looking along -Z; poses are in CAVE space. The maths is
 * input_desk_step(), a pure function of the controls, so it is tested without a window.
 * The window shows these keys and a live map of the head and the wand (desk_view.h), drawn
 * into a pixel_window (pixel_window.h) on each poll; where the display offers no OpenGL it
 * stays dark and the first poll says so. */
#ifndef CAVELIGHT_INPUT_DESK_H
#define CAVELIGHT_INPUT_DESK_H

#include <stddef.h>
#include "input_source.h"

typedef struct input_desk_controls {
    int forward, back, left, right, up, down;   /* held keys */
    float cursor[2];                             /* [0,1] x right, y down; 0.5 = centre */
    float scroll;                                /* wheel steps since the last step */
    uint32_t buttons;                            /* logical buttons held */
    float axes[2];                               /* X, Y in [-1, 1] */
} input_desk_controls;

typedef struct input_desk_state {
    float head[3];
    float reach;                                 /* wand distance in front of the head */
    int started;
} input_desk_state;

/* Advances the simulated head and wand by dt seconds and writes them into st at time now. */
void input_desk_step(input_desk_state *ds, const input_desk_controls *c, double dt,
                     input_source_state *st, double now);

typedef struct input_desk_desc {
    const char *name;
    int width, height;                           /* window size, 0 = 360 x 240 */
} input_desk_desc;

/* Opens the window; fails with one line when there is no display. */
input_source *input_desk_open(const input_desk_desc *desc, char *err, size_t errlen);
/* The GLFW window (GLFWwindow *), for tests. */
void *input_desk_window(input_source *s);

#endif
