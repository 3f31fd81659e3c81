/* Units of the frame pass (docs/node.md): the injection's energy <L|1> is exactly the flux
 * the VPLs carry (gi_ilpv_stats.injected_energy), so it can be checked against closed
 * forms.
 *   - a spot straight down onto the floor: the floor reflects albedo * I * integral of
 *     the cone factor over solid angle (the RSM's per-texel solid angles must add up);
 *   - the emissive panel alone (a surface light): pi * L_e * area;
 *   - a point light inside a closed box: albedo * 4 pi * I (the six cube faces cover every
 *     direction exactly once: their margins carry no flux), in the lattice and in the VPL
 *     maps every GI method reads (gi_rsm_read_layer());
 *   - a directional light onto a floor: albedo * E * area * cos(slant), in the VPL source
 *     (a flat scene's lattice is one cell thick, so the half-cell offset leaves it). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"
#include "renderer.h"
#include "renderer_rsm.h"

static const double PI = 3.14159265358979323846;

static void lattice_energy_after_injection(gltest *t, double e[3])
{
    t->params.lpv_steps = 0;
    renderer_frame_pass(t->r, &t->params);
    gi_ilpv_stats st;
    gi_ilpv_stats_get(gi_ilpv_of(renderer_gi(t->r)), &st);
    memcpy(e, st.injected_energy, sizeof st.injected_energy);
}

static void test_spot_flux_on_floor(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
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
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
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

/* A renderer with 0 steps and no history on a scene built in code (one material): the
 * lattice's energy and the summed flux of the VPL source. */
static void code_scene_energy(scene *s, const frame_light *l, int rsm, double e[3],
                              double vpl[3])
{
    char err[512];
    assert_int_equal(scene_finish(s, err, sizeof err), 0);
    glctx_desc gd = {.backend = GLCTX_EGL};
    glctx *ctx = glctx_create(&gd, err, sizeof err);
    assert_non_null(ctx);
    frame_params p;
    frame_params_default(&p);
    p.light_count = 1;
    p.lights[0] = *l;
    p.lpv_steps = 0;
    p.lambda_incr = 0.0f;
    gltest_setn(&p, "rsm", rsm);
    gltest_setn(&p, "lattice", 16);
    gltest_set(&p, "lpv", "cpu");
    renderer_desc rd = {.gl = glctx_gl(ctx), .scene = s, .first = &p};
    renderer *r = renderer_create(&rd, err, sizeof err);
    assert_non_null(r);
    renderer_frame_pass(r, &p);
    gi_ilpv_stats st; /* the injection's energy (the lattice holds the splat's near field too) */
    gi_ilpv_stats_get(gi_ilpv_of(renderer_gi(r)), &st);
    memcpy(e, st.injected_energy, sizeof st.injected_energy);
    gi_rsm maps;
    gi_rsm_reader reader = {0};
    renderer_gi_rsm(r, &maps);
    vpl[0] = vpl[1] = vpl[2] = 0;
    for (int layer = 0; layer < maps.layers; layer++) {
        const float *pos, *nrm, *flux;
        assert_int_equal(gi_rsm_read_layer(&reader, glctx_gl(ctx), &maps, layer, &pos, &nrm, &flux), 0);
        for (int i = 0; i < maps.size * maps.size; i++)
            if (pos[4 * i + 3] != 0.0f)
                for (int c = 0; c < 3; c++)
                    vpl[c] += flux[4 * i + c];
    }
    gi_rsm_reader_free(&reader);
    renderer_destroy(r);
    glctx_destroy(ctx);
}

static void test_point_flux_in_closed_box(void **state)
{
    (void)state;
    for (int rsm = 64; rsm <= 256; rsm *= 4) {
        scene s;
        memset(&s, 0, sizeof s);
        const float albedo = 0.6f, lo[3] = {-1, 0, -1.5f}, hi[3] = {1.5f, 2, 1};
        assert_int_equal(scene_add_material(&s, &(scene_material){.base_color = {albedo, albedo, albedo, 1},
                                                                  .base_color_texture = -1,
                                                                  .roughness = 1}), 0);
        assert_int_equal(scene_add_box(&s, lo, hi, 1, 0), 0);
        frame_light l = {.enabled = 1, .type = SCENE_LIGHT_POINT, .position = {0.1f, 1.2f, -0.15f},
                         .direction = {0, -1, 0}, .color = {1.0f, 0.5f, 0.25f}, .intensity = 3};
        double e[3], vpl[3];
        code_scene_energy(&s, &l, rsm, e, vpl);
        for (int c = 0; c < 3; c++) {
            double want = albedo * 4.0 * PI * l.intensity * l.color[c];
            printf("point light, RSM %d: channel %d: injected %.5f W, VPLs %.5f W, albedo 4 pi I "
                   "%.5f W\n", rsm, c, e[c], vpl[c], want);
            assert_true(fabs(e[c] - want) < 0.001 * want);
            assert_true(fabs(vpl[c] - want) < 0.001 * want);
        }
        scene_free(&s);
    }
}

static void test_directional_flux_on_floor(void **state)
{
    (void)state;
    const float d[2][3] = {{0, -1, 0}, {0.3f, -1, 0.2f}};
    for (int k = 0; k < 2; k++) {
        scene s;
        memset(&s, 0, sizeof s);
        const float albedo = 0.5f, lo[3] = {-2, 0, -2}, hi[3] = {2, 0, 2};
        assert_int_equal(scene_add_material(&s, &(scene_material){.base_color = {albedo, albedo, albedo, 1},
                                                                  .base_color_texture = -1,
                                                                  .roughness = 1}), 0);
        assert_int_equal(scene_add_rect(&s, lo, hi, 1, 0), 0);
        frame_light l = {.enabled = 1, .type = SCENE_LIGHT_DIRECTIONAL, .color = {1, 1, 1},
                         .intensity = 2};
        float len = sqrtf(d[k][0] * d[k][0] + d[k][1] * d[k][1] + d[k][2] * d[k][2]);
        for (int a = 0; a < 3; a++)
            l.direction[a] = d[k][a] / len;
        double e[3], vpl[3];
        code_scene_energy(&s, &l, 128, e, vpl);
        double want = albedo * l.intensity * 16.0 * -l.direction[1];
        printf("directional light, slant %.3f rad: VPLs %.5f W, albedo E A cos %.5f W\n",
               acos(-l.direction[1]), vpl[0], want);
        /* Straight down the window is the floor; slanted, its texels cut the floor's edges. */
        assert_true(fabs(vpl[0] - want) < (k ? 0.01 : 1e-5) * want);
        scene_free(&s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spot_flux_on_floor),
        cmocka_unit_test(test_surface_light_flux),
        cmocka_unit_test(test_point_flux_in_closed_box),
        cmocka_unit_test(test_directional_flux_on_floor),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
