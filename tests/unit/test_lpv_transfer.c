/* The step's rule (lpv_transfer.h): offsets, per-axis weights, the basis around a
 * direction, the split of a cell's light, and the step probability. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>

#include "base/vec3.h"
#include "gi/ilpv/lpv_transfer.h"
#include "gi/ilpv/sh.h"
#include "lpv_testutil.h"

static void test_offsets_are_antipodal_and_z_major(void **state)
{
    (void)state;
    int k = 0;
    for (int z = -1; z <= 1; z++)
        for (int y = -1; y <= 1; y++)
            for (int x = -1; x <= 1; x++) {
                if (!x && !y && !z)
                    continue;
                const int *o = lpv_transfer_offsets[k], *a = lpv_transfer_offsets[25 - k];
                assert_true(o[0] == x && o[1] == y && o[2] == z);
                assert_true(a[0] == -x && a[1] == -y && a[2] == -z);
                k++;
            }
    assert_int_equal(k, LPV_NEIGHBOURS);
}

/* Positive, sum 1, mean v (the light moves v per step along the axis), spread (1 - v^2)/2. */
static void test_axis_weights_move_one_cell_per_step(void **state)
{
    (void)state;
    for (int i = -100; i <= 100; i++) {
        float v = i / 100.0f, w[3];
        lpv_transfer_axis_weights(v, w);
        for (int k = 0; k < 3; k++)
            assert_true(w[k] >= 0.0f);
        assert_float_equal(w[0] + w[1] + w[2], 1.0f, 1e-6f);
        assert_float_equal(w[2] - w[0], v, 1e-6f);
        assert_float_equal(w[2] + w[0] - v * v, 0.5f * (1.0f - v * v), 1e-6f);
    }
    float w[3];
    lpv_transfer_axis_weights(1.0000002f, w); /* rounding of a unit vector: still >= 0 */
    assert_true(w[0] >= 0.0f && w[1] >= 0.0f && w[2] == 1.0f);
}

static void test_basis_is_orthonormal(void **state)
{
    (void)state;
    uint64_t rng = 5;
    for (int i = 0; i < 1000; i++) {
        float d[3] = {testutil_rand(&rng) - 0.5f, testutil_rand(&rng) - 0.5f, testutil_rand(&rng) - 0.5f};
        if (i == 0)
            d[0] = 0, d[1] = 0, d[2] = -1; /* the branch's edge */
        if (i == 1)
            d[0] = 0, d[1] = 0, d[2] = -0.0f;
        if (i == 1)
            d[1] = 1;
        float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int a = 0; a < 3; a++)
            d[a] /= len;
        float t1[3], t2[3];
        vec3_basis(d, t1, t2);
        const float *v[3] = {d, t1, t2};
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                float dot = v[a][0] * v[b][0] + v[a][1] * v[b][1] + v[a][2] * v[b][2];
                assert_float_equal(dot, a == b ? 1.0f : 0.0f, 2e-6f);
            }
    }
}

/* The two directions are unit vectors whose mean is the light's mean direction u = F/E:
 * energy and flux are kept. */
static void test_split_keeps_energy_and_flux(void **state)
{
    (void)state;
    uint64_t rng = 11;
    for (int i = 0; i < 2000; i++) {
        float n[3] = {testutil_rand(&rng) - 0.5f, testutil_rand(&rng) - 0.5f, testutil_rand(&rng) - 0.5f};
        float L[4], beam = testutil_rand(&rng), iso = testutil_rand(&rng);
        sh_eval(n, L); /* a beam along n, plus isotropic light */
        for (int s = 0; s < 4; s++)
            L[s] *= beam;
        L[0] += iso * (float)SH_Y0;
        float e, sp[3], sm[3];
        assert_int_equal(lpv_transfer_split(L, 0.0f, 0.0f, (unsigned)i, &e, sp, sm), 1);
        assert_float_equal(e, (float)SH_ENERGY * L[0], 1e-5f * e);
        float f[3] = {-L[3] / (float)SH_Y1, -L[1] / (float)SH_Y1, L[2] / (float)SH_Y1};
        for (int a = 0; a < 3; a++)
            assert_float_equal(0.5f * (sp[a] + sm[a]) * e, f[a], 1e-5f * e);
        assert_float_equal(sp[0] * sp[0] + sp[1] * sp[1] + sp[2] * sp[2], 1.0f, 1e-5f);
        assert_float_equal(sm[0] * sm[0] + sm[1] * sm[1] + sm[2] * sm[2], 1.0f, 1e-5f);
    }
}

