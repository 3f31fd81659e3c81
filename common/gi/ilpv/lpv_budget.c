#include "gi/ilpv/lpv_budget.h"

#include <math.h>

int lpv_budget_choose(const lpv_budget_desc *d, lpv_budget_choice *out)
{
    if (!d || !d->candidates || d->count < 1 || !(d->budget_ms > 0) || !isfinite(d->budget_ms))
        return -1;
    int min_steps = d->min_steps > 0 ? d->min_steps : 4;
    int max_steps = d->max_steps > 0 ? d->max_steps : 8;
    if (max_steps < min_steps)
        max_steps = min_steps;
    int finest = -1, coarsest = -1;
    for (int i = 0; i < d->count; i++) {
        const lpv_budget_candidate *c = &d->candidates[i];
        if (!(c->step_ms > 0) || !isfinite(c->step_ms) || !(c->fixed_ms >= 0) ||
            !isfinite(c->fixed_ms))
            return -1;
        if (coarsest < 0 || c->cells < d->candidates[coarsest].cells)
            coarsest = i;
        if (c->fixed_ms + min_steps * c->step_ms <= d->budget_ms &&
            (finest < 0 || c->cells > d->candidates[finest].cells))
            finest = i;
    }
    int pick = finest >= 0 ? finest : coarsest;
    const lpv_budget_candidate *c = &d->candidates[pick];
    double fit = floor((d->budget_ms - c->fixed_ms) / c->step_ms);
    int steps = fit > max_steps ? max_steps : fit < 1 ? 1 : (int)fit;
    *out = (lpv_budget_choice){
        .index = pick,
        .axis_cells = c->axis_cells,
        .steps = steps,
        .predicted_ms = c->fixed_ms + steps * c->step_ms,
        .fits = finest >= 0,
    };
    return 0;
}
