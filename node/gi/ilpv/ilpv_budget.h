/* ilpv_budget: --budget-ms for the ILPV: the costs of its candidate lattices measured on
 * this machine and GL context (one propagation step, and the rest of a frame's LPV work),
 * and the lattice and steps lpv_budget_choose() takes from them. A cluster measures every
 * node and chooses once from the slowest node's costs (the master). Not here: the rule
 * itself (lpv/lpv_budget.h). */
#ifndef CAVELIGHT_ILPV_BUDGET_H
#define CAVELIGHT_ILPV_BUDGET_H

#include <stddef.h>

#include "lpv/lpv_budget.h"
#include "renderer.h"

enum { ILPV_BUDGET_CANDIDATES = 5 }; /* lattices of 16, 24, 32, 48 and 64 cells */

/* Each candidate lattice with base's context and scene and fp's other settings: one step
 * and the frame's LPV work besides the steps (a frame of 0 steps), each the median of three
 * tries (what a frame meets on a shared machine, not its luckiest moment). Returns 0, or
 * -1 with one line in err. */
int ilpv_budget_measure(const renderer_desc *base, const frame_params *fp,
                        lpv_budget_candidate out[ILPV_BUDGET_CANDIDATES], char *err,
                        size_t errlen);
/* The choice within budget_ms for these costs (the incremental or classic mode's steps,
 * from fp), written into fp's lattice and steps. Returns 0, or -1 when nothing can be
 * chosen. */
int ilpv_budget_apply(double budget_ms, const lpv_budget_candidate *cand, int count,
                      frame_params *fp, lpv_budget_choice *choice);

#endif
