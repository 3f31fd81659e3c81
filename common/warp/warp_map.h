/* warp_map: how one screen's rendered image reaches its projector (warp and blend), read
 * once at start from an MPCDI file (mpcdi.h) or a warp mesh file (warp_mesh.h).
 *
 * The projector image (out_w x out_h pixels; 0 x 0: the rendered image's size) shows at
 * each of its points a point of the rendered screen image, found one of three ways:
 *   WARP_UV_GRID     a grid over the projector image holds that point (u, v), each 0..1 from
 *                    the rendered image's bottom-left corner (MPCDI profile 2d)
 *   WARP_POINT_GRID  a grid holds the surface point (x, y, z, metres) each projector pixel
 *                    lights; every frame it is projected through the eye's view of the
 *                    screen, so the warp follows the tracked head (MPCDI profile 3d)
 *   WARP_MESH        a mesh of vertices, each with its place in the projector image, the
 *                    point (u, v) it shows and a blend weight (warp_mesh.h)
 *   WARP_NONE        the image as rendered (blend maps may still apply)
 * Projector image coordinates run 0..1 from its bottom-left corner (OpenGL's, as MPCDI
 * says). Grids are uniform and in "fill" layout: sample (i, j) sits at the centre of cell
 * i of grid_w across the image and row j of grid_h up from the bottom (rows bottom first,
 * the PFM order); between centres values are interpolated linearly, beyond the outer
 * centres extrapolated, so an affine warp is exact with 2 x 2 samples. A sample that is
 * unknown (NaN in the file) is WARP_UNKNOWN, and pixels that use it stay black.
 *
 * Blend (MPCDI section 2.4), in linear light: P = Pi alpha (1 - beta) + beta, with
 * alpha = (map value)^alpha_gamma and beta as stored; the maps cover the projector image
 * (bilinear), 1 or 3 channels, values 0..1, rows top first (PNG order). A map with no
 * values is alpha 1 or beta 0. GL-free: node/present/present_warp.c draws it. */
#ifndef CAVELIGHT_WARP_MAP_H
#define CAVELIGHT_WARP_MAP_H

#include <stddef.h>
#include <stdint.h>

/* A grid sample the file left unknown. */
#define WARP_UNKNOWN (-1e30f)

typedef enum warp_kind {
    WARP_NONE = 0,
    WARP_UV_GRID,
    WARP_POINT_GRID,
    WARP_MESH,
} warp_kind;

typedef struct warp_blend_map {
    int width, height, channels; /* channels 1 or 3 */
    float *values;               /* width * height * channels, rows top first; NULL: none */
} warp_blend_map;

typedef struct warp_map {
    warp_kind kind;
    int out_w, out_h;       /* projector image pixels; 0: the rendered image's size */
    int place[2];           /* MPCDI: the region's top-left in its buffer (the window),
                               pixels from the top-left; -1: beside the node's other screens */
    int grid_w, grid_h;     /* UV_GRID, POINT_GRID */
    float *grid;            /* grid_w * grid_h * 3 (u v error, or x y z), rows bottom first */
    int mesh_cols, mesh_rows;
    float *mesh;            /* MESH: cols * rows vertices of x y u v weight, row by row */
    warp_blend_map alpha, beta;
    float alpha_gamma;      /* the alpha map's embedded gamma; 1 = linear */
} warp_map;

void warp_map_free(warp_map *m);

/* The most float values one decoded grid or map may hold (256 MiB): a 4K projector's RGB
 * map, an 8K one's grey map. */
#define WARP_MAX_VALUES ((size_t)1 << 26)

/* Decoders for what MPCDI containers and warp files hold, from memory; each returns 0, or
 * -1 with the reason in why (no file name: the caller names the part). A grid or map wider
 * than max_w or taller than max_h (the projector image the file declares; 0: no such
 * bound), or of more than WARP_MAX_VALUES values, is refused from its header, before
 * anything is decoded: a small compressed file cannot claim gigabytes. */
/* PFM (netpbm: "PF" colour or "Pf" grey, either byte order, rows bottom first). */
int warp_decode_pfm(const uint8_t *data, size_t len, int max_w, int max_h, int *width,
                    int *height, int *channels, float **values, char *why, size_t whylen);
/* PNG grey or RGB, 8 or 16 bits, values as stored scaled to 0..1 (no colour conversion:
 * a blend map is data, not a picture); bits: the file's bit depth. */
int warp_decode_png(const uint8_t *data, size_t len, int max_w, int max_h, warp_blend_map *out,
                    int *bits, char *why, size_t whylen);

#endif
