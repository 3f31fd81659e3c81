#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <xmmintrin.h>

#include "lpv/lpv_geometry.h"
#include "lpv/lpv_inject.h"
#include "lpv/lpv_propagate.h"
#include "lpv_reference.h"
#include "lpv_testutil.h"
#include "lpv/sh.h"

static lpv_transfer tr;

static int setup(void **state)
{
    (void)state;
    return lpv_transfer_compute(NULL, &tr);
}

/* Light with a positive energy and a strong direction in every cell, and blocking in
 * [-0.2, 1.8]-ish so that the clamp to [0, 1] is exercised on both sides. */
static void fill_random(lpv_volume *light, lpv_volume *geo, uint64_t seed)
{
    uint64_t rng = seed;
    for (size_t i = 0; i < light->cells; i++)
        for (int c = 0; c < 3; c++) {
            light->ch[4 * c][i] = testutil_rand(&rng);
            for (int s = 1; s < 4; s++)
                light->ch[4 * c + s][i] = 1.2f * (testutil_rand(&rng) - 0.5f);
        }
    if (geo)
        for (size_t i = 0; i < geo->cells; i++) {
            geo->ch[0][i] = testutil_rand(&rng) < 0.7f ? 0.0f : 4.0f * testutil_rand(&rng);
            for (int s = 1; s < 4; s++)
                geo->ch[s][i] = geo->ch[0][i] * (testutil_rand(&rng) - 0.5f);
        }
}

static void test_fast_path_matches_reference(void **state)
{
    (void)state;
    const int shapes[][3] = {{1, 1, 1}, {3, 2, 5}, {8, 4, 4}, {9, 3, 3}, {16, 2, 2},
                             {17, 5, 3}, {7, 7, 7}, {130, 3, 2}, {19, 13, 11}};
    const float coeff[][2] = {{0, 0}, {0.1f, 0.05f}, {0.3f, 0.9f}};
    workpool *pool = workpool_create(2);
    for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++) {
        lpv_volume src, fast, ref, geo;
        assert_int_equal(lpv_volume_init(&src, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&fast, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&ref, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&geo, shapes[k], LPV_GEOMETRY_CHANNELS), 0);
        fill_random(&src, &geo, 17 + k);
        for (int blocking = 0; blocking < 2; blocking++)
            for (int clamp = 0; clamp < 2; clamp++)
                for (size_t c = 0; c < sizeof coeff / sizeof coeff[0]; c++) {
                    lpv_propagate_desc pd = {.transfer = &tr, .geometry = &geo,
                                             .use_blocking = blocking, .absorption = coeff[c][0],
                                             .scattering = coeff[c][1], .clamp_negative = clamp,
                                             .pool = pool};
                    lpv_reference_desc rd = {.transfer = &tr, .geometry = &geo,
                                             .use_blocking = blocking, .absorption = coeff[c][0],
                                             .scattering = coeff[c][1], .clamp_negative = clamp};
                    lpv_propagate_step(&pd, &src, &fast);
                    lpv_reference_step(&rd, &src, &ref);
                    double d = testutil_rel_diff(&fast, &ref);
                    if (d >= 1e-5)
                        printf("shape %d %d %d blocking %d clamp %d coeff %zu: rel diff %g\n",
                               shapes[k][0], shapes[k][1], shapes[k][2], blocking, clamp, c, d);
                    assert_true(d < 1e-5);
                }
        lpv_volume_free(&src);
        lpv_volume_free(&fast);
        lpv_volume_free(&ref);
        lpv_volume_free(&geo);
    }
    workpool_destroy(pool);
}

/* 1, 2 and 7 threads give the same bits after several blocked, scattering steps. */
static void test_bit_identical_for_any_thread_count(void **state)
{
    (void)state;
    int n[3] = {37, 17, 21};
    lpv_volume init, geo, a, b;
    assert_int_equal(lpv_volume_init(&init, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&geo, n, LPV_GEOMETRY_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&a, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, n, LPV_LIGHT_CHANNELS), 0);
    fill_random(&init, &geo, 5);
    const int threads[] = {1, 2, 7};
    uint64_t sums[3];
    lpv_volume first;
    assert_int_equal(lpv_volume_init(&first, n, LPV_LIGHT_CHANNELS), 0);
    for (int t = 0; t < 3; t++) {
        workpool *pool = workpool_create(threads[t]);
        assert_non_null(pool);
        assert_int_equal(workpool_threads(pool), threads[t]);
        lpv_volume_copy(&a, &init);
        for (int step = 0; step < 4; step++) {
            lpv_propagate_desc pd = {.transfer = &tr, .geometry = &geo, .use_blocking = step > 0,
                                     .absorption = 0.05f, .scattering = 0.1f,
                                     .clamp_negative = step == 3, .pool = pool};
            lpv_propagate_step(&pd, step % 2 ? &b : &a, step % 2 ? &a : &b);
        }
        sums[t] = lpv_volume_checksum(&a);
        if (t == 0)
            lpv_volume_copy(&first, &a);
        else
            for (int c = 0; c < 12; c++)
                assert_memory_equal(first.ch[c], a.ch[c], a.cells * sizeof(float));
        workpool_destroy(pool);
    }
    assert_true(sums[0] == sums[1] && sums[1] == sums[2]);
    lpv_volume_free(&init);
    lpv_volume_free(&geo);
    lpv_volume_free(&a);
    lpv_volume_free(&b);
    lpv_volume_free(&first);
}

