/* vpl_select: chooses the virtual point lights (VPLs) of the vpl GI method (node/gi_vpl.c)
 * from every candidate (RSM texels, emissive triangles), and what a candidate is.
 *
 * Selection samples the candidates in proportion to an importance q_j by stratified
 * sampling of their cumulative distribution (the host's summed table; the high-res RSM
 * paper builds the same sums as summed-area tables on the GPU): slot i of n takes the
 * candidate whose interval holds (i + u_i) / n. A chosen candidate j (probability
 * p_j = q_j / Q per slot) gets flux and area times 1 / (n p_j): the sum over the slots of
 * any quantity linear in flux is then an unbiased estimate of its sum over all candidates,
 * for every rule below, as long as q_j > 0 wherever the flux is. The rules:
 *
 *   flux     q_j = flux_j (three channels summed); u_i a fixed random number of (seed, i).
 *   view     bidirectional: q_j = flux_j (1 / F + v_j / S), the mixture of flux alone and of
 *            flux times the view term v_j (vpl_view_term(): what the candidate sends to the
 *            points the viewer sees), half each; F = sum flux, S = sum flux v. The flux half
 *            keeps q_j > 0 where no view sample sees the candidate's light (unbiased) and
 *            bounds each weight at twice the flux rule's.
 *   regular  the thesis's regular pattern: one offset u for all slots, and every RSM texel
 *            with flux alike (q_j = the texels' mean flux), so the chosen texels are evenly
 *            spaced in texel order (systematic sampling: still unbiased over the offset);
 *            emitters, which the thesis has none of, by their flux (q_j = flux_j): taken
 *            alike, the few triangles of a bright panel would get a slot in a thousand
 *            runs and then carry all its light.
 *
 * The same candidates, view term and seed give the same VPLs on every node and every
 * frame (a static light keeps its VPLs); a light that moves shifts the sums a little, so
 * most slots keep their candidate or take its neighbour.
 *
 * Plain maths on host arrays; no GL, no allocation. Candidates come from vpl_source.h. */
#ifndef CAVELIGHT_VPL_SELECT_H
#define CAVELIGHT_VPL_SELECT_H

#include <stddef.h>
#include <stdint.h>

#include "gi/vpl/vpl_selection.h"
#include "gi/vpl_source.h"


typedef struct vpl_select_desc {
    const vpl *candidates;
    size_t count;
    size_t texels;       /* the first texels candidates are RSM texels, the rest emitters */
    vpl_selection rule;
    const double *view;  /* VPL_SELECT_VIEW: count values (vpl_view_term()); else unread */
    int n;               /* VPLs to choose */
    uint32_t seed;
} vpl_select_desc;

/* Chooses d->n VPLs into out (n of them), using cdf (d->count doubles) as scratch; chosen
 * (room for n, or NULL) gets each slot's candidate index. Returns n, or 0 when no
 * candidate has positive flux (out untouched). */
int vpl_select(const vpl_select_desc *d, double *cdf, vpl *out, size_t *chosen);
/* The view term of every candidate: the mean over the view samples (6 floats each: a
 * point the viewer sees and its unit normal turned to the viewer) of what a unit of the
 * candidate's flux gives there, cos_l cos_x / (A + pi r^2) with the gather's bound
 * (shade.frag's vpl_light(); eq. 10 of the high-res RSM paper with that bound for its
 * clamped 1 / max(1, r^2)), visibility left out. Candidates are evaluated every stride-th
 * (stride >= 1), counted afresh from the first emitter (candidate texels), and the ones
 * between take the value of the last evaluated: the term is smooth across neighbouring
 * texels, an emitter never takes a texel's, and any positive importance keeps the
 * selection unbiased, so the shortcut costs variance only. Writes count values into out. */
void vpl_view_term(const vpl *candidates, size_t count, size_t texels, const float *samples,
                   int nsamples, size_t stride, double *out);
/* FNV-1a over the VPLs' float bit patterns (byte-order independent): what READY carries. */
uint64_t vpl_checksum(const vpl *v, int n);
#endif
