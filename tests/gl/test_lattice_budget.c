/* renderer_desc.lattice_cell_budget: a total number of cells spent on the scene's shape.
 * The long corridor gets several times finer cells than the same count as a cube, the
 * budget holds, and the renderer lights the scene with it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "gl_testutil.h"

static lattice_desc open_corridor(glctx *ctx, const scene *s, int axis_cells, long budget)
{
    char err[512];
    frame_params p;
    frame_params_default(&p);
    frame_params_lights_from_scene(&p, s);
    gltest_setn(&p, "rsm", 64);
    gltest_set(&p, "lpv", "cpu");
    if (axis_cells > 0)
        gltest_setn(&p, "lattice", axis_cells);
    gltest_setn(&p, "lattice-cells", (double)budget);
    renderer_desc rd = {.gl = glctx_gl(ctx), .scene = s, .first = &p, .threads = 2};
    renderer *r = renderer_create(&rd, err, sizeof err);
    assert_non_null(r);
    lattice_desc lat = *gi_ilpv_lattice(gi_ilpv_of(renderer_gi(r)));
    renderer_frame_pass(r, &p);
    double e[3];
    lpv_volume_energy(gi_ilpv_volume(gi_ilpv_of(renderer_gi(r))), e);
    assert_true(e[0] > 0 && e[1] > 0 && e[2] > 0); /* light got into the lattice */
    renderer_destroy(r);
    return lat;
}

static void test_budget_follows_the_shape(void **state)
{
    (void)state;
    char err[512];
    glctx_desc gd = {.backend = GLCTX_EGL};
    glctx *ctx = glctx_create(&gd, err, sizeof err);
    assert_non_null(ctx);
    scene s;
    assert_int_equal(scene_load("corridor", &s, err, sizeof err), 0);
    const long budget = 16 * 16 * 16;
    lattice_desc cube_axis = open_corridor(ctx, &s, 16, 0);
    lattice_desc fitted = open_corridor(ctx, &s, 0, budget);
    long cells = (long)lattice_cell_count(&fitted);
    printf("16 along the longest axis: %dx%dx%d, cell %.3f m; budget %ld: %dx%dx%d (%ld), "
           "cell %.3f m\n", cube_axis.n[0], cube_axis.n[1], cube_axis.n[2], cube_axis.cell,
           budget, fitted.n[0], fitted.n[1], fitted.n[2], cells, fitted.cell);
    assert_true(cells <= budget);
    assert_true(cells >= budget * 8 / 10);       /* the cell grows in 0.5% steps */
    assert_true(fitted.cell < cube_axis.cell / 2); /* the corridor is 5x longer than wide */
    assert_true(fitted.n[0] > 2 * fitted.n[1] && fitted.n[0] > 2 * fitted.n[2]);
    scene_free(&s);
    glctx_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_budget_follows_the_shape),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
