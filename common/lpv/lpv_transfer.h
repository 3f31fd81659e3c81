/* lpv_transfer: the 26 neighbour transfer vectors, their energy scale and the
 * outscattering fractions, plus the normalization of absorption and scattering.
 *
 * Neighbour j has offset lpv_transfer_offsets[j] in {-1,0,1}^3 \ {0}, in a fixed order
 * used by every propagation path. Gamma_j is kappa times the mean clamped-cosine lobe
 * towards sample points drawn uniformly in neighbour cell j (rejection sampling against
 * a visibility cone, see the .c), with a fixed seed: identical on every machine.
 * Neighbours j and 25 - j are antipodal and get mirrored vectors. kappa is found by
 * golden-section search so that one unblocked, unabsorbed step conserves energy. */
#ifndef CAVELIGHT_LPV_TRANSFER_H
#define CAVELIGHT_LPV_TRANSFER_H

#include <stdint.h>

enum { LPV_NEIGHBOURS = 26 };

/* Mean distance to the 26 neighbours in cells: (6 + 12 sqrt 2 + 8 sqrt 3) / 26. */
#define LPV_MEAN_NEIGHBOUR_DISTANCE 1.4164218f

extern const int lpv_transfer_offsets[LPV_NEIGHBOURS][3];

typedef struct lpv_transfer_desc {
    int samples_per_neighbour; /* 0 = 4096 */
    uint64_t seed;             /* 0 = fixed default */
    double search_lo, search_hi; /* golden-section interval; 0,0 = [0.1, 0.4] */
    double tolerance;          /* 0 = 1e-6 */
} lpv_transfer_desc;

typedef struct lpv_transfer {
    float gamma[LPV_NEIGHBOURS][4];  /* scaled transfer vectors */
    float outscatter[LPV_NEIGHBOURS]; /* gamma_j = Gamma_j0 / sum_k Gamma_k0 */
    double kappa;                     /* scale found by the search */
    double energy_error;              /* relative energy error of one unblocked step */
    int search_probes;                /* factors probed by the search */
} lpv_transfer;

int lpv_transfer_compute(const lpv_transfer_desc *desc, lpv_transfer *out);

/* Probability of an event over one step of d_mean * cell metres, for a per-metre
 * probability sigma in [0,1]: 1 - (1 - sigma)^(d_mean * cell). Tends to 0 as the cell
 * shrinks and to 1 as sigma -> 1. NaN or out-of-range sigma is clamped to [0,1]. */
float lpv_transfer_step_probability(float sigma_per_metre, float cell);

#endif
