#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "lpv/ilpv.h"
#include "lpv/lpv_inject.h"
#include "lpv_testutil.h"

static lpv_transfer tr;

static int setup(void **state)
{
    (void)state;
    return lpv_transfer_compute(NULL, &tr);
}

static void inject(lpv_volume *v, const lattice_desc *lat, float r, float g, float b)
{
    lpv_volume_clear(v);
    float mid = 0.5f * lat->n[0] * lat->cell;
    lpv_vpl vpls[] = {
        {.position = {mid, mid, mid}, .normal = {0.2f, 1, 0.1f}, .flux = {r, g, b}},
        {.position = {mid + 0.3f, mid, mid - 0.4f}, .normal = {-1, 0.3f, 0}, .flux = {r, g, b}},
    };
    lpv_inject_vpls(v, lat, vpls, 2, NULL);
}

/* T: `steps` propagation steps, the first without blocking (none here anyway). */
static void propagate(lpv_volume *v, lpv_volume *tmp, int steps)
{
    lpv_propagate_desc pd = {.transfer = &tr};
    for (int s = 0; s < steps; s++) {
        lpv_propagate_step(&pd, v, tmp);
        lpv_volume_copy(v, tmp);
    }
}

static void test_first_frame_ignores_lambda(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {9, 10, 11}};
    ilpv s;
    assert_int_equal(ilpv_init(&s, &lat), 0);
    ilpv_begin_frame(&s);
    inject(ilpv_injection(&s), &lat, 1, 2, 3);
    lpv_volume expect, tmp;
    assert_int_equal(lpv_volume_init(&expect, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&tmp, lat.n, LPV_LIGHT_CHANNELS), 0);
    lpv_volume_copy(&expect, ilpv_injection(&s));
    propagate(&expect, &tmp, 3);
    ilpv_frame(&s, &(ilpv_frame_desc){.steps = 3, .lambda_incr = 0.8f, .emitted_energy = 1.0,
                                      .propagate = {.transfer = &tr}});
    for (int c = 0; c < 12; c++)
        assert_memory_equal(ilpv_result(&s)->ch[c], expect.ch[c], expect.cells * sizeof(float));
    /* After frames with history, a reset gives the first frame's result again. */
    for (int f = 0; f < 3; f++)
        ilpv_frame(&s, &(ilpv_frame_desc){.steps = 3, .lambda_incr = 0.8f, .emitted_energy = 1.0,
                                          .propagate = {.transfer = &tr}});
    assert_true(lpv_volume_checksum(ilpv_result(&s)) != lpv_volume_checksum(&expect));
    ilpv_reset(&s);
    ilpv_frame(&s, &(ilpv_frame_desc){.steps = 3, .lambda_incr = 0.8f, .emitted_energy = 1.0,
                                      .propagate = {.transfer = &tr}});
    assert_true(lpv_volume_checksum(ilpv_result(&s)) == lpv_volume_checksum(&expect));
    /* No energy last frame (lights off) also forces lambda to 0. */
    ilpv_frame(&s, &(ilpv_frame_desc){.steps = 3, .lambda_incr = 0.8f, .emitted_energy = 0.0,
                                      .propagate = {.transfer = &tr}});
    ilpv_frame(&s, &(ilpv_frame_desc){.steps = 3, .lambda_incr = 0.8f, .emitted_energy = 1.0,
                                      .propagate = {.transfer = &tr}});
    assert_true(lpv_volume_checksum(ilpv_result(&s)) == lpv_volume_checksum(&expect));
    lpv_volume_free(&expect);
    lpv_volume_free(&tmp);
    ilpv_free(&s);
}

/* With static lights the frames converge to L* = (1 - l) sum_k l^k T^(k+1) I. */
static void test_converges_to_geometric_series(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {12, 12, 12}};
    const float lambdas[] = {0.0f, 0.5f, 0.8f, 0.9f};
    const int steps = 2;
    lpv_volume series, term, tmp;
    assert_int_equal(lpv_volume_init(&series, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&term, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&tmp, lat.n, LPV_LIGHT_CHANNELS), 0);
    for (size_t k = 0; k < sizeof lambdas / sizeof lambdas[0]; k++) {
        double l = lambdas[k];
        ilpv s;
        assert_int_equal(ilpv_init(&s, &lat), 0);
        int frames = l > 0.0 ? (int)ceil(log(1e-7) / log(l)) + 5 : 3;
        for (int f = 0; f < frames; f++) {
            ilpv_begin_frame(&s);
            inject(ilpv_injection(&s), &lat, 1, 0.5f, 0.25f);
            ilpv_frame(&s, &(ilpv_frame_desc){.steps = steps, .lambda_incr = (float)l,
                                              .emitted_energy = 7.0, .propagate = {.transfer = &tr}});
        }
        /* The explicit series, truncated where l^k < 1e-8. */
        inject(&term, &lat, 1, 0.5f, 0.25f);
        lpv_volume_clear(&series);
        double w = 1.0 - l;
        for (int i = 0; i < 400 && w > 1e-8; i++, w *= l) {
            propagate(&term, &tmp, steps);
            for (int c = 0; c < 12; c++)
                for (size_t x = 0; x < series.cells; x++)
                    series.ch[c][x] += (float)w * term.ch[c][x];
            if (l == 0.0)
                break;
        }
        double d = testutil_rel_diff(ilpv_result(&s), &series);
        assert_true(d < 1e-4);
        ilpv_free(&s);
    }
    lpv_volume_free(&series);
    lpv_volume_free(&term);
    lpv_volume_free(&tmp);
}

