/* warp_map: see warp_map.h. */
#include "warp/warp_map.h"

#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The largest grid or map side a file may give (a 16K projector). */
enum { WARP_MAX_SIDE = 16384 };

void warp_map_free(warp_map *m)
{
    if (!m)
        return;
    free(m->grid);
    free(m->mesh);
    free(m->alpha.values);
    free(m->beta.values);
    memset(m, 0, sizeof *m);
}

/* The next whitespace-separated token of a PFM header as a number; 0 or -1. */
static int header_number(const uint8_t *d, size_t len, size_t *at, double *out)
{
    while (*at < len && (d[*at] == ' ' || d[*at] == '\t' || d[*at] == '\r' || d[*at] == '\n'))
        (*at)++;
    char tok[32];
    size_t n = 0;
    while (*at < len && n < sizeof tok - 1 && d[*at] > ' ')
        tok[n++] = (char)d[(*at)++];
    tok[n] = 0;
    char *end;
    *out = strtod(tok, &end);
    return n > 0 && *end == 0 && isfinite(*out) ? 0 : -1;
}

/* 0 when a w x h grid or map of c channels is within the bounds (warp_map.h), else -1 with
 * why. */
static int size_check(const char *what, double w, double h, int c, int max_w, int max_h,
                      char *why, size_t whylen)
{
    if (w != floor(w) || h != floor(h) || w < 1 || h < 1 || w > WARP_MAX_SIDE || h > WARP_MAX_SIDE) {
        snprintf(why, whylen, "%s size %g x %g is outside 1..%d", what, w, h, WARP_MAX_SIDE);
        return -1;
    }
    if ((max_w > 0 && w > max_w) || (max_h > 0 && h > max_h)) {
        snprintf(why, whylen, "%s size %g x %g is larger than the %d x %d projector image the "
                 "file declares", what, w, h, max_w, max_h);
        return -1;
    }
    if (w * h * c > (double)WARP_MAX_VALUES) {
        snprintf(why, whylen, "%s size %g x %g x %d values is over the limit of %zu (256 MiB)",
                 what, w, h, c, WARP_MAX_VALUES);
        return -1;
    }
    return 0;
}

