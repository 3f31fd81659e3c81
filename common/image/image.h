/* image: writing and reading the node's pictures.
 *
 * PNG (8-bit RGB, through libpng) for people; PFM (little-endian linear float RGB) for
 * measurement. Pixel arrays are top row first in memory; PFM stores the bottom row first
 * on disk, which image_write_pfm/image_read_pfm handle. */
#ifndef CAVELIGHT_IMAGE_H
#define CAVELIGHT_IMAGE_H

#include <stdint.h>
#include <stddef.h>

int image_write_png(const char *path, int width, int height, const uint8_t *rgb,
                    char *err, size_t errlen);
int image_write_pfm(const char *path, int width, int height, const float *rgb,
                    char *err, size_t errlen);
/* Allocates *rgb (free() it). Returns 0 or -1 with a reason. */
int image_read_pfm(const char *path, int *width, int *height, float **rgb,
                   char *err, size_t errlen);

/* 8-bit sRGB-encoded RGB as libpng's simplified API gives it: an 8-bit sRGB file comes back
 * byte for byte; grey is expanded, alpha is composited on black, other gammas and 16-bit
 * files are converted. Allocates *rgb (free() it). Returns 0 or -1 with a reason. */
int image_read_png(const char *path, int *width, int *height, uint8_t **rgb,
                   char *err, size_t errlen);

#endif
