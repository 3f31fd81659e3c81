/* mpcdi: one region of a VESA MPCDI file (a zip holding mpcdi.xml, PFM warps and PNG blend
 * maps; libzip and libxml2) as a warp_map.
 *
 * Profiles 2d (a uniform grid of (u, v) into the rendered image) and 3d (a grid of surface
 * points, projected every frame through the tracked eye's view of the screen; the region's
 * frustum is checked but the view comes from the cluster config's screen) are read; a3 and
 * sl are refused. The region's xResolution x yResolution is the projector image's size and
 * its x, y (0..1 of its buffer, y from the top) place it in the window. Its fileset must
 * hold a geometryWarpFile (3 channel PFM, at least 2 x 2) and an alphaMap (PNG whose
 * channels and bit depth are the XML's componentDepth and bitDepth, at least 2 x 2); a
 * betaMap is optional. 3d points are scaled to metres by geometricUnit (unknown: metres).
 * Tag and attribute names are matched without case, values and paths with it (the
 * standard's rule). Does not: read colour LUTs, distortion maps or extensions (ignored),
 * nor follow anything outside the zip.
 *
 * Every refusal is one line naming the file and the part:
 *   "MPCDI wall.mpcdi: region p1: fileset: no alphaMap (an alpha map is required)". */
#ifndef CAVELIGHT_MPCDI_H
#define CAVELIGHT_MPCDI_H

#include <stddef.h>

#include "warp/warp_map.h"

/* region: the region's id, or NULL/"" for the file's only region. 0, or -1 with err. */
int mpcdi_load(const char *path, const char *region, warp_map *out, char *err, size_t errlen);
/* The same from the zip's bytes; name is what err calls the file. */
int mpcdi_parse(const void *zip, size_t len, const char *name, const char *region, warp_map *out,
                char *err, size_t errlen);

#endif
