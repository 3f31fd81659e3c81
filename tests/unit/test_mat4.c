/* mat4: column-major product and point transform, including aliased output; the double
 * product and the general inverse. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>
#include <math.h>

#include "base/mat4.h"

/* Translation by (1, 2, 3) and a non-uniform scale (2, 3, 4), column-major. */
static const float T[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1};
static const float S[16] = {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 0, 0, 0, 1};

static void test_order_and_layout(void **state)
{
    float ts[16], st[16], p[3];
    const float x[3] = {1, 1, 1};
    mat4_mul(T, S, ts); /* scale first, then translate */
    mat4_mul(S, T, st); /* translate first, then scale */
    mat4_transform_point(ts, x, p);
    assert_true(p[0] == 3 && p[1] == 5 && p[2] == 7);
    mat4_transform_point(st, x, p);
    assert_true(p[0] == 4 && p[1] == 9 && p[2] == 16);
    /* The translation sits in elements 12..14. */
    assert_true(st[12] == 2 && st[13] == 6 && st[14] == 12 && st[15] == 1);
}

static void test_aliased_output(void **state)
{
    float a[16], b[16], want[16];
    for (int i = 0; i < 16; i++) {
        a[i] = (float)(i + 1);
        b[i] = (float)(16 - i) * 0.5f;
    }
    mat4_mul(a, b, want);
    float c[16];
    memcpy(c, a, sizeof c);
    mat4_mul(c, b, c);
    assert_memory_equal(c, want, sizeof want);
    memcpy(c, b, sizeof c);
    mat4_mul(a, c, c);
    assert_memory_equal(c, want, sizeof want);
}

/* The double product: the float one's layout and order, aliasing allowed; identity neutral. */
static void test_double_product(void **state)
{
    double t[16], sc[16], ts[16], id[16], c[16];
    mat4d_from_float(T, t);
    mat4d_from_float(S, sc);
    mat4d_mul(t, sc, ts);
    float want[16];
    mat4_mul(T, S, want);
    for (int i = 0; i < 16; i++)
        assert_true(ts[i] == want[i]);
    mat4d_identity(id);
    memcpy(c, ts, sizeof c);
    mat4d_mul(id, c, c);
    assert_memory_equal(c, ts, sizeof c);
    mat4d_mul(c, id, c);
    assert_memory_equal(c, ts, sizeof c);
}

/* The general inverse undoes a perspective projection times a view; singular is -1. */
static void test_double_inverse(void **state)
{
    const double p[16] = {1.5, 0, 0, 0, 0, 2, 0, 0, 0, 0, -1.2, -1, 0, 0, -0.22, 0};
    double t[16], m[16], inv[16], prod[16];
    mat4d_from_float(T, t);
    mat4d_mul(p, t, m);
    assert_int_equal(mat4d_inverse(m, inv), 0);
    mat4d_mul(m, inv, prod);
    for (int i = 0; i < 16; i++)
        assert_true(fabs(prod[i] - (i % 5 == 0)) < 1e-12);
    double flat[16] = {1, 2, 3, 4, 2, 4, 6, 8}; /* two parallel columns, two zero ones */
    memcpy(inv, p, sizeof inv);
    assert_int_equal(mat4d_inverse(flat, inv), -1);
    assert_memory_equal(inv, p, sizeof inv);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_order_and_layout),
        cmocka_unit_test(test_aliased_output),
        cmocka_unit_test(test_double_product),
        cmocka_unit_test(test_double_inverse),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
