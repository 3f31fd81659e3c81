/* A very small and a very large scene: the default room scaled by 0.01 (4 cm) and by 1000
 * (4 km). Positions, the camera and its clip planes scale by s, the spot's intensity by
 * s^2 (irradiance goes with 1/r^2), emitted radiance stays: the picture should not change.
 * The lattice is fitted to the bounds, so it scales too.
 *
 * Measured (build/stability_scene_scale), lattice 20, RSM 64, 160x120, 12 frames;
 * "diff" is mean |scaled - unscaled| / mean of the unscaled linear image:
 *   before the fix (fixed 5 cm RSM near plane, 1 cm normal offset, 10 cm light distance):
 *     s = 0.01: LPV energy / s^2 0.442, diff final 0.433, direct 0.430, indirect 0.538,
 *               8-bit mean |diff| 13.2 (the RSM missed everything closer than 5 cm and
 *               the falloff was clamped at 10 cm in a 4 cm room)
 *     s = 1000: energy 1.0006, final 0.0054, direct 0.0055, indirect 0.0011, 8-bit 0.12
 *               (the shadow depth bias was kilometres long: no shadows at all)
 *   after (those lengths are fractions of the scene's diagonal, node/renderer.c; the
 *   shadow test's offset is in RSM texels, shade.frag):
 *     s = 0.01: energy 1.0005, final 2.3e-4, direct 3.2e-7, indirect 1.4e-3, 8-bit 0.010
 *     s = 1000: energy 1.0012, final 1.6e-4, direct 3.8e-6, indirect 9.5e-4, 8-bit 0.007
 *   (direct was 8.3e-6 and 5.5e-5 with the diagonal-relative normal offset and constant
 *   depth bias)
 *   (final was 4.1e-5 and 8.0e-5 before the indirect level followed the injected energy,
 *   which made the indirect share of the image, and so its difference, larger).
 *   with the ballistic transport (lpv_transfer.h), its binary blockers and its splat:
 *     s = 0.01: energy 1.00196, final 6.4e-3, direct 3.2e-7, indirect 4.9e-2, 8-bit 0.59
 *     s = 1000: energy 0.99269, final 3.7e-3, direct 3.8e-6, indirect 2.8e-2, 8-bit 0.32
 *   The room's walls lie on cell centres (the lattice's half-cell margin), and whether a
 *   centre on a wall's plane counts as in front of it is decided by the rounding of the
 *   vertices' coordinates in cells, which differs with the scale: the blocked hops, and so
 *   the indirect light, differ a little. Treating centres within 1e-4 cells of a plane as
 *   on it halves the indirect figure at s = 0.01 (1.9e-2) but moves the energy at both
 *   scales by some 0.4%: not settled (docs/lpv.md, "Open").
 * Bounds: |energy - 1| <= 0.01; final <= 0.01, direct <= 3e-4, indirect <= 0.075;
 * 8-bit 1.0. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "stability_util.h"

enum { W = 160, H = 120, FRAMES = 12 };

typedef struct scaled_render {
    float *final, *direct, *indirect;
    uint8_t *rgb;
    double lpv_energy;
    size_t nonfinite;
    float cell;
    int n[3];
} scaled_render;

static void render_scaled(float s, scaled_render *out)
{
    scene sc;
    char err[256];
    assert_int_equal(scene_load("default", &sc, err, sizeof err), 0);
    for (size_t i = 0; i < 9 * sc.triangle_count; i++)
        sc.positions[i] *= s;
    for (int a = 0; a < 3; a++) {
        sc.lights[0].position[a] *= s;
        sc.camera.position[a] *= s;
        sc.camera.target[a] *= s;
    }
    sc.lights[0].intensity *= s * s;
    assert_int_equal(scene_finish(&sc, err, sizeof err), 0);
    stab_gl g;
    assert_int_equal(stab_open(&g, &sc, 20), 0);
    frame_params p;
    frame_params_default(&p);
    frame_params_lights_from_scene(&p, &sc);
    for (int f = 0; f < FRAMES; f++)
        stab_frame_pass(&g, &p);
    renderer_view v;
    stab_view(&v, sc.camera.position, sc.camera.target, sc.camera.yfov, W, H, 0.05f * s,
              50.0f * s);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(g.r, &v, 1, &img), 0);
    size_t n = (size_t)W * H * 3;
    out->final = malloc(n * sizeof(float));
    out->direct = malloc(n * sizeof(float));
    out->indirect = malloc(n * sizeof(float));
    out->rgb = malloc(n);
    assert_true(out->final && out->direct && out->indirect && out->rgb);
    memcpy(out->final, img.final, n * sizeof(float));
    memcpy(out->direct, img.direct, n * sizeof(float));
    memcpy(out->indirect, img.indirect, n * sizeof(float));
    memcpy(out->rgb, img.rgb, n);
    out->nonfinite = stab_image_nonfinite(&img) + lpv_volume_count_nonfinite(gi_ilpv_volume(gi_ilpv_of(renderer_gi(g.r))));
    out->lpv_energy = stab_energy(gi_ilpv_volume(gi_ilpv_of(renderer_gi(g.r))));
    out->cell = gi_ilpv_lattice(gi_ilpv_of(renderer_gi(g.r)))->cell;
    memcpy(out->n, gi_ilpv_lattice(gi_ilpv_of(renderer_gi(g.r)))->n, sizeof out->n);
    stab_close(&g);
    scene_free(&sc);
}

static void free_render(scaled_render *r)
{
    free(r->final);
    free(r->direct);
    free(r->indirect);
    free(r->rgb);
}

/* Mean |a - b| over the mean of b. */
static double rel_diff(const float *a, const float *b)
{
    double d = 0, m = 0;
    for (size_t i = 0; i < (size_t)W * H * 3; i++) {
        d += fabs((double)a[i] - b[i]);
        m += b[i];
    }
    return d / m;
}

