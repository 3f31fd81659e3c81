/* val_select: which virtual area lights (VALs: RSM texels, each a Lambertian disk of its
 * texel's area, vpl_select.h's vpl) light the caches method's caches this frame, after the
 * high-res RSM paper's section 4 (bidirectional importance, summed-area tables, binary
 * search, 1/P weights). The host's copy of node/gi/caches/'s compute shaders, in the same
 * float operations and order, to test them against and to document them; the node runs
 * the shaders.
 *
 * Importance of texel j, two channels:
 *   view  q_v = Phi_j V_j, V_j = (1 / N_VS) sum_s cos_l cos_s / (A_j + pi r^2) over the view
 *         samples s (points the tracked head sees: equation 10, with the disk bound of the
 *         gather in place of the paper's clamp max(1, r^2), which is in metres);
 *   flux  q_f = Phi_j,
 * Phi the flux's three channels summed. Sampling density p_j = (q_v / Q_v + q_f / Q_f) / 2
 * (Q the channel's sum over all texels): the paper's importance with a flux half, so that a
 * lit texel no view sample sees can still be chosen (p_j > 0 wherever Phi_j > 0: unbiased),
 * the mixture vpl_select.h's view rule uses.
 *
 * Summed-area tables: the texels of all layers are columns (layer, x) of rows y; each
 * column's inclusive sums down its rows (one GPU invocation per column), then the
 * inclusive sums of the column totals (VAL_SAT_CHUNKS chunks summed in order, then the
 * chunks' offsets), both channels.
 *
 * Selection: slot i of n takes the texel whose interval of the mixed sums holds
 * T (i + u_i) / n (u_i = vpl_slot_random(seed, i, 0): a fixed jitter per slot, so a static
 * scene keeps its VALs), found by binary search over the column totals, then down the
 * column. Its weight 1 / (n p) = T / (n interval) scales its flux, not its area (the
 * paper's equation 14): each VAL's irradiance at a cache, Phi k(A, r), is then estimated
 * without bias by stratified importance sampling. (The vpl method scales the area too,
 * which bounds a rare VAL's spike near a receiver at the price of a bias.)
 * Plain maths on host arrays; no GL, no allocation. */
#ifndef CAVELIGHT_VAL_SELECT_H
#define CAVELIGHT_VAL_SELECT_H

#include <stddef.h>
#include <stdint.h>

#include "gi/vpl_source.h"

enum { VAL_SAT_CHUNKS = 256 };

/* The view term V_j of a VAL for nsamples view samples (6 floats each: point, unit normal
 * turned to the viewer). */
float val_view_term(const vpl *v, const float *samples, int nsamples);
/* Both channels of its importance into out[0] (view), out[1] (flux). */
void val_importance(const vpl *v, const float *samples, int nsamples, float out[2]);

/* In place: imp (2 floats per texel, texel (c, y) at 2 (c rows + y)) becomes each column's
 * inclusive sums; row (2 floats per column) the inclusive sums of the column totals. */
void val_sat_build(float *imp, int columns, int rows, float *row);

/* One pick: the texel and its weight 1 / (n p). */
typedef struct val_pick {
    int column, row;
    float weight;
} val_pick;

/* n slots from the tables; returns n, or 0 when nothing is lit (Q_f = 0). */
int val_sat_select(const float *sums, const float *row, int columns, int rows, int n,
                   uint32_t seed, val_pick *out);
/* FNV-1a continued from h over n 32-bit words (ints, or floats' bits), each word's bytes
 * from the lowest: the same on every host. */
uint64_t val_hash_words(uint64_t h, const void *words, size_t n);
/* val_hash_words() over the picks (column, row, weight bits): what READY carries. */
uint64_t val_pick_checksum(const val_pick *p, int n, uint64_t h);

#endif
