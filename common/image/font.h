/* font: a 5x7 bitmap font for labels drawn into RGB images (screen names on the
 * calibration pattern and the overview, the desk window's key help), so that no font
 * library or font file is needed on a render host.
 *
 * Upper-case letters, digits and common punctuation; lower-case letters are drawn as
 * upper-case ones, anything else as a blank. Each glyph cell is FONT_ADVANCE x FONT_HEIGHT
 * pixels at scale 1 (one column and one row of spacing included); text is scaled by whole
 * pixels. Drawing clips at the image's edges. */
#ifndef CAVELIGHT_FONT_H
#define CAVELIGHT_FONT_H

#include <stdint.h>

enum { FONT_GLYPH_W = 5, FONT_GLYPH_H = 7, FONT_ADVANCE = 6, FONT_HEIGHT = 8 };

/* Width in pixels of text at scale. */
int font_text_width(const char *text, int scale);
/* Draws text with its top-left corner at (x, y) in rgb (w x h, 3 bytes a pixel, top row
 * first) in colour; with a background colour (not NULL) the cells are filled first, so
 * that the label reads on any image. */
void font_draw(uint8_t *rgb, int w, int h, int x, int y, int scale, const char *text,
               const uint8_t color[3], const uint8_t *background);

#endif