/* A GL driver may leave the calling thread flushing denormals while the pool's workers
 * do not (llvmpipe does). Light near the denormal range must still give the same bits
 * whatever mode the caller is in and however many threads share the work. */
static void test_caller_fp_mode_does_not_matter(void **state)
{
    (void)state;
    int n[3] = {24, 9, 17};
    lpv_volume init, a, b;
    assert_int_equal(lpv_volume_init(&init, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&a, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, n, LPV_LIGHT_CHANNELS), 0);
    fill_random(&init, NULL, 11);
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++)
        for (size_t i = 0; i < init.cells; i++)
            init.ch[c][i] *= 1e-36f; /* a few steps of products land below 1.2e-38 */
    uint64_t sums[3];
    const int threads[] = {1, 2, 2};
    const int caller_flushes[] = {0, 0, 1};
    for (int t = 0; t < 3; t++) {
        workpool *pool = workpool_create(threads[t]);
        assert_non_null(pool);
        unsigned saved = _mm_getcsr();
        if (caller_flushes[t])
            _mm_setcsr(saved | 0x8040); /* flush-to-zero and denormals-are-zero */
        lpv_volume_copy(&a, &init);
        for (int step = 0; step < 4; step++) {
            lpv_propagate_desc pd = {.transfer = &tr, .pool = pool};
            lpv_propagate_step(&pd, step % 2 ? &b : &a, step % 2 ? &a : &b);
        }
        _mm_setcsr(saved);
        sums[t] = lpv_volume_checksum(&a);
        workpool_destroy(pool);
    }
    assert_true(sums[0] == sums[1]);
    assert_true(sums[0] == sums[2]);
    lpv_volume_free(&init);
    lpv_volume_free(&a);
    lpv_volume_free(&b);
}

static void inject_centre(lpv_volume *v, const lattice_desc *lat, uint64_t seed)
{
    uint64_t rng = seed;
    lpv_vpl vpls[64];
    float mid = 0.5f * lat->n[0] * lat->cell;
    for (int i = 0; i < 64; i++)
        for (int a = 0; a < 3; a++) {
            vpls[i].position[a] = mid + 2.0f * (testutil_rand(&rng) - 0.5f) * lat->cell;
            vpls[i].normal[a] = testutil_rand(&rng) - 0.5f;
            vpls[i].flux[a] = 0.1f + testutil_rand(&rng);
        }
    lpv_inject_vpls(v, lat, vpls, 64, NULL);
}

/* Away from the borders, every unblocked step keeps the energy (exactly, up to round-off),
 * and absorption removes l_a of it per step while scattering keeps it. */
static void test_energy_per_step(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {25, 25, 25}};
    lpv_volume a, b;
    assert_int_equal(lpv_volume_init(&a, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, lat.n, LPV_LIGHT_CHANNELS), 0);
    const float coeff[][2] = {{0, 0}, {0, 0.3f}, {0.1f, 0.05f}};
    for (int c = 0; c < 3; c++) {
        lpv_volume_clear(&a);
        inject_centre(&a, &lat, 3);
        lpv_propagate_desc pd = {.transfer = &tr, .absorption = coeff[c][0], .scattering = coeff[c][1]};
        for (int step = 0; step < 9; step++) { /* light reaches at most 9 + 2 cells out */
            double before = testutil_energy(step % 2 ? &b : &a);
            lpv_propagate_step(&pd, step % 2 ? &b : &a, step % 2 ? &a : &b);
            double after = testutil_energy(step % 2 ? &a : &b);
            double expect = before * (1.0 - coeff[c][0]);
            assert_true(fabs(after - expect) < 2e-6 * before);
        }
    }
    lpv_volume_free(&a);
    lpv_volume_free(&b);
}

/* 1000 steps with blocking, scattering and light leaving at the borders, re-emitting the
 * injected light before every step (a light that stays on): nothing turns into NaN or Inf,
 * the energy never exceeds what was emitted so far, and it settles to a steady state. */
