/* One propagation step (lpv_propagate.h): the fast path against the scalar reference,
 * bit-identical for any thread count, energy kept, beams moving one cell per step, a
 * uniform field staying uniform, blocking in both directions, bad arguments. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_propagate.h"
#include "gi/ilpv/sh.h"
#include "lpv_reference.h"
#include "lpv_testutil.h"

static void test_fast_path_matches_reference(void **state)
{
    (void)state;
    const int shapes[][3] = {{1, 1, 1}, {3, 2, 5}, {8, 4, 4}, {9, 3, 3}, {16, 2, 2},
                             {17, 5, 3}, {7, 7, 7}, {130, 3, 2}, {19, 13, 11}};
    const float coeff[][2] = {{0, 0}, {0.1f, 0.05f}, {0.3f, 0.9f}};
    workpool *pool = workpool_create(2);
    for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++) {
        lpv_volume src, fast, ref, source, acc_fast, acc_ref;
        lpv_blockers b;
        assert_int_equal(lpv_volume_init(&src, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&fast, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&ref, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&source, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&acc_fast, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&acc_ref, shapes[k], LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_blockers_init(&b, shapes[k]), 0);
        testutil_fill_light(&src, &b, 17 + k);
        testutil_fill_light(&source, NULL, 99 + k);
        for (int blocking = 0; blocking < 2; blocking++)
            for (int c = 0; c < 3; c++)
                for (unsigned step = 0; step < 3; step++) {
                    lpv_volume_copy(&acc_fast, &source);
                    lpv_volume_copy(&acc_ref, &source);
                    lpv_propagate_desc pd = {.blockers = blocking ? &b : NULL,
                                             .accum = c == 1 ? &acc_fast : NULL,
                                             .absorption = coeff[c][0], .scattering = coeff[c][1],
                                             .step = step, .pool = pool};
                    lpv_propagate_step(&pd, &src, &fast);
                    pd.accum = c == 1 ? &acc_ref : NULL;
                    lpv_reference_step(&pd, &src, &ref);
                    double d = testutil_rel_diff(&fast, &ref);
                    if (c == 1)
                        d = fmax(d, testutil_rel_diff(&acc_fast, &acc_ref));
                    if (d > 1e-5)
                        printf("shape %d %d %d blocking %d coeff %d step %u: %g\n", shapes[k][0],
                               shapes[k][1], shapes[k][2], blocking, c, step, d);
                    assert_true(d <= 1e-5);
                }
        lpv_volume_free(&src);
        lpv_volume_free(&fast);
        lpv_volume_free(&ref);
        lpv_volume_free(&source);
        lpv_volume_free(&acc_fast);
        lpv_volume_free(&acc_ref);
        lpv_blockers_free(&b);
    }
    workpool_destroy(pool);
}

static void test_bit_identical_for_any_thread_count(void **state)
{
    (void)state;
    const int n[3] = {21, 17, 35};
    lpv_volume src, out[3], acc[3];
    lpv_blockers b;
    assert_int_equal(lpv_volume_init(&src, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_blockers_init(&b, n), 0);
    testutil_fill_light(&src, &b, 3);
    const int threads[3] = {1, 2, 7};
    for (int t = 0; t < 3; t++) {
        assert_int_equal(lpv_volume_init(&out[t], n, LPV_LIGHT_CHANNELS), 0);
        assert_int_equal(lpv_volume_init(&acc[t], n, LPV_LIGHT_CHANNELS), 0);
        lpv_volume_copy(&acc[t], &src);
        workpool *pool = workpool_create(threads[t]);
        lpv_propagate_desc pd = {.blockers = &b, .accum = &acc[t], .absorption = 0.02f,
                                 .scattering = 0.1f, .step = 5, .pool = pool};
        lpv_propagate_step(&pd, &src, &out[t]);
        workpool_destroy(pool);
    }
    for (int t = 1; t < 3; t++) {
        assert_true(lpv_volume_checksum(&out[0]) == lpv_volume_checksum(&out[t]));
        assert_true(lpv_volume_checksum(&acc[0]) == lpv_volume_checksum(&acc[t]));
    }
    for (int t = 0; t < 3; t++) {
        lpv_volume_free(&out[t]);
        lpv_volume_free(&acc[t]);
    }
    lpv_volume_free(&src);
    lpv_blockers_free(&b);
}

/* Light in the middle of a lattice keeps its energy (it cannot leave in one step), and
 * loses exactly the absorbed share; nothing becomes negative. */
