/* lattice: a box of cubic cells fitted to a scene's bounds.
 *
 * Cells are cubes of edge `cell`; the counts per axis follow the scene's shape, so an
 * elongated scene gets an elongated lattice. Cell (i,j,k) covers
 * [origin + (i,j,k)*cell, origin + (i+1,j+1,k+1)*cell); its centre is at +0.5 cell.
 * Linear index: i + nx*(j + ny*k) (x fastest). */
#ifndef CAVELIGHT_LATTICE_H
#define CAVELIGHT_LATTICE_H

#include <stddef.h>

enum { LATTICE_DEFAULT_AXIS_CELLS = 32 };

typedef struct lattice_desc {
    float origin[3]; /* world position of the lattice's minimum corner */
    float cell;      /* cell edge length in metres, > 0 */
    int n[3];        /* cells per axis, each >= 1 */
} lattice_desc;

typedef struct lattice_fit_desc {
    float bounds_min[3], bounds_max[3]; /* scene bounds in world space */
    int max_axis_cells;  /* cells along the longest axis; 0 = LATTICE_DEFAULT_AXIS_CELLS */
    long max_cells;      /* total cell budget; 0 = 64^3. The cell grows until it fits. */
    float margin_cells;  /* empty cells added around the bounds on each side; < 0 = 0.5 */
} lattice_fit_desc;

/* Fits a lattice to the bounds. Returns 0, or -1 with a one-line reason in err for
 * empty, inverted or non-finite bounds and impossible budgets. */
int lattice_fit(const lattice_fit_desc *desc, lattice_desc *out, char *err, size_t errlen);

size_t lattice_cell_count(const lattice_desc *lat);
void lattice_world_to_lattice(const lattice_desc *lat, const float world[3], float out[3]); /* in cells */
void lattice_lattice_to_world(const lattice_desc *lat, const float cells[3], float out[3]);
/* Cell containing a world point; returns 0 and the index, or -1 if outside or not finite. */
int lattice_cell_of(const lattice_desc *lat, const float world[3], int ijk[3], size_t *index);

#endif
