/* vec3: each helper against values worked out by hand, and normalize's zero case. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "base/vec3.h"

static void test_products(void **state)
{
    const float x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
    float z[3], d[3];
    vec3_cross(x, y, z);
    assert_true(z[0] == 0 && z[1] == 0 && z[2] == 1);
    assert_true(vec3_dot(x, y) == 0 && vec3_dot(z, z) == 1);
    vec3_sub((const float[3]){3, 5, 7}, (const float[3]){1, 1, 1}, d);
    assert_true(d[0] == 2 && d[1] == 4 && d[2] == 6);
    const double a[3] = {0, 0, 2}, b[3] = {3, 0, 0};
    double c[3];
    vec3d_cross(a, b, c);
    assert_true(c[0] == 0 && c[1] == 6 && c[2] == 0 && vec3d_dot(c, c) == 36);
}

static void test_normalize(void **state)
{
    float v[3] = {3, 0, 4};
    assert_true(vec3_normalize(v) == 5);
    assert_true(v[0] == 0.6f && v[2] == 0.8f);
    float zero[3] = {0, 0, 0};
    assert_true(vec3_normalize(zero) == 0);
    assert_true(zero[0] == 0 && zero[1] == 0 && zero[2] == 0);
}

static void test_triangle(void **state)
{
    /* Right triangle with legs 2 and 3 in the xz plane, turning from +x to -z: normal +y. */
    const float p[9] = {1, 1, 1, 3, 1, 1, 1, 1, -2};
    float n[3];
    vec3_triangle_normal(p, n);
    assert_true(n[0] == 0 && n[1] == 6 && n[2] == 0);
    assert_true(vec3_triangle_area(p) == 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_products),
        cmocka_unit_test(test_normalize),
        cmocka_unit_test(test_triangle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
