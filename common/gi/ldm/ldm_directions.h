/* ldm_directions: the layered depth maps' deterministic directions, one per map.
 *
 * The upper hemisphere (+y, the world's up) is split into n regions of equal area and
 * small diameter by the recursive zonal equal-area partition (Leopardi 2006) restricted
 * to a hemisphere: a polar cap of area 2 pi / n, then collars of whole regions down to
 * the equator, each collar's boundaries moved so that it holds exactly its regions' area.
 * A region's direction is its centre (the pole for the cap; the middle colatitude and
 * longitude of a collar's sector). A map is traced both ways, so the n directions and
 * their opposites are 2 n directions of equal-area regions over the whole sphere.
 *
 * Pure function of n (no state, no randomness): every node computes the same set in the
 * same order. Does not place or build maps (ldm_map.h). */
#ifndef CAVELIGHT_LDM_DIRECTIONS_H
#define CAVELIGHT_LDM_DIRECTIONS_H

#include "frame/ldm_limits.h"

/* The n unit directions (n in 1..LDM_DIRECTIONS_MAX) into out, cap first, then collar by
 * collar from the pole down, each collar by longitude. Returns n, or 0 for a bad n. */
int ldm_directions(int n, float (*out)[3]);
/* The region of the partition into n that holds the unit direction w of the upper
 * hemisphere (w.y >= 0), as the index ldm_directions() gives its centre; a direction
 * below the equator is mirrored through the origin first. -1 for a bad n. */
int ldm_direction_region(int n, const float w[3]);

#endif
