#include "frame/pattern.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "image/font.h"

const uint8_t PATTERN_BACKGROUND[3] = {16, 20, 36};
const uint8_t PATTERN_LINE[3] = {140, 140, 150};
const uint8_t PATTERN_METRE_LINE[3] = {255, 255, 255};
const uint8_t PATTERN_TEXT[3] = {255, 210, 60};
const uint8_t PATTERN_HEAD[3] = {255, 70, 70};
const uint8_t PATTERN_WAND[3] = {70, 230, 100};

static const uint8_t label_background[3] = {0, 0, 0};

void pattern_point(const pattern_desc *d, int width, int height, double px, double py, double out[3])
{
    double s = px / width, t = 1.0 - py / height;
    for (int i = 0; i < 3; i++)
        out[i] = d->bottom_left[i] + s * (d->bottom_right[i] - d->bottom_left[i]) +
                 t * (d->top_left[i] - d->bottom_left[i]);
}

static void put(uint8_t *rgb, int w, int h, int x, int y, const uint8_t c[3])
{
    if (x < 0 || y < 0 || x >= w || y >= h)
        return;
    memcpy(rgb + ((size_t)y * w + x) * 3, c, 3);
}

/* Screen coordinates (s right, t up, in [0, 1]) of a CAVE point on the screen's plane. */
static void screen_coords(const pattern_desc *d, const double p[3], double *s, double *t)
{
    double r[3], u[3], rr = 0, uu = 0, pr = 0, pu = 0;
    for (int i = 0; i < 3; i++) {
        r[i] = d->bottom_right[i] - d->bottom_left[i];
        u[i] = d->top_left[i] - d->bottom_left[i];
        rr += r[i] * r[i];
        uu += u[i] * u[i];
        pr += (p[i] - d->bottom_left[i]) * r[i];
        pu += (p[i] - d->bottom_left[i]) * u[i];
    }
    *s = pr / rr;
    *t = pu / uu;
}

static void normal(const pattern_desc *d, double n[3])
{
    double r[3], u[3];
    for (int i = 0; i < 3; i++) {
        r[i] = d->bottom_right[i] - d->bottom_left[i];
        u[i] = d->top_left[i] - d->bottom_left[i];
    }
    n[0] = r[1] * u[2] - r[2] * u[1];
    n[1] = r[2] * u[0] - r[0] * u[2];
    n[2] = r[0] * u[1] - r[1] * u[0];
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int i = 0; i < 3; i++)
        n[i] /= l;
}

static void grid(const pattern_desc *d, int w, int h, uint8_t *rgb)
{
    double step = d->grid > 0 ? d->grid : PATTERN_GRID_M;
    double dx[3], dy[3], lo_ext[3], hi_ext[3];
    for (int a = 0; a < 3; a++) {
        dx[a] = (d->bottom_right[a] - d->bottom_left[a]) / w;  /* one pixel right */
        dy[a] = -(d->top_left[a] - d->bottom_left[a]) / h;     /* one pixel down */
        lo_ext[a] = fmin(0, dx[a]) + fmin(0, dy[a]);
        hi_ext[a] = fmax(0, dx[a]) + fmax(0, dy[a]);
    }
    /* An axis the screen is (nearly) perpendicular to draws no lines. */
    int used[3];
    for (int a = 0; a < 3; a++)
        used[a] = fabs(dx[a] * w) + fabs(dy[a] * h) > 1e-3;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double p[3];
            pattern_point(d, w, h, x, y, p); /* the pixel's top-left corner */
            const uint8_t *c = PATTERN_BACKGROUND;
            for (int a = 0; a < 3; a++) {
                if (!used[a])
                    continue;
                /* Shifted by a micrometre: a line exactly on a pixel border belongs to the
                 * pixel before it, whatever the rounding of the corners. */
                double lo = p[a] + lo_ext[a] + 1e-6, hi = p[a] + hi_ext[a] + 1e-6;
                if (floor(lo) != floor(hi)) {
                    c = PATTERN_METRE_LINE;
                    break;
                }
                if (floor(lo / step) != floor(hi / step))
                    c = PATTERN_LINE;
            }
            memcpy(rgb + ((size_t)y * w + x) * 3, c, 3);
        }
}

/* A label with its anchor corner at (x, y): ax, ay 0 = left/top, 1 = right/bottom. */
static void label(uint8_t *rgb, int w, int h, int x, int y, int ax, int ay, int scale, const char *text,
                  const uint8_t color[3])
{
    int tw = font_text_width(text, scale), th = FONT_GLYPH_H * scale;
    font_draw(rgb, w, h, ax ? x - tw : x, ay ? y - th : y, scale, text, color, label_background);
}