static void test_thousand_steps_stay_finite_and_bounded(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {10, 12, 14}};
    lpv_volume a, b, inj, geo;
    assert_int_equal(lpv_volume_init(&a, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&inj, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&geo, lat.n, LPV_GEOMETRY_CHANNELS), 0);
    /* An open box (5 faces of both orientations) around the light. */
    float box[] = {1, 1, 1, 9, 1, 1, 9, 11, 1, 1, 11, 1, 1, 1, 13, 9, 1, 13, 9, 11, 13, 1, 11, 13};
    unsigned faces[] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 0, 4, 7, 0, 7, 3,
                        1, 2, 6, 1, 6, 5};
    unsigned flipped[30];
    for (int t = 0; t < 10; t++) {
        flipped[3 * t] = faces[3 * t];
        flipped[3 * t + 1] = faces[3 * t + 2];
        flipped[3 * t + 2] = faces[3 * t + 1];
    }
    lpv_geometry_add_triangles(&geo, &lat, box, 8, faces, 10, NULL);
    lpv_geometry_add_triangles(&geo, &lat, box, 8, flipped, 10, NULL);
    inject_centre(&inj, &lat, 11);
    double e_inj = testutil_energy(&inj);
    for (int clamp = 0; clamp < 2; clamp++) {
        lpv_volume_clear(&a);
        lpv_propagate_desc pd = {.transfer = &tr, .geometry = &geo, .use_blocking = 1,
                                 .scattering = 0.05f, .absorption = 0.01f, .clamp_negative = clamp};
        double e = 0.0, e_prev = 0.0;
        for (int step = 0; step < 1000; step++) {
            for (int c = 0; c < LPV_LIGHT_CHANNELS; c++)
                for (size_t i = 0; i < a.cells; i++)
                    a.ch[c][i] += inj.ch[c][i];
            lpv_propagate_step(&pd, &a, &b);
            lpv_volume_copy(&a, &b);
            e_prev = e;
            e = testutil_energy(&a);
            assert_true(isfinite(e));
            /* The clamp removes negative light and so adds a little energy. */
            assert_true(e <= (step + 1) * e_inj * (clamp ? 1.02 : 1.0 + 1e-5));
            if (step % 100 == 99)
                assert_int_equal(lpv_volume_count_nonfinite(&a), 0);
        }
        assert_true(e > 0.5 * e_inj);
        assert_true(fabs(e - e_prev) < 1e-5 * e); /* steady */
    }
    lpv_volume_free(&a);
    lpv_volume_free(&b);
    lpv_volume_free(&inj);
    lpv_volume_free(&geo);
}

/* A wall between the light and the far side: blocking keeps most light on the near side. */
static void test_wall_blocks_light(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {16, 16, 16}};
    lpv_volume a, b, geo;
    assert_int_equal(lpv_volume_init(&a, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&geo, lat.n, LPV_GEOMETRY_CHANNELS), 0);
    /* A wall at x = 10.5 facing -x (towards the light) and its back face. */
    float wall[] = {10.5f, 0, 0, 10.5f, 0, 16, 10.5f, 16, 16, 10.5f, 16, 0};
    unsigned front[] = {0, 1, 2, 0, 2, 3}, back[] = {0, 2, 1, 0, 3, 2};
    lpv_geometry_add_triangles(&geo, &lat, wall, 4, front, 2, NULL);
    lpv_geometry_add_triangles(&geo, &lat, wall, 4, back, 2, NULL);
    double beyond[2];
    for (int blocking = 0; blocking < 2; blocking++) {
        lpv_volume_clear(&a);
        lpv_vpl vpl = {.position = {6.5f, 8, 8}, .normal = {1, 0, 0}, .flux = {1, 1, 1}};
        lpv_inject_vpls(&a, &lat, &vpl, 1, NULL);
        lpv_propagate_desc pd = {.transfer = &tr, .geometry = &geo};
        for (int step = 0; step < 8; step++) {
            pd.use_blocking = blocking && step > 0;
            lpv_propagate_step(&pd, step % 2 ? &b : &a, step % 2 ? &a : &b);
        }
        double e = 0.0;
        for (int z = 0; z < 16; z++)
            for (int y = 0; y < 16; y++)
                for (int x = 11; x < 16; x++)
                    e += a.ch[0][x + 16 * (y + 16 * z)];
        beyond[blocking] = e;
    }
    assert_true(beyond[0] > 0.0);
    assert_true(beyond[1] < 0.25 * beyond[0]);
    lpv_volume_free(&a);
    lpv_volume_free(&b);
    lpv_volume_free(&geo);
}

