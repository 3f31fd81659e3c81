/* A spot outside the lattice, far outside it, and exactly on its faces and corner. The
 * lattice covers the scene's bounds (plus half a cell), not the lights: a light outside
 * it still renders its RSM, and its VPLs lie on surfaces inside it. Nothing may go NaN,
 * the lattice may hold at most what the spot's light reflects over the steps it lives
 * (the albedo times the mean chord 4V/A in cells, ilpv.h), and the floor must be lit
 * where the spot's axis hits it, as brightly as I cos / r^2 says.
 *
 * Scene: open on three sides, a 4 x 4 m floor (albedo 0.75), a back wall at z = -2 and a
 * box; every spot aims at a clear floor point T, seen from above.
 *
 * Measured (build/stability_light_outside), lattice 16x12x16 (0.25 m cells), RSM 64,
 * 10 frames, cone 0.3 rad, I = 2 r^2 (2 W/m^2 at T):
 *   case                      lattice E / emitted   direct at T / (albedo/pi I cos/r^2)
 *   outside, 3 m in front     3.908                 1.049
 *   far outside (50 m)        0.148                 1.054
 *   on the lattice's +x face  5.600                 1.083
 *   on the lattice's corner   5.180                 1.043
 *   on the bounds' top face   5.670                 1.051
 *   below the floor, up       0                     0 (top of the floor stays dark)
 * (the ~5% above 1 is the Blinn-Phong specular term the model leaves out), non-finite 0;
 * the mean chord is 23.6 cells. (Before the chain scheme the lattice held a normalized
 * mixture of ages, 0.0016 .. 0.0839 of the emitted energy.)
 * Bounds: non-finite 0; lattice E / emitted <= 0.75 x chord; 0.95 .. 1.15 at T; from
 * below 1e-6. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"
#include "stability_util.h"

enum { W = 160, H = 120, FRAMES = 10 };

static void build_scene(scene *s)
{
    memset(s, 0, sizeof *s);
    scene_material white = {{0.75f, 0.75f, 0.75f, 1}, -1, {0, 0, 0}, 1.0f};
    assert_int_equal(scene_add_material(s, &white), 0);
    const float floor_tris[18] = {-2, 0, -2, -2, 0, 2, 2, 0, 2, -2, 0, -2, 2, 0, 2, 2, 0, -2};
    const float wall_tris[18] = {-2, 0, -2, 2, 0, -2, 2, 3, -2, -2, 0, -2, 2, 3, -2, -2, 3, -2};
    for (int t = 0; t < 2; t++) {
        assert_true(scene_add_triangle(s, floor_tris + 9 * t, NULL, NULL, 0) >= 0);
        assert_true(scene_add_triangle(s, wall_tris + 9 * t, NULL, NULL, 0) >= 0);
    }
    const float lo[3] = {0.6f, 0, -1.5f}, hi[3] = {1.4f, 1.0f, -0.7f};
    assert_int_equal(scene_add_box(s, lo, hi, 0, 0), 0);
    char err[256];
    assert_int_equal(scene_finish(s, err, sizeof err), 0);
}

typedef struct spot_case {
    const char *name;
    float position[3];
    float target[3];   /* on the floor, in the clear */
} spot_case;

