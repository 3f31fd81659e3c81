#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "gi/ilpv/lpv_volume.h"
#include "gi/ilpv/sh.h"

static void test_init_refuses_bad_shapes(void **state)
{
    (void)state;
    lpv_volume v;
    assert_int_equal(lpv_volume_init(&v, (int[3]){0, 4, 4}, 12), -1);
    assert_int_equal(lpv_volume_init(&v, (int[3]){4, -1, 4}, 12), -1);
    assert_int_equal(lpv_volume_init(&v, (int[3]){4, 4, 4}, 5), -1);
    lpv_volume_free(&v); /* safe on a refused volume */
}

static void test_layout_energy_checksum(void **state)
{
    (void)state;
    lpv_volume v, w;
    assert_int_equal(lpv_volume_init(&v, (int[3]){5, 3, 2}, 12), 0);
    assert_int_equal(lpv_volume_init(&w, (int[3]){5, 3, 2}, 12), 0);
    assert_int_equal(v.cells, 30);
    for (int c = 0; c < 12; c++) {
        assert_int_equal((uintptr_t)v.ch[c] % 64, 0);
        for (int g = 1; g <= LPV_VOLUME_GUARD; g++) /* zero guards on both sides */
            assert_true(v.ch[c][-g] == 0.0f && v.ch[c][v.cells - 1 + g] == 0.0f);
        for (size_t i = 0; i < v.cells; i++)
            assert_true(v.ch[c][i] == 0.0f);
    }
    v.ch[0][3] = 2.0f; /* red L0 */
    v.ch[8][7] = 1.0f; /* blue L0 */
    v.ch[5][7] = 9.0f; /* green L1: no energy */
    double e[3];
    lpv_volume_energy(&v, e);
    assert_true(fabs(e[0] - 2.0 * SH_ENERGY) < 1e-12);
    assert_true(fabs(e[1]) < 1e-12);
    assert_true(fabs(e[2] - SH_ENERGY) < 1e-12);

    lpv_volume_copy(&w, &v);
    assert_true(lpv_volume_checksum(&w) == lpv_volume_checksum(&v));
    w.ch[11][29] = -0.0f; /* one bit differs from +0 */
    assert_true(lpv_volume_checksum(&w) != lpv_volume_checksum(&v));
    assert_int_equal(lpv_volume_count_nonfinite(&w), 0);
    w.ch[2][0] = NAN;
    w.ch[4][1] = INFINITY;
    assert_int_equal(lpv_volume_count_nonfinite(&w), 2);
    lpv_volume_clear(&w);
    assert_int_equal(lpv_volume_count_nonfinite(&w), 0);
    lpv_volume_energy(&w, e);
    assert_true(e[0] == 0.0 && e[1] == 0.0 && e[2] == 0.0);
    lpv_volume_free(&v);
    lpv_volume_free(&w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_init_refuses_bad_shapes),
        cmocka_unit_test(test_layout_energy_checksum),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
