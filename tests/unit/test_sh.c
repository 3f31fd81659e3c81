#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>

#include "gi/ilpv/sh.h"

static double clamped_cosine(void *ctx, const double w[3])
{
    const float *n = ctx;
    double c = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
    return c > 0.0 ? c : 0.0;
}

static double constant_one(void *ctx, const double w[3])
{
    (void)ctx;
    (void)w;
    return 1.0;
}

static double basis_function(void *ctx, const double w[3])
{
    int i = *(const int *)ctx;
    float wf[3] = {(float)w[0], (float)w[1], (float)w[2]}, y[4];
    sh_eval(wf, y);
    return y[i];
}

static void test_lobe_at_its_normal_is_three_quarters(void **state)
{
    (void)state;
    const float dirs[][3] = {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}, {0.3f, -0.5f, 0.8f}};
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        float lobe[4];
        sh_cosine_lobe(dirs[i], lobe);
        assert_float_equal(sh_value(lobe, dirs[i]), 0.75f, 1e-6f);
    }
}

static void test_lobe_energy_and_norm_do_not_depend_on_direction(void **state)
{
    (void)state;
    float ref[4];
    sh_cosine_lobe((float[3]){0, 0, 1}, ref);
    double ref_norm = sqrt(ref[1] * ref[1] + ref[2] * ref[2] + ref[3] * ref[3]);
    for (int k = 0; k < 50; k++) {
        float a = 0.37f * k, b = 0.11f * k;
        float n[3] = {cosf(a) * sinf(b + 0.2f), sinf(a) * sinf(b + 0.2f), cosf(b + 0.2f)}, lobe[4];
        sh_cosine_lobe(n, lobe);
        assert_float_equal(lobe[0], ref[0], 0.0f); /* energy 2 sqrt(pi) L0 is the same */
        double norm = sqrt(lobe[1] * lobe[1] + lobe[2] * lobe[2] + lobe[3] * lobe[3]);
        assert_true(fabs(norm - ref_norm) < 1e-6);
    }
    assert_float_equal(ref[0], 0.8862269f, 1e-6f);
    assert_float_equal(ref[2], 1.0233267f, 1e-6f);
}

static void test_projection_of_constant_and_of_basis(void **state)
{
    (void)state;
    double c[4];
    sh_project(constant_one, NULL, 64, c);
    assert_true(fabs(c[0] - SH_ENERGY) < 1e-9);
    for (int s = 1; s < 4; s++)
        assert_true(fabs(c[s]) < 1e-9);
    /* Orthonormal basis: projecting Y_i gives the unit vector e_i. */
    for (int i = 0; i < 4; i++) {
        sh_project(basis_function, &i, 128, c);
        for (int s = 0; s < 4; s++)
            assert_true(fabs(c[s] - (s == i ? 1.0 : 0.0)) < 1e-4);
    }
}

static void test_projection_of_clamped_cosine_matches_lobe(void **state)
{
    (void)state;
    const float dirs[][3] = {{0, 0, 1}, {0.6f, 0.8f, 0}, {-0.48f, 0.6f, -0.64f}};
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        double c[4];
        float lobe[4];
        sh_project(clamped_cosine, (void *)dirs[i], 400, c);
        sh_cosine_lobe(dirs[i], lobe);
        for (int s = 0; s < 4; s++)
            assert_true(fabs(c[s] - lobe[s]) < 2e-4);
    }
}

static void test_dot_and_eval(void **state)
{
    (void)state;
    float a[4] = {1, 2, 3, 4}, b[4] = {0.5f, -1, 2, 0.25f};
    assert_float_equal(sh_dot(a, b), 0.5f - 2 + 6 + 1, 1e-6f);
    float y[4];
    sh_eval((float[3]){0, 0, 2}, y); /* not unit: normalized inside */
    assert_float_equal(y[0], 0.2820948f, 1e-6f);
    assert_float_equal(y[2], 0.4886025f, 1e-6f);
    assert_float_equal(y[1], 0.0f, 1e-7f);
    sh_eval((float[3]){1, 0, 0}, y);
    assert_float_equal(y[3], -0.4886025f, 1e-6f);
    sh_eval((float[3]){0, 0, 0}, y); /* zero vector: constant term only, no NaN */
    assert_float_equal(y[0], 0.2820948f, 1e-6f);
    assert_float_equal(y[1] + y[2] + y[3], 0.0f, 0.0f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lobe_at_its_normal_is_three_quarters),
        cmocka_unit_test(test_lobe_energy_and_norm_do_not_depend_on_direction),
        cmocka_unit_test(test_projection_of_constant_and_of_basis),
        cmocka_unit_test(test_projection_of_clamped_cosine_matches_lobe),
        cmocka_unit_test(test_dot_and_eval),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
