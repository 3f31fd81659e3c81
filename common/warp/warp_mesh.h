/* warp_mesh: cavelight's plain warp mesh file, for warps made by hand or by a script.
 *
 *   cavelight-warp-mesh 1
 *   # a comment; blank lines are skipped
 *   grid COLS ROWS          vertices across and up, each 2..1024
 *   output WIDTH HEIGHT     optional: the projector image's pixels (default: the rendered
 *                           image's size)
 *   x y u v w               COLS x ROWS vertex lines, row by row, each row COLS vertices
 *
 * x y: the vertex's place in the projector image, 0..1 from its bottom-left corner (a
 * vertex may lie outside: the cells are cut at the image's edge); u v: the point of the
 * rendered screen image shown there, 0..1 from its bottom-left corner; w: the blend weight
 * there, 0..1 of linear light (1: full). Vertex (c, r) is vertex line r * COLS + c; each
 * cell (c, r) (c+1, r) (c, r+1) (c+1, r+1) is drawn as two triangles, u, v and w linear
 * across them; the projector image is black where no cell covers it. Numbers are decimal
 * (strtod); anything else on a line is refused.
 *
 * Every refusal is one line: "warp mesh left.warp: line 7: w 1.5 is outside 0..1". */
#ifndef CAVELIGHT_WARP_MESH_H
#define CAVELIGHT_WARP_MESH_H

#include <stddef.h>

#include "warp/warp_map.h"

int warp_mesh_load(const char *path, warp_map *out, char *err, size_t errlen);
/* The same from the file's text; name is what err calls the file. */
int warp_mesh_parse(const char *text, size_t len, const char *name, warp_map *out, char *err,
                    size_t errlen);

#endif