int warp_decode_pfm(const uint8_t *d, size_t len, int max_w, int max_h, int *width,
                    int *height, int *channels, float **values, char *why, size_t whylen)
{
    if (len < 2 || d[0] != 'P' || (d[1] != 'F' && d[1] != 'f')) {
        snprintf(why, whylen, "not a PFM (no PF or Pf header)");
        return -1;
    }
    int c = d[1] == 'F' ? 3 : 1;
    size_t at = 2;
    double w, h, scale;
    if (header_number(d, len, &at, &w) || header_number(d, len, &at, &h) ||
        header_number(d, len, &at, &scale) || at >= len || scale == 0) {
        snprintf(why, whylen, "PFM header is not \"PF width height scale\"");
        return -1;
    }
    if (size_check("PFM", w, h, c, max_w, max_h, why, whylen))
        return -1;
    at++; /* the one whitespace character before the samples */
    size_t count = (size_t)w * (size_t)h * (size_t)c;
    if (len - at < count * 4) {
        snprintf(why, whylen, "PFM truncated: %zu bytes of samples, %zu needed", len - at, count * 4);
        return -1;
    }
    /* not xalloc: a PFM file's size: refused in its error line */
    float *v = malloc(count * sizeof *v);
    if (!v) {
        snprintf(why, whylen, "out of memory for %zu PFM samples", count);
        return -1;
    }
    int little = scale < 0;
    for (size_t i = 0; i < count; i++) {
        const uint8_t *b = d + at + 4 * i;
        uint32_t u = little ? (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24
                            : (uint32_t)b[3] | (uint32_t)b[2] << 8 | (uint32_t)b[1] << 16 | (uint32_t)b[0] << 24;
        memcpy(&v[i], &u, sizeof u);
    }
    *width = (int)w;
    *height = (int)h;
    *channels = c;
    *values = v;
    return 0;
}

typedef struct png_memory {
    const uint8_t *data;
    size_t len, at;
    char *why;
    size_t whylen;
    jmp_buf jump;
} png_memory;

static void png_read_memory(png_structp png, png_bytep out, size_t n)
{
    png_memory *m = png_get_io_ptr(png);
    if (m->len - m->at < n)
        png_error(png, "truncated");
    memcpy(out, m->data + m->at, n);
    m->at += n;
}

static void png_fail(png_structp png, png_const_charp msg)
{
    png_memory *m = png_get_error_ptr(png);
    snprintf(m->why, m->whylen, "PNG: %s", msg);
    longjmp(m->jump, 1);
}

static void png_quiet(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

/* The decoded rows (8 or 16 bits, big-endian samples) as floats 0..1. */
static float *png_values(const uint8_t *rows, int w, int h, int c, int bits)
{
    size_t n = (size_t)w * h * c;
    /* not xalloc: a PNG file's size: NULL is refused by the caller */
    float *v = malloc(n * sizeof *v);
    if (!v)
        return NULL;
    for (size_t i = 0; i < n; i++)
        v[i] = bits == 16 ? (float)(rows[2 * i] << 8 | rows[2 * i + 1]) / 65535.0f
                          : (float)rows[i] / 255.0f;
    return v;
}

int warp_decode_png(const uint8_t *data, size_t len, int max_w, int max_h, warp_blend_map *out,
                    int *bits, char *why, size_t whylen)
{
    png_memory m = {.data = data, .len = len, .why = why, .whylen = whylen};
    if (len < 8 || png_sig_cmp(data, 0, 8) != 0) {
        snprintf(why, whylen, "not a PNG");
        return -1;
    }
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &m, png_fail, png_quiet);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    uint8_t *volatile rows = NULL;
    png_bytep *volatile ptr = NULL;
    if (!info || setjmp(m.jump)) {
        if (!info)
            snprintf(why, whylen, "out of memory for the PNG reader");
        free(rows);
        free(ptr);
        png_destroy_read_struct(&png, info ? &info : NULL, NULL);
        return -1;
    }
    png_set_user_limits(png, WARP_MAX_SIDE, WARP_MAX_SIDE);
    png_set_read_fn(png, &m, png_read_memory);
    png_read_info(png, info);
    int type = png_get_color_type(png, info), depth = png_get_bit_depth(png, info);
    if (type & PNG_COLOR_MASK_ALPHA)
        png_error(png, "has an alpha channel (a blend map is grey or RGB)");
    if (type == PNG_COLOR_TYPE_PALETTE || depth < 8)
        png_set_expand(png);
    png_read_update_info(png, info);
    int w = (int)png_get_image_width(png, info), h = (int)png_get_image_height(png, info);
    int c = png_get_channels(png, info), b = png_get_bit_depth(png, info);
    if (size_check("PNG", w, h, c, max_w, max_h, why, whylen))
        longjmp(m.jump, 1);
    size_t stride = png_get_rowbytes(png, info);
    /* not xalloc: a PNG file's size: png_error() refuses it */
    rows = malloc(stride * (size_t)h);
    ptr = rows ? malloc((size_t)h * sizeof *ptr) : NULL;
    if (!ptr)
        png_error(png, "out of memory for the image");
    for (int y = 0; y < h; y++)
        ptr[y] = rows + (size_t)y * stride;
    png_read_image(png, ptr);
    float *v = png_values(rows, w, h, c, b);
    free(ptr);
    free(rows);
    png_destroy_read_struct(&png, &info, NULL);
    if (!v) {
        snprintf(why, whylen, "out of memory for %d x %d map values", w, h);
        return -1;
    }
    *out = (warp_blend_map){.width = w, .height = h, .channels = c, .values = v};
    *bits = b;
    return 0;
}
