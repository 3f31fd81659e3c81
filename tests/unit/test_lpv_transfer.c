#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "lpv/lpv_propagate.h"
#include "lpv_testutil.h"
#include "lpv/lpv_transfer.h"
#include "lpv/sh.h"

static lpv_transfer tr;

static int setup(void **state)
{
    (void)state;
    return lpv_transfer_compute(NULL, &tr);
}

static void test_scale_matches_the_analytic_factor(void **state)
{
    (void)state;
    double kappa = 1.0 / sqrt(26.0 * 3.14159265358979 / 4.0); /* LPV-MATH.md */
    assert_true(fabs(tr.kappa - kappa) < 1e-5);
    for (int j = 0; j < LPV_NEIGHBOURS; j++)
        assert_true(fabs(tr.gamma[j][0] - 1.0 / sqrt(26.0)) < 1e-5);
    assert_true(tr.energy_error < 1e-4);
    assert_in_range(tr.search_probes, 10, 60);
}

static void test_outscattering_fractions_are_uniform(void **state)
{
    (void)state;
    double sum = 0.0;
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        assert_true(fabs(tr.outscatter[j] - 1.0 / 26.0) < 1e-6);
        sum += tr.outscatter[j];
    }
    assert_true(fabs(sum - 1.0) < 1e-6);
}

static void test_vectors_point_at_their_neighbours_and_are_deterministic(void **state)
{
    (void)state;
    lpv_transfer again;
    assert_int_equal(lpv_transfer_compute(&(lpv_transfer_desc){0}, &again), 0);
    assert_memory_equal(again.gamma, tr.gamma, sizeof tr.gamma);
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        const int *o = lpv_transfer_offsets[j];
        float dir[3] = {(float)o[0], (float)o[1], (float)o[2]};
        /* The lobe's direction (SH_cos convention) is close to the neighbour's. */
        float lx = -tr.gamma[j][3], ly = -tr.gamma[j][1], lz = tr.gamma[j][2];
        float len = sqrtf(lx * lx + ly * ly + lz * lz);
        float olen = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        float cosang = (lx * dir[0] + ly * dir[1] + lz * dir[2]) / (len * olen);
        assert_true(cosang > 0.999f);
        /* Antipodal neighbours have mirrored vectors. */
        const float *m = tr.gamma[LPV_NEIGHBOURS - 1 - j];
        assert_true(m[0] == tr.gamma[j][0] && m[1] == -tr.gamma[j][1] &&
                    m[2] == -tr.gamma[j][2] && m[3] == -tr.gamma[j][3]);
    }
    lpv_transfer other;
    assert_int_equal(lpv_transfer_compute(&(lpv_transfer_desc){.seed = 12345}, &other), 0);
    assert_memory_not_equal(other.gamma, tr.gamma, sizeof tr.gamma);
    assert_true(fabs(other.kappa - tr.kappa) < 1e-5);
}

/* The lower 3x3 block of sum_j G_j G_j^T is a multiple of the identity (LPV-MATH.md). */
static void test_directional_part_decays_isotropically(void **state)
{
    (void)state;
    double m[4][4] = {{0}};
    for (int j = 0; j < LPV_NEIGHBOURS; j++)
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++)
                m[r][c] += (double)tr.gamma[j][r] * tr.gamma[j][c];
    assert_true(fabs(m[0][0] - 1.0) < 1e-5);
    for (int r = 1; r < 4; r++) {
        assert_true(fabs(m[0][r]) < 1e-6);
        assert_in_range((long)(m[r][r] * 1000), 300, 700);
        assert_true(fabs(m[r][r] - m[1][1]) < 0.02 * m[1][1]);
        for (int c = 1; c < 4; c++)
            if (c != r)
                assert_true(fabs(m[r][c]) < 0.01 * m[1][1]);
    }
}

/* One unblocked step out of a single interior cell keeps the energy of any distribution. */
static void test_one_step_conserves_energy(void **state)
{
    (void)state;
    int n[3] = {5, 5, 5};
    lpv_volume src, dst;
    assert_int_equal(lpv_volume_init(&src, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&dst, n, LPV_LIGHT_CHANNELS), 0);
    uint64_t rng = 99;
    lpv_propagate_desc pd = {.transfer = &tr};
    for (int trial = 0; trial < 20; trial++) {
        lpv_volume_clear(&src);
        size_t centre = 2 + 5 * (2 + 5 * 2);
        for (int c = 0; c < 3; c++) {
            float dir[3] = {testutil_rand(&rng) - 0.5f, testutil_rand(&rng) - 0.5f, testutil_rand(&rng) - 0.5f};
            float lobe[4];
            sh_cosine_lobe(dir, lobe);
            for (int s = 0; s < 4; s++) /* directional enough to send negative light back */
                src.ch[4 * c + s][centre] = (1.0f + testutil_rand(&rng)) * lobe[s] * (s ? 1.5f : 1.0f);
        }
        lpv_propagate_step(&pd, &src, &dst);
        double before[3], after[3];
        lpv_volume_energy(&src, before);
        lpv_volume_energy(&dst, after);
        for (int c = 0; c < 3; c++)
            assert_true(fabs(after[c] - before[c]) < 1e-5 * before[c]);
    }
    lpv_volume_free(&src);
    lpv_volume_free(&dst);
}

static void test_step_probability_limits(void **state)
{
    (void)state;
    assert_float_equal(lpv_transfer_step_probability(0.3f, 0.0f), 0.0f, 0.0f);
    assert_true(lpv_transfer_step_probability(0.3f, 1e-6f) < 1e-6f); /* small cells: -> 0 */
    assert_float_equal(lpv_transfer_step_probability(1.0f, 0.2f), 1.0f, 0.0f);
    assert_float_equal(lpv_transfer_step_probability(0.0f, 0.2f), 0.0f, 0.0f);
    /* One step of exactly one metre keeps sigma. */
    assert_float_equal(lpv_transfer_step_probability(0.5f, 1.0f / LPV_MEAN_NEIGHBOUR_DISTANCE), 0.5f, 1e-6f);
    float prev = 0.0f;
    for (int k = 1; k <= 10; k++) { /* grows with the cell and stays a probability */
        float p = lpv_transfer_step_probability(0.2f, 0.25f * k);
        assert_true(p > prev && p <= 1.0f);
        prev = p;
    }
    assert_float_equal(lpv_transfer_step_probability(NAN, 1.0f), 0.0f, 0.0f);
    assert_float_equal(lpv_transfer_step_probability(-1.0f, 1.0f), 0.0f, 0.0f);
    assert_float_equal(lpv_transfer_step_probability(7.0f, 1.0f), 1.0f, 0.0f);
    assert_float_equal(lpv_transfer_step_probability(0.5f, NAN), 0.0f, 0.0f);
}

static void test_bad_search_interval_is_refused(void **state)
{
    (void)state;
    lpv_transfer t;
    assert_int_equal(lpv_transfer_compute(&(lpv_transfer_desc){.search_lo = 0.5, .search_hi = 0.1}, &t), -1);
    assert_int_equal(lpv_transfer_compute(&(lpv_transfer_desc){.search_lo = -1, .search_hi = 0.4}, &t), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scale_matches_the_analytic_factor),
        cmocka_unit_test(test_outscattering_fractions_are_uniform),
        cmocka_unit_test(test_vectors_point_at_their_neighbours_and_are_deterministic),
        cmocka_unit_test(test_directional_part_decays_isotropically),
        cmocka_unit_test(test_one_step_conserves_energy),
        cmocka_unit_test(test_step_probability_limits),
        cmocka_unit_test(test_bad_search_interval_is_refused),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
