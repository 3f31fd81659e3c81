/* lpv_paper: the constants of the thesis's propagation (papers/incremental-lpv-cave.txt,
 * sections 2.7 and 3.2.2, listing 5.2), the `paper` transport of lpv_propagate.h.
 *
 * One step sends, from every cell c to each of its 26 neighbours j,
 *   p_j = max(0, (1 - b_j) ((1 - l_a - l_s) <L_c | G_j> + gamma_j l_s <L_c | 1>))
 * as p_j G_j (SH coefficients), summed at the neighbour. G_j is kappa times the mean
 * clamped-cosine lobe towards points drawn uniformly in neighbour cell j, keeping only the
 * points inside the visibility cone from c's centre that touches the neighbour's inscribed
 * sphere (half-angle asin(0.5 / |o_j|): 30 degrees for faces, 20.7 for edges, 16.8 for
 * corners): stochastic rejection sampling, each neighbour sampled on its own, with a fixed
 * seed, so every machine gets the same bits. kappa is found by golden-section search over
 * an interval ([0.1, 0.4]) so that one step out of a cell conserves the energy of random
 * distributions (a clamped-cosine lobe of random direction and weight plus isotropic
 * light); without sampling error it is 1 / sqrt(26 pi / 4) = 0.2213 (every G_j0 is then
 * 1 / sqrt(26)). gamma_j = G_j0 / sum_k G_k0 are the outscattering fractions. b_j is 1 when
 * the blockers (lpv_geometry.h) mark the segment to neighbour j, else 0: the thesis's fuzzy
 * blocking clamp(<B|G_j>, 0, 1) read from a lattice of surface normals would need a second
 * geometry lattice, and the segment test is what both transports share.
 *
 * The scattered share gamma_j l_s <L|1> multiplies G_j as printed (listing 5.2), so the
 * scattered light arriving carries <G_j|1> = 2 sqrt(pi) G_j0 = 0.695 of what was scattered:
 * the thesis loses about 30% of all scattered light per step; `paper` keeps that. The clamp
 * at 0 (the listings' max) makes the step non-linear: light behind a strongly directional
 * distribution is dropped, not sent as negative light, and energy is then gained (a pure
 * clamped-cosine lobe: docs/lpv.md). Absorption and scattering are probabilities per metre
 * normalized to one step of the mean neighbour distance (lpv_paper_step_probability()).
 * Not here: the step itself (lpv_propagate.h), the frame (lpv_paper_frame.h). */
#ifndef CAVELIGHT_LPV_PAPER_H
#define CAVELIGHT_LPV_PAPER_H

#include <stddef.h>
#include <stdint.h>

#include "gi/ilpv/lpv_transfer.h"

/* Mean distance to the 26 neighbours in cells: (6 + 12 sqrt 2 + 8 sqrt 3) / 26. */
#define LPV_MEAN_NEIGHBOUR_DISTANCE 1.4164218f

/* Zero means default for every field. */
typedef struct lpv_paper_desc {
    int samples_per_neighbour;   /* accepted samples per neighbour: 0 = 1 << 16 */
    uint64_t seed;               /* 0 = LPV_PAPER_DEFAULT_SEED */
    double search_lo, search_hi; /* golden-section interval: 0, 0 = [0.1, 0.4] */
    double tolerance;            /* relative interval width that ends the search: 0 = 1e-6 */
} lpv_paper_desc;

#define LPV_PAPER_DEFAULT_SEED 0x6361766531696768ull

typedef struct lpv_paper_transfer {
    float gamma[LPV_NEIGHBOURS][4];    /* G_j, scaled */
    float outscatter[LPV_NEIGHBOURS];  /* gamma_j */
    double kappa;                      /* the scale the search found */
    double energy_error;               /* mean relative |energy change| of one step over the
                                          search's distributions, with the stored floats */
    double imbalance;                  /* |sum_j G_j0 (G_j1, G_j2, G_j3)| / sum_j G_j0^2: the
                                          sampling error that keeps energy from balancing */
    int search_probes;                 /* factors the search evaluated */
} lpv_paper_transfer;

/* Returns 0, or -1 (out untouched) for a bad interval or tolerance, or when a neighbour's
 * cone accepts too few samples. Takes about 0.1 s with the default samples. */
int lpv_paper_transfer_compute(const lpv_paper_desc *desc, lpv_paper_transfer *out);

/* The transfer of the default desc, computed once per process (thread-safe). */
const lpv_paper_transfer *lpv_paper_transfer_default(void);

/* Probability of an event over one step of the mean neighbour distance,
 * LPV_MEAN_NEIGHBOUR_DISTANCE * cell metres, for a per-metre probability sigma in [0,1]:
 * 1 - (1 - sigma)^(d_mean cell), the form of lpv_transfer_step_probability() (the thesis
 * prints sigma^(d_mean), which tends to 1, everything absorbed, as cells shrink). */
float lpv_paper_step_probability(float sigma_per_metre, float cell);

/* The GL shader's body (node/gi/ilpv/paper_propagate.comp's @BODY@ line): 26 gather() calls
 * with the offsets, transfer vectors and outscattering fractions as constants. Returns the
 * length written, or 0 when n is too small. */
size_t lpv_paper_shader_body(const lpv_paper_transfer *t, char *out, size_t n);

#endif
