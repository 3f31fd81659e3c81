/* lpv_geometry: the blocking (geometry) lattice from triangles, paper Algorithm 1.
 *
 * Each triangle is sampled uniformly: it is cut into m^2 congruent sub-triangles with edges
 * of at most a quarter cell (m grows with the triangle's size over the cell) and sampled at
 * their centroids, so no cell a triangle crosses is left without a sample, however large
 * the triangle. Each sample adds the clamped-cosine lobe around -normal (the direction into
 * the front face), weighted by its area so that a cell fully covered by a plane blocks
 * (about) fully; the blocking of a transfer is later clamp(<B|Gamma_j>, 0, 1). Deterministic:
 * no randomness, triangles in order. See docs/lpv.md. */
#ifndef CAVELIGHT_LPV_GEOMETRY_H
#define CAVELIGHT_LPV_GEOMETRY_H

#include <stddef.h>
#include "lpv/lattice.h"
#include "lpv/lpv_volume.h"

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
