/* lpv_propagate: one propagation step (the rule in lpv_transfer.h) over a whole lattice.
 *
 *   dst = sum over cells of what each sends to itself and its 26 neighbours
 *   accum += dst   (when an accumulation volume is given)
 *
 * A cell's light in each colour moves as two beams one cell further, spread over the 27
 * targets by the per-axis weights of lpv_transfer.h; a target's share is dropped when the
 * blockers mark the segment to it (lpv_geometry.h) or when it lies outside the lattice
 * (light leaving the lattice is lost). Work items own ranges of destination z slabs and add
 * the sources in lattice order, so the result is bit-identical for any thread count. */
#ifndef CAVELIGHT_LPV_PROPAGATE_H
#define CAVELIGHT_LPV_PROPAGATE_H

#include "base/workpool.h"
#include "lpv/lpv_geometry.h"
#include "lpv/lpv_transfer.h"
#include "lpv/lpv_volume.h"

typedef struct lpv_propagate_desc {
    const lpv_blockers *blockers; /* NULL: nothing blocks */
    lpv_volume *accum;            /* 12 channels the result is added into, or NULL */
    float absorption;             /* l_a per step (lpv_transfer_step_probability) */
    float scattering;             /* l_s per step */
    unsigned step;                /* steps since the light's chain started: the split axis */
    workpool *pool;               /* NULL = run on the calling thread */
} lpv_propagate_desc;

/* src, dst and accum must have the same shape and 12 channels, and must all differ;
 * blockers, when given, the same shape. Otherwise dst is left alone. */
void lpv_propagate_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst);

/* Floating-point operations of one step on a lattice of `cells` cells, as counted for the
 * benchmark's GFLOP/s. */
double lpv_propagate_flops(size_t cells);

#endif
