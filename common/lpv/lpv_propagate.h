/* lpv_propagate: one propagation step over a whole lattice, by one of two transports.
 *
 *   dst = sum over cells of what each sends to its neighbours
 *   accum += dst   (when an accumulation volume is given)
 *
 * beams (the default): a cell's light in each colour moves as two beams one cell further,
 * spread over the 27 targets (itself included) by the per-axis weights of lpv_transfer.h.
 * paper: the thesis's step (lpv_paper.h): each of the 26 neighbours gets
 * max(0, <L|A_j>) G_j. Either way a share is dropped when the blockers mark the segment to
 * its target (lpv_geometry.h) or when the target lies outside the lattice (light leaving
 * the lattice is lost). Work items own ranges of destination z slabs and every destination
 * cell adds its sources in a fixed order, so the result is bit-identical for any thread
 * count. */
#ifndef CAVELIGHT_LPV_PROPAGATE_H
#define CAVELIGHT_LPV_PROPAGATE_H

#include "base/workpool.h"
#include "lpv/lpv_geometry.h"
#include "lpv/lpv_paper.h"
#include "lpv/lpv_transfer.h"
#include "lpv/lpv_volume.h"

typedef enum lpv_transport {
    LPV_TRANSPORT_BEAMS = 0, /* two beams per cell and colour (lpv_transfer.h) */
    LPV_TRANSPORT_PAPER,     /* the thesis's transfer vectors (lpv_paper.h) */
    LPV_TRANSPORT_COUNT
} lpv_transport;

/* Each transport's name, indexed by lpv_transport: "beams", "paper". */
extern const char *const lpv_transport_names[LPV_TRANSPORT_COUNT];

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

/* src, dst and accum must have the same shape and 12 channels, and must all differ;
 * blockers, when given, the same shape. Otherwise dst is left alone. */
void lpv_propagate_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst);

/* Floating-point operations of one step of transport t on a lattice of `cells` cells, as
 * counted for the benchmark's GFLOP/s. */
double lpv_propagate_flops(lpv_transport t, size_t cells);

/* A per-step probability (absorption, scattering) into [0, 1]; NaN -> 0. */
static inline float lpv_probability_clamp(float x)
{
    return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;
}

#endif
