/* ilpv: incremental light propagation volumes: the steady indirect field, a few
 * propagation steps per frame.
 *
 * The field to render is the light of every age at once: near + sum over s >= 0 of
 * T^s shell, where lpv_splat.h gives the first cells of this frame's injection in closed
 * form (near) and the light leaving them (shell), and T is one propagation step
 * (lpv_propagate.h). That sum is the fixed point of X <- shell + T X, which every step of
 * every frame iterates from the frame before's X (the history): the fixed point does not
 * depend on the steps per frame, and it is reached after about as many steps as light
 * survives in the scene (it leaves through or is absorbed by surfaces). Per frame:
 *   1. splat this frame's injection (ilpv_injection(), ilpv_origin(), lpv_inject.h);
 *   2. X <- a X, a = ilpv_merge_factors(): the history scaled by E_now / E_prev (the
 *      lights' emitted energy, from their parameters), and by lambda_incr as well when a
 *      light moved, so that light from where it was fades faster; no history (X = 0) on
 *      the first frame, after ilpv_reset(), with lambda_incr = 0, and when E_prev is 0 or
 *      E_now is negative or not finite;
 *   3. `steps` times X <- shell + T X;
 *   4. result = near + X (ilpv_result()).
 * ilpv_merge_factors() is that rule, once, for this core and for the GL path
 * (node/renderer_lpv.c). lambda_incr's range [0,1) is the caller's (frame_params_sanitize()). */
#ifndef CAVELIGHT_ILPV_H
#define CAVELIGHT_ILPV_H

#include "lpv/lattice.h"
#include "lpv/lpv_propagate.h"
#include "lpv/lpv_splat.h"
#include "lpv/lpv_volume.h"

/* What the merge needs to know of the frames before. */
typedef struct ilpv_history {
    int have_history;
    double previous_energy; /* emitted energy the history was made with */
    unsigned steps;         /* steps since the history started (lpv_propagate_desc.step) */
} ilpv_history;

/* X <- a X; with_history 0: X <- 0, the history unread (it may hold anything). */
typedef struct ilpv_merge {
    float a;
    int with_history;
} ilpv_merge;

typedef struct ilpv {
    lattice_desc lattice;
    lpv_volume injected, origin; /* this frame's VPLs (lpv_inject.h) */
    lpv_volume near, shell;      /* lpv_splat.h */
    lpv_volume volume[2];        /* X, ping-pong */
    lpv_volume result;           /* near + X */
    lpv_splat splat;
    int current;                 /* index of the volume holding X */
    ilpv_history history;
} ilpv;

typedef struct ilpv_frame_desc {
    int steps;                 /* propagation steps this frame, >= 0 */
    float lambda_incr;         /* [0,1): history kept when a light moved; 0 = no history */
    int lights_moved;          /* a light's position, direction or cone changed */
    double emitted_energy;     /* E of this frame's lights, from their parameters */
    lpv_propagate_desc propagate; /* blockers, absorption, scattering, pool (source and
                                     step are the frame's) */
} ilpv_frame_desc;

int ilpv_init(ilpv *s, const lattice_desc *lat);
void ilpv_free(ilpv *s);
void ilpv_reset(ilpv *s);                 /* forget the history */
lpv_volume *ilpv_injection(ilpv *s);      /* cleared by ilpv_begin_frame() */
lpv_volume *ilpv_origin(ilpv *s);         /* cleared by ilpv_begin_frame() */
void ilpv_begin_frame(ilpv *s);
/* Returns 0, or -1 when the splat ran out of memory (the frame is then black). */
int ilpv_frame(ilpv *s, const ilpv_frame_desc *desc);
const lpv_volume *ilpv_result(const ilpv *s);

/* This frame's merge factor from the history, lambda_incr, whether a light moved and the
 * lights' emitted energy. */
ilpv_merge ilpv_merge_factors(const ilpv_history *h, float lambda_incr, int lights_moved,
                              double emitted_energy);
/* After a frame of `steps` steps merged with m: the history exists and was made with
 * emitted_energy. */
void ilpv_history_advance(ilpv_history *h, ilpv_merge m, int steps, double emitted_energy);

#endif
