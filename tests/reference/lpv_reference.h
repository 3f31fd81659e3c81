/* lpv_reference: a plain scalar propagation step in scatter form, summing in double, for
 * either transport (desc->transport). beams, straight from the rule in lpv_transfer.h:
 * every source cell splits its light (lpv_transfer_split) and sends each half to the 27
 * targets with lpv_transfer_axis_weights(); shares only those two functions with the fast
 * path. paper, straight from lpv_paper.h: every source cell sends
 * max(0, (1 - b_j)((1 - l_a - l_s) <L|G_j> + gamma_j l_s <L|1>)) G_j to each neighbour;
 * shares only the transfer vectors with the fast path. Used to check the fast paths and
 * as the speed baseline. Not for production. */
#ifndef CAVELIGHT_LPV_REFERENCE_H
#define CAVELIGHT_LPV_REFERENCE_H

#include "gi/ilpv/lpv_propagate.h"

/* The same arguments as lpv_propagate_step() (the pool is ignored). */
void lpv_reference_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst);

/* How far a is from ref: per light channel, the largest |a - ref| over that channel's
 * largest |ref| (the absolute difference where ref's channel is all zero); the worst
 * channel. The measure the fast paths and the GL steps are held to. */
double lpv_reference_rel_diff(const lpv_volume *a, const lpv_volume *ref);

#endif
