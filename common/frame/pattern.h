/* pattern: the calibration pattern a screen shows instead of the scene (master --pattern).
 *
 * Everything is drawn in CAVE coordinates on the screen's own surface, so it does not
 * depend on the eye: a pixel shows the point bottom_left + s (bottom_right - bottom_left)
 * + t (top_left - bottom_left) at its centre (s, t in [0, 1], t up). A pixel is a grid line
 * when a CAVE coordinate crosses a multiple of the grid step inside the pixel, so the lines
 * of neighbouring screens meet where the screens meet when their corners are right, and
 * visibly do not when they are wrong. Lines at whole metres are brighter. The screen's name
 * sits in the middle, each corner's coordinates near it; the tracked head is a cross at its
 * foot on the screen (where the head would touch it), the wand a ring where its pointing
 * ray (-Z) meets the screen. CPU only, no GL. */
#ifndef CAVELIGHT_PATTERN_H
#define CAVELIGHT_PATTERN_H

#include <stdint.h>

#define PATTERN_GRID_M 0.25f

/* Colours, so that a test (and a person) can tell the pattern's parts apart. */
extern const uint8_t PATTERN_BACKGROUND[3], PATTERN_LINE[3], PATTERN_METRE_LINE[3],
    PATTERN_TEXT[3], PATTERN_HEAD[3], PATTERN_WAND[3];

typedef struct pattern_desc {
    const float *bottom_left, *bottom_right, *top_left; /* CAVE space, metres */
    const char *name;
    const float *head;  /* head pose (mat4, CAVE space), or NULL */
    const float *wand;  /* wand pose (mat4, CAVE space, pointing along its -Z), or NULL */
    float grid;         /* metres between lines; 0 = PATTERN_GRID_M */
} pattern_desc;

/* Draws the pattern into rgb (width x height, 3 bytes a pixel, top row first). */
void pattern_draw(const pattern_desc *d, int width, int height, uint8_t *rgb);
/* The CAVE point at pixel coordinates (px, py) of the image (0, 0 = its top-left corner;
 * pixel centres at + 0.5). */
void pattern_point(const pattern_desc *d, int width, int height, double px, double py, double out[3]);

#endif
