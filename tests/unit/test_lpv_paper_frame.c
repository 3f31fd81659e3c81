/* The thesis's incremental frame (lpv_paper_frame.h): the merge factors' rule, the level
 * the merge converges to for a constant injection against the closed form
 * (1 - lambda) sum_k lambda^k T^(S(k+1)) I (LPV-MATH.md), the energy-preserving factor
 * when the lights change, the first step unblocked, the same bits for 1, 2 and 7 threads. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gi/ilpv/lpv_paper_frame.h"
#include "gi/ilpv/sh.h"
#include "lpv_testutil.h"

static void test_merge_factors(void **state)
{
    (void)state;
    lpv_paper_history h = {0};
    lpv_paper_merge m = lpv_paper_merge_factors(&h, 0.8f, 10.0); /* first frame */
    assert_true(m.a == 0.0f && m.b == 1.0f);
    lpv_paper_history_advance(&h, 10.0);
    m = lpv_paper_merge_factors(&h, 0.8f, 15.0);
    assert_float_equal(m.a, 1.5f * 0.8f, 1e-7f);
    assert_float_equal(m.b, 0.2f, 1e-7f);
    /* energy-preserving: a E_prev + b E_now = E_now */
    assert_float_equal(m.a * 10.0 + m.b * 15.0, 15.0, 1e-5);
    const double untrusted[] = {-1.0, NAN, INFINITY};
    for (int k = 0; k < 3; k++) {
        m = lpv_paper_merge_factors(&h, 0.8f, untrusted[k]);
        assert_true(m.a == 0.0f && m.b == 1.0f);
    }
    m = lpv_paper_merge_factors(&h, 0.0f, 15.0);
    assert_true(m.a == 0.0f && m.b == 1.0f);
    lpv_paper_history_advance(&h, 0.0); /* dark frame: the next one cannot scale */
    m = lpv_paper_merge_factors(&h, 0.8f, 15.0);
    assert_true(m.a == 0.0f && m.b == 1.0f);
}

enum { N = 12, STEPS = 2 };
static const float LAMBDA = 0.8f;

/* Isotropic light in every cell with a faint tilt: no factor is negative, so the steps are
 * linear and the closed form holds (up to rounding) -- except next to the lattice's faces,
 * where cells receive from one side only and the clamp drops the negative factors they
 * would send back inwards: interior() leaves the outer three layers out. */
static void inject(lpv_volume *v, float scale)
{
    uint64_t rng = 11;
    for (size_t i = 0; i < v->cells; i++)
        for (int c = 0; c < 3; c++) {
            v->ch[4 * c][i] = scale * (0.5f + testutil_rand(&rng));
            v->ch[4 * c + 2][i] = scale * 0.05f * testutil_rand(&rng);
        }
}

/* Largest difference over the cells at least three layers in, relative to the largest
 * value there. */
static double interior_rel_diff(const lpv_volume *a, const lpv_volume *b)
{
    double diff = 0.0, scale = 0.0;
    for (int z = 3; z < N - 3; z++)
        for (int y = 3; y < N - 3; y++)
            for (int x = 3; x < N - 3; x++) {
                size_t i = (size_t)x + N * ((size_t)y + N * (size_t)z);
                for (int c = 0; c < LPV_LIGHT_CHANNELS; c++) {
                    diff = fmax(diff, fabs((double)a->ch[c][i] - b->ch[c][i]));
                    scale = fmax(scale, fabs(b->ch[c][i]));
                }
            }
    return diff / scale;
}

static void propagate(lpv_volume *a, lpv_volume *b, int steps, workpool *pool)
{
    for (int s = 0; s < steps; s++) {
        lpv_propagate_step(&(lpv_propagate_desc){.transport = LPV_TRANSPORT_PAPER, .pool = pool},
                           a, b);
        lpv_volume_copy(a, b);
    }
}

/* Runs frames of the incremental LPV on the injection above with the given pool. */
static void run_frames(lpv_paper_lpv *s, int frames, float scale, workpool *pool)
{
    for (int f = 0; f < frames; f++) {
        lpv_paper_begin_frame(s);
        inject(lpv_paper_injection(s), scale);
        lpv_paper_frame_desc fd = {.steps = STEPS, .lambda_incr = LAMBDA,
                                   .emitted_energy = 10.0 * scale,
                                   .propagate = {.pool = pool}};
        lpv_paper_frame(s, &fd);
    }
}