/* Switch the light from red to green with the same emitted energy: the red (stale) energy
 * decays as l^k exactly, the green one grows as 1 - l^k, the total stays. Frames to fall
 * below 1% match ln(0.01) / ln(l). The lattice leaves room so that no light leaves. */
static void test_history_decays_at_the_predicted_rate(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {45, 45, 45}};
    const float lambdas[] = {0.5f, 0.8f, 0.9f};
    for (size_t k = 0; k < sizeof lambdas / sizeof lambdas[0]; k++) {
        double l = lambdas[k];
        ilpv s;
        assert_int_equal(ilpv_init(&s, &lat), 0);
        ilpv_frame_desc fd = {.steps = 1, .lambda_incr = (float)l, .emitted_energy = 3.0,
                              .propagate = {.transfer = &tr}};
        ilpv_begin_frame(&s);
        inject(ilpv_injection(&s), &lat, 1, 0, 0);
        ilpv_frame(&s, &fd);
        double e0[3];
        lpv_volume_energy(ilpv_result(&s), e0);
        int below = -1, predicted = (int)ceil(log(0.01) / log(l));
        for (int f = 1; f <= 20; f++) {
            ilpv_begin_frame(&s);
            inject(ilpv_injection(&s), &lat, 0, 1, 0);
            ilpv_frame(&s, &fd);
            double e[3];
            lpv_volume_energy(ilpv_result(&s), e);
            double decay = pow(l, f);
            assert_true(fabs(e[0] / e0[0] - decay) < 1e-4);
            assert_true(fabs(e[1] / e0[0] - (1.0 - decay)) < 1e-4);
            if (below < 0 && e[0] < 0.01 * e0[0])
                below = f;
        }
        if (predicted <= 20)
            assert_int_equal(below, predicted);
        else
            assert_int_equal(below, -1);
        ilpv_free(&s);
    }
}

/* Lights twice as strong: the merge scales the history with E_now / E_prev, so the total
 * energy follows the lights at once instead of lagging. */
static void test_merge_follows_emitted_energy(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {21, 21, 21}};
    ilpv s;
    assert_int_equal(ilpv_init(&s, &lat), 0);
    ilpv_begin_frame(&s);
    inject(ilpv_injection(&s), &lat, 1, 1, 1);
    ilpv_frame(&s, &(ilpv_frame_desc){.steps = 2, .lambda_incr = 0.8f, .emitted_energy = 1.0,
                                      .propagate = {.transfer = &tr}});
    double e1 = testutil_energy(ilpv_result(&s));
    ilpv_begin_frame(&s);
    inject(ilpv_injection(&s), &lat, 2, 2, 2);
    ilpv_frame(&s, &(ilpv_frame_desc){.steps = 2, .lambda_incr = 0.8f, .emitted_energy = 2.0,
                                      .propagate = {.transfer = &tr}});
    double e2 = testutil_energy(ilpv_result(&s));
    assert_true(fabs(e2 - 2.0 * e1) < 1e-5 * e1);
    /* Zero steps: the result is the merge itself. */
    ilpv_begin_frame(&s);
    inject(ilpv_injection(&s), &lat, 2, 2, 2);
    ilpv_frame(&s, &(ilpv_frame_desc){.steps = 0, .lambda_incr = 0.5f, .emitted_energy = 2.0,
                                      .propagate = {.transfer = &tr}});
    assert_true(fabs(testutil_energy(ilpv_result(&s)) - e2) < 1e-5 * e2);
    ilpv_free(&s);
    lattice_desc bad = {{0, 0, 0}, 0.0f, {4, 4, 4}};
    assert_int_equal(ilpv_init(&s, &bad), -1);
    lattice_desc bad2 = {{0, 0, 0}, 1.0f, {4, 0, 4}};
    assert_int_equal(ilpv_init(&s, &bad2), -1);
}

/* The merge rule both the CPU core and the GL path use: no history, no previous energy, or
 * an energy that cannot be trusted (negative, NaN, inf) mean lambda 0. */
static void test_merge_factors(void **state)
{
    ilpv_history h = {0};
    ilpv_merge m = ilpv_merge_factors(&h, 0.8f, 2.0);
    assert_int_equal(m.with_history, 0);
    assert_true(m.a == 0.0f && m.b == 1.0f);
    ilpv_history_advance(&h, 2.0);
    m = ilpv_merge_factors(&h, 0.8f, 3.0);
    assert_int_equal(m.with_history, 1);
    assert_true(m.a == (float)(3.0 / 2.0 * (double)0.8f) && m.b == (float)(1.0 - (double)0.8f));
    const double untrusted[3] = {-1.0, NAN, INFINITY};
    for (int i = 0; i < 3; i++) {
        m = ilpv_merge_factors(&h, 0.8f, untrusted[i]);
        assert_int_equal(m.with_history, 0);
        assert_true(m.a == 0.0f && m.b == 1.0f);
    }
    ilpv_history_advance(&h, NAN); /* no usable energy: the next frame starts over */
    assert_int_equal(ilpv_merge_factors(&h, 0.8f, 3.0).with_history, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_first_frame_ignores_lambda),
        cmocka_unit_test(test_converges_to_geometric_series),
        cmocka_unit_test(test_history_decays_at_the_predicted_rate),
        cmocka_unit_test(test_merge_follows_emitted_energy),
        cmocka_unit_test(test_merge_factors),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