static void test_energy_is_kept(void **state)
{
    (void)state;
    const int n[3] = {9, 9, 9};
    lpv_volume src, dst;
    assert_int_equal(lpv_volume_init(&src, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&dst, n, LPV_LIGHT_CHANNELS), 0);
    uint64_t rng = 7;
    for (int trial = 0; trial < 50; trial++) {
        lpv_volume_clear(&src);
        size_t centre = 4 + 9 * (4 + 9 * 4);
        for (int c = 0; c < 3; c++) {
            float d[3] = {testutil_rand(&rng) - 0.5f, testutil_rand(&rng) - 0.5f,
                          testutil_rand(&rng) - 0.5f}, L[4];
            sh_eval(d, L);
            float beam = testutil_rand(&rng), iso = testutil_rand(&rng) * (trial % 2);
            for (int s = 0; s < 4; s++)
                src.ch[4 * c + s][centre] = beam * L[s] + (s == 0 ? iso * (float)SH_Y0 : 0.0f);
        }
        float la = trial < 25 ? 0.0f : 0.1f;
        lpv_propagate_step(&(lpv_propagate_desc){.absorption = la, .scattering = 0.3f,
                                                 .step = (unsigned)trial},
                           &src, &dst);
        double before[3], after[3];
        lpv_volume_energy(&src, before);
        lpv_volume_energy(&dst, after);
        for (int c = 0; c < 3; c++)
            assert_true(fabs(after[c] - (1.0 - la) * before[c]) < 2e-6 * before[c]);
        for (size_t i = 0; i < dst.cells; i++)
            for (int c = 0; c < 3; c++)
                assert_true(dst.ch[4 * c][i] >= 0.0f);
    }
    lpv_volume_free(&src);
    lpv_volume_free(&dst);
}

/* Energy-weighted mean position of a colour's light. */
static void centroid(const lpv_volume *v, int c, double out[3])
{
    double sum = 0.0, m[3] = {0, 0, 0};
    for (int z = 0; z < v->n[2]; z++)
        for (int y = 0; y < v->n[1]; y++)
            for (int x = 0; x < v->n[0]; x++) {
                double e = v->ch[4 * c][(size_t)x + (size_t)v->n[0] * ((size_t)y + (size_t)v->n[1] * z)];
                sum += e;
                m[0] += e * x;
                m[1] += e * y;
                m[2] += e * z;
            }
    for (int a = 0; a < 3; a++)
        out[a] = m[a] / sum;
}

/* A beam moves one cell per step along its direction, whatever the direction, and stays a
 * beam: after 10 steps its centroid is 10 cells further and its flux still equals its
 * energy. */
static void test_a_beam_travels_one_cell_per_step(void **state)
{
    (void)state;
    const int n[3] = {25, 25, 25};
    lpv_volume a, b;
    assert_int_equal(lpv_volume_init(&a, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, n, LPV_LIGHT_CHANNELS), 0);
    const float dirs[][3] = {{1, 0, 0}, {0, 0, -1}, {1, 1, 0}, {1, 1, 1}, {0.3f, -0.8f, 0.52f}};
    for (size_t k = 0; k < sizeof dirs / sizeof dirs[0]; k++) {
        float len = sqrtf(dirs[k][0] * dirs[k][0] + dirs[k][1] * dirs[k][1] + dirs[k][2] * dirs[k][2]);
        float d[3] = {dirs[k][0] / len, dirs[k][1] / len, dirs[k][2] / len}, L[4];
        sh_eval(d, L);
        lpv_volume_clear(&a);
        size_t centre = 12 + 25 * (12 + 25 * 12);
        for (int s = 0; s < 4; s++)
            a.ch[4 + s][centre] = L[s];
        lpv_volume *src = &a, *dst = &b;
        for (unsigned step = 0; step < 10; step++) {
            lpv_propagate_step(&(lpv_propagate_desc){.step = step}, src, dst);
            lpv_volume *t = src;
            src = dst;
            dst = t;
        }
        double m[3], e[3];
        centroid(src, 1, m);
        lpv_volume_energy(src, e);
        for (int a2 = 0; a2 < 3; a2++)
            assert_true(fabs(m[a2] - (12.0 + 10.0 * d[a2])) < 1e-3);
        double fz = 0, fx = 0, fy = 0;
        for (size_t i = 0; i < src->cells; i++) {
            fx += -src->ch[7][i] / SH_Y1;
            fy += -src->ch[5][i] / SH_Y1;
            fz += src->ch[6][i] / SH_Y1;
        }
        assert_true(fabs(sqrt(fx * fx + fy * fy + fz * fz) - e[1]) < 1e-4 * e[1]);
    }
    lpv_volume_free(&a);
    lpv_volume_free(&b);
}

/* Free transport keeps a uniform field uniform: every interior cell of a lattice whose
 * cells all hold the same light gets that light back. */
