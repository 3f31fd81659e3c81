/* lpv_receive: the irradiance a surface point receives from the rendered LPV field: the
 * rule shaders/shade.frag implements on the GPU, here in C for the tests and tools (no test
 * compares the two yet).
 *
 * The field is read at p + cell/2 * n by trilinear interpolation of the SH coefficients,
 * leaving out the cells whose centre lies behind the surface's plane (light behind a wall
 * must not reach its front; the remaining weights are renormalized, and a point with no
 * cell in front receives nothing). Each colour's coefficients are then read as an energy E
 * and a mean direction with mean cosine q (lpv_transfer.h) and taken as the closest of
 * four shapes whose irradiance on a surface facing m = -n is known in closed form, with
 * t = m . d and theta = acos t:
 *   beam (q = 1):            E max(t, 0)
 *   clamped cosine (q = 2/3): E ((pi - theta) cos theta + sin theta) 2 / (3 pi)
 *   hemisphere (q = 1/2):     E (1 + t) / 4
 *   isotropic (q = 0):        E / 4
 * mixed linearly in q between neighbouring shapes, over the cell's area. Negative energy
 * receives nothing. */
#ifndef CAVELIGHT_LPV_RECEIVE_H
#define CAVELIGHT_LPV_RECEIVE_H

#include "gi/ilpv/lattice.h"
#include "gi/ilpv/lpv_volume.h"

/* A cell centre is behind the surface when it lies more than this many cells behind the
 * plane: rounding must not decide for a centre on the plane (a wall through cell
 * centres). The shader gets it as LPV_BEHIND. */
#define LPV_RECEIVE_BEHIND 1e-4f

/* A surface point with unit normal n reads the cells whose centre lies in front of its
 * plane by less than this (in cells): 1 for an axis-aligned surface, whose first layer of
 * cells in front is always within one cell, and 0.5 more per unit of |n_x|+|n_y|+|n_z|
 * beyond 1 for slanted ones, less LPV_RECEIVE_BEHIND so that rounding does not decide for
 * a centre exactly one layer out. lpv_splat.h keeps a surface's own light out of that
 * layer, so that a lit surface sees what arrives, not its own outgoing light. The shader
 * has the same formula. */
static inline float lpv_own_layer(const float n[3])
{
    float l1 = (n[0] < 0 ? -n[0] : n[0]) + (n[1] < 0 ? -n[1] : n[1]) + (n[2] < 0 ? -n[2] : n[2]);
    return 0.5f * l1 + 0.5f - LPV_RECEIVE_BEHIND;
}

/* Irradiance per unit area (W/m^2 for a field in W/sr) from one colour's coefficients L of
 * a cell of edge `cell`, on a surface with unit normal n. */
float lpv_receive_closure(const float L[4], const float n[3], float cell);

/* Irradiance at world point p with unit normal n, per colour. on_surface 0 reads all eight
 * cells (a point in free space, for the tests of the field itself). */
void lpv_receive_irradiance(const lpv_volume *field, const lattice_desc *lat, const float p[3],
                            const float n[3], int on_surface, float out_rgb[3]);

#endif