/* LPV-MATH.md: a lattice whose cells all hold the same L maps, away from the borders, to
 * the same DC and a direction shrunk by the diagonal of sum_j G_j G_j^T's lower block. */
static void test_uniform_lattice_keeps_dc_and_shrinks_direction(void **state)
{
    (void)state;
    int n[3] = {7, 6, 5};
    lpv_volume a, b;
    assert_int_equal(lpv_volume_init(&a, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, n, LPV_LIGHT_CHANNELS), 0);
    const float L[4] = {1.0f, 0.3f, -0.5f, 0.2f};
    for (int c = 0; c < 12; c++)
        for (size_t i = 0; i < a.cells; i++)
            a.ch[c][i] = L[c % 4] * (1.0f + c / 4);
    double m[4][4] = {{0}};
    for (int j = 0; j < LPV_NEIGHBOURS; j++)
        for (int k = 0; k < 4; k++)
            for (int l = 0; l < 4; l++)
                m[k][l] += (double)tr.gamma[j][k] * tr.gamma[j][l];
    lpv_propagate_step(&(lpv_propagate_desc){.transfer = &tr}, &a, &b);
    size_t centre = 3 + 7 * (3 + 6 * 2);
    for (int c = 0; c < 3; c++) {
        assert_true(fabs(b.ch[4 * c][centre] - a.ch[4 * c][centre]) < 1e-5 * a.ch[4 * c][centre]);
        for (int k = 1; k < 4; k++) {
            double expect = 0.0;
            for (int l = 0; l < 4; l++)
                expect += m[k][l] * a.ch[4 * c + l][centre];
            assert_true(fabs(b.ch[4 * c + k][centre] - expect) < 1e-5 * (1.0 + c));
            /* Uniform shrink by about 0.4, up to the sampling noise of the vectors. */
            double uniform = m[1][1] * a.ch[4 * c + k][centre];
            assert_true(fabs(b.ch[4 * c + k][centre] - uniform) < 0.01 * (1.0 + c));
            assert_in_range((long)(m[k][k] * 1000), 380, 460);
        }
    }
    lpv_volume_free(&a);
    lpv_volume_free(&b);
}

static void test_bad_arguments_leave_destination_alone(void **state)
{
    (void)state;
    lpv_volume a, b, small;
    assert_int_equal(lpv_volume_init(&a, (int[3]){4, 4, 4}, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, (int[3]){4, 4, 4}, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&small, (int[3]){4, 4, 3}, LPV_LIGHT_CHANNELS), 0);
    fill_random(&a, NULL, 9);
    fill_random(&b, NULL, 10);
    fill_random(&small, NULL, 11);
    uint64_t before = lpv_volume_checksum(&b), before_small = lpv_volume_checksum(&small);
    lpv_propagate_step(&(lpv_propagate_desc){.transfer = &tr}, &a, &small);
    lpv_propagate_step(&(lpv_propagate_desc){.transfer = NULL}, &a, &b);
    lpv_propagate_step(&(lpv_propagate_desc){.transfer = &tr}, &b, &b);
    assert_true(lpv_volume_checksum(&b) == before);
    assert_true(lpv_volume_checksum(&small) == before_small);
    /* NaN coefficients count as zero; a mismatched geometry volume means no blocking. */
    lpv_volume geo;
    assert_int_equal(lpv_volume_init(&geo, (int[3]){4, 4, 3}, LPV_GEOMETRY_CHANNELS), 0);
    lpv_propagate_step(&(lpv_propagate_desc){.transfer = &tr, .absorption = NAN, .scattering = NAN,
                                             .geometry = &geo, .use_blocking = 1}, &a, &b);
    assert_int_equal(lpv_volume_count_nonfinite(&b), 0);
    assert_true(lpv_propagate_flops(100, 1) > lpv_propagate_flops(100, 0));
    assert_true(lpv_propagate_flops(200, 0) == 2 * lpv_propagate_flops(100, 0));
    lpv_volume_free(&geo);
    lpv_volume_free(&a);
    lpv_volume_free(&b);
    lpv_volume_free(&small);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fast_path_matches_reference),
        cmocka_unit_test(test_bit_identical_for_any_thread_count),
        cmocka_unit_test(test_caller_fp_mode_does_not_matter),
        cmocka_unit_test(test_energy_per_step),
        cmocka_unit_test(test_thousand_steps_stay_finite_and_bounded),
        cmocka_unit_test(test_wall_blocks_light),
        cmocka_unit_test(test_uniform_lattice_keeps_dc_and_shrinks_direction),
        cmocka_unit_test(test_bad_arguments_leave_destination_alone),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
