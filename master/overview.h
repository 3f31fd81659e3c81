/* overview: the unfolded CAVE in one picture, the one place that lays the walls out (the
 * --overview file at the end of a session and the live --preview window both use it).
 *
 * Reads each screen's PNG (DIR/SCREEN-EYE.png, as png-output nodes write them, replaced
 * atomically) and places it at the screen's "overview" pixel offset from the config, on a
 * dark canvas just large enough for all of them, each labelled with its name in its
 * top-left corner. Screens without an offset are left out. The eye is "left" for stereo
 * nodes and the node's only eye otherwise. */
#ifndef CAVELIGHT_OVERVIEW_H
#define CAVELIGHT_OVERVIEW_H

#include <stddef.h>
#include <stdint.h>

#include "cluster/cluster_config.h"

/* The canvas every screen fits on, from the configured resolutions. Returns 0, or -1 with
 * a one-line reason when no screen has an "overview" offset. */
int overview_size(const cluster_config *cfg, int *width, int *height, char *err, size_t errlen);
/* Draws the screens' images from dir onto canvas (RGB, top row first, the size from
 * overview_size()), each with its label. A missing image is an error (-1, one line naming
 * the file) unless missing_ok, when its place stays dark: a live view before the nodes'
 * first frame. Returns how many screens it drew, or -1. */
int overview_draw(const cluster_config *cfg, const char *dir, int missing_ok, uint8_t *canvas, int width,
                  int height, char *err, size_t errlen);
/* overview_size(), overview_draw() of every screen, and the PNG at out_path. Returns 0, or
 * -1 with a one-line reason (e.g. the missing file) in err. */
int overview_compose(const cluster_config *cfg, const char *dir, const char *out_path, char *err, size_t errlen);

/* Where a screen's label goes on a w x h image placed at (x0, y0): its top-left corner and
 * the font scale (2 on images of at least 128 pixels a side), and its colours. */
void overview_label_place(int x0, int y0, int w, int h, int *x, int *y, int *scale);
extern const uint8_t overview_label_text[3], overview_label_back[3];

#endif
