/* input_desk: keyboard and mouse stand-in for head tracker and wand (GLFW window). */
#include "input_desk.h"
#include "base/xalloc.h"
#include "desk_view.h"
#include "pixel_window.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <GLFW/glfw3.h>

void input_desk_step(input_desk_state *ds, const input_desk_controls *c, double dt,
                     input_source_state *st, double now)
{
    if (!ds->started) {
        ds->head[0] = 0.0f;
        ds->head[1] = 1.7f;
        ds->head[2] = 0.0f;
        ds->reach = 0.4f;
        ds->started = 1;
    }
    const float speed = 1.0f, d = (float)dt * speed;
    ds->head[2] += d * (float)(c->back - c->forward);
    ds->head[0] += d * (float)(c->right - c->left);
    ds->head[1] += d * (float)(c->up - c->down);
    ds->head[1] = ds->head[1] < 0.5f ? 0.5f : ds->head[1] > 2.5f ? 2.5f : ds->head[1];
    ds->reach += 0.05f * c->scroll;
    ds->reach = ds->reach < 0.1f ? 0.1f : ds->reach > 1.0f ? 1.0f : ds->reach;

    input_pose head = {.valid = 1, .time = now,
                       .position = {ds->head[0], ds->head[1], ds->head[2]},
                       .rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1}};
    /* Wand: yaw about Y then pitch about X; it points along its -Z. */
    float yaw = (0.5f - c->cursor[0]) * 3.14159265f, pitch = (0.5f - c->cursor[1]) * 1.5707963f;
    float cy = cosf(yaw), sy = sinf(yaw), cp = cosf(pitch), sp = sinf(pitch);
    /* R = Ry(yaw) * Rx(pitch), column-major */
    const float r[9] = {cy, 0, -sy, sy * sp, cp, cy * sp, sy * cp, -sp, cy * cp};
    float fwd[3] = {-r[6], -r[7], -r[8]};
    /* held 0.25 m below the eyes, reach metres along the horizontal pointing direction */
    float hl = sqrtf(fwd[0] * fwd[0] + fwd[2] * fwd[2]);
    float hx = hl > 1e-4f ? fwd[0] / hl : 0.0f, hz = hl > 1e-4f ? fwd[2] / hl : -1.0f;
    input_pose wand = {.valid = 1, .time = now,
                       .position = {ds->head[0] + ds->reach * hx, ds->head[1] - 0.25f,
                                    ds->head[2] + ds->reach * hz}};
    memcpy(wand.rotation, r, sizeof r);
    if (!st->head.valid || memcmp(st->head.position, head.position, sizeof head.position))
        st->head = head;
    if (!st->wand.valid || memcmp(st->wand.position, wand.position, sizeof wand.position) ||
        memcmp(st->wand.rotation, wand.rotation, sizeof wand.rotation))
        st->wand = wand;
    input_source_set_buttons(st, c->buttons, now);
    input_source_set_axes(st, c->axes, 2, now);
}

typedef struct desk_source {
    input_source base;
    pixel_window *pw;
    GLFWwindow *win;
    input_desk_state ds;
    input_desk_controls c;
    double last;
    int closed;
    int width, height;
    uint8_t *picture;          /* desk_view's image, top row first; NULL: no GL, the window stays dark */
    int tell_no_picture;       /* the first poll says why the window is dark */
} desk_source;

/* Draws the key help and the live map (desk_view.h) into the window. */
static void show(desk_source *d)
{
    desk_view_draw(d->picture, d->width, d->height, &d->base.st);
    pixel_window_show(d->pw, d->picture, d->width, d->height);
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    desk_source *d = glfwGetWindowUserPointer(w);
    d->c.scroll += (float)dy;
}

static int key(GLFWwindow *w, int k) { return glfwGetKey(w, k) == GLFW_PRESS; }