static void test_split_absorbs_scatters_and_refuses_bad_light(void **state)
{
    (void)state;
    float L[4], e, sp[3], sm[3];
    sh_eval((float[3]){0, 0, 1}, L); /* a beam along +z */
    assert_int_equal(lpv_transfer_split(L, 0.25f, 0.0f, 0, &e, sp, sm), 1);
    assert_float_equal(e, 0.75f, 1e-6f);
    assert_float_equal(sp[2], 1.0f, 1e-6f); /* a beam stays a beam */
    assert_float_equal(sm[2], 1.0f, 1e-6f);
    assert_int_equal(lpv_transfer_split(L, 0.0f, 0.5f, 0, &e, sp, sm), 1);
    assert_float_equal(e, 1.0f, 1e-6f);        /* scattering keeps the energy */
    assert_float_equal(0.5f * (sp[2] + sm[2]), 0.5f, 1e-6f); /* and halves the flux */
    /* No flux: the two directions are opposite, perpendicular to the lattice axis
     * (x + y + z) mod 3. */
    float iso[4] = {(float)SH_Y0, 0, 0, 0};
    for (unsigned parity = 0; parity < 6; parity++) {
        assert_int_equal(lpv_transfer_split(iso, 0.0f, 0.0f, parity, &e, sp, sm), 1);
        for (int a = 0; a < 3; a++)
            assert_float_equal(sp[a] + sm[a], 0.0f, 1e-6f);
        assert_float_equal(sp[parity % 3], 0.0f, 1e-6f);
    }
    const float bad[][4] = {{0, 0, 0, 0}, {-1, 0, 0, 0}, {NAN, 0, 0, 0}, {1, NAN, 0, 0},
                            {INFINITY, 0, 0, 0}, {1, INFINITY, 0, 0}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(lpv_transfer_split(bad[i], 0.0f, 0.0f, 0, &e, sp, sm), 0);
        assert_true(e == 0.0f);
    }
    /* More flux than energy allows (not a distribution): read as a beam. */
    float over[4] = {(float)SH_Y0, 0, 3.0f * (float)SH_Y1, 0};
    assert_int_equal(lpv_transfer_split(over, 0.0f, 0.0f, 0, &e, sp, sm), 1);
    assert_float_equal(sp[2], 1.0f, 1e-6f);
}

static void test_step_probability_limits(void **state)
{
    (void)state;
    assert_float_equal(lpv_transfer_step_probability(0.3f, 0.0f), 0.0f, 0.0f);
    assert_true(lpv_transfer_step_probability(0.3f, 1e-6f) < 1e-6f); /* small cells: -> 0 */
    assert_float_equal(lpv_transfer_step_probability(1.0f, 0.2f), 1.0f, 0.0f);
    assert_float_equal(lpv_transfer_step_probability(0.0f, 0.2f), 0.0f, 0.0f);
    /* A step of one metre keeps sigma: light moves one cell per step. */
    assert_float_equal(lpv_transfer_step_probability(0.5f, 1.0f), 0.5f, 1e-6f);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_offsets_are_antipodal_and_z_major),
        cmocka_unit_test(test_axis_weights_move_one_cell_per_step),
        cmocka_unit_test(test_basis_is_orthonormal),
        cmocka_unit_test(test_split_keeps_energy_and_flux),
        cmocka_unit_test(test_split_absorbs_scatters_and_refuses_bad_light),
        cmocka_unit_test(test_step_probability_limits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