static void corner_labels(const pattern_desc *d, int w, int h, uint8_t *rgb, int scale)
{
    float top_right[3];
    for (int i = 0; i < 3; i++)
        top_right[i] = d->bottom_right[i] + d->top_left[i] - d->bottom_left[i];
    const float *corner[4] = {d->bottom_left, d->bottom_right, d->top_left, top_right};
    const int right[4] = {0, 1, 0, 1}, bottom[4] = {1, 1, 0, 0};
    static const char axis[3] = {'x', 'y', 'z'};
    int inset = 4 * scale, line = FONT_HEIGHT * scale + scale;
    /* One coordinate a line; left out where two labels would not fit side by side, so
     * that no label reaches an edge (the seams must show the grid). */
    if (2 * (font_text_width("x -00.00", scale) + 2 * inset) > w || 8 * line > h)
        return;
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < 3; i++) {
            char text[32];
            snprintf(text, sizeof text, "%c %.2f", axis[i], corner[k][i]);
            int row = bottom[k] ? h - inset - (2 - i) * line : inset + i * line;
            label(rgb, w, h, right[k] ? w - inset : inset, row, right[k], bottom[k], scale, text, PATTERN_TEXT);
        }
}

static void head_marker(const pattern_desc *d, int w, int h, uint8_t *rgb, int scale)
{
    double n[3], p[3] = {d->head[12], d->head[13], d->head[14]}, off = 0, s, t;
    normal(d, n);
    for (int i = 0; i < 3; i++)
        off += (p[i] - d->bottom_left[i]) * n[i];
    for (int i = 0; i < 3; i++)
        p[i] -= off * n[i];
    screen_coords(d, p, &s, &t);
    if (!(s >= 0 && s <= 1 && t >= 0 && t <= 1))
        return;
    int cx = (int)(s * w), cy = (int)((1 - t) * h), arm = h / 16 + 2;
    for (int k = -arm; k <= arm; k++)
        for (int q = -scale / 2; q <= scale / 2; q++) {
            put(rgb, w, h, cx + k, cy + q, PATTERN_HEAD);
            put(rgb, w, h, cx + q, cy + k, PATTERN_HEAD);
        }
    label(rgb, w, h, cx + arm / 2, cy - arm / 2, 0, 1, scale, "head", PATTERN_HEAD);
}

static void wand_marker(const pattern_desc *d, int w, int h, uint8_t *rgb, int scale)
{
    double n[3], o[3] = {d->wand[12], d->wand[13], d->wand[14]};
    double dir[3] = {-d->wand[8], -d->wand[9], -d->wand[10]}, denom = 0, num = 0;
    normal(d, n);
    for (int i = 0; i < 3; i++) {
        denom += dir[i] * n[i];
        num += (d->bottom_left[i] - o[i]) * n[i];
    }
    if (!(fabs(denom) > 1e-9) || !(num / denom > 0))
        return;
    double p[3], s, t;
    for (int i = 0; i < 3; i++)
        p[i] = o[i] + num / denom * dir[i];
    screen_coords(d, p, &s, &t);
    if (!(s >= 0 && s <= 1 && t >= 0 && t <= 1))
        return;
    int cx = (int)(s * w), cy = (int)((1 - t) * h), r = h / 24 + 2;
    for (int y = -r - scale; y <= r + scale; y++)
        for (int x = -r - scale; x <= r + scale; x++) {
            double dist = sqrt((double)(x * x + y * y));
            if (fabs(dist - r) <= 0.5 * scale + 0.5)
                put(rgb, w, h, cx + x, cy + y, PATTERN_WAND);
        }
    label(rgb, w, h, cx + r, cy + r, 0, 0, scale, "wand", PATTERN_WAND);
}

void pattern_draw(const pattern_desc *d, int width, int height, uint8_t *rgb)
{
    grid(d, width, height, rgb);
    int small = height / 160 > 1 ? height / 160 : 1, big = height / 60 > 1 ? height / 60 : 1;
    while (big > 1 && font_text_width(d->name, big) > width * 3 / 4)
        big--;
    corner_labels(d, width, height, rgb, small);
    label(rgb, width, height, (width - font_text_width(d->name, big)) / 2,
          (height - FONT_GLYPH_H * big) / 2, 0, 0, big, d->name, PATTERN_TEXT);
    if (d->head)
        head_marker(d, width, height, rgb, small);
    if (d->wand)
        wand_marker(d, width, height, rgb, small);
}
