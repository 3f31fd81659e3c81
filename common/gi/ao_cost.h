/* ao_cost: what the frame's ambient occlusion (frame/ao.h) asks of memory. Its layered
 * depth maps (`ao ldm`) are the ldm method's maps, so the check lives beside the methods'
 * costs; the renderer and gi_check() ask it. */
#ifndef CAVELIGHT_AO_COST_H
#define CAVELIGHT_AO_COST_H

#include "frame/frame_params.h"

/* NULL, or one line when the frame's AO maps (ao ldm) exceed ldm-memory. */
const char *ao_check(const frame_params *p);

#endif
