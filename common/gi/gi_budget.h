/* gi_budget: --budget-ms for whichever method the frame runs, when that method has a
 * budget rule (gi_method_settings.budget; today the ILPV's, ilpv_budget.h).
 *
 * A plan is a fixed list of measuring frames (each a frame_params the caller renders:
 * a standalone node on its own renderer, the master on every node, where a frame counts at
 * its slowest node), their frame-pass ms recorded one by one, then one choice of the
 * method's settings written into the session's frame. No GL, no method named here: the
 * master, the node and the tests use only this. Not here: running the frames
 * (node/standalone.c, master/session.c); the method's rule (its own folder). */
#ifndef CAVELIGHT_GI_BUDGET_H
#define CAVELIGHT_GI_BUDGET_H

#include <stddef.h>

#include "frame/frame_params.h"

/* What a rule chose: named figures for the report and one line for people. */
enum { GI_BUDGET_FIGURES_MAX = 8 };
typedef struct gi_budget_choice {
    double predicted_ms;           /* the frame pass the choice is expected to take */
    int fits;                      /* predicted_ms within the budget */
    int figure_count;
    struct {
        const char *name;          /* a report key: "lattice_cells", "steps" */
        double value;
    } figure[GI_BUDGET_FIGURES_MAX];
    char summary[96];              /* "lattice 32, 4 steps" */
    char detail[160];              /* what it was measured at, or "" */
} gi_budget_choice;

/* What a method's settings give to have a budget (gi_method_settings.budget). The plan's
 * state is plan_size bytes, zeroed before plan_init(). */
typedef struct gi_budget_rule {
    const char *const *chooses;    /* the settings it sets, NULL-terminated: refused beside
                                      --budget-ms */
    int frames;                    /* measuring frames */
    size_t plan_size;
    void (*plan_init)(void *plan, const frame_params *base, const float bounds_min[3],
                      const float bounds_max[3]);
    void (*plan_frame)(const void *plan, int i, frame_params *out);
    void (*plan_record)(void *plan, int i, double frame_ms);
    /* The choice within budget_ms, written into fp: 0, or -1 with one line in err. */
    int (*choose)(const void *plan, double budget_ms, frame_params *fp, gi_budget_choice *out,
                  char *err, size_t errlen);
} gi_budget_rule;

/* Why --budget-ms cannot choose for frame p: its method has no rule, or a setting the rule
 * chooses was given too (given(ctx, name) says whether the user gave one). NULL when it
 * can. */
const char *gi_budget_check(const frame_params *p, int (*given)(void *ctx, const char *name),
                            void *ctx);

typedef struct gi_budget_plan gi_budget_plan;
/* The plan of base's method (gi_budget_check() said yes) for a scene of these bounds. */
gi_budget_plan *gi_budget_plan_create(const frame_params *base, const float bounds_min[3],
                                      const float bounds_max[3]);
void gi_budget_plan_destroy(gi_budget_plan *plan);
int gi_budget_plan_frames(const gi_budget_plan *plan);
/* Measuring frame i (0 <= i < frames). */
void gi_budget_plan_frame(const gi_budget_plan *plan, int i, frame_params *out);
/* Frame i's frame-pass ms (a cluster's: the slowest node's). */
void gi_budget_plan_record(gi_budget_plan *plan, int i, double frame_ms);
/* The choice within budget_ms from the recorded frames, written into fp: 0, or -1 with
 * one line in err. */
int gi_budget_plan_choose(const gi_budget_plan *plan, double budget_ms, frame_params *fp,
                          gi_budget_choice *out, char *err, size_t errlen);

#endif
