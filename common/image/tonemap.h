/* tonemap: the display mapping of shaders/final.frag on the host, for images made without
 * GL (the path-traced reference) and for comparing against what a node shows. */
#ifndef CAVELIGHT_TONEMAP_H
#define CAVELIGHT_TONEMAP_H

#include <stddef.h>
#include <stdint.h>

/* L / (1 + L) of linear RGB (negative values count as 0), then the encoding gamma,
 * rounded to 8 bits. */
void tonemap_rgb8(const float *linear, size_t pixels, float encoding_gamma, uint8_t *rgb);

#endif
