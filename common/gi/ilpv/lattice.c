#include "gi/ilpv/lattice.h"

#include <math.h>
#include <stdio.h>

static int fail(char *err, size_t errlen, const char *msg)
{
    if (err && errlen)
        snprintf(err, errlen, "%s", msg);
    return -1;
}

/* Cells per axis for a given cell size: the extent plus the margin on both sides. The
 * tiny relative slack keeps an exact fit (longest axis) from rounding up one cell. */
static void counts_for(const double ext[3], double cell, double margin, double n[3])
{
    for (int a = 0; a < 3; a++) {
        double x = ext[a] / cell + 2.0 * margin;
        n[a] = fmax(1.0, ceil(x * (1.0 - 1e-9)));
    }
}

int lattice_fit(const lattice_fit_desc *desc, lattice_desc *out, char *err, size_t errlen)
{
    double ext[3], longest = 0.0;
    for (int a = 0; a < 3; a++) {
        if (!isfinite(desc->bounds_min[a]) || !isfinite(desc->bounds_max[a]))
            return fail(err, errlen, "lattice: scene bounds are not finite; check the scene's vertex positions");
        ext[a] = (double)desc->bounds_max[a] - desc->bounds_min[a];
        if (ext[a] < 0.0)
            return fail(err, errlen, "lattice: scene bounds are inverted (max < min); pass min and max in that order");
        longest = fmax(longest, ext[a]);
    }
    if (!(longest > 0.0))
        return fail(err, errlen, "lattice: scene bounds have zero size; the scene needs geometry with extent");
    int axis_cells = desc->max_axis_cells ? desc->max_axis_cells : LATTICE_DEFAULT_AXIS_CELLS;
    long budget = desc->max_cells ? desc->max_cells : 64L * 64 * 64;
    double margin = desc->margin_cells < 0.0f ? 0.0 : desc->margin_cells;
    if (axis_cells < 1 || axis_cells > (1 << 16))
        return fail(err, errlen, "lattice: max_axis_cells must be in 1..65536");
    if (budget < 1)
        return fail(err, errlen, "lattice: max_cells must be at least 1");
    if (!isfinite(margin) || (double)axis_cells - 2.0 * margin <= 0.0)
        return fail(err, errlen, "lattice: the margin leaves no cells for the scene; lower margin_cells or raise max_axis_cells");

    double cell = longest / ((double)axis_cells - 2.0 * margin), n[3];
    counts_for(ext, cell, margin, n);
    /* Grow the cell until the budget holds; counts never drop below 1, so this ends. */
    while (n[0] * n[1] * n[2] > (double)budget) {
        cell *= 1.005;
        counts_for(ext, cell, margin, n);
    }
    out->cell = (float)cell;
    for (int a = 0; a < 3; a++) {
        out->n[a] = (int)n[a];
        double centre = 0.5 * ((double)desc->bounds_min[a] + desc->bounds_max[a]);
        out->origin[a] = (float)(centre - 0.5 * n[a] * cell);
    }
    return 0;
}

size_t lattice_cell_count(const lattice_desc *lat)
{
    return (size_t)lat->n[0] * (size_t)lat->n[1] * (size_t)lat->n[2];
}

void lattice_world_to_lattice(const lattice_desc *lat, const float world[3], float out[3])
{
    for (int a = 0; a < 3; a++)
        out[a] = (world[a] - lat->origin[a]) / lat->cell;
}

void lattice_lattice_to_world(const lattice_desc *lat, const float cells[3], float out[3])
{
    for (int a = 0; a < 3; a++)
        out[a] = lat->origin[a] + cells[a] * lat->cell;
}

int lattice_cell_of(const lattice_desc *lat, const float world[3], int ijk[3], size_t *index)
{
    float c[3];
    lattice_world_to_lattice(lat, world, c);
    int t[3];
    for (int a = 0; a < 3; a++) {
        if (!isfinite(c[a]) || c[a] < 0.0f || c[a] >= (float)lat->n[a])
            return -1;
        t[a] = (int)c[a];
        if (t[a] >= lat->n[a]) /* rounding at the upper face */
            return -1;
    }
    if (ijk)
        for (int a = 0; a < 3; a++)
            ijk[a] = t[a];
    if (index)
        *index = (size_t)t[0] + (size_t)lat->n[0] * ((size_t)t[1] + (size_t)lat->n[1] * (size_t)t[2]);
    return 0;
}
