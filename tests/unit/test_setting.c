/* setting: one row's parser (the reason text every program prints), its clamp (what a
 * receiver does with a value it did not check), its format and its field. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "base/setting.h"

typedef struct owner {
    int32_t count;
    float gamma;
    int32_t kind;
    int32_t size;
    float offset;
} owner;

static const char *const kinds[] = {"exact", "ism", "ism-splat"};
static const setting count = {"count", "N", SETTING_INT, 64, 4096, 256, NULL, 0, 0,
                              offsetof(owner, count), "lights"};
static const setting gamma_row = {"gamma", "G", SETTING_FLOAT, 0.1, 10, 2.2, NULL, 0, 0,
                                  offsetof(owner, gamma), "gamma"};
static const setting kind = {"kind", NULL, SETTING_CHOICE, 0, 0, 1, kinds, 3, SETTING_REBUILD,
                             offsetof(owner, kind), "kind"};
static const setting size = {"size", "N", SETTING_INT, 8, 256, 32, NULL, 0, SETTING_POW2,
                             offsetof(owner, size), "size"};
static const setting offset = {"offset", "X", SETTING_FLOAT, -1, 1, 0, NULL, 0, 0,
                               offsetof(owner, offset), "offset"};

static void test_parse(void **state)
{
    setting_value v;
    assert_null(setting_parse(&count, "1024", &v));
    assert_int_equal(v.i, 1024);
    assert_string_equal(setting_parse(&count, "5000", &v), "a whole number in 64..4096");
    assert_non_null(setting_parse(&count, "63", &v));
    assert_non_null(setting_parse(&count, "100x", &v));
    assert_non_null(setting_parse(&count, "", &v));
    assert_null(setting_parse(&gamma_row, "2.4", &v));
    assert_float_equal(v.f, 2.4f, 0);
    assert_string_equal(setting_parse(&gamma_row, "11", &v), "a number in [0.1, 10]");
    assert_non_null(setting_parse(&gamma_row, "nan", &v));
    assert_non_null(setting_parse(&gamma_row, "inf", &v));
    assert_null(setting_parse(&kind, "ism-splat", &v));
    assert_int_equal(v.i, 2);
    assert_string_equal(setting_parse(&kind, "isms", &v), "one of exact, ism or ism-splat");
    assert_null(setting_parse(&size, "64", &v));
    assert_string_equal(setting_parse(&size, "48", &v), "a power of two in 8..256");
    assert_non_null(setting_parse(&size, "512", &v));
}

static void test_clamp(void **state)
{
    setting_value v = {.i = 5000};
    assert_int_equal(setting_clamp(&count, &v), 1);
    assert_int_equal(v.i, 4096);
    v.i = 10;
    assert_int_equal(setting_clamp(&count, &v), 1);
    assert_int_equal(v.i, 64);
    v.i = 0; /* nothing, where the range is positive: the default */
    assert_int_equal(setting_clamp(&count, &v), 1);
    assert_int_equal(v.i, 256);
    v.i = 300;
    assert_int_equal(setting_clamp(&count, &v), 0);
    v.f = NAN;
    assert_int_equal(setting_clamp(&gamma_row, &v), 1);
    assert_float_equal(v.f, 2.2f, 0);
    v.f = -1; /* a gamma of -1 means nothing: the default */
    setting_clamp(&gamma_row, &v);
    assert_float_equal(v.f, 2.2f, 0);
    v.f = INFINITY;
    setting_clamp(&gamma_row, &v);
    assert_float_equal(v.f, 10.0f, 0);
    v.f = -5; /* a range that takes negative values: its nearest end */
    setting_clamp(&offset, &v);
    assert_float_equal(v.f, -1.0f, 0);
    v.i = 7;
    assert_int_equal(setting_clamp(&kind, &v), 1);
    assert_int_equal(v.i, 1);
    v.i = 100; /* the power of two below */
    setting_clamp(&size, &v);
    assert_int_equal(v.i, 64);
    v.i = 3;
    setting_clamp(&size, &v);
    assert_int_equal(v.i, 8);
}

static void test_format_and_fields(void **state)
{
    char buf[64];
    setting_format(&kind, (setting_value){.i = 2}, buf, sizeof buf);
    assert_string_equal(buf, "ism-splat");
    setting_format(&gamma_row, (setting_value){.f = 2.5f}, buf, sizeof buf);
    assert_string_equal(buf, "2.5");
    setting_format(&count, setting_default(&count), buf, sizeof buf);
    assert_string_equal(buf, "256");
    setting_arg(&kind, buf, sizeof buf);
    assert_string_equal(buf, "exact|ism|ism-splat");
    setting_arg(&count, buf, sizeof buf);
    assert_string_equal(buf, "N");
    owner o = {0};
    setting_store(&gamma_row, (setting_value){.f = 1.5f}, &o);
    setting_store(&kind, (setting_value){.i = 2}, &o);
    assert_float_equal(o.gamma, 1.5f, 0);
    assert_int_equal(o.kind, 2);
    assert_int_equal(setting_load(&kind, &o).i, 2);
    const setting rows[3] = {count, gamma_row, kind};
    assert_int_equal(setting_find(rows, 3, "kind"), 2);
    assert_int_equal(setting_find(rows, 3, "none"), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parse),
        cmocka_unit_test(test_clamp),
        cmocka_unit_test(test_format_and_fields),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
