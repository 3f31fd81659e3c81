/* lpv_geometry: the blocking (geometry) lattice from triangles, paper Algorithm 1.
 *
 * Each triangle is sampled uniformly with a sample count that grows with its area over
 * the cell's cross-section, so no cell a triangle crosses is left without a sample,
 * however large the triangle. Each sample adds its normal's clamped-cosine lobe, weighted
 * so that a fully covered cell blocks fully; the blocking of a transfer is later
 * clamp(<B|Gamma_j>, 0, 1). Deterministic: fixed seed, triangles in order. */
#ifndef CAVELIGHT_LPV_GEOMETRY_H
#define CAVELIGHT_LPV_GEOMETRY_H

#include <stddef.h>
#include "lattice.h"
#include "lpv_volume.h"

typedef struct lpv_geometry_stats {
    size_t triangles;   /* accepted */
    size_t degenerate;  /* zero area: skipped */
    size_t invalid;     /* NaN/Inf vertex: skipped */
    size_t samples;     /* samples injected */
    size_t outside;     /* samples outside the lattice */
} lpv_geometry_stats;

/* positions: 3 floats per vertex (world space); indices: 3 per triangle, or NULL for
 * consecutive triangles. Adds into a 4-channel volume. stats may be NULL. */
void lpv_geometry_add_triangles(lpv_volume *geometry, const lattice_desc *lat,
                                const float *positions, size_t vertex_count,
                                const unsigned *indices, size_t triangle_count,
                                lpv_geometry_stats *stats);

#endif