static void test_spots_outside_and_on_the_edge(void **state)
{
    (void)state;
    scene s;
    build_scene(&s);
    stab_gl g;
    assert_int_equal(stab_open(&g, &s, 16), 0);
    const lattice_desc *lat = gi_ilpv_lattice(gi_ilpv_of(renderer_gi(g.r)));
    float lmax[3];
    for (int a = 0; a < 3; a++)
        lmax[a] = lat->origin[a] + lat->n[a] * lat->cell;
    printf("lattice origin %.3f %.3f %.3f, max %.3f %.3f %.3f, cell %.3f\n", lat->origin[0],
           lat->origin[1], lat->origin[2], lmax[0], lmax[1], lmax[2], lat->cell);
    const spot_case cases[] = {
        {"outside, in front", {0.0f, 2.0f, 5.0f}, {-0.5f, 0.0f, 0.5f}},
        {"far outside (50 m)", {0.0f, 30.0f, 40.0f}, {-0.5f, 0.0f, 0.0f}},
        {"on the lattice's +x face", {lmax[0], 1.5f, 0.0f}, {0.0f, 0.0f, 0.5f}},
        {"on the lattice's corner", {lat->origin[0], lmax[1], lmax[2]}, {-1.0f, 0.0f, 0.5f}},
        {"on the bounds' top face", {-0.5f, 3.0f, 0.5f}, {-0.5f, 0.0f, 0.5f}},
        {"below the floor", {0.0f, -1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}},
    };
    renderer_view v;
    const float eye[3] = {0.0f, 6.0f, 3.0f}, at[3] = {0.0f, 0.0f, 0.0f};
    stab_view(&v, eye, at, 1.0f, W, H, 0.05f, 100.0f);
    double worst_energy = 0, lo = 1e30, hi = 0;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const spot_case *k = &cases[c];
        frame_params p;
        frame_params_default(&p);
        p.light_count = 1;
        frame_light *l = &p.lights[0];
        *l = (frame_light){.enabled = 1, .color = {1, 1, 1}, .outer_angle = 0.3f,
                           .inner_angle = 0.25f};
        float r2 = 0;
        for (int a = 0; a < 3; a++) {
            l->position[a] = k->position[a];
            l->direction[a] = k->target[a] - k->position[a];
            r2 += l->direction[a] * l->direction[a];
        }
        for (int a = 0; a < 3; a++)
            l->direction[a] /= sqrtf(r2);
        l->intensity = 2.0f * r2; /* about 2 W/m^2 at T whatever the distance */
        p.reset_epoch = (uint32_t)c + 1;
        for (int f = 0; f < FRAMES; f++)
            stab_frame_pass(&g, &p);
        const lpv_volume *lpv = gi_ilpv_volume(gi_ilpv_of(renderer_gi(g.r)));
        size_t bad = lpv_volume_count_nonfinite(lpv);
        double energy = stab_energy(lpv) / 3.0 / stab_spot_energy(l);
        renderer_image img;
        assert_int_equal(renderer_eye_pass(g.r, &v, 1, &img), 0);
        bad += stab_image_nonfinite(&img);
        float px[2];
        gltest_project(&v, k->target, px);
        double d[3];
        gltest_window_mean(img.direct, W, H, (int)px[0], (int)px[1], 1, d);
        /* Expected: albedo / pi * I cos / r^2 for the floor (normal +y), diffuse part. */
        float cos_t = -l->direction[1];
        double expect = cos_t > 0 ? 0.75 / 3.14159265 * l->intensity * cos_t / r2 : 0.0;
        double lit = expect > 0 ? (d[0] + d[1] + d[2]) / 3.0 / expect : (d[0] + d[1] + d[2]);
        printf("%-26s non-finite %zu, lattice energy / emitted %.4f, direct at T %.4g "
               "(%s %.3f)\n", k->name, bad, energy, (d[0] + d[1] + d[2]) / 3.0,
               expect > 0 ? "over I cos/r^2 model" : "absolute", lit);
        assert_int_equal(bad, 0);
        /* From below the floor: its underside's VPLs land outside the lattice (half a
         * cell along their normal), and the top stays dark. */
        if (expect == 0)
            assert_true(energy <= 1e-6 && lit <= 1e-6);
        worst_energy = fmax(worst_energy, energy);
        if (expect > 0) {
            lo = fmin(lo, lit);
            hi = fmax(hi, lit);
        }
    }
    double chord = stab_mean_chord_cells(&s, gi_ilpv_lattice(gi_ilpv_of(renderer_gi(g.r)))->cell);
    printf("largest lattice energy / emitted %.4f (mean chord %.3f cells); lit at T / model "
           "%.3f .. %.3f\n", worst_energy, chord, lo, hi);
    assert_true(worst_energy <= 0.75 * chord);
    assert_true(lo >= 0.95 && hi <= 1.15);
    stab_close(&g);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spots_outside_and_on_the_edge),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
