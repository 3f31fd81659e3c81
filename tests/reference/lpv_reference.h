/* lpv_reference: a plain scalar propagation step, straight from eq. 2.4 in scatter form.
 *
 * Every source cell sends, to each of its 26 neighbours inside the lattice,
 *   (1 - b) ((1 - l_t) <L|G_j> + g_j l_s <L|1> / <G_j|1>) G_j
 * with b = clamp(<B|G_j>, 0, 1) of the source cell. Shares only the transfer vectors with
 * the fast path; used to check it and as the speed baseline. Not for production. */
#ifndef CAVELIGHT_LPV_REFERENCE_H
#define CAVELIGHT_LPV_REFERENCE_H

#include "lpv/lpv_transfer.h"
#include "lpv/lpv_volume.h"

typedef struct lpv_reference_desc {
    const lpv_transfer *transfer;
    const lpv_volume *geometry; /* NULL or use_blocking 0: no blocking */
    int use_blocking;
    float absorption, scattering; /* per step, as in lpv_propagate_desc */
    int clamp_negative;           /* clamp the factor sent to a neighbour at 0 */
} lpv_reference_desc;

void lpv_reference_step(const lpv_reference_desc *desc, const lpv_volume *src, lpv_volume *dst);

#endif
