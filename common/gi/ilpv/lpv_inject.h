/* lpv_inject: virtual point lights into the injection volume, summed per cell.
 *
 * A VPL adds flux * SH_cos(normal) to the light volume's cell containing
 * position + 0.5 * cell * (|n_x| + |n_y| + |n_z|) * normal: far enough along the normal that
 * the cell's centre lies on the VPL's side of its surface (light sits at cell centres, and
 * the blockers of lpv_geometry.h stop it where a segment between centres crosses a
 * surface). The origin volume, when given, gathers where in that cell the light comes
 * from: the VPLs' positions in lattice units (cell centres at integers) weighted by their
 * flux summed over the colours, and that weight (channels x, y, z, weight); lpv_splat.h
 * starts the light there. Bad input is skipped and counted, never fatal. */
#ifndef CAVELIGHT_LPV_INJECT_H
#define CAVELIGHT_LPV_INJECT_H

#include <stddef.h>
#include "gi/ilpv/lattice.h"
#include "gi/ilpv/lpv_volume.h"

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

/* Adds VPLs in array order (deterministic). origin (4 channels) may be NULL; stats may be
 * NULL; counts accumulate. */
void lpv_inject_vpls(lpv_volume *light, lpv_volume *origin, const lattice_desc *lat,
                     const lpv_vpl *vpls, size_t count, lpv_inject_stats *stats);

#endif
