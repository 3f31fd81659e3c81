/* lpv_paper_frame: the thesis's incremental LPV frame (papers/incremental-lpv-cave.txt,
 * section 3.4 and listing 5.1) on the `paper` transport (lpv_paper.h), the CPU side.
 *
 * Per frame: clear and fill the injection (lpv_inject.h), then lpv_paper_frame() merges
 *   L = a P + b I ,  a = (E_now / E_prev) lambda_incr ,  b = 1 - lambda_incr
 * (P the last frame's result, I this frame's injection, E the lights' emitted energy from
 * their parameters) and propagates L `steps` steps, blocking off in the first one (the
 * thesis's rule: a fresh injection must not block itself). The field after the last step
 * is both what is rendered and next frame's P: no accumulation, so with energy-conserving
 * steps the lattice holds the injected energy, spread over the geometric mixture of ages
 * (1 - lambda) sum_k lambda^k T^(S(k+1)) I at the steady state. lambda_incr is taken as 0
 * (a = 0, b = 1: no history, the history volume not even read) on the first frame, after
 * lpv_paper_reset(), when E_prev is 0 and when E_now is negative or not finite.
 * lambda_incr = 0 every frame is the thesis's plain (classic) LPV: S steps of the fresh
 * injection. lambda_incr's range [0, 1) is the caller's (frame_params_sanitize()).
 * lpv_paper_merge_factors() and lpv_paper_history_advance() are the rule, once, for this
 * core and a GL path (which runs the merge with node/gi/ilpv/accumulate.comp and the steps
 * with node/gi/ilpv/paper_propagate.comp). Deterministic: the same bits for any thread count. */
#ifndef CAVELIGHT_LPV_PAPER_FRAME_H
#define CAVELIGHT_LPV_PAPER_FRAME_H

#include "gi/ilpv/lattice.h"
#include "gi/ilpv/lpv_propagate.h"
#include "gi/ilpv/lpv_volume.h"

typedef struct lpv_paper_history {
    int have_history;
    double previous_energy; /* E of the last frame; 0 when it could not be trusted */
} lpv_paper_history;

/* L = a P + b I. a = 0: P is not read. */
typedef struct lpv_paper_merge {
    float a, b;
} lpv_paper_merge;

typedef struct lpv_paper_lpv {
    lattice_desc lattice;
    lpv_volume injected;  /* this frame's VPLs */
    lpv_volume volume[2]; /* merge target and propagation ping-pong */
    int current;          /* index of the volume holding the result */
    lpv_paper_history history;
} lpv_paper_lpv;

typedef struct lpv_paper_frame_desc {
    int steps;                    /* propagation steps this frame, >= 0 */
    float lambda_incr;            /* [0,1): share of the last frame's light kept */
    double emitted_energy;        /* E of this frame's lights, from their parameters */
    lpv_propagate_desc propagate; /* paper transfer, blockers, absorption and scattering per
                                     step (lpv_paper_step_probability()), pool; the
                                     transport is paper whatever it says, accum unused */
} lpv_paper_frame_desc;

/* This frame's merge from the history, lambda_incr and E_now. */
lpv_paper_merge lpv_paper_merge_factors(const lpv_paper_history *h, float lambda_incr,
                                        double emitted_energy);
/* Records E_now after a frame. */
void lpv_paper_history_advance(lpv_paper_history *h, double emitted_energy);
/* out = m.a history + m.b injected; out may be history. Same shapes, 12 channels. */
void lpv_paper_merge_run(lpv_paper_merge m, const lpv_volume *history,
                         const lpv_volume *injected, lpv_volume *out, workpool *pool);

/* Bytes of the volumes lpv_paper_init() allocates for this lattice (a GL path holds as
 * many textures). */
double lpv_paper_state_bytes(const lattice_desc *lat);
/* Returns 0, or -1 for a bad lattice or no memory. */
int lpv_paper_init(lpv_paper_lpv *s, const lattice_desc *lat);
void lpv_paper_free(lpv_paper_lpv *s);
void lpv_paper_reset(lpv_paper_lpv *s);            /* forget the history */
lpv_volume *lpv_paper_injection(lpv_paper_lpv *s); /* cleared by lpv_paper_begin_frame() */
void lpv_paper_begin_frame(lpv_paper_lpv *s);
void lpv_paper_frame(lpv_paper_lpv *s, const lpv_paper_frame_desc *desc);
const lpv_volume *lpv_paper_result(const lpv_paper_lpv *s);

#endif
