/* The `paper` transport (lpv_paper.h): the transfer vectors and their scale against the
 * closed forms of LPV-MATH.md, the step's energy without blocking and absorption, its
 * scattering loss, the fast path against the scalar reference, the same bits for 1, 2 and
 * 7 threads, the step probability. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_paper.h"
#include "gi/ilpv/lpv_propagate.h"
#include "gi/ilpv/sh.h"
#include "lpv_reference.h"
#include "lpv_testutil.h"

static const double PI = 3.14159265358979323846;
static const lpv_paper_transfer *tr;

static int setup(void **state)
{
    (void)state;
    tr = lpv_paper_transfer_default();
    return tr->search_probes > 0 ? 0 : -1;
}

/* kappa = 1 / sqrt(26 pi / 4) = 0.2213 up to the sampling error: the directional sums
 * sum_j G_j0 G_jk that sampling leaves (imbalance) tilt the energy balance of a
 * distribution by at most imbalance |L_dir| / L_0 <= imbalance c1 / c0, and kappa moves by
 * half of that, plus the search's tolerance. */
static void test_kappa_is_the_closed_form_within_the_sampling_error(void **state)
{
    (void)state;
    double exact = 1.0 / sqrt(26.0 * PI / 4.0);
    double bound = exact * (0.5 * tr->imbalance * SH_COS1 / SH_COS0 + 1e-6);
    printf("kappa %.6f (closed form %.6f, bound %.2g), imbalance %.3g, energy error %.3g, "
           "%d probes\n", tr->kappa, exact, bound, tr->imbalance, tr->energy_error,
           tr->search_probes);
    assert_true(fabs(tr->kappa - exact) <= bound);
    assert_true(tr->imbalance < 1e-3); /* 2^16 samples per neighbour */
    for (int j = 0; j < LPV_NEIGHBOURS; j++) /* every sample's lobe has DC sqrt(pi) / 2 */
        assert_float_equal(tr->gamma[j][0], (float)(tr->kappa * SH_COS0), 1e-7f);
    assert_in_range(tr->search_probes, 10, 60); /* the thesis: 10 to 20 */
    lpv_paper_transfer other; /* another seed: other vectors, the same kappa */
    assert_int_equal(lpv_paper_transfer_compute(&(lpv_paper_desc){.seed = 12345}, &other), 0);
    assert_memory_not_equal(other.gamma, tr->gamma, sizeof tr->gamma);
    assert_true(fabs(other.kappa - exact) <=
                exact * (0.5 * other.imbalance * SH_COS1 / SH_COS0 + 1e-6));
}

static void test_outscattering_fractions_are_one_in_26(void **state)
{
    (void)state;
    double sum = 0.0;
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        assert_float_equal(tr->outscatter[j], 1.0f / 26.0f, 1e-7f);
        sum += tr->outscatter[j];
    }
    assert_float_equal(sum, 1.0, 1e-6);
}

/* Each G_j is a lobe around its neighbour's direction, as wide as its cone allows; the
 * same seed gives the same bits. */
static void test_vectors_point_at_their_neighbours(void **state)
{
    (void)state;
    lpv_paper_transfer again;
    assert_int_equal(lpv_paper_transfer_compute(NULL, &again), 0);
    assert_memory_equal(again.gamma, tr->gamma, sizeof tr->gamma);
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        const int *o = lpv_transfer_offsets[j];
        double l[3] = {-tr->gamma[j][3], -tr->gamma[j][1], tr->gamma[j][2]};
        double len = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
        double olen = sqrt((double)(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]));
        assert_true((l[0] * o[0] + l[1] * o[1] + l[2] * o[2]) / (len * olen) > 0.999);
        /* |mean direction| < 1: the cone's spread (at most 30 degrees off the axis) */
        double mean = len / (tr->kappa * SH_COS1);
        assert_true(mean < 1.0 && mean > cos(30.0 * PI / 180.0));
    }
}

