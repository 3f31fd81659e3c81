/* ilpv_budget: see ilpv_budget.h. */
#include "gi/ilpv/ilpv_budget.h"

#include <math.h>
#include <stdio.h>

#include "gi/ilpv/gi_ilpv.h"
#include "lpv/lattice.h"

static const int axes[ILPV_BUDGET_CANDIDATES] = {16, 24, 32, 48, 64};

static double median3(double v[3])
{
    double a = fmin(v[0], v[1]), b = fmax(v[0], v[1]);
    return fmax(a, fmin(b, v[2]));
}

int ilpv_budget_measure(const renderer_desc *base, const frame_params *fp,
                        lpv_budget_candidate out[ILPV_BUDGET_CANDIDATES], char *err,
                        size_t errlen)
{
    for (int k = 0; k < ILPV_BUDGET_CANDIDATES; k++) {
        frame_params none = *fp;
        none.lpv_steps = 0;
        const char *why = gi_set(&none, "gi", "ilpv");
        if (!why)
            why = gi_set_number(&none, "lattice", axes[k]);
        if (!why)
            why = gi_set(&none, "lattice-cells", "0");
        if (why) {
            snprintf(err, errlen, "--budget-ms: %s", why);
            return -1;
        }
        renderer_desc rd = *base;
        rd.first = &none;
        rd.no_reuse = 1;
        renderer *r = renderer_create(&rd, err, errlen);
        if (!r)
            return -1;
        gi_ilpv *l = gi_ilpv_of(renderer_gi(r));
        double step_try[3], fixed_try[3];
        renderer_frame_pass(r, &none); /* the first frame pays for first touches */
        for (int i = 0; i < 3; i++) {
            step_try[i] = gi_ilpv_measure_step_ms(l, 3);
            renderer_frame_pass(r, &none);
            renderer_timings t;
            renderer_get_timings(r, &t);
            fixed_try[i] = gi_stats_total_ms(&t.gi);
        }
        out[k] = (lpv_budget_candidate){
            .axis_cells = axes[k],
            .cells = lattice_cell_count(gi_ilpv_lattice(l)),
            .step_ms = fmax(median3(step_try), 1e-6), /* a step is never free */
            .fixed_ms = median3(fixed_try),
        };
        renderer_destroy(r);
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
