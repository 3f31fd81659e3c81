/* mat4: column-major product and point transform, including aliased output. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_order_and_layout),
        cmocka_unit_test(test_aliased_output),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
