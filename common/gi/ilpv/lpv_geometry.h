/* lpv_geometry: which transfers between neighbouring cells a scene's surfaces block.
 *
 * Light sits at cell centres and moves between neighbours (lpv_transfer.h), so a surface
 * stops it exactly when it crosses the segment between the two centres. For each cell the
 * blockers hold one bit per neighbour k (lpv_transfer_offsets): set when the segment from
 * this centre to the neighbour's crosses a triangle. Both sides block (a single-sided,
 * zero-thickness wall stops light from behind as well), the bit is set in both cells of a
 * segment, and a centre exactly on a triangle's plane counts as being in front of it, so
 * light in a cell whose centre lies on a wall can still leave on the wall's front side.
 * Deterministic; triangles in any order give the same bits. Not the light: lpv_volume.h. */
#ifndef CAVELIGHT_LPV_GEOMETRY_H
#define CAVELIGHT_LPV_GEOMETRY_H

#include <stddef.h>
#include <stdint.h>
#include "gi/ilpv/lattice.h"

typedef struct lpv_blockers {
    int n[3];
    size_t cells;
    uint32_t *mask; /* per cell, in lattice order: bit k blocks the transfer to neighbour k */
} lpv_blockers;

typedef struct lpv_geometry_stats {
    size_t triangles;   /* accepted */
    size_t degenerate;  /* zero area: skipped */
    size_t invalid;     /* NaN/Inf vertex or bad index: skipped */
    size_t segments;    /* segment crossings found (a segment crossed twice counts twice) */
} lpv_geometry_stats;

/* Returns 0, or -1 for bad sizes or no memory. All bits clear. */
int lpv_blockers_init(lpv_blockers *b, const int n[3]);
void lpv_blockers_free(lpv_blockers *b);

/* positions: 3 floats per vertex (world space); indices: 3 per triangle, or NULL for
 * consecutive triangles. Sets bits; never clears them. stats may be NULL (counts add). */
void lpv_geometry_add_triangles(lpv_blockers *b, const lattice_desc *lat,
                                const float *positions, size_t vertex_count,
                                const unsigned *indices, size_t triangle_count,
                                lpv_geometry_stats *stats);

/* 1 when the transfer from cell (x, y, z) to its neighbour k is blocked. */
int lpv_blockers_blocked(const lpv_blockers *b, int x, int y, int z, int k);

#endif
