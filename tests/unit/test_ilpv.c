/* The incremental core (ilpv.h): a chain sums the ages of this frame's splat, so after k
 * steps in all it equals the classic LPV with k steps, whatever the steps per frame, and it
 * converges (stops changing) once the light has left; a changed injection restarts the
 * chain, and the far part of what was shown, in E_now / E_prev, fills in until the new
 * chain reaches it, fading at least as lambda_incr^k; the rule itself. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gi/ilpv/ilpv.h"
#include "gi/ilpv/lpv_inject.h"
#include "lpv_testutil.h"

static void inject(ilpv *s, float r, float shift)
{
    const lattice_desc *lat = &s->lattice;
    float mid = 0.5f * lat->n[0] * lat->cell;
    lpv_vpl vpls[] = {
        {.position = {mid + shift, mid, mid}, .normal = {0.2f, 1, 0.1f}, .flux = {r, 2 * r, 3 * r}},
        {.position = {mid + 0.3f, mid, mid - 0.4f}, .normal = {-1, 0.3f, 0}, .flux = {r, 2 * r, 3 * r}},
    };
    ilpv_begin_frame(s);
    lpv_inject_vpls(ilpv_injection(s), ilpv_origin(s), lat, vpls, 2, NULL);
}

static void frame(ilpv *s, int steps, float lambda, double energy, float r, float shift)
{
    inject(s, r, shift);
    assert_int_equal(ilpv_frame(s, &(ilpv_frame_desc){.steps = steps, .lambda_incr = lambda,
                                                      .emitted_energy = energy}), 0);
}

/* k steps in all, 1, 4 or 8 per frame: the classic LPV's k-step sum, bit for bit. */
static void test_chain_equals_classic_whatever_the_steps_per_frame(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 0.5f, {12, 9, 10}};
    const int per_frame[3] = {1, 4, 8};
    ilpv c;
    assert_int_equal(ilpv_init(&c, &(ilpv_desc){.lattice = &lat}), 0);
    for (int k = 0; k < 3; k++) {
        ilpv s;
        assert_int_equal(ilpv_init(&s, &(ilpv_desc){.lattice = &lat}), 0);
        for (int f = 0; f < 24 / per_frame[k]; f++)
            frame(&s, per_frame[k], 0.8f, 1.0, 1.0f, 0.0f);
        lpv_volume_copy(ilpv_injection(&c), ilpv_injection(&s));
        lpv_volume_copy(ilpv_origin(&c), ilpv_origin(&s));
        assert_int_equal(ilpv_frame(&c, &(ilpv_frame_desc){.steps = 24, .classic = 1}), 0);
        assert_true(lpv_volume_checksum(ilpv_result(&s)) == lpv_volume_checksum(ilpv_result(&c)));
        ilpv_free(&s);
    }
    ilpv_free(&c);
}

/* Static lights: the result stops changing once the front's light has left the lattice. */
static void test_converges(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 0.5f, {12, 9, 10}};
    ilpv s;
    assert_int_equal(ilpv_init(&s, &(ilpv_desc){.lattice = &lat}), 0);
    uint64_t last = 0;
    int same = 0;
    for (int f = 0; f < 60 && same < 3; f++) {
        frame(&s, 4, 0.8f, 1.0, 1.0f, 0.0f);
        uint64_t sum = lpv_volume_checksum(ilpv_result(&s));
        same = sum == last ? same + 1 : 0;
        last = sum;
    }
    assert_int_equal(same, 3);
    ilpv_free(&s);
}

/* The first frame, a reset and lambda 0 show no history; a moved VPL restarts the chain,
 * and the far part of the last result (the result less the old chain's first-frame sum), in
 * this frame's power, fills in what the new chain lacks: its weight is 1 - (<sum|1> -
 * <early|1>) / <faded|1>, and at most lambda^k k frames later. */
