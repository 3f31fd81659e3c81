/* lpv_classic: classic light propagation volumes (Kaplanyan & Dachsbacher 2010), the
 * baseline the incremental scheme (ilpv.h) is measured against, with the same splat and
 * the same transport.
 *
 * Each frame starts from the fresh injection only (no history): it is splatted
 * (lpv_splat.h) and the shell propagated `steps` steps, every step's light summed:
 *   A = near + shell + T shell + T^2 shell + ... + T^steps shell ,
 * the field of every age up to steps cells past the splat, which is what is rendered
 * (0 steps: near + shell). The ILPV's steady state is the same sum without the cut. The
 * result does not depend on the thread count. */
#ifndef CAVELIGHT_LPV_CLASSIC_H
#define CAVELIGHT_LPV_CLASSIC_H

#include "lpv/lattice.h"
#include "lpv/lpv_propagate.h"
#include "lpv/lpv_splat.h"
#include "lpv/lpv_volume.h"

typedef struct lpv_classic {
    lpv_volume near, shell; /* lpv_splat.h */
    lpv_volume work[2];     /* propagation source / destination */
    lpv_volume accum;       /* the result */
    lpv_splat splat;
} lpv_classic;

int lpv_classic_init(lpv_classic *c, const lattice_desc *lat);
void lpv_classic_free(lpv_classic *c);
/* injected, origin: this frame's injection (lpv_inject.h), left unchanged. propagate:
 * blockers, absorption, scattering, pool. Returns 0, or -1 when the splat ran out of
 * memory (the result is then black). */
int lpv_classic_frame(lpv_classic *c, const lpv_volume *injected, const lpv_volume *origin,
                      int steps, const lpv_propagate_desc *propagate);
const lpv_volume *lpv_classic_result(const lpv_classic *c);

#endif
