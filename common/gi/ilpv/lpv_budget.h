/* lpv_budget: pick the lattice resolution and steps per frame that fit an LPV budget in
 * milliseconds per frame, from measured costs.
 *
 * A candidate's frame costs fixed_ms (injection, merge, upload, checksum: work that does
 * not depend on the steps) plus steps * step_ms. Rule: take the finest candidate whose
 * min_steps steps fit the budget, and give it as many steps as fit, at most max_steps.
 * When not even the coarsest fits min_steps, take the coarsest with as many steps as fit,
 * at least 1, and say it does not fit. Defaults
 * (incremental LPV, paper section 3.4): min 4 steps (4 give good results with history),
 * max 8 (8 steps with lambda 0.8 match 32 classic steps; latency hardly differs between 4
 * and 8). Classic LPV has no history and needs more: callers pass e.g. 8 and 16. */
#ifndef CAVELIGHT_LPV_BUDGET_H
#define CAVELIGHT_LPV_BUDGET_H

#include <stddef.h>

typedef struct lpv_budget_candidate {
    int axis_cells;   /* cells along the longest axis (renderer_desc.lattice_cells) */
    size_t cells;     /* cells of the fitted lattice */
    double step_ms;   /* cost of one propagation step, > 0 */
    double fixed_ms;  /* cost per frame besides the steps, >= 0 */
} lpv_budget_candidate;

typedef struct lpv_budget_desc {
    double budget_ms;                      /* > 0 */
    const lpv_budget_candidate *candidates; /* any order */
    int count;
    int min_steps;                         /* 0 = 4 */
    int max_steps;                         /* 0 = 8 */
} lpv_budget_desc;

typedef struct lpv_budget_choice {
    int index;           /* into candidates */
    int axis_cells;
    int steps;
    double predicted_ms; /* fixed_ms + steps * step_ms */
    int fits;            /* predicted_ms <= budget_ms with at least min_steps */
} lpv_budget_choice;

/* Returns 0, or -1 (choice untouched) without candidates, with a budget that is not a
 * positive number, or with a candidate whose step cost is not positive and finite or
 * whose fixed cost is negative or not finite. */
int lpv_budget_choose(const lpv_budget_desc *desc, lpv_budget_choice *out);

#endif