static void test_bad_desc_is_refused(void **state)
{
    (void)state;
    lpv_paper_transfer t;
    assert_int_equal(lpv_paper_transfer_compute(&(lpv_paper_desc){.search_lo = 0.5, .search_hi = 0.1}, &t), -1);
    assert_int_equal(lpv_paper_transfer_compute(&(lpv_paper_desc){.search_lo = -1, .search_hi = 0.4}, &t), -1);
    assert_int_equal(lpv_paper_transfer_compute(&(lpv_paper_desc){.search_lo = 0.1, .search_hi = INFINITY}, &t), -1);
}

/* How far one linear step's energy may be from balance for light with energy coefficient
 * L0 and directional coefficients L1..L3 (LPV-MATH.md: the step conserves energy exactly
 * when sum_j G_j0 G_j = (1, 0, 0, 0)): sum_j G_j0^2 = 26 kappa^2 c0^2 is off 1 by twice
 * kappa's bound, and the sampling imbalance tilts it by imbalance |L_dir| / L0; 1e-6 for
 * the floats. */
static double balance_bound(const float *L0, const float *L1, const float *L2, const float *L3,
                            size_t i)
{
    double dir = sqrt((double)L1[i] * L1[i] + (double)L2[i] * L2[i] + (double)L3[i] * L3[i]);
    return tr->imbalance * (SH_COS1 / SH_COS0 + dir / L0[i]) + 3e-6;
}

/* Light in the middle of a lattice: a lobe of random direction with enough isotropic light
 * that no neighbour's factor is negative (no clamp). Returns the relative energy change of
 * one step with absorption la and scattering ls beyond the closed form *expected, and its
 * bound (balance_bound(), the worst colour). */
static double one_step_energy_change(uint64_t *rng, float la, float ls, double *expected,
                                     double *bound)
{
    const int n[3] = {5, 5, 5};
    lpv_volume src, dst;
    assert_int_equal(lpv_volume_init(&src, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&dst, n, LPV_LIGHT_CHANNELS), 0);
    size_t centre = 2 + 5 * (2 + 5 * 2);
    for (int c = 0; c < 3; c++) {
        float d[3] = {testutil_rand(rng) - 0.5f, testutil_rand(rng) - 0.5f,
                      testutil_rand(rng) - 0.5f}, lobe[4];
        sh_cosine_lobe(d, lobe);
        float a = testutil_rand(rng), iso = a * (0.3f + testutil_rand(rng));
        for (int s = 0; s < 4; s++)
            src.ch[4 * c + s][centre] = a * lobe[s] + (s == 0 ? iso : 0.0f);
    }
    lpv_propagate_step(&(lpv_propagate_desc){.transport = LPV_TRANSPORT_PAPER, .absorption = la,
                                             .scattering = ls},
                       &src, &dst);
    double before = testutil_energy(&src), after = testutil_energy(&dst);
    *bound = 0.0;
    for (int c = 0; c < 3; c++)
        *bound = fmax(*bound, balance_bound(src.ch[4 * c], src.ch[4 * c + 1], src.ch[4 * c + 2],
                                            src.ch[4 * c + 3], centre));
    /* the scattered share arrives as a factor of G_j, whose energy is 2 sqrt(pi) G_j0 */
    *expected = (1.0 - la - ls) + ls * SH_ENERGY * tr->gamma[0][0];
    lpv_volume_free(&src);
    lpv_volume_free(&dst);
    return after / before - *expected;
}

static void test_one_step_keeps_energy_without_blocking_and_absorption(void **state)
{
    (void)state;
    uint64_t rng = 99;
    double worst = 0.0, mean = 0.0, expected, bound;
    for (int trial = 0; trial < 50; trial++) {
        double d = fabs(one_step_energy_change(&rng, 0.0f, 0.0f, &expected, &bound));
        assert_true(expected == 1.0);
        assert_true(d <= bound);
        worst = fmax(worst, d);
        mean += d / 50;
    }
    printf("relative energy change of one step: mean %.3g, largest %.3g\n", mean, worst);
}

