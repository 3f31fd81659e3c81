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

#include "gi/ilpv/lpv_step.h"

/* Each transport's name, indexed by lpv_transport: "beams", "paper". */
extern const char *const lpv_transport_names[LPV_TRANSPORT_COUNT];

/* src, dst and accum must have the same shape and 12 channels, and must all differ;
 * blockers, when given, the same shape. Otherwise dst is left alone. */
void lpv_propagate_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst);

/* Floating-point operations of one step of transport t on a lattice of `cells` cells, as
 * counted for the benchmark's GFLOP/s. */
double lpv_propagate_flops(lpv_transport t, size_t cells);

#endif
