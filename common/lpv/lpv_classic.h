/* lpv_classic: classic light propagation volumes (Kaplanyan & Dachsbacher 2010), the
 * baseline the incremental scheme (ilpv.h) is measured against.
 *
 * Each frame starts from the fresh injection only (no history): the injected volume I is
 * propagated `steps` steps, and every step's result is added into an accumulation volume,
 *   A = T I + T^2 I + ... + T^steps I ,
 * which is what is rendered. The injection itself (the first solution) is not added, as
 * in the original scheme. Blocking is off in the first step, like in ilpv. steps = 0
 * gives a black (zero) result. The accumulation adds slices in a fixed order, so the
 * result does not depend on the thread count. */
#ifndef CAVELIGHT_LPV_CLASSIC_H
#define CAVELIGHT_LPV_CLASSIC_H

#include "lpv/lattice.h"
#include "lpv/lpv_propagate.h"
#include "lpv/lpv_volume.h"

typedef struct lpv_classic {
    lpv_volume work[2];     /* propagation source / destination */
    lpv_volume accum;       /* the result */
} lpv_classic;

int lpv_classic_init(lpv_classic *c, const lattice_desc *lat);
void lpv_classic_free(lpv_classic *c);
/* injected: this frame's injection, same shape, left unchanged. */
void lpv_classic_frame(lpv_classic *c, const lpv_volume *injected, int steps,
                       const lpv_propagate_desc *propagate);
const lpv_volume *lpv_classic_result(const lpv_classic *c);

#endif
