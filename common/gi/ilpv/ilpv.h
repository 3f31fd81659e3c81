/* ilpv: incremental light propagation volumes: the steady indirect field, a few
 * propagation steps per frame.
 *
 * The field to render is the light of every age at once, near + sum over s >= 0 of
 * T^s shell: lpv_splat.h gives the first cells of the injection in closed form (near) and
 * the light leaving them (shell), T is one propagation step (lpv_propagate.h). A chain
 * builds that sum over frames: it starts with sum = near + shell and front = shell, and
 * every step sets front <- T front, sum += front, so after k steps the sum holds the ages
 * 0 .. k; it converges to the whole field as the front's light leaves or is absorbed (after
 * about as many steps as light survives in the scene), whatever the steps per frame, and
 * then stops changing. T is not linear, so this is not the fixed point of
 * X <- shell + T X (that iteration need not converge): each age is propagated alone, as
 * the classic LPV does within one frame (lpv_classic.h).
 *
 * A chain restarts when this frame's injection differs from the last one's (a light
 * moved, turned, changed, the absorption or scattering changed: lpv_volume_checksum() of
 * the injected light and its origins, with the step probabilities), and every frame when
 * lambda_incr is 0 (no temporal reuse: the classic sum of `steps` steps). The far part of
 * the light shown before then stands in for the new chain's far ages until they arrive: at
 * a restart
 *   faded = (E_now / E_prev) x (the last result - early)   (E: the lights' emitted energy)
 * with early the old chain's sum after its first frame (its near field and first `steps`
 * ages, which the new chain has from its first frame on), and every frame shows
 * result = sum + w faded, with
 *   w = lambda_incr^k (1 - (<sum|1> - <early|1>) / <faded|1>)  (the bracket clamped to [0, 1]),
 * k the frames since the restart, early now the new chain's: the old far light fills in
 * what the new chain has not reached yet, in proportion to the energy still missing. So the
 * picture keeps its level and shape while a light moves (a restart every frame: the near
 * field follows the light, the far field stays as it was when the motion began), and the
 * old light fades at least as fast as lambda_incr^k once the lights stop -- also when the
 * energy ratio misjudges its level (one of two lights changed), so nothing of it stays for
 * good. No history (faded = 0) on the first frame, after
 * ilpv_reset(), with lambda_incr = 0, and when E_prev is 0 or E_now is negative or not
 * finite. lambda_incr's range [0,1) is the caller's (frame_params_sanitize()).
 *
 * Classic mode (Kaplanyan & Dachsbacher 2010, the baseline the incremental scheme is
 * measured against) starts a new chain from this frame's splat every frame and shows its
 * sum after `steps` steps, no history: near + shell + T shell + ... + T^steps shell.
 *
 * One driver for both modes and every backend: the sequence of a frame (the rule, the
 * fade, the splat, the chain's steps, the composition) is ilpv_frame(), once. A backend
 * (ilpv_backend) holds the chain's front and sum where its steps run and does them: the CPU
 * one here (ilpv_cpu_backend(), lpv_propagate.h on a workpool), the GL one in
 * node/gi/ilpv/. The injection, splat, history and composition stay on the host, so every
 * backend shows a result composed by the same code. */
#ifndef CAVELIGHT_ILPV_H
#define CAVELIGHT_ILPV_H

#include <stdint.h>

#include "base/workpool.h"
#include "gi/ilpv/lattice.h"
#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_splat.h"
#include "gi/ilpv/lpv_volume.h"

/* What the rule needs to know of the frames before. */
typedef struct ilpv_history {
    int have_history;
    double previous_energy; /* emitted energy of the last frame */
    uint64_t key;           /* of the last frame's injection (ilpv_injection_key()) */
    unsigned chain_steps;   /* steps since the chain started (lpv_propagate_desc.step) */
    unsigned chain_frames;  /* frames since the chain started */
    double faded_energy;    /* <faded|1>, all colours */
    double early_energy;    /* <early|1>, all colours */
    double sum_energy;      /* <sum|1> after the last frame */
    double pending;         /* share of the result the next frames may still change */
} ilpv_history;

typedef struct ilpv_rule {
    int restart;  /* start a new chain from this frame's splat */
    float keep;   /* at a restart, faded = keep x the last result (0: nothing kept) */
} ilpv_rule;

/* Where a chain is propagated. Every call gets the backend's own state. */
typedef struct ilpv_backend {
    void *state;
    /* A new chain: front = shell, sum = near + shell. */
    void (*start)(void *state, const lpv_volume *near, const lpv_volume *shell);
    /* steps steps of the chain (lpv_propagate_step(), step indices first, first + 1, ...):
     * front <- T front, sum += front. absorption, scattering: per step. */
    void (*steps)(void *state, int steps, unsigned first, float absorption, float scattering);
    /* The chain's sum on the host (the GL backend reads it back). */
    const lpv_volume *(*sum)(void *state);
    void (*destroy)(void *state); /* may be NULL: the state is the caller's */
} ilpv_backend;

