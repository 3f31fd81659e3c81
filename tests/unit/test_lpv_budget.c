/* The budget rule on synthetic cost tables: the finest lattice that affords min_steps,
 * with as many steps as fit up to max_steps; the coarsest (and "does not fit") when none
 * does; the per-frame cost; refused inputs. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>

#include "gi/ilpv/lpv_budget.h"

/* Cost per step proportional to the cells of a 2:1:2 room, as the node fits it. */
static const lpv_budget_candidate table[] = {
    {48, 48 * 24 * 48, 5.5296, 0}, {16, 16 * 8 * 16, 0.2048, 0}, {64, 64 * 32 * 64, 13.1072, 0},
    {24, 24 * 12 * 24, 0.6912, 0}, {32, 32 * 16 * 32, 1.6384, 0},
};

static lpv_budget_choice choose(double budget, int min_steps, int max_steps)
{
    lpv_budget_desc d = {.budget_ms = budget, .candidates = table, .count = 5,
                         .min_steps = min_steps, .max_steps = max_steps};
    lpv_budget_choice c;
    assert_int_equal(lpv_budget_choose(&d, &c), 0);
    assert_true(fabs(c.predicted_ms - c.steps * table[c.index].step_ms) < 1e-12); /* fixed 0 */
    assert_int_equal(c.axis_cells, table[c.index].axis_cells);
    return c;
}

static void test_rule(void **state)
{
    (void)state;
    lpv_budget_choice c = choose(100.0, 0, 0); /* 64: 4 steps = 52 ms, 7 fit */
    assert_int_equal(c.axis_cells, 64);
    assert_int_equal(c.steps, 7);
    assert_true(c.fits);
    c = choose(200.0, 0, 0); /* capped at 8 */
    assert_int_equal(c.axis_cells, 64);
    assert_int_equal(c.steps, 8);
    c = choose(30.0, 0, 0); /* 64 needs 52 ms for 4 steps; 48 needs 22: 5 fit */
    assert_int_equal(c.axis_cells, 48);
    assert_int_equal(c.steps, 5);
    c = choose(6.6, 0, 0); /* 32: 4 steps = 6.55 ms, exactly 4 fit */
    assert_int_equal(c.axis_cells, 32);
    assert_int_equal(c.steps, 4);
    c = choose(6.5, 0, 0);
    assert_int_equal(c.axis_cells, 24);
    assert_int_equal(c.steps, 8);
    assert_true(c.predicted_ms <= 6.5);
    c = choose(0.5, 0, 0); /* not even 16 at 4 steps: coarsest, 2 steps, over the rule */
    assert_int_equal(c.axis_cells, 16);
    assert_int_equal(c.steps, 2);
    assert_false(c.fits);
    c = choose(0.1, 0, 0); /* at least one step */
    assert_int_equal(c.axis_cells, 16);
    assert_int_equal(c.steps, 1);
    assert_false(c.fits);
    c = choose(30.0, 8, 16); /* classic: 8 steps at least */
    assert_int_equal(c.axis_cells, 32);
    assert_int_equal(c.steps, 16);
}

/* The per-frame cost counts against the budget before the steps do. */
static void test_fixed_cost(void **state)
{
    (void)state;
    lpv_budget_candidate t[2] = {{16, 3072, 0.2, 0.5}, {32, 24576, 1.6, 4.0}};
    lpv_budget_desc d = {.budget_ms = 10.0, .candidates = t, .count = 2};
    lpv_budget_choice c;
    assert_int_equal(lpv_budget_choose(&d, &c), 0); /* 32: 4 + 4 * 1.6 > 10 */
    assert_int_equal(c.axis_cells, 16);
    assert_int_equal(c.steps, 8);
    assert_true(fabs(c.predicted_ms - 2.1) < 1e-12);
    d.budget_ms = 10.5;
    assert_int_equal(lpv_budget_choose(&d, &c), 0);
    assert_int_equal(c.axis_cells, 32);
    assert_int_equal(c.steps, 4);
    t[0].fixed_ms = -1;
    assert_int_equal(lpv_budget_choose(&d, &c), -1);
}

static void test_refused(void **state)
{
    (void)state;
    lpv_budget_choice c = {.steps = -7};
    lpv_budget_desc d = {.budget_ms = 10, .candidates = table, .count = 0};
    assert_int_equal(lpv_budget_choose(&d, &c), -1);
    d.count = 5;
    d.budget_ms = NAN;
    assert_int_equal(lpv_budget_choose(&d, &c), -1);
    d.budget_ms = 0;
    assert_int_equal(lpv_budget_choose(&d, &c), -1);
    lpv_budget_candidate bad[2] = {{16, 100, 1.0, 0}, {32, 800, NAN, 0}};
    d = (lpv_budget_desc){.budget_ms = 10, .candidates = bad, .count = 2};
    assert_int_equal(lpv_budget_choose(&d, &c), -1);
    assert_int_equal(c.steps, -7);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rule),
        cmocka_unit_test(test_fixed_cost),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