static int desk_poll(input_source *s, double now, char *err, size_t errlen)
{
    desk_source *d = (desk_source *)s;
    if (d->closed)
        return 0;
    glfwPollEvents();
    GLFWwindow *w = d->win;
    if (glfwWindowShouldClose(w)) {
        d->closed = 1;
        input_source_set_buttons(&s->st, 0, now);
        snprintf(err, errlen, "input %s: desk simulator window closed; its input stops", s->name);
        return -1;
    }
    input_desk_controls *c = &d->c;
    c->forward = key(w, GLFW_KEY_W);
    c->back = key(w, GLFW_KEY_S);
    c->left = key(w, GLFW_KEY_A);
    c->right = key(w, GLFW_KEY_D);
    c->up = key(w, GLFW_KEY_PAGE_UP);
    c->down = key(w, GLFW_KEY_PAGE_DOWN);
    double x, y;
    int ww, wh;
    glfwGetCursorPos(w, &x, &y);
    glfwGetWindowSize(w, &ww, &wh);
    c->cursor[0] = ww > 0 ? (float)fmin(fmax(x / ww, 0.0), 1.0) : 0.5f;
    c->cursor[1] = wh > 0 ? (float)fmin(fmax(y / wh, 0.0), 1.0) : 0.5f;
    uint32_t b = 0;
    if (key(w, GLFW_KEY_1) || glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS)
        b |= 1u << INPUT_BUTTON_L;
    if (key(w, GLFW_KEY_2) || glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS)
        b |= 1u << INPUT_BUTTON_M;
    if (key(w, GLFW_KEY_3) || key(w, GLFW_KEY_TAB))
        b |= 1u << INPUT_BUTTON_R;
    if (key(w, GLFW_KEY_4) || glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS)
        b |= 1u << INPUT_BUTTON_C;
    if (key(w, GLFW_KEY_5))
        b |= 1u << INPUT_BUTTON_AUX;
    c->buttons = b;
    c->axes[0] = (float)(key(w, GLFW_KEY_RIGHT) - key(w, GLFW_KEY_LEFT));
    c->axes[1] = (float)(key(w, GLFW_KEY_UP) - key(w, GLFW_KEY_DOWN));
    double dt = d->last > 0 ? now - d->last : 0.0;
    d->last = now;
    input_desk_step(&d->ds, c, dt, &s->st, now);
    c->scroll = 0.0f;
    if (d->picture)
        show(d);
    if (d->tell_no_picture) {
        d->tell_no_picture = 0;
        snprintf(err, errlen, "input %s: no OpenGL on this display for the desk window's picture: it stays "
                 "dark (the keys: docs/input.md)", s->name);
        return 1;
    }
    return 0;
}

static void desk_close(input_source *s)
{
    desk_source *d = (desk_source *)s;
    pixel_window_close(d->pw);
    free(d->picture);
    free(d);
}

input_source *input_desk_open(const input_desk_desc *desc, char *err, size_t errlen)
{
    desk_source *d = xcalloc(1, sizeof *d);
    snprintf(d->base.name, sizeof d->base.name, "%s", desc->name ? desc->name : "desk");
    d->base.cave_space = 1;
    d->base.poll = desk_poll;
    d->base.close = desk_close;
    d->width = desc->width > 0 ? desc->width : 360;
    d->height = desc->height > 0 ? desc->height : 240;
    char why[400];
    d->pw = pixel_window_open(&(pixel_window_desc){.title = "cavelight desk: WASD head, mouse wand, 1-5 buttons",
                                                   .width = d->width, .height = d->height},
                              why, sizeof why);
    if (!d->pw) {
        snprintf(err, errlen, "input %s: cannot open the desk simulator window: %s", d->base.name, why);
        free(d);
        return NULL;
    }
    d->win = pixel_window_glfw(d->pw);
    if (pixel_window_has_picture(d->pw))
        d->picture = xmalloc((size_t)d->width * d->height * 3);
    else
        d->tell_no_picture = 1;
    glfwSetWindowUserPointer(d->win, d);
    glfwSetScrollCallback(d->win, on_scroll);
    d->c.cursor[0] = d->c.cursor[1] = 0.5f;
    return &d->base;
}

void *input_desk_window(input_source *s)
{
    return ((desk_source *)s)->win;
}
