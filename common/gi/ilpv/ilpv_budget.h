/* ilpv_budget: --budget-ms for the ILPV. A plan of frames measures each candidate lattice
 * (16, 24, 32, 48 and 64 cells along the scene's longest axis): frames of 0 steps and of
 * ILPV_BUDGET_STEPS steps, alternating, after one frame that pays for building it; their
 * frame-pass times (RSM and GI, host ms) give each candidate's cost per frame besides the
 * steps and per step, and lpv_budget_choose() takes the lattice and steps from those costs.
 *
 * The same plan runs on a standalone node's renderer and, through the master, on every
 * node of a cluster, where each frame counts at its slowest node: one choice for the whole
 * wall. No GL. Not here: the rule (gi/ilpv/lpv_budget.h); running the frames (through
 * gi_budget.h: node/standalone.c, master/session.c). */
#ifndef CAVELIGHT_ILPV_BUDGET_H
#define CAVELIGHT_ILPV_BUDGET_H

#include <stddef.h>

#include "frame/frame_params.h"
#include "gi/gi_budget.h"
#include "gi/ilpv/lpv_budget.h"

enum {
    ILPV_BUDGET_CANDIDATES = 5,
    ILPV_BUDGET_TRIES = 3,   /* medians of three: what a frame meets on a shared machine */
    ILPV_BUDGET_STEPS = 4,   /* steps of a measuring frame: one step alone is lost in noise */
    ILPV_BUDGET_FRAMES_EACH = 1 + 2 * ILPV_BUDGET_TRIES,
    ILPV_BUDGET_FRAMES = ILPV_BUDGET_CANDIDATES * ILPV_BUDGET_FRAMES_EACH,
};

typedef struct ilpv_budget_plan {
    frame_params base;                      /* the session's settings */
    float bounds_min[3], bounds_max[3];     /* the scene's */
    double ms[ILPV_BUDGET_FRAMES];          /* each measuring frame's frame pass */
} ilpv_budget_plan;

void ilpv_budget_plan_init(ilpv_budget_plan *p, const frame_params *base, const float bounds_min[3],
                           const float bounds_max[3]);
/* Measuring frame i (0 <= i < ILPV_BUDGET_FRAMES): base with the ILPV on candidate i's
 * lattice, its steps, and no frame skipped for convergence. */
void ilpv_budget_plan_frame(const ilpv_budget_plan *p, int i, frame_params *out);
/* Frame i's frame-pass ms (a cluster's: the slowest node's). */
void ilpv_budget_plan_record(ilpv_budget_plan *p, int i, double frame_ms);
/* The candidates' costs from the recorded frames. Returns 0, or -1 with one line in err
 * (the scene gives no lattice). */
int ilpv_budget_plan_costs(const ilpv_budget_plan *p, lpv_budget_candidate out[ILPV_BUDGET_CANDIDATES],
                           char *err, size_t errlen);
/* The plan above as the method's --budget-ms rule (gi_budget.h): it chooses lattice,
 * lattice-cells and steps. */
extern const gi_budget_rule ilpv_budget_rule;
/* The choice within budget_ms for these costs (the incremental or classic mode's steps,
 * from fp), written into fp's lattice and steps. Returns 0, or -1 when nothing can be
 * chosen. */
int ilpv_budget_apply(double budget_ms, const lpv_budget_candidate *cand, int count,
                      frame_params *fp, lpv_budget_choice *choice);

#endif
