/* ilpv: incremental light propagation volumes (paper section 3.4).
 *
 * One ilpv owns the injection volume and two light volumes (source and destination of
 * propagation); after a frame, ilpv_result() is both what is rendered and next frame's
 * history. Per frame: clear and fill the injection volume (ilpv_injection()), then
 * ilpv_frame() merges L = a * history + (1 - lambda) * injected with
 * a = (E_now / E_prev) * lambda, and propagates `steps` steps (blocking off in the first).
 * ilpv_merge_factors() is that rule, once, for this core and for the GL path
 * (node/renderer_lpv.c): lambda is taken as 0 on the first frame, after ilpv_reset(), when
 * E_prev is 0 and when E_now is negative or not finite. lambda's range [0,1) is the
 * caller's (frame_params_sanitize()); 1 would freeze the history. */
#ifndef CAVELIGHT_ILPV_H
#define CAVELIGHT_ILPV_H

#include "lpv/lattice.h"
#include "lpv/lpv_propagate.h"
#include "lpv/lpv_volume.h"

/* What the merge needs to know of the frames before: whether there is a history and the
 * emitted energy it was made with. */
typedef struct ilpv_history {
    int have_history;
    double previous_energy;
} ilpv_history;

/* L = a * history + b * injected; with_history 0: L = b * injected, the history unread. */
typedef struct ilpv_merge {
    float a, b;
    int with_history;
} ilpv_merge;

typedef struct ilpv {
    lattice_desc lattice;
    lpv_volume injected;
    lpv_volume volume[2];
    int current;            /* index of the volume holding the latest result */
    ilpv_history history;
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

/* This frame's merge factors from the history and the lights' emitted energy. */
ilpv_merge ilpv_merge_factors(const ilpv_history *h, float lambda_incr, double emitted_energy);
/* After a merge: the history now exists and was made with emitted_energy. */
void ilpv_history_advance(ilpv_history *h, double emitted_energy);

#endif