static double rgb_diff(const uint8_t *a, const uint8_t *b)
{
    double d = 0;
    for (size_t i = 0; i < (size_t)W * H * 3; i++)
        d += abs((int)a[i] - (int)b[i]);
    return d / ((double)W * H * 3);
}

static void test_scaled_rooms_look_the_same(void **state)
{
    (void)state;
    scaled_render ref;
    render_scaled(1.0f, &ref);
    assert_int_equal(ref.nonfinite, 0);
    const float scales[2] = {0.01f, 1000.0f};
    for (int i = 0; i < 2; i++) {
        scaled_render r;
        render_scaled(scales[i], &r);
        double e = r.lpv_energy / (ref.lpv_energy * scales[i] * scales[i]);
        double final = rel_diff(r.final, ref.final), direct = rel_diff(r.direct, ref.direct),
               indirect = rel_diff(r.indirect, ref.indirect), rgb = rgb_diff(r.rgb, ref.rgb);
        printf("scale %g: cell %.4g m, non-finite %zu, LPV energy / (s^2 x unscaled) %.5f, "
               "mean |diff| / mean: final %.2e direct %.2e indirect %.2e; 8-bit mean |diff| "
               "%.3f\n", scales[i], r.cell, r.nonfinite, e, final, direct, indirect, rgb);
        assert_int_equal(r.nonfinite, 0);
        /* the same lattice, scaled */
        assert_memory_equal(r.n, ref.n, sizeof r.n);
        assert_true(fabs(r.cell / (ref.cell * scales[i]) - 1.0) < 1e-4);
        assert_true(fabs(e - 1.0) <= 0.01);
        assert_true(final <= 0.01 && direct <= 3e-4 && indirect <= 0.075);
        assert_true(rgb <= 1.0);
        free_render(&r);
    }
    free_render(&ref);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scaled_rooms_look_the_same),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
