/* lpv_reference: a plain scalar propagation step in scatter form, straight from the rule
 * in lpv_transfer.h: every source cell splits its light (lpv_transfer_split) and sends
 * each half to the 27 targets with lpv_transfer_axis_weights(), summing in double. Shares
 * only those two functions with the fast path; used to check it and as the speed
 * baseline. Not for production. */
#ifndef CAVELIGHT_LPV_REFERENCE_H
#define CAVELIGHT_LPV_REFERENCE_H

#include "lpv/lpv_propagate.h"

/* The same arguments as lpv_propagate_step() (the pool is ignored). */
void lpv_reference_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst);

#endif
