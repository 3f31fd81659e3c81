/* gi_budget: see gi_budget.h. */
#include "gi/gi_budget.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/xalloc.h"
#include "gi/gi_settings.h"

struct gi_budget_plan {
    const gi_budget_rule *rule;
    void *state;
};

static const gi_budget_rule *rule_of(const frame_params *p)
{
    const gi_method_settings *m = gi_method_at(p->gi);
    return m ? m->budget : NULL;
}

const char *gi_budget_check(const frame_params *p, int (*given)(void *ctx, const char *name),
                            void *ctx)
{
    static _Thread_local char why[256];
    const gi_budget_rule *rule = rule_of(p);
    if (!rule) {
        int n = snprintf(why, sizeof why, "--budget-ms: --gi %s has no budget rule; it needs --gi",
                         gi_method_at(p->gi) ? gi_method_at(p->gi)->name : "?");
        const char *sep = " ";
        for (int m = 0; m < gi_method_count() && n > 0 && (size_t)n < sizeof why; m++)
            if (gi_method_at(m)->budget) {
                n += snprintf(why + n, sizeof why - (size_t)n, "%s%s", sep, gi_method_at(m)->name);
                sep = "|";
            }
        return why;
    }
    for (const char *const *name = rule->chooses; *name; name++)
        if (given(ctx, *name)) {
            snprintf(why, sizeof why, "--budget-ms chooses --%s: give either the budget or it",
                     *name);
            return why;
        }
    return NULL;
}

gi_budget_plan *gi_budget_plan_create(const frame_params *base, const float bounds_min[3],
                                      const float bounds_max[3])
{
    gi_budget_plan *plan = xcalloc(1, sizeof *plan);
    plan->rule = rule_of(base);
    plan->state = xcalloc(1, plan->rule->plan_size);
    plan->rule->plan_init(plan->state, base, bounds_min, bounds_max);
    return plan;
}

void gi_budget_plan_destroy(gi_budget_plan *plan)
{
    if (!plan)
        return;
    free(plan->state);
    free(plan);
}

int gi_budget_plan_frames(const gi_budget_plan *plan) { return plan->rule->frames; }

void gi_budget_plan_frame(const gi_budget_plan *plan, int i, frame_params *out)
{
    plan->rule->plan_frame(plan->state, i, out);
}

void gi_budget_plan_record(gi_budget_plan *plan, int i, double frame_ms)
{
    plan->rule->plan_record(plan->state, i, frame_ms);
}

int gi_budget_plan_choose(const gi_budget_plan *plan, double budget_ms, frame_params *fp,
                          gi_budget_choice *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    return plan->rule->choose(plan->state, budget_ms, fp, out, err, errlen);
}