static void test_steady_state_is_the_geometric_mixture_of_ages(void **state)
{
    (void)state;
    const int n[3] = {N, N, N};
    lattice_desc lat = {{0, 0, 0}, 0.25f, {N, N, N}};
    lpv_paper_lpv s;
    assert_int_equal(lpv_paper_init(&s, &lat), 0);
    run_frames(&s, 80, 1.0f, NULL); /* lambda^80 = 2e-8 */
    /* closed form: (1 - lambda) sum_k lambda^k T^(S(k+1)) I, to a remainder of 1e-8 */
    lpv_volume term, tmp, sum;
    assert_int_equal(lpv_volume_init(&term, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&tmp, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&sum, n, LPV_LIGHT_CHANNELS), 0);
    inject(&term, 1.0f);
    double weight = 1.0 - LAMBDA;
    for (int k = 0; weight > 1e-8; k++) {
        propagate(&term, &tmp, STEPS, NULL);
        lpv_volume_add_scaled(&sum, &term, (float)weight);
        weight *= LAMBDA;
    }
    double d = interior_rel_diff(lpv_paper_result(&s), &sum);
    double e_res = testutil_energy(lpv_paper_result(&s)), e_sum = testutil_energy(&sum);
    printf("steady state against the series: largest difference %.3g, energy %.7g / %.7g\n",
           d, e_res, e_sum);
    assert_true(d < 1e-5);
    assert_true(fabs(e_res - e_sum) < 1e-5 * e_sum);
    /* The lights twice as bright: the merge scales the history by E_now / E_prev, so the
     * very next frame is the steady state of the brighter injection. */
    run_frames(&s, 1, 2.0f, NULL);
    lpv_volume_scale(&sum, 2.0f);
    d = interior_rel_diff(lpv_paper_result(&s), &sum);
    printf("first frame at twice the power against twice the steady state: %.3g\n", d);
    assert_true(d < 1e-5);
    lpv_volume_free(&term);
    lpv_volume_free(&tmp);
    lpv_volume_free(&sum);
    lpv_paper_free(&s);
}

/* The first step of a frame ignores the blockers, the later ones do not. */
static void test_first_step_is_unblocked(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {5, 1, 1}};
    lpv_paper_lpv s;
    assert_int_equal(lpv_paper_init(&s, &lat), 0);
    lpv_blockers b;
    assert_int_equal(lpv_blockers_init(&b, lat.n), 0);
    for (size_t i = 0; i < b.cells; i++)
        b.mask[i] = (1u << LPV_NEIGHBOURS) - 1; /* everything blocked */
    for (int steps = 1; steps <= 2; steps++) {
        lpv_paper_reset(&s);
        lpv_paper_begin_frame(&s);
        lpv_paper_injection(&s)->ch[0][2] = 1.0f;
        lpv_paper_frame(&s, &(lpv_paper_frame_desc){.steps = steps, .emitted_energy = 1.0,
                                                     .propagate = {.blockers = &b}});
        double e = testutil_energy(lpv_paper_result(&s));
        if (steps == 1)
            assert_true(e > 0.0);
        else
            assert_true(e == 0.0);
    }
    lpv_blockers_free(&b);
    lpv_paper_free(&s);
}

static void test_bit_identical_for_1_2_and_7_threads(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 0.25f, {13, 9, 19}};
    uint64_t sums[3];
    const int threads[3] = {1, 2, 7};
    for (int t = 0; t < 3; t++) {
        lpv_paper_lpv s;
        assert_int_equal(lpv_paper_init(&s, &lat), 0);
        workpool *pool = workpool_create(threads[t]);
        run_frames(&s, 3, 1.0f, pool);
        run_frames(&s, 1, 1.5f, pool);
        sums[t] = lpv_volume_checksum(lpv_paper_result(&s));
        workpool_destroy(pool);
        lpv_paper_free(&s);
    }
    assert_true(sums[0] == sums[1] && sums[0] == sums[2]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_merge_factors),
        cmocka_unit_test(test_steady_state_is_the_geometric_mixture_of_ages),
        cmocka_unit_test(test_first_step_is_unblocked),
        cmocka_unit_test(test_bit_identical_for_1_2_and_7_threads),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
