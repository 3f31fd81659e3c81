#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "gi/ilpv/lattice.h"

static void test_elongated_scene_gets_elongated_lattice(void **state)
{
    (void)state;
    lattice_fit_desc d = {.bounds_min = {-34, 0, -13.5f}, .bounds_max = {34, 15, 13.5f},
                          .max_axis_cells = 64, .max_cells = 64L * 64 * 64, .margin_cells = 0.5f};
    lattice_desc lat;
    char err[200];
    assert_int_equal(lattice_fit(&d, &lat, err, sizeof err), 0);
    assert_int_equal(lat.n[0], 64);
    assert_in_range(lat.n[1], 14, 16); /* not 64: no cube of empty cells */
    assert_in_range(lat.n[2], 26, 28);
    /* The lattice holds the bounds with at least the margin on each side. */
    for (int a = 0; a < 3; a++) {
        float hi = lat.origin[a] + lat.n[a] * lat.cell;
        assert_true(lat.origin[a] <= d.bounds_min[a] - 0.49f * lat.cell);
        assert_true(hi >= d.bounds_max[a] + 0.49f * lat.cell);
    }
    assert_true(fabsf(lat.cell - 68.0f / 63.0f) < 1e-4f);
}

static void test_budget_grows_the_cell(void **state)
{
    (void)state;
    lattice_fit_desc d = {.bounds_min = {0, 0, 0}, .bounds_max = {10, 10, 10},
                          .max_axis_cells = 64, .max_cells = 1000};
    lattice_desc lat;
    assert_int_equal(lattice_fit(&d, &lat, NULL, 0), 0);
    assert_true(lattice_cell_count(&lat) <= 1000);
    assert_true(lattice_cell_count(&lat) >= 700); /* grows in small steps, not to the extreme */
    assert_true(lat.cell * lat.n[0] >= 10.0f);
    /* Defaults: 32 cells on the longest axis, 64^3 budget, zero margin when 0. */
    lattice_fit_desc def = {.bounds_min = {0, 0, 0}, .bounds_max = {8, 2, 1}};
    assert_int_equal(lattice_fit(&def, &lat, NULL, 0), 0);
    assert_int_equal(lat.n[0], 32);
    assert_int_equal(lat.n[1], 8);
    assert_int_equal(lat.n[2], 4);
    /* A flat scene gets one layer, not zero. */
    lattice_fit_desc flat = {.bounds_min = {0, 0, 0}, .bounds_max = {4, 0, 4}};
    assert_int_equal(lattice_fit(&flat, &lat, NULL, 0), 0);
    assert_int_equal(lat.n[1], 1);
}

static void test_transforms_and_cell_lookup(void **state)
{
    (void)state;
    lattice_desc lat = {{-1, 2, 3}, 0.5f, {4, 6, 8}};
    float w[3] = {0.1f, 4.2f, 6.9f}, c[3], back[3];
    lattice_world_to_lattice(&lat, w, c);
    lattice_lattice_to_world(&lat, c, back);
    for (int a = 0; a < 3; a++)
        assert_true(fabsf(back[a] - w[a]) < 1e-5f);
    int ijk[3];
    size_t idx;
    assert_int_equal(lattice_cell_of(&lat, w, ijk, &idx), 0);
    assert_int_equal(ijk[0], 2);
    assert_int_equal(ijk[1], 4);
    assert_int_equal(ijk[2], 7);
    assert_int_equal(idx, 2 + 4 * (4 + 6 * 7));
    assert_int_equal(lattice_cell_count(&lat), 4 * 6 * 8);
    float outside[3] = {1.0f, 2.5f, 3.5f}; /* x = 1 is the upper face: outside */
    assert_int_equal(lattice_cell_of(&lat, outside, NULL, NULL), -1);
    float below[3] = {-1.01f, 2.5f, 3.5f};
    assert_int_equal(lattice_cell_of(&lat, below, NULL, NULL), -1);
    float nan[3] = {NAN, 2.5f, 3.5f};
    assert_int_equal(lattice_cell_of(&lat, nan, NULL, NULL), -1);
}

static void test_bad_bounds_are_refused_with_a_message(void **state)
{
    (void)state;
    lattice_desc lat;
    char err[200];
    lattice_fit_desc cases[] = {
        {.bounds_min = {1, 1, 1}, .bounds_max = {1, 1, 1}},            /* zero size */
        {.bounds_min = {0, 0, 0}, .bounds_max = {-1, 1, 1}},           /* inverted */
        {.bounds_min = {0, NAN, 0}, .bounds_max = {1, 1, 1}},          /* not finite */
        {.bounds_min = {0, 0, 0}, .bounds_max = {1, INFINITY, 1}},
        {.bounds_min = {0, 0, 0}, .bounds_max = {1, 1, 1}, .max_cells = -5},
        {.bounds_min = {0, 0, 0}, .bounds_max = {1, 1, 1}, .max_axis_cells = 2, .margin_cells = 1.0f},
        {.bounds_min = {0, 0, 0}, .bounds_max = {1, 1, 1}, .max_axis_cells = -3},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        err[0] = 0;
        assert_int_equal(lattice_fit(&cases[i], &lat, err, sizeof err), -1);
        assert_true(strncmp(err, "lattice: ", 9) == 0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_elongated_scene_gets_elongated_lattice),
        cmocka_unit_test(test_budget_grows_the_cell),
        cmocka_unit_test(test_transforms_and_cell_lookup),
        cmocka_unit_test(test_bad_bounds_are_refused_with_a_message),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
