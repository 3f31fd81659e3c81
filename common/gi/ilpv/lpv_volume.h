/* lpv_volume: a light or geometry lattice stored as structure of arrays.
 *
 * A light volume has 12 channels (colour c in R,G,B times SH coefficient s in 0..3,
 * channel = 4*c + s); a geometry (blocking) volume has 4. Each channel is a float array
 * of nx*ny*nz values in lattice order, 64-byte aligned, so that the propagation's inner
 * loops run along x with aligned vector loads. Each channel has LPV_VOLUME_GUARD zero
 * floats before and after it (never written), so that vector loads a few cells past
 * either end stay in bounds. The caller owns the struct; init allocates, free releases,
 * nothing else allocates. */
#ifndef CAVELIGHT_LPV_VOLUME_H
#define CAVELIGHT_LPV_VOLUME_H

#include <stddef.h>
#include <stdint.h>
#include "gi/ilpv/lattice.h"

enum { LPV_LIGHT_CHANNELS = 12, LPV_GEOMETRY_CHANNELS = 4, LPV_MAX_CHANNELS = 12,
       LPV_VOLUME_GUARD = 64 };

typedef struct lpv_volume {
    int n[3];
    size_t cells;
    int channels;
    float *ch[LPV_MAX_CHANNELS];
} lpv_volume;

/* Returns 0, or -1 for bad sizes (any n < 1, channels not 4 or 12) or no memory. Zeroed. */
int lpv_volume_init(lpv_volume *v, const int n[3], int channels);
void lpv_volume_free(lpv_volume *v);
void lpv_volume_clear(lpv_volume *v);
void lpv_volume_copy(lpv_volume *dst, const lpv_volume *src); /* same shape required */
void lpv_volume_add(lpv_volume *dst, const lpv_volume *src);  /* dst += src, same shape */
void lpv_volume_add_scaled(lpv_volume *dst, const lpv_volume *src, float a); /* dst += a src */
/* dst += src over the cells of z in [z0, z1) (a propagation job's slab), same shape. */
void lpv_volume_add_slab(lpv_volume *dst, const lpv_volume *src, int z0, int z1);
void lpv_volume_scale(lpv_volume *v, float a);                /* v *= a */

/* Total energy per colour, <L|1> = 2 sqrt(pi) L0 summed over cells, in double. */
void lpv_volume_energy(const lpv_volume *v, double energy_rgb[3]);
/* 64-bit FNV-1a over the 32-bit words (raw float bits) of every channel, in lattice order,
 * one multiply per value: equal on two nodes exactly when their volumes are bit-identical. */
uint64_t lpv_volume_checksum(const lpv_volume *v);
/* Counts NaN and Inf values. */
size_t lpv_volume_count_nonfinite(const lpv_volume *v);

#endif