/* Absorption removes its share; scattering keeps 2 sqrt(pi) G_j0 = 0.695 of its share, the
 * thesis's loss of scattered light. */
static void test_absorption_and_scattering_closed_form(void **state)
{
    (void)state;
    uint64_t rng = 5;
    const float cases[][2] = {{0.1f, 0.0f}, {0.0f, 0.3f}, {0.05f, 0.2f}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double expected, bound;
        double d = one_step_energy_change(&rng, cases[k][0], cases[k][1], &expected, &bound);
        printf("absorption %.2f scattering %.2f: energy kept %.4f (closed form), off by %.2g\n",
               cases[k][0], cases[k][1], expected, d);
        assert_true(fabs(d) <= bound);
    }
    double expected, bound;
    one_step_energy_change(&rng, 0.0f, 1.0f, &expected, &bound);
    assert_float_equal(expected, 2.0 * sqrt(PI) / sqrt(26.0), 1e-6);
}

/* A pure clamped-cosine lobe (a VPL as injected) sends negative factors backwards, which
 * the clamp drops: its first step gains energy. */
static void test_the_clamp_drops_backward_light(void **state)
{
    (void)state;
    const int n[3] = {5, 5, 5};
    lpv_volume src, dst;
    assert_int_equal(lpv_volume_init(&src, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&dst, n, LPV_LIGHT_CHANNELS), 0);
    float lobe[4];
    sh_cosine_lobe((float[3]){0, 0, 1}, lobe);
    for (int s = 0; s < 4; s++)
        src.ch[s][2 + 5 * (2 + 5 * 2)] = lobe[s];
    lpv_propagate_step(&(lpv_propagate_desc){.transport = LPV_TRANSPORT_PAPER}, &src, &dst);
    double gain = testutil_energy(&dst) / testutil_energy(&src);
    printf("one step of a clamped-cosine lobe: energy x %.4f\n", gain);
    assert_true(gain > 1.01);
    assert_true(dst.ch[0][2 + 5 * (2 + 5 * 1)] == 0.0f); /* nothing straight back */
    assert_true(dst.ch[0][1 + 5 * (2 + 5 * 1)] > 0.0f);  /* the edges behind: 135 degrees */
    lpv_volume_free(&src);
    lpv_volume_free(&dst);
}

static void test_fast_path_matches_reference(void **state)
{
    (void)state;
    const int shapes[][3] = {{1, 1, 1}, {3, 2, 5}, {8, 4, 4}, {9, 3, 3}, {16, 2, 2},
                             {17, 5, 3}, {7, 7, 7}, {130, 3, 2}, {19, 13, 11}};
    const float coeff[][2] = {{0, 0}, {0.1f, 0.05f}, {0.3f, 0.9f}};
    workpool *pool = workpool_create(2);
    for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++) {
        lpv_volume src, fast, ref, acc_fast, acc_ref;
        lpv_blockers b;
        assert_int_equal(lpv_volume_init(&src, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&fast, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&ref, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&acc_fast, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&acc_ref, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_blockers_init(&b, shapes[k]), 0);
        testutil_fill_light(&src, &b, 17 + k);
        testutil_fill_light(&acc_fast, NULL, 99 + k);
        lpv_volume_copy(&acc_ref, &acc_fast);
        for (int blocking = 0; blocking < 2; blocking++)
            for (int c = 0; c < 3; c++) {
                lpv_propagate_desc pd = {.transport = LPV_TRANSPORT_PAPER,
                                         .blockers = blocking ? &b : NULL,
                                         .accum = c == 1 ? &acc_fast : NULL,
                                         .absorption = coeff[c][0], .scattering = coeff[c][1],
                                         .pool = pool};
                lpv_propagate_step(&pd, &src, &fast);
                pd.accum = c == 1 ? &acc_ref : NULL;
                lpv_reference_step(&pd, &src, &ref);
                double d = fmax(testutil_rel_diff(&fast, &ref), testutil_rel_diff(&acc_fast, &acc_ref));
                if (d > 1e-5)
                    printf("shape %d %d %d blocking %d coeff %d: %g\n", shapes[k][0],
                           shapes[k][1], shapes[k][2], blocking, c, d);
                assert_true(d <= 1e-5);
            }
        lpv_volume_free(&src);
        lpv_volume_free(&fast);
        lpv_volume_free(&ref);
        lpv_volume_free(&acc_fast);
        lpv_volume_free(&acc_ref);
        lpv_blockers_free(&b);
    }
    workpool_destroy(pool);
}