static void test_uniform_field_stays_uniform(void **state)
{
    (void)state;
    const int n[3] = {6, 6, 6};
    lpv_volume a, b;
    assert_int_equal(lpv_volume_init(&a, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, n, LPV_LIGHT_CHANNELS), 0);
    float L[4];
    sh_eval((float[3]){0.2f, 0.5f, -0.3f}, L);
    for (size_t i = 0; i < a.cells; i++)
        for (int s = 0; s < 4; s++)
            a.ch[s][i] = 0.6f * L[s] + (s == 0 ? 0.4f * (float)SH_Y0 : 0.0f);
    size_t i = 2 + 6 * (3 + 6 * 2);
    for (unsigned step = 0; step < 2; step++) {
        lpv_propagate_step(&(lpv_propagate_desc){.step = step}, &a, &b);
        for (int s = 0; s < 4; s++)
            assert_float_equal(b.ch[s][i], a.ch[s][i], 1e-6f);
    }
    lpv_volume_free(&a);
    lpv_volume_free(&b);
}

/* A blocked segment passes nothing in either direction: light on both sides of a wall of
 * blocked segments stays on its side. */
static void test_blocking_stops_light_both_ways(void **state)
{
    (void)state;
    const int n[3] = {12, 6, 6};
    lpv_volume a, b;
    lpv_blockers bl;
    assert_int_equal(lpv_volume_init(&a, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_blockers_init(&bl, n), 0);
    for (int z = 0; z < 6; z++) /* every segment between x = 5 and x = 6 */
        for (int y = 0; y < 6; y++)
            for (int k = 0; k < LPV_NEIGHBOURS; k++) {
                int o = lpv_transfer_offsets[k][0];
                if (o == 1)
                    bl.mask[5 + 12 * (y + 6 * z)] |= 1u << k;
                if (o == -1)
                    bl.mask[6 + 12 * (y + 6 * z)] |= 1u << k;
            }
    float left[4], right[4];
    sh_eval((float[3]){1, 0, 0}, left);   /* heading for the wall from the left */
    sh_eval((float[3]){-1, 0.2f, 0}, right); /* and from the right */
    for (int s = 0; s < 4; s++) {
        a.ch[s][3 + 12 * (3 + 6 * 3)] = left[s];
        a.ch[4 + s][8 + 12 * (3 + 6 * 3)] = right[s];
    }
    lpv_volume *src = &a, *dst = &b;
    for (unsigned step = 0; step < 6; step++) {
        lpv_propagate_step(&(lpv_propagate_desc){.blockers = &bl, .step = step}, src, dst);
        lpv_volume *t = src;
        src = dst;
        dst = t;
    }
    for (int z = 0; z < 6; z++)
        for (int y = 0; y < 6; y++)
            for (int x = 0; x < 12; x++) {
                size_t i = (size_t)x + 12 * ((size_t)y + 6 * z);
                if (x >= 6)
                    assert_true(src->ch[0][i] == 0.0f);
                else
                    assert_true(src->ch[4][i] == 0.0f);
            }
    lpv_volume_free(&a);
    lpv_volume_free(&b);
    lpv_blockers_free(&bl);
}

static void test_bad_arguments_leave_dst_alone(void **state)
{
    (void)state;
    const int n[3] = {4, 4, 4}, m[3] = {4, 4, 5};
    lpv_volume a, b, c, g;
    assert_int_equal(lpv_volume_init(&a, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&c, m, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&g, n, LPV_GEOMETRY_CHANNELS), 0);
    lpv_blockers bm;
    assert_int_equal(lpv_blockers_init(&bm, m), 0);
    for (size_t i = 0; i < a.cells; i++)
        a.ch[0][i] = 1.0f;
    b.ch[0][0] = 42.0f;
    lpv_propagate_desc pd = {0};
    lpv_propagate_step(NULL, &a, &b);
    lpv_propagate_step(&pd, &a, &a);
    lpv_propagate_step(&pd, &a, &c);
    lpv_propagate_step(&pd, &g, &b);
    lpv_propagate_step(&(lpv_propagate_desc){.accum = &b}, &a, &b);
    lpv_propagate_step(&(lpv_propagate_desc){.accum = &a}, &a, &b);
    lpv_propagate_step(&(lpv_propagate_desc){.accum = &c}, &a, &b);
    lpv_propagate_step(&(lpv_propagate_desc){.blockers = &bm}, &a, &b);
    assert_true(b.ch[0][0] == 42.0f);
    lpv_blockers_free(&bm);
    lpv_volume_free(&a);
    lpv_volume_free(&b);
    lpv_volume_free(&c);
    lpv_volume_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fast_path_matches_reference),
        cmocka_unit_test(test_bit_identical_for_any_thread_count),
        cmocka_unit_test(test_energy_is_kept),
        cmocka_unit_test(test_a_beam_travels_one_cell_per_step),
        cmocka_unit_test(test_uniform_field_stays_uniform),
        cmocka_unit_test(test_blocking_stops_light_both_ways),
        cmocka_unit_test(test_bad_arguments_leave_dst_alone),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
