/* Classic LPV accumulation: 0 steps give black; the sum over steps equals the sum of the
 * scalar reference's steps (first unblocked, then blocked, with absorption and
 * scattering); the result is bit-identical for 1, 2 and 3 threads and does not depend on
 * the previous frame. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lpv/lpv_classic.h"
#include "lpv_reference.h"
#include "lpv_testutil.h"

static lpv_transfer tr;

static int setup(void **state)
{
    (void)state;
    return lpv_transfer_compute(NULL, &tr);
}

/* Random light in a few cells (the rest zero, so light spreads) and random blockers. */
static void fill(lpv_volume *light, lpv_volume *geo, uint64_t seed)
{
    uint64_t rng = seed;
    lpv_volume_clear(light);
    for (int k = 0; k < 6; k++) {
        size_t i = (size_t)(testutil_rand(&rng) * light->cells);
        for (int c = 0; c < 3; c++) {
            light->ch[4 * c][i] = 1.0f + testutil_rand(&rng);
            for (int s = 1; s < 4; s++)
                light->ch[4 * c + s][i] = 1.2f * (testutil_rand(&rng) - 0.5f);
        }
    }
    for (size_t i = 0; i < geo->cells; i++) {
        geo->ch[0][i] = testutil_rand(&rng) < 0.8f ? 0.0f : 3.0f * testutil_rand(&rng);
        for (int s = 1; s < 4; s++)
            geo->ch[s][i] = geo->ch[0][i] * (testutil_rand(&rng) - 0.5f);
    }
}

static void test_zero_steps_is_black(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 0.5f, {7, 5, 6}};
    lpv_volume in, geo;
    assert_int_equal(lpv_volume_init(&in, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&geo, lat.n, LPV_GEOMETRY_CHANNELS), 0);
    fill(&in, &geo, 3);
    lpv_classic c;
    assert_int_equal(lpv_classic_init(&c, &lat), 0);
    lpv_propagate_desc pd = {.transfer = &tr, .geometry = &geo, .use_blocking = 1};
    lpv_classic_frame(&c, &in, 3, &pd);
    assert_true(testutil_energy(lpv_classic_result(&c)) > 0.0);
    lpv_classic_frame(&c, &in, 0, &pd); /* after a lit frame: nothing stale survives */
    for (int ch = 0; ch < LPV_LIGHT_CHANNELS; ch++)
        for (size_t i = 0; i < in.cells; i++)
            assert_true(lpv_classic_result(&c)->ch[ch][i] == 0.0f);
    lpv_classic_free(&c);
    lpv_volume_free(&in);
    lpv_volume_free(&geo);
}

static void test_sum_matches_reference_steps(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 0.5f, {11, 9, 13}};
    const int steps = 6;
    lpv_volume in, geo, a, b, sum;
    assert_int_equal(lpv_volume_init(&in, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&geo, lat.n, LPV_GEOMETRY_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&a, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&sum, lat.n, LPV_LIGHT_CHANNELS), 0);
    fill(&in, &geo, 11);
    /* The reference: each step separately, summed in double. */
    lpv_volume_copy(&a, &in);
    double *acc = calloc(LPV_LIGHT_CHANNELS * in.cells, sizeof *acc);
    assert_non_null(acc);
    for (int s = 0; s < steps; s++) {
        lpv_reference_desc rd = {.transfer = &tr, .geometry = &geo, .use_blocking = s > 0,
                                 .absorption = 0.05f, .scattering = 0.1f};
        lpv_reference_step(&rd, &a, &b);
        lpv_volume_copy(&a, &b);
        for (int ch = 0; ch < LPV_LIGHT_CHANNELS; ch++)
            for (size_t i = 0; i < in.cells; i++)
                acc[ch * in.cells + i] += a.ch[ch][i];
    }
    for (int ch = 0; ch < LPV_LIGHT_CHANNELS; ch++)
        for (size_t i = 0; i < in.cells; i++)
            sum.ch[ch][i] = (float)acc[ch * in.cells + i];
    free(acc);

    uint64_t first = 0;
    for (int threads = 1; threads <= 3; threads++) {
        workpool *pool = workpool_create(threads);
        lpv_classic c;
        assert_int_equal(lpv_classic_init(&c, &lat), 0);
        lpv_propagate_desc pd = {.transfer = &tr, .geometry = &geo, .use_blocking = 1,
                                 .absorption = 0.05f, .scattering = 0.1f, .pool = pool};
        lpv_classic_frame(&c, &in, steps, &pd);
        double d = testutil_rel_diff(lpv_classic_result(&c), &sum);
        printf("threads %d: relative difference to the reference sum %.3g\n", threads, d);
        assert_true(d < 1e-5);
        /* More light than one step holds: the sum is not just the last step. */
        assert_true(testutil_energy(lpv_classic_result(&c)) > 2.0 * testutil_energy(&a));
        uint64_t sum_bits = lpv_volume_checksum(lpv_classic_result(&c));
        if (threads == 1)
            first = sum_bits;
        assert_true(sum_bits == first);
        /* No history: the same injection gives the same bits again. */
        lpv_classic_frame(&c, &in, steps, &pd);
        assert_true(lpv_volume_checksum(lpv_classic_result(&c)) == first);
        lpv_classic_free(&c);
        workpool_destroy(pool);
    }
    lpv_volume_free(&in);
    lpv_volume_free(&geo);
    lpv_volume_free(&a);
    lpv_volume_free(&b);
    lpv_volume_free(&sum);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_zero_steps_is_black),
        cmocka_unit_test(test_sum_matches_reference_steps),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
