/* ratelog: a burst, then one line per interval that says how many were left out. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "base/ratelog.h"

static void test_burst_then_interval(void **state)
{
    (void)state;
    ratelog r = {0};
    uint64_t skipped = 99;
    int printed = 0;
    for (int i = 0; i < 10000; i++) /* a flood within one millisecond */
        printed += ratelog_event(&r, 1000.0, &skipped);
    assert_int_equal(printed, RATELOG_BURST);
    assert_int_equal(r.count, 10000);
    assert_int_equal(r.skipped, 10000 - RATELOG_BURST);
    /* Still inside the interval: nothing. */
    assert_int_equal(ratelog_event(&r, 1000.0 + RATELOG_INTERVAL_MS - 1, NULL), 0);
    /* The interval has passed: one line, reporting what was left out. */
    assert_int_equal(ratelog_event(&r, 1000.0 + RATELOG_INTERVAL_MS, &skipped), 1);
    assert_int_equal(skipped, 10000 - RATELOG_BURST + 1);
    assert_int_equal(ratelog_event(&r, 1000.0 + RATELOG_INTERVAL_MS + 1, NULL), 0);
    /* 10,000 events spread over 100 s print the burst plus about one per interval. */
    ratelog s = {0};
    printed = 0;
    for (int i = 0; i < 10000; i++)
        printed += ratelog_event(&s, i * 10.0, NULL);
    assert_in_range(printed, RATELOG_BURST + 9, RATELOG_BURST + 11);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_burst_then_interval)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