static void test_restart_and_fade(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {10, 10, 10}};
    ilpv s;
    assert_int_equal(ilpv_init(&s, &(ilpv_desc){.lattice = &lat}), 0);
    frame(&s, 3, 0.8f, 1.0, 1.0f, 0.0f);
    lpv_volume first;
    assert_int_equal(lpv_volume_init(&first, lat.n, LPV_LIGHT_CHANNELS), 0);
    lpv_volume_copy(&first, ilpv_result(&s));
    for (int f = 0; f < 3; f++)
        frame(&s, 3, 0.8f, 1.0, 1.0f, 0.0f);
    ilpv_reset(&s);
    frame(&s, 3, 0.8f, 1.0, 1.0f, 0.0f);
    assert_true(lpv_volume_checksum(ilpv_result(&s)) == lpv_volume_checksum(&first));
    for (int f = 0; f < 10; f++)
        frame(&s, 3, 0.8f, 1.0, 1.0f, 0.0f);
    /* Move a VPL with twice the power: faded = 2 x (the last result - its chain's early). */
    lpv_volume shown, early;
    assert_int_equal(lpv_volume_init(&shown, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&early, lat.n, LPV_LIGHT_CHANNELS), 0);
    lpv_volume_copy(&shown, ilpv_result(&s));
    lpv_volume_copy(&early, &s.early);
    frame(&s, 3, 0.5f, 2.0, 2.0f, 0.7f);
    for (size_t i = 0; i < shown.cells; i++) {
        float far = shown.ch[4][i] - early.ch[4][i];
        assert_float_equal(s.faded.ch[4][i], 2.0f * far,
                           1e-5f * (fabsf(shown.ch[4][i]) + fabsf(early.ch[4][i])) + 1e-12f);
    }
    /* The new chain's first frame is its early sum: nothing of the far part is replaced yet. */
    float w = ilpv_faded_weight(&s.history, 0.5f, testutil_energy(ilpv_sum(&s)) - s.history.early_energy);
    assert_true(w == 1.0f);
    for (size_t i = 0; i < shown.cells; i++)
        assert_float_equal(ilpv_result(&s)->ch[4][i], ilpv_sum(&s)->ch[4][i] + s.faded.ch[4][i],
                           1e-5f * (fabsf(ilpv_sum(&s)->ch[4][i]) + fabsf(s.faded.ch[4][i])) + 1e-12f);
    /* ... so the picture keeps its level across the move (twice the power: twice the level). */
    double ratio = testutil_energy(ilpv_result(&s)) / (2.0 * testutil_energy(&shown));
    printf("moved VPL: result energy over 2 x the last one %.4f\n", ratio);
    assert_true(fabs(ratio - 1.0) < 0.05);
    /* Unchanged from then on: the weight falls at least as lambda^k. */
    for (int k = 1; k < 6; k++) {
        frame(&s, 3, 0.5f, 2.0, 2.0f, 0.7f);
        float wk = ilpv_faded_weight(&s.history, 0.5f,
                                     testutil_energy(ilpv_sum(&s)) - s.history.early_energy);
        assert_true(wk <= powf(0.5f, (float)k) + 1e-7f);
    }
    /* lambda 0: nothing faded is kept. */
    frame(&s, 3, 0.0f, 2.0, 2.0f, 0.0f);
    assert_true(lpv_volume_checksum(ilpv_result(&s)) == lpv_volume_checksum(ilpv_sum(&s)));
    lpv_volume_free(&early);
    lpv_volume_free(&shown);
    lpv_volume_free(&first);
    ilpv_free(&s);
}

static void test_history_rule(void **state)
{
    (void)state;
    ilpv_history h = {0};
    ilpv_rule r = ilpv_history_rule(&h, 0.8f, 7, 2.0);
    assert_true(r.restart && r.keep == 0.0f); /* no history yet */
    ilpv_history_advance(&h, r, 4, 7, 2.0, 0.0);
    assert_true(h.chain_steps == 4u && h.chain_frames == 0u);
    r = ilpv_history_rule(&h, 0.8f, 7, 3.0);
    assert_true(!r.restart);
    assert_float_equal(r.keep, 1.5f, 1e-6f);
    ilpv_history_advance(&h, r, 4, 7, 3.0, 0.0);
    assert_true(h.chain_steps == 8u && h.chain_frames == 1u); /* the chain goes on */
    r = ilpv_history_rule(&h, 0.8f, 8, 3.0);
    assert_true(r.restart);
    r = ilpv_history_rule(&h, 0.0f, 7, 3.0);
    assert_true(r.restart && r.keep == 0.0f); /* lambda 0: a new chain every frame */
    const double untrusted[] = {-1.0, NAN, INFINITY};
    for (int i = 0; i < 3; i++)
        assert_true(ilpv_history_rule(&h, 0.8f, 7, untrusted[i]).keep == 0.0f);
    ilpv_history_advance(&h, ilpv_history_rule(&h, 0.8f, 8, 3.0), 4, 8, NAN, 10.0);
    assert_true(h.chain_steps == 4u && h.faded_energy == 10.0);
    assert_true(ilpv_history_rule(&h, 0.8f, 8, 3.0).keep == 0.0f); /* no usable energy */
    /* The faded weight: lambda^k times the share of the energy the chain still lacks. */
    assert_float_equal(ilpv_faded_weight(&h, 0.8f, 4.0), 0.6f, 1e-6f);
    assert_float_equal(ilpv_faded_weight(&h, 0.8f, 12.0), 0.0f, 0.0f);
    assert_float_equal(ilpv_faded_weight(&h, 0.0f, 4.0), 0.0f, 0.0f);
    h.chain_frames = 3;
    assert_float_equal(ilpv_faded_weight(&h, 0.5f, 0.0), 0.125f, 1e-6f);
    assert_float_equal(ilpv_faded_weight(&h, 0.5f, 4.0), 0.075f, 1e-6f);
    /* The key follows the injection and the step probabilities. */
    lattice_desc lat = {{0, 0, 0}, 1.0f, {4, 4, 4}};
    ilpv s;
    assert_int_equal(ilpv_init(&s, &(ilpv_desc){.lattice = &lat}), 0);
    uint64_t k0 = ilpv_injection_key(&s.injected, &s.origin, 0.0f, 0.0f);
    assert_true(ilpv_injection_key(&s.injected, &s.origin, 0.1f, 0.0f) != k0);
    assert_true(ilpv_injection_key(&s.injected, &s.origin, 0.0f, 0.1f) != k0);
    s.origin.ch[0][3] = 1.0f;
    assert_true(ilpv_injection_key(&s.injected, &s.origin, 0.0f, 0.0f) != k0);
    ilpv_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_chain_equals_classic_whatever_the_steps_per_frame),
        cmocka_unit_test(test_converges),
        cmocka_unit_test(test_restart_and_fade),
        cmocka_unit_test(test_history_rule),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
