#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/regular_file.h"

#include "image/image.h"

int image_write_png(const char *path, int width, int height, const uint8_t *rgb,
                    char *err, size_t errlen)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = (png_uint_32)width;
    img.height = (png_uint_32)height;
    img.format = PNG_FORMAT_RGB;
    if (!png_image_write_to_file(&img, path, 0, rgb, width * 3, NULL)) {
        snprintf(err, errlen, "PNG %s: cannot write (%s; check the folder exists and is "
                 "writable)", path, img.message);
        return -1;
    }
    return 0;
}

int image_write_pfm(const char *path, int width, int height, const float *rgb,
                    char *err, size_t errlen)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        snprintf(err, errlen, "PFM %s: cannot open (%s)", path, strerror(errno));
        return -1;
    }
    /* Negative scale = little endian, which is what this machine writes. */
    int ok = fprintf(f, "PF\n%d %d\n-1.0\n", width, height) > 0;
    for (int y = height - 1; ok && y >= 0; y--)
        ok = fwrite(rgb + (size_t)y * width * 3, sizeof(float), (size_t)width * 3, f) ==
             (size_t)width * 3;
    if (fclose(f) != 0 || !ok) {
        snprintf(err, errlen, "PFM %s: write failed (disk full?)", path);
        return -1;
    }
    return 0;
}

int image_read_pfm(const char *path, int *width, int *height, float **rgb,
                   char *err, size_t errlen)
{
    char why[128];
    FILE *f = regular_fopen(path, why, sizeof why);
    if (!f) {
        snprintf(err, errlen, "PFM %s: %s", path, why);
        return -1;
    }
    char magic[3] = {0};
    int w = 0, h = 0;
    float scale = 0;
    if (fscanf(f, "%2s %d %d %f", magic, &w, &h, &scale) != 4 || strcmp(magic, "PF") != 0 ||
        w <= 0 || h <= 0 || w > 65536 || h > 65536 || scale >= 0 || fgetc(f) == EOF) {
        fclose(f);
        snprintf(err, errlen, "PFM %s: not a little-endian colour PFM", path);
        return -1;
    }
    /* not xalloc: the image file's size: refused in its error line */
    float *p = malloc((size_t)w * h * 3 * sizeof *p);
    int ok = p != NULL;
    for (int y = h - 1; ok && y >= 0; y--)
        ok = fread(p + (size_t)y * w * 3, sizeof(float), (size_t)w * 3, f) == (size_t)w * 3;
    fclose(f);
    if (!ok) {
        free(p);
        snprintf(err, errlen, "PFM %s: truncated", path);
        return -1;
    }
    *width = w;
    *height = h;
    *rgb = p;
    return 0;
}

int image_read_png(const char *path, int *width, int *height, uint8_t **rgb,
                   char *err, size_t errlen)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path)) {
        snprintf(err, errlen, "PNG %s: cannot read (%s)", path, img.message);
        return -1;
    }
    img.format = PNG_FORMAT_RGB;
    /* Zeroed: with no background colour libpng composites alpha onto the buffer. */
    /* not xalloc: the image file's size: refused in its error line */
    uint8_t *p = calloc(PNG_IMAGE_SIZE(img), 1);
    if (!p) {
        png_image_free(&img);
        snprintf(err, errlen, "PNG %s: out of memory for %ux%u pixels", path, img.width,
                 img.height);
        return -1;
    }
    if (!png_image_finish_read(&img, NULL, p, 0, NULL)) {
        free(p);
        snprintf(err, errlen, "PNG %s: cannot decode (%s)", path, img.message);
        return -1;
    }
    *width = (int)img.width;
    *height = (int)img.height;
    *rgb = p;
    return 0;
}
