/* lambda_incr close to 1 and beyond. The ILPV shows the light of every age (ilpv.h): for
 * static lights its chain converges to that sum whatever lambda is, and lambda only sets
 * how fast the light shown before a change fades (lambda^k). The sum's energy is the
 * injected energy times the number of steps light lives, about the mean chord 4V/A in
 * cells (light moves one cell a step; walls take it): bounded, and no lambda can make it
 * grow. At 1 a faded picture would never go, so frame_params_sanitize() (the one place a
 * frame's values are clamped) makes lambda >= 1 (and +inf) 0.999 and NaN 0.
 *
 * Measured (build/stability_lambda), CPU core on the default room at 16 cells, 4 steps:
 *   lambda 0.99, 1000 frames and 0.999, 3000 frames: largest E(L) / E(I) 7.0166 (mean
 *   chord 8.757 cells; the splat's near field counts once and its shell starts some 2.5
 *   cells out: 1 + 8.76 - 2.5 = 7.3), residual 0 at frame 10 and after (the chain is
 *   complete: every age has reached a wall within 40 steps);
 *   renderer (default room, lattice 20, lambda 0.999 then 1.5, 12 frames each): largest
 *   lattice energy / emitted energy 5.6 (mean chord 10.9 cells; the walls reflect less
 *   than they receive).
 *   (Before the chain scheme the lattice was a normalized mixture of ages, E(L) / E(I)
 *   0.47, and the renderer rescaled it by a fitted factor.)
 * (residual: largest change of any cell between two frames over the largest cell.)
 * Bounds: chord / 2 <= E(L) / E(I) <= chord; last residual <= 3e-7 and <= 2e-6 x the
 * residual at frame 10; renderer lattice energy <= chord x emitted. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "stability_util.h"

enum { STEPS = 4 };

typedef struct lambda_run {
    double max_ratio;       /* largest E(L) / E(I) */
    double chord;           /* the mean chord in cells */
    double residual_10;     /* relative change of the lattice at frame 10 */
    double residual_last;   /* ... at the last frame */
    uint64_t checksum;
    size_t nonfinite;
} lambda_run;

static lambda_run run(float lambda, int frames)
{
    stab_cpu c;
    assert_int_equal(stab_cpu_open(&c, 16), 0);
    lpv_volume prev;
    assert_int_equal(lpv_volume_init(&prev, c.lattice.n, LPV_LIGHT_CHANNELS), 0);
    lambda_run out = {0};
    for (int f = 1; f <= frames; f++) {
        lpv_volume_copy(&prev, ilpv_result(&c.ilpv));
        stab_cpu_frame(&c, lambda, STEPS, 1.0);
        const lpv_volume *l = ilpv_result(&c.ilpv);
        out.max_ratio = fmax(out.max_ratio, stab_energy(l) / stab_energy(ilpv_injection(&c.ilpv)));
        if (f == 10)
            out.residual_10 = testutil_rel_diff(l, &prev);
        if (f == frames)
            out.residual_last = testutil_rel_diff(l, &prev);
    }
    out.checksum = lpv_volume_checksum(ilpv_result(&c.ilpv));
    out.chord = stab_mean_chord_cells(&c.scene, c.lattice.cell);
    out.nonfinite = lpv_volume_count_nonfinite(ilpv_result(&c.ilpv));
    printf("lambda %g, %d frames: largest E(L)/E(I) %.4f (mean chord %.3f cells), residual "
           "frame 10 %.3g, frame %d %.3g\n", lambda, frames, out.max_ratio, out.chord,
           out.residual_10, frames, out.residual_last);
    lpv_volume_free(&prev);
    stab_cpu_close(&c);
    return out;
}

static void test_close_to_one_is_bounded_and_converges(void **state)
{
    (void)state;
    const float lambdas[2] = {0.99f, 0.999f};
    const int frames[2] = {1000, 3000};
    for (int i = 0; i < 2; i++) {
        lambda_run r = run(lambdas[i], frames[i]);
        assert_int_equal(r.nonfinite, 0);
        assert_true(r.max_ratio >= 0.5 * r.chord && r.max_ratio <= r.chord);
        assert_true(r.residual_last <= 3e-7);
        assert_true(r.residual_last <= 2e-6 * r.residual_10);
    }
}

/* lambda as a frame carries it to the core: through frame_params_sanitize(). */
static float sanitized(float lambda)
{
    frame_params p;
    frame_params_default(&p);
    p.lambda_incr = lambda;
    frame_params_sanitize(&p);
    return p.lambda_incr;
}

/* 1, 1.5 and +inf behave exactly as 0.999; NaN exactly as the default, 0.8. */
static void test_one_and_above_are_clamped(void **state)
{
    (void)state;
    const int frames = 30;
    uint64_t at_0 = run(0.0f, frames).checksum, at_default = run(0.8f, frames).checksum;
    uint64_t at_0999 = run(0.999f, frames).checksum;
    const float above[3] = {1.0f, 1.5f, INFINITY};
    for (int i = 0; i < 3; i++) {
        lambda_run r = run(sanitized(above[i]), frames);
        assert_int_equal(r.nonfinite, 0);
        assert_true(r.checksum == at_0999);
    }
    assert_true(run(sanitized(NAN), frames).checksum == at_default);
    assert_true(at_0 != at_0999);
}

/* The real renderer with lambda 0.999 then 1.5: finite, energy below what the lights emit
 * times the steps light lives (the lattice holds reflected flux, albedo < 1). */
static void test_renderer_near_one(void **state)
{
    (void)state;
    scene s;
    char err[256];
    assert_int_equal(scene_load("default", &s, err, sizeof err), 0);
    stab_gl g;
    assert_int_equal(stab_open(&g, &s, 20), 0);
    frame_params p;
    frame_params_default(&p);
    frame_params_lights_from_scene(&p, &s);
    /* the emissive panel: pi * area * mean radiance */
    double emitted = stab_spot_energy(&p.lights[0]) + 3.14159265 * 0.32 * (4.0 + 3.2 + 2.0) / 3;
    double largest = 0;
    const float lambdas[2] = {0.999f, 1.5f};
    for (int i = 0; i < 2; i++) {
        p.lambda_incr = lambdas[i];
        for (int f = 0; f < 12; f++) {
            stab_frame_pass(&g, &p);
            const lpv_volume *l = gi_ilpv_volume(gi_ilpv_of(renderer_gi(g.r)));
            assert_int_equal(lpv_volume_count_nonfinite(l), 0);
            largest = fmax(largest, stab_energy(l) / 3.0 / emitted);
        }
    }
    double chord = stab_mean_chord_cells(&s, gi_ilpv_lattice(gi_ilpv_of(renderer_gi(g.r)))->cell);
    printf("renderer, lambda 0.999 and 1.5: largest lattice energy / emitted %.4f (mean chord "
           "%.3f cells)\n", largest, chord);
    assert_true(largest > 0 && largest <= chord);
    stab_close(&g);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_close_to_one_is_bounded_and_converges),
        cmocka_unit_test(test_one_and_above_are_clamped),
        cmocka_unit_test(test_renderer_near_one),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
