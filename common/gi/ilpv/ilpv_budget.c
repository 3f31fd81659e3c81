/* ilpv_budget: see ilpv_budget.h. */
#include "gi/ilpv/ilpv_budget.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gi/ilpv/ilpv_settings.h"

static const int axes[ILPV_BUDGET_CANDIDATES] = {16, 24, 32, 48, 64};

void ilpv_budget_plan_init(ilpv_budget_plan *p, const frame_params *base, const float bounds_min[3],
                           const float bounds_max[3])
{
    memset(p, 0, sizeof *p);
    p->base = *base;
    memcpy(p->bounds_min, bounds_min, sizeof p->bounds_min);
    memcpy(p->bounds_max, bounds_max, sizeof p->bounds_max);
}

/* Within a candidate's frames: 0 builds it, then odd ones run 0 steps, even ones
 * ILPV_BUDGET_STEPS. */
static int steps_of(int j) { return j > 0 && j % 2 == 0 ? ILPV_BUDGET_STEPS : 0; }

void ilpv_budget_plan_frame(const ilpv_budget_plan *p, int i, frame_params *out)
{
    *out = p->base;
    gi_set(out, "gi", "ilpv");
    gi_set_number(out, "lattice", axes[i / ILPV_BUDGET_FRAMES_EACH]);
    gi_set(out, "lattice-cells", "0");
    gi_set_number(out, "converge-threshold", -1);
    out->lpv_steps = steps_of(i % ILPV_BUDGET_FRAMES_EACH);
}

void ilpv_budget_plan_record(ilpv_budget_plan *p, int i, double frame_ms)
{
    p->ms[i] = isfinite(frame_ms) && frame_ms > 0 ? frame_ms : 0;
}

static double median3(const double v[3])
{
    double a = fmin(v[0], v[1]), b = fmax(v[0], v[1]);
    return fmax(a, fmin(b, v[2]));
}

int ilpv_budget_plan_costs(const ilpv_budget_plan *p, lpv_budget_candidate out[ILPV_BUDGET_CANDIDATES],
                           char *err, size_t errlen)
{
    _Static_assert(ILPV_BUDGET_TRIES == 3, "median3 takes three tries");
    for (int k = 0; k < ILPV_BUDGET_CANDIDATES; k++) {
        const double *ms = p->ms + k * ILPV_BUDGET_FRAMES_EACH;
        double fixed[ILPV_BUDGET_TRIES], step[ILPV_BUDGET_TRIES];
        for (int t = 0; t < ILPV_BUDGET_TRIES; t++) {
            fixed[t] = ms[1 + 2 * t];
            step[t] = (ms[2 + 2 * t] - ms[1 + 2 * t]) / ILPV_BUDGET_STEPS;
        }
        frame_params f;
        ilpv_budget_plan_frame(p, k * ILPV_BUDGET_FRAMES_EACH, &f);
        ilpv_settings s;
        ilpv_settings_get(&f, &s);
        lattice_desc lat;
        if (ilpv_settings_lattice(&s, p->bounds_min, p->bounds_max, &lat, err, errlen) != 0)
            return -1;
        out[k] = (lpv_budget_candidate){
            .axis_cells = axes[k],
            .cells = lattice_cell_count(&lat),
            .step_ms = fmax(median3(step), 1e-6), /* a step is never free */
            .fixed_ms = median3(fixed),
        };
    }
    return 0;
}


int ilpv_budget_apply(double budget_ms, const lpv_budget_candidate *cand, int count,
                      frame_params *fp, lpv_budget_choice *choice)
{
    ilpv_settings s;
    ilpv_settings_get(fp, &s);
    int classic = s.mode == ILPV_MODE_CLASSIC;
    lpv_budget_desc bd = {.budget_ms = budget_ms, .candidates = cand, .count = count,
                          .min_steps = classic ? 8 : 4, .max_steps = classic ? 16 : 8};
    if (lpv_budget_choose(&bd, choice) != 0)
        return -1;
    gi_set_number(fp, "lattice", choice->axis_cells);
    gi_set(fp, "lattice-cells", "0");
    fp->lpv_steps = choice->steps;
    return 0;
}

static void rule_init(void *plan, const frame_params *base, const float bounds_min[3],
                      const float bounds_max[3])
{
    ilpv_budget_plan_init(plan, base, bounds_min, bounds_max);
}

static void rule_frame(const void *plan, int i, frame_params *out)
{
    ilpv_budget_plan_frame(plan, i, out);
}

static void rule_record(void *plan, int i, double frame_ms)
{
    ilpv_budget_plan_record(plan, i, frame_ms);
}

static int rule_choose(const void *plan, double budget_ms, frame_params *fp,
                       gi_budget_choice *out, char *err, size_t errlen)
{
    lpv_budget_candidate cand[ILPV_BUDGET_CANDIDATES];
    lpv_budget_choice c;
    if (ilpv_budget_plan_costs(plan, cand, err, errlen) != 0)
        return -1;
    if (ilpv_budget_apply(budget_ms, cand, ILPV_BUDGET_CANDIDATES, fp, &c) != 0) {
        snprintf(err, errlen, "no choice from the measured costs");
        return -1;
    }
    out->predicted_ms = c.predicted_ms;
    out->fits = c.fits;
    out->figure_count = 2;
    out->figure[0].name = "lattice_cells";
    out->figure[0].value = c.axis_cells;
    out->figure[1].name = "steps";
    out->figure[1].value = c.steps;
    snprintf(out->summary, sizeof out->summary, "lattice %d, %d step%s", c.axis_cells, c.steps,
             c.steps == 1 ? "" : "s");
    snprintf(out->detail, sizeof out->detail,
             "measured %.3g ms per step, %.3g ms per frame besides the steps",
             cand[c.index].step_ms, cand[c.index].fixed_ms);
    return 0;
}

static const char *const chosen[] = {"lattice", "lattice-cells", "steps", NULL};

const gi_budget_rule ilpv_budget_rule = {
    .chooses = chosen,
    .frames = ILPV_BUDGET_FRAMES,
    .plan_size = sizeof(ilpv_budget_plan),
    .plan_init = rule_init,
    .plan_frame = rule_frame,
    .plan_record = rule_record,
    .choose = rule_choose,
};
