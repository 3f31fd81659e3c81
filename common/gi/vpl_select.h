/* vpl_select: chooses the virtual point lights (VPLs) of the vpl GI method (node/gi_vpl.c)
 * from every candidate (RSM texels, emissive triangles), and what a candidate is.
 *
 * Selection is importance sampling in proportion to flux (its three channels summed) by
 * stratified sampling of the candidates' cumulative distribution: slot i of n takes the
 * candidate whose CDF interval holds (i + u_i) / n, u_i a fixed random number of (seed, i).
 * A chosen candidate j (probability p_j = flux_j / total per slot) gets flux and area
 * times 1 / (n p_j): the sum over the slots of any quantity linear in flux is then an
 * unbiased estimate of its sum over all candidates, and the chosen fluxes add up to the
 * total exactly. The same candidates and seed give the same VPLs on every node and every
 * frame (a static light keeps its VPLs); a light that moves shifts the CDF a little, so
 * most slots keep their candidate or take its neighbour.
 *
 * Plain maths on host arrays; no GL, no allocation. Candidates come from vpl_source.h. */
#ifndef CAVELIGHT_VPL_SELECT_H
#define CAVELIGHT_VPL_SELECT_H

#include <stddef.h>
#include <stdint.h>

/* A Lambertian emitter at a point: radiant intensity flux / pi * cos(angle to normal). */
typedef struct vpl {
    float position[3];
    float normal[3];   /* unit */
    float flux[3];     /* W it sends into its hemisphere, linear RGB */
    float area;        /* m^2 of surface it stands for */
} vpl;

/* Chooses n VPLs from count candidates into out (n of them), using cdf (count doubles) as
 * scratch; chosen (room for n, or NULL) gets each slot's candidate index. Returns n, or 0
 * when no candidate has positive flux (out untouched). */
int vpl_select(const vpl *candidates, size_t count, int n, uint32_t seed, double *cdf,
               vpl *out, size_t *chosen);
/* The fixed random number in [0, 1) of slot i under seed, dimension dim: 0 is the
 * selection's, 1 and 2 place a chosen emitter's VPL on its triangle (vpl_source.h). */
double vpl_slot_random(uint32_t seed, int i, int dim);
/* FNV-1a over the VPLs' float bit patterns (byte-order independent): what READY carries. */
uint64_t vpl_checksum(const vpl *v, int n);
#endif
