/* desk_view: the picture in the desk simulator's window, so that it is never black: the
 * keys on the left, and on the right a live top-down map of the CAVE floor (X right, -Z
 * up, DESK_VIEW_MAP_M metres across, the 3 m CAVE's walls outlined) with the head as a dot,
 * the wand as a dot and a ray along where it points, and below them the head's position
 * and the buttons held. Draws into an RGB image (top row first) and nothing else: the
 * window is input_desk's. */
#ifndef CAVELIGHT_DESK_VIEW_H
#define CAVELIGHT_DESK_VIEW_H

#include <stdint.h>

#include "input/input_source.h"

#define DESK_VIEW_MAP_M 4.0f /* metres across the map: the CAVE and a step around it */

/* Head and wand from st (invalid poses are left out). */
void desk_view_draw(uint8_t *rgb, int w, int h, const input_source_state *st);
/* Where the floor point (x, z) lies on the map of a w x h picture, in pixels. */
void desk_view_map_pixel(int w, int h, float x, float z, int *px, int *py);

/* Colours, for tests. */
extern const uint8_t desk_view_head_color[3], desk_view_wand_color[3], desk_view_text_color[3];

#endif
