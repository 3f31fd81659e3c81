/* Units of the frame pass (docs/node.md): the injection's energy <L|1> is exactly the flux
 * the VPLs carry (renderer_lpv_stats.injected_energy), so it can be checked against closed
 * forms.
 *   - a spot straight down onto the floor: the floor reflects albedo * I * integral of
 *     the cone factor over solid angle (the RSM's per-texel solid angles must add up);
 *   - the emissive panel alone (a surface light): pi * L_e * area. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"

static const double PI = 3.14159265358979323846;

static void lattice_energy_after_injection(gltest *t, double e[3])
{
    t->params.lpv_steps = 0;
    renderer_frame_pass(t->r, &t->params);
    renderer_lpv_stats st;
    renderer_get_lpv_stats(t->r, &st);
    memcpy(e, st.injected_energy, sizeof st.injected_energy);
}

static void test_spot_flux_on_floor(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, RENDERER_LPV_CPU, 0), 0);
    /* The emissive panel must not count: measure it alone and subtract. */
    double panel[3], both[3];
    t.params.lights[0].enabled = 0;
    lattice_energy_after_injection(&t, panel);
    frame_light *l = &t.params.lights[0];
    *l = (frame_light){.enabled = 1, .position = {-1.0f, 2.5f, -0.2f}, .direction = {0, -1, 0},
                       .color = {1.0f, 0.5f, 0.25f}, .intensity = 10.0f,
                       .outer_angle = 0.30f, .inner_angle = 0.20f};
    lattice_energy_after_injection(&t, both);
    double ci = cos(0.20), co = cos(0.30);
    double cone = 2.0 * PI * ((1.0 - ci) + 0.5 * (ci - co)); /* integral of the D3D factor */
    double floor_albedo = t.scene.materials[0].base_color[0];
    for (int c = 0; c < 3; c++) {
        double want = floor_albedo * l->intensity * l->color[c] * cone;
        double got = both[c] - panel[c];
        printf("channel %d: lattice %.5f W, closed form %.5f W\n", c, got, want);
        assert_true(fabs(got - want) < 0.02 * want);
    }
    gltest_close(&t);
}

static void test_surface_light_flux(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, RENDERER_LPV_CPU, 0), 0);
    t.params.light_count = 0;
    double e[3];
    lattice_energy_after_injection(&t, e);
    double want[3] = {0, 0, 0};
    for (size_t i = 0; i < t.scene.triangle_count; i++) {
        const float *em = t.scene.materials[t.scene.triangle_material[i]].emissive;
        const float *p = t.scene.positions + 9 * i;
        double a[3], b[3];
        for (int k = 0; k < 3; k++) {
            a[k] = p[3 + k] - p[k];
            b[k] = p[6 + k] - p[k];
        }
        double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2],
               cz = a[0] * b[1] - a[1] * b[0];
        double area = 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
        for (int c = 0; c < 3; c++)
            want[c] += PI * em[c] * area;
    }
    for (int c = 0; c < 3; c++) {
        printf("channel %d: lattice %.6f W, pi L_e A %.6f W\n", c, e[c], want[c]);
        assert_true(want[c] > 0);
        assert_true(fabs(e[c] - want[c]) < 1e-4 * want[c]);
    }
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spot_flux_on_floor),
        cmocka_unit_test(test_surface_light_flux),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
