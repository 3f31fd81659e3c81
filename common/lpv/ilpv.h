/* ilpv: incremental light propagation volumes (paper section 3.4).
 *
 * One ilpv owns the injection volume and two light volumes (source and destination of
 * propagation); after a frame, ilpv_result() is both what is rendered and next frame's
 * history. Per frame: clear and fill the injection volume (ilpv_injection()), then
 * ilpv_frame() merges L = a * history + (1 - lambda) * injected with
 * a = (E_now / E_prev) * lambda, and propagates `steps` steps (blocking off in the first).
 * lambda is forced to 0 on the first frame, after ilpv_reset(), when E_prev is 0 and when
 * E_now is negative or not finite. */
#ifndef CAVELIGHT_ILPV_H
#define CAVELIGHT_ILPV_H

#include "lpv/lattice.h"
#include "lpv/lpv_propagate.h"
#include "lpv/lpv_volume.h"

typedef struct ilpv {
    lattice_desc lattice;
    lpv_volume injected;
    lpv_volume volume[2];
    int current;            /* index of the volume holding the latest result */
    int have_history;
    double previous_energy;
} ilpv;

typedef struct ilpv_frame_desc {
    int steps;                 /* propagation steps this frame, >= 0 */
    float lambda_incr;         /* [0,1): share of last frame's light kept */
    double emitted_energy;     /* E of this frame's lights, from their parameters */
    lpv_propagate_desc propagate; /* transfer, geometry, absorption, scattering, pool */
} ilpv_frame_desc;

int ilpv_init(ilpv *s, const lattice_desc *lat);
void ilpv_free(ilpv *s);
void ilpv_reset(ilpv *s);                 /* forget the history */
lpv_volume *ilpv_injection(ilpv *s);      /* cleared by ilpv_begin_frame() */
void ilpv_begin_frame(ilpv *s);
void ilpv_frame(ilpv *s, const ilpv_frame_desc *desc);
const lpv_volume *ilpv_result(const ilpv *s);

#endif
