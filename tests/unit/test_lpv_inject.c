#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>

#include "gi/ilpv/lpv_inject.h"
#include "gi/ilpv/sh.h"
#include "lpv_testutil.h"

static void test_vpl_lands_half_a_cell_along_its_normal(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 0.5f, {8, 8, 8}};
    lpv_volume v;
    assert_int_equal(lpv_volume_init(&v, lat.n, LPV_LIGHT_CHANNELS), 0);
    /* On the boundary between cells 3 and 4 along y; the normal pushes it into cell 4. */
    lpv_vpl vpl = {.position = {1.1f, 2.0f, 1.6f}, .normal = {0, 3, 0}, .flux = {1, 2, 0.5f}};
    lpv_inject_stats st = {0};
    lpv_inject_vpls(&v, NULL, &lat, &vpl, 1, &st);
    assert_int_equal(st.injected, 1);
    size_t idx = 2 + 8 * (4 + 8 * 3);
    float lobe[4];
    sh_cosine_lobe((float[3]){0, 1, 0}, lobe);
    for (int c = 0; c < 3; c++)
        for (int s = 0; s < 4; s++)
            assert_float_equal(v.ch[4 * c + s][idx], vpl.flux[c] * lobe[s], 1e-6f);
    double e[3];
    lpv_volume_energy(&v, e); /* flux * pi: the integral of a clamped cosine */
    assert_true(fabs(e[1] - 2.0 * 3.14159265358979) < 1e-5);
    /* Pointing down, the same VPL goes to cell 3. */
    vpl.normal[1] = -1.0f;
    lpv_inject_vpls(&v, NULL, &lat, &vpl, 1, &st);
    assert_int_equal(st.injected, 2);
    assert_true(v.ch[0][2 + 8 * (3 + 8 * 3)] > 0.0f);
    lpv_volume_free(&v);
}

static void test_bad_vpls_are_skipped_and_counted(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {4, 4, 4}};
    lpv_volume v;
    assert_int_equal(lpv_volume_init(&v, lat.n, LPV_LIGHT_CHANNELS), 0);
    lpv_vpl vpls[] = {
        {.position = {2, 2, 2}, .normal = {0, 0, 1}, .flux = {1, 1, 1}},   /* fine */
        {.position = {NAN, 2, 2}, .normal = {0, 0, 1}, .flux = {1, 1, 1}}, /* invalid */
        {.position = {2, 2, 2}, .normal = {0, 0, 0}, .flux = {1, 1, 1}},   /* invalid */
        {.position = {2, 2, 2}, .normal = {0, 0, 1}, .flux = {INFINITY, 1, 1}},
        {.position = {2, 2, 2}, .normal = {0, NAN, 1}, .flux = {1, 1, 1}},
        {.position = {9, 2, 2}, .normal = {0, 0, 1}, .flux = {1, 1, 1}},   /* outside */
        {.position = {2, 2, 3.8f}, .normal = {0, 0, 1}, .flux = {1, 1, 1}}, /* pushed out */
        {.position = {2, 2, 2}, .normal = {1e30f, 1e30f, 1e30f}, .flux = {1, 1, 1}}, /* overflow */
    };
    lpv_inject_stats st = {0};
    lpv_inject_vpls(&v, NULL, &lat, vpls, sizeof vpls / sizeof vpls[0], &st);
    assert_int_equal(st.injected, 1);
    assert_int_equal(st.invalid, 5);
    assert_int_equal(st.outside, 2);
    assert_int_equal(lpv_volume_count_nonfinite(&v), 0);
    lpv_inject_vpls(&v, NULL, &lat, vpls, 1, NULL); /* stats may be NULL */
    /* A lattice that does not match the volume injects nothing. */
    lattice_desc other = {{0, 0, 0}, 1.0f, {5, 4, 4}};
    lpv_inject_stats st2 = {0};
    lpv_inject_vpls(&v, NULL, &other, vpls, 1, &st2);
    assert_int_equal(st2.injected, 0);
    assert_int_equal(st2.outside, 1);
    lpv_volume_free(&v);
}

/* A slanted VPL goes (|n_x| + |n_y| + |n_z|) / 2 cells along its normal, so that its
 * cell's centre lies in front of its surface; the origin volume records where the light
 * comes from (lattice units, centres at integers) weighted by the flux. */
static void test_slanted_vpl_cell_centre_is_in_front_and_origin_is_kept(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {8, 8, 8}};
    lpv_volume v, o;
    assert_int_equal(lpv_volume_init(&v, lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&o, lat.n, LPV_GEOMETRY_CHANNELS), 0);
    uint64_t rng = 9;
    for (int i = 0; i < 500; i++) {
        lpv_volume_clear(&v);
        lpv_volume_clear(&o);
        lpv_vpl vpl = {.position = {2 + 4 * testutil_rand(&rng), 2 + 4 * testutil_rand(&rng),
                                    2 + 4 * testutil_rand(&rng)},
                       .normal = {testutil_rand(&rng) - 0.5f, testutil_rand(&rng) - 0.5f,
                                  testutil_rand(&rng) - 0.5f},
                       .flux = {1, 2, 3}};
        lpv_inject_vpls(&v, &o, &lat, &vpl, 1, NULL);
        size_t at = 0;
        for (size_t k = 0; k < v.cells; k++)
            if (v.ch[0][k] != 0.0f)
                at = k;
        int c[3] = {(int)(at % 8), (int)(at / 8 % 8), (int)(at / 64)};
        float ahead = 0.0f;
        for (int a = 0; a < 3; a++)
            ahead += ((float)c[a] + 0.5f - vpl.position[a]) * vpl.normal[a];
        assert_true(ahead >= -1e-5f);
        assert_float_equal(o.ch[3][at], 6.0f, 1e-6f);
        for (int a = 0; a < 3; a++)
            assert_float_equal(o.ch[a][at] / o.ch[3][at], vpl.position[a] - 0.5f, 1e-5f);
    }
    lpv_volume_free(&v);
    lpv_volume_free(&o);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vpl_lands_half_a_cell_along_its_normal),
        cmocka_unit_test(test_slanted_vpl_cell_centre_is_in_front_and_origin_is_kept),
        cmocka_unit_test(test_bad_vpls_are_skipped_and_counted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
