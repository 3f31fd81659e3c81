/* lpv_step: what one propagation step of either transport takes (lpv_propagate.h runs
 * it; lpv_paper_step.h is the paper transport's kernel). Types and one inline rule only. */
#ifndef CAVELIGHT_LPV_STEP_H
#define CAVELIGHT_LPV_STEP_H

#include "base/workpool.h"
#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_paper.h"
#include "gi/ilpv/lpv_transfer.h"
#include "gi/ilpv/lpv_volume.h"

typedef enum lpv_transport {
    LPV_TRANSPORT_BEAMS = 0, /* two beams per cell and colour (lpv_transfer.h) */
    LPV_TRANSPORT_PAPER,     /* the thesis's transfer vectors (lpv_paper.h) */
    LPV_TRANSPORT_COUNT
} lpv_transport;

typedef struct lpv_propagate_desc {
    lpv_transport transport;
    const lpv_paper_transfer *paper; /* paper: G_j and gamma_j; NULL = lpv_paper_transfer_default() */
    const lpv_blockers *blockers; /* NULL: nothing blocks */
    lpv_volume *accum;            /* 12 channels the result is added into, or NULL */
    float absorption;             /* l_a per step: lpv_transfer_step_probability() (beams),
                                     lpv_paper_step_probability() (paper) */
    float scattering;             /* l_s per step, the same way */
    unsigned step;                /* beams: steps since the light's chain started (split axis) */
    workpool *pool;               /* NULL = run on the calling thread */
} lpv_propagate_desc;

/* A per-step probability (absorption, scattering) into [0, 1]; NaN -> 0. */
static inline float lpv_probability_clamp(float x)
{
    return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;
}

#endif
