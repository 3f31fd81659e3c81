/* lpv_propagate: one propagation step of light between the 26 neighbours (paper eq. 2.4),
 * as a gather: each destination cell sums what its neighbours send it, in the fixed order
 * of lpv_transfer_offsets, so the result does not depend on the thread count.
 *
 *   dst[c] = sum_j (1 - b_j) ((1 - l_t) <S|G_j> + g_j l_s <S|1> / <G_j|1>) G_j ,  S = src[c - o_j]
 *
 * with b_j = clamp(<B[c - o_j] | G_j>, 0, 1) from the source cell's blocking (0 when
 * blocking is off), l_t = l_a + l_s clamped to 1, <S|1> = 2 sqrt(pi) S_0. The division by
 * <G_j|1> = 2 sqrt(pi) G_j0 turns the scattered energy into the factor of G_j that carries
 * it, so scattering redirects light and only absorption removes it (eq. 2.4 as printed
 * drops this factor and loses about 30% of all scattered light; see docs/lpv.md).
 * Light leaving the lattice is lost. With clamp_negative, the factor sent to each
 * neighbour (everything before G_j) is clamped at 0. */
#ifndef CAVELIGHT_LPV_PROPAGATE_H
#define CAVELIGHT_LPV_PROPAGATE_H

#include "lpv/lpv_transfer.h"
#include "lpv/lpv_volume.h"
#include "base/workpool.h"

typedef struct lpv_propagate_desc {
    const lpv_transfer *transfer;
    const lpv_volume *geometry; /* 4-channel blocking volume, or NULL for none */
    int use_blocking;           /* 0 in the first step after injection */
    float absorption;           /* l_a per step (see lpv_transfer_step_probability) */
    float scattering;           /* l_s per step */
    int clamp_negative;         /* clamp the factor sent at 0: no negative light, not linear */
    workpool *pool;             /* NULL = run on the calling thread */
} lpv_propagate_desc;

/* src and dst must have the same shape and 12 channels, and must differ. */
void lpv_propagate_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst);

/* Floating-point operations of one step on a lattice of `cells` cells, as counted for the
 * benchmark's GFLOP/s. */
double lpv_propagate_flops(size_t cells, int use_blocking);

#endif
