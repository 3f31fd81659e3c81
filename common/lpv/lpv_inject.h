/* lpv_inject: virtual point lights and surface samples into lattices.
 *
 * A VPL adds flux * SH_cos(normal) to the light volume's cell containing
 * position + 0.5 * cell * normal (the half-cell offset avoids self-lighting). Bad input is
 * skipped and counted, never fatal. */
#ifndef CAVELIGHT_LPV_INJECT_H
#define CAVELIGHT_LPV_INJECT_H

#include <stddef.h>
#include "lpv/lattice.h"
#include "lpv/lpv_volume.h"

typedef struct lpv_vpl {
    float position[3];
    float normal[3]; /* need not be unit length; zero or non-finite is skipped */
    float flux[3];   /* RGB */
} lpv_vpl;

typedef struct lpv_inject_stats {
    size_t injected;
    size_t outside;  /* fell outside the lattice after the offset */
    size_t invalid;  /* NaN/Inf position, normal or flux, or zero normal */
} lpv_inject_stats;

/* Adds VPLs in array order (deterministic). stats may be NULL; counts accumulate. */
void lpv_inject_vpls(lpv_volume *light, const lattice_desc *lat, const lpv_vpl *vpls,
                     size_t count, lpv_inject_stats *stats);

#endif