typedef struct ilpv {
    lattice_desc lattice;
    const lpv_blockers *blockers; /* the splat's (the backend has them too) */
    workpool *pool;
    lpv_volume injected, origin; /* this frame's VPLs (lpv_inject.h) */
    lpv_volume near, shell;      /* lpv_splat.h */
    lpv_volume early;            /* the sum after the chain's first frame */
    lpv_volume faded;            /* the light shown when the chain started */
    lpv_volume result;           /* sum + w faded (classic: the sum) */
    lpv_splat splat;
    ilpv_history history;
    ilpv_backend backend;
} ilpv;

typedef struct ilpv_frame_desc {
    int steps;                 /* propagation steps this frame, >= 0 */
    float lambda_incr;         /* [0,1): share of the earlier light kept per frame */
    double emitted_energy;     /* E of this frame's lights, from their parameters */
    int classic;               /* 1: classic LPV, this frame's chain alone */
    float absorption, scattering; /* per step (lpv_transfer_step_probability()) */
} ilpv_frame_desc;

typedef struct ilpv_desc {
    const lattice_desc *lattice;
    const lpv_blockers *blockers; /* what blocks light (lpv_geometry.h); NULL: nothing. The
                                     backend must hold the same ones */
    workpool *pool;               /* the splat's threads; NULL: the calling thread */
    const ilpv_backend *backend;  /* where the chain runs; NULL: a CPU backend of its own
                                     with these blockers and pool */
} ilpv_desc;

/* Returns 0, or -1 (nothing to free) for a bad lattice or no memory; the backend is then
 * destroyed. */
int ilpv_init(ilpv *s, const ilpv_desc *desc);
/* The bytes a lattice's driver and a backend's chain take (what the method's memory
 * limit counts, gi_cost.h). */
double ilpv_state_bytes(const lattice_desc *lat);
void ilpv_free(ilpv *s);
void ilpv_reset(ilpv *s);                 /* forget the history */
lpv_volume *ilpv_injection(ilpv *s);      /* cleared by ilpv_begin_frame() */
lpv_volume *ilpv_origin(ilpv *s);         /* cleared by ilpv_begin_frame() */
void ilpv_begin_frame(ilpv *s);
/* Returns 0, or -1 when the splat ran out of memory (the frame then shows its history). */
int ilpv_frame(ilpv *s, const ilpv_frame_desc *desc);
const lpv_volume *ilpv_result(const ilpv *s);
/* The chain's sum (its backend's). */
const lpv_volume *ilpv_sum(ilpv *s);

/* The CPU backend: the chain's front and sum in host memory, propagated by
 * lpv_propagate_step() with these blockers (NULL: none) on this pool (NULL: the calling
 * thread). NULL when out of memory. */
typedef struct ilpv_cpu ilpv_cpu;
ilpv_cpu *ilpv_cpu_create(const lattice_desc *lat, const lpv_blockers *blockers, workpool *pool);
ilpv_backend ilpv_cpu_backend(ilpv_cpu *c);

/* The injection's key: what a chain depends on (the injected light and its origins, the
 * absorption and scattering per step). */
uint64_t ilpv_injection_key(const lpv_volume *injected, const lpv_volume *origin,
                            float absorption, float scattering);
/* This frame's rule from the history, lambda_incr, the injection's key and the lights'
 * emitted energy; ilpv_history_advance() records the frame. */
ilpv_rule ilpv_history_rule(const ilpv_history *h, float lambda_incr, uint64_t key,
                            double emitted_energy);
/* After a frame of `steps` steps under rule r, faded holding faded_energy. */
void ilpv_history_advance(ilpv_history *h, ilpv_rule r, int steps, uint64_t key,
                          double emitted_energy, double faded_energy);
/* w of this frame, from the history (after ilpv_history_advance()), lambda_incr and the
 * energy the chain's sum holds beyond its early sum (<sum|1> - <early|1>, all colours). */
float ilpv_faded_weight(const ilpv_history *h, float lambda_incr, double sum_energy);
/* After the frame's result: records the sum's energy and the pending share, what this
 * frame's steps added plus the faded light still shown, over the result's energy (with
 * lambda_incr 0 only the faded light: the next frame computes the same chain again). */
void ilpv_history_settle(ilpv_history *h, ilpv_rule r, float lambda_incr, double sum_energy,
                         float w);
/* The pending share of the last frame (lpv_converge_end()); 0 in classic mode. */
double ilpv_pending(const ilpv *s);

#endif