static void test_bit_identical_for_1_2_and_7_threads(void **state)
{
    (void)state;
    const int n[3] = {21, 17, 35};
    lpv_volume src, out[3];
    lpv_blockers b;
    assert_int_equal(lpv_volume_init(&src, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_blockers_init(&b, n), 0);
    testutil_fill_light(&src, &b, 3);
    const int threads[3] = {1, 2, 7};
    for (int t = 0; t < 3; t++) {
        assert_int_equal(lpv_volume_init(&out[t], n, LPV_LIGHT_CHANNELS), 0);
        workpool *pool = workpool_create(threads[t]);
        lpv_propagate_desc pd = {.transport = LPV_TRANSPORT_PAPER, .blockers = &b,
                                 .absorption = 0.02f, .scattering = 0.1f, .pool = pool};
        lpv_propagate_step(&pd, &src, &out[t]);
        workpool_destroy(pool);
    }
    for (int t = 1; t < 3; t++)
        assert_true(lpv_volume_checksum(&out[0]) == lpv_volume_checksum(&out[t]));
    for (int t = 0; t < 3; t++)
        lpv_volume_free(&out[t]);
    lpv_volume_free(&src);
    lpv_blockers_free(&b);
}

/* Normalized by the mean neighbour distance: a step of exactly one metre keeps sigma. */
static void test_step_probability_uses_the_mean_neighbour_distance(void **state)
{
    (void)state;
    assert_float_equal(LPV_MEAN_NEIGHBOUR_DISTANCE,
                       (6.0 + 12.0 * sqrt(2.0) + 8.0 * sqrt(3.0)) / 26.0, 1e-7);
    assert_float_equal(lpv_paper_step_probability(0.5f, 1.0f / LPV_MEAN_NEIGHBOUR_DISTANCE), 0.5f, 1e-6f);
    assert_true(lpv_paper_step_probability(0.3f, 1e-6f) < 1e-6f); /* small cells: -> 0 */
    assert_float_equal(lpv_paper_step_probability(1.0f, 0.2f), 1.0f, 0.0f);
    assert_float_equal(lpv_paper_step_probability(NAN, 1.0f), 0.0f, 0.0f);
}

static void test_shader_body_has_every_neighbour(void **state)
{
    (void)state;
    char body[8192];
    assert_true(lpv_paper_shader_body(tr, body, sizeof body) > 0);
    int calls = 0;
    for (const char *p = body; (p = strstr(p, "gather(")) != NULL; p++)
        calls++;
    assert_int_equal(calls, LPV_NEIGHBOURS);
    assert_int_equal(lpv_paper_shader_body(tr, body, 100), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kappa_is_the_closed_form_within_the_sampling_error),
        cmocka_unit_test(test_outscattering_fractions_are_one_in_26),
        cmocka_unit_test(test_vectors_point_at_their_neighbours),
        cmocka_unit_test(test_bad_desc_is_refused),
        cmocka_unit_test(test_one_step_keeps_energy_without_blocking_and_absorption),
        cmocka_unit_test(test_absorption_and_scattering_closed_form),
        cmocka_unit_test(test_the_clamp_drops_backward_light),
        cmocka_unit_test(test_fast_path_matches_reference),
        cmocka_unit_test(test_bit_identical_for_1_2_and_7_threads),
        cmocka_unit_test(test_step_probability_uses_the_mean_neighbour_distance),
        cmocka_unit_test(test_shader_body_has_every_neighbour),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
