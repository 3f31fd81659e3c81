/* desk_view: see desk_view.h. */
#include "desk_view.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/font.h"

const uint8_t desk_view_head_color[3] = {255, 210, 60}, desk_view_wand_color[3] = {80, 220, 255},
              desk_view_text_color[3] = {230, 230, 230};
static const uint8_t background[3] = {28, 30, 36}, map_back[3] = {16, 18, 22}, wall[3] = {110, 110, 120};

static const char *const help[] = {
    "KEYS",         "W A S D  HEAD",  "PGUP PGDN  UP/DOWN", "MOUSE  WAND",      "WHEEL  REACH",
    "LMB OR 4  C",  "RMB OR 1  L",    "MMB OR 2  M",        "3 OR TAB  R",      "5  AUX",
    "ARROWS  AXES",
};

/* The map: a square on the right, as large as the picture allows. */
static void map_rect(int w, int h, int *x0, int *y0, int *size)
{
    int s = h - 8 < w / 2 ? h - 8 : w / 2;
    *size = s > 8 ? s : 8;
    *x0 = w - *size - 4;
    *y0 = 4;
}

void desk_view_map_pixel(int w, int h, float x, float z, int *px, int *py)
{
    int x0, y0, size;
    map_rect(w, h, &x0, &y0, &size);
    float ppm = (float)size / DESK_VIEW_MAP_M;
    *px = x0 + (int)lroundf(size * 0.5f + x * ppm);
    *py = y0 + (int)lroundf(size * 0.5f + z * ppm); /* -Z (the front wall) is up */
}

static void put(uint8_t *rgb, int w, int h, int x, int y, const uint8_t c[3])
{
    if (x >= 0 && y >= 0 && x < w && y < h)
        memcpy(rgb + ((size_t)y * w + x) * 3, c, 3);
}

static void dot(uint8_t *rgb, int w, int h, int x, int y, int r, const uint8_t c[3])
{
    for (int dy = -r; dy <= r; dy++)
        for (int dx = -r; dx <= r; dx++)
            put(rgb, w, h, x + dx, y + dy, c);
}

static void line(uint8_t *rgb, int w, int h, int xa, int ya, int xb, int yb, const uint8_t c[3])
{
    int steps = abs(xb - xa) > abs(yb - ya) ? abs(xb - xa) : abs(yb - ya);
    for (int i = 0; i <= steps; i++) {
        float t = steps ? (float)i / steps : 0.0f;
        put(rgb, w, h, xa + (int)lroundf(t * (xb - xa)), ya + (int)lroundf(t * (yb - ya)), c);
    }
}

void desk_view_draw(uint8_t *rgb, int w, int h, const input_source_state *st)
{
    for (size_t i = 0; i < (size_t)w * h; i++)
        memcpy(rgb + i * 3, background, 3);
    for (size_t i = 0; i < sizeof help / sizeof *help; i++)
        font_draw(rgb, w, h, 6, 6 + (int)i * FONT_HEIGHT * 5 / 4, 1, help[i], desk_view_text_color, NULL);

    int x0, y0, size;
    map_rect(w, h, &x0, &y0, &size);
    for (int y = y0; y < y0 + size; y++)
        for (int x = x0; x < x0 + size; x++)
            put(rgb, w, h, x, y, map_back);
    /* The walls of a 3 m CAVE centred on the origin. */
    int ax, ay, bx, by;
    desk_view_map_pixel(w, h, -1.5f, -1.5f, &ax, &ay);
    desk_view_map_pixel(w, h, 1.5f, 1.5f, &bx, &by);
    line(rgb, w, h, ax, ay, bx, ay, wall);
    line(rgb, w, h, ax, ay, ax, by, wall);
    line(rgb, w, h, bx, ay, bx, by, wall);
    font_draw(rgb, w, h, (ax + bx) / 2 - font_text_width("FRONT", 1) / 2, ay + 3, 1, "FRONT", wall, NULL);

    char text[64];
    int ty = y0 + size - 2 * FONT_HEIGHT;
    if (st->wand.valid) {
        const float *p = st->wand.position, *r = st->wand.rotation; /* points along its -Z column */
        int wx, wy, ex, ey;
        desk_view_map_pixel(w, h, p[0], p[2], &wx, &wy);
        desk_view_map_pixel(w, h, p[0] - 0.5f * r[6], p[2] - 0.5f * r[8], &ex, &ey);
        line(rgb, w, h, wx, wy, ex, ey, desk_view_wand_color);
        dot(rgb, w, h, wx, wy, 1, desk_view_wand_color);
    }
    if (st->head.valid) {
        const float *p = st->head.position;
        int hx, hy;
        desk_view_map_pixel(w, h, p[0], p[2], &hx, &hy);
        dot(rgb, w, h, hx, hy, 2, desk_view_head_color);
        snprintf(text, sizeof text, "HEAD %.2f %.2f %.2f", p[0], p[1], p[2]);
        font_draw(rgb, w, h, 6, ty, 1, text, desk_view_head_color, NULL);
    }
    int n = snprintf(text, sizeof text, "BUTTONS");
    for (int b = 0; b < INPUT_BUTTON_COUNT; b++)
        if ((st->buttons & (1u << b)) && input_button_name(b))
            n += snprintf(text + n, sizeof text - (size_t)n, " %s", input_button_name(b));
    font_draw(rgb, w, h, 6, ty + FONT_HEIGHT, 1, text, desk_view_wand_color, NULL);
}
