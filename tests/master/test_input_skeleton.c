/* The device sources' shared skeleton (input_source.h): naming, one report per outage,
 * buttons released on a loss, retry pacing, a source that does not retry, the lines when
 * a device first answers and answers again, and their rate limit. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "base/ratelog.h"
#include "input/input_source.h"

static int no_poll(input_source *s, double now, char *err, size_t errlen) { return 0; }
static void no_close(input_source *s) { free(s); }

typedef struct fake_source {
    input_source base;
    int device;
} fake_source;

static void test_alloc_names_and_zeroes(void **state)
{
    fake_source *f = input_source_alloc(sizeof *f, NULL, "fake", no_poll, no_close);
    assert_non_null(f);
    assert_string_equal(f->base.name, "fake");
    assert_int_equal(f->device, 0);
    assert_ptr_equal(f->base.poll, no_poll);
    f->base.close(&f->base);
    f = input_source_alloc(sizeof *f, "wand", "fake", no_poll, no_close);
    assert_string_equal(f->base.name, "wand");
    f->base.close(&f->base);
}

static void test_one_report_per_outage_and_retry(void **state)
{
    char err[256] = "";
    fake_source *f = input_source_alloc(sizeof *f, "tracker", "fake", no_poll, no_close);
    f->base.retry_interval = 0.5;
    assert_true(input_source_retry_due(&f->base, 0.0)); /* the first attempt is due at once */
    input_source_set_buttons(&f->base.st, 1u << INPUT_BUTTON_C, 1.0);
    assert_int_equal(input_source_lost(&f->base, 2.0, "gone", err, sizeof err), -1);
    assert_string_equal(err, "input tracker: gone; retrying every 0.5 s");
    assert_int_equal(f->base.st.buttons, 0); /* never left flying */
    assert_false(input_source_retry_due(&f->base, 2.4));
    assert_true(input_source_retry_due(&f->base, 2.5));
    err[0] = 0;
    assert_int_equal(input_source_lost(&f->base, 2.5, "still gone", err, sizeof err), 0);
    assert_string_equal(err, "");
    assert_int_equal(input_source_up(&f->base, 3.5, "answers", err, sizeof err), 1);
    assert_string_equal(err, "input tracker: answers again after 1.5 s"); /* 2.0 to 3.5 */
    assert_int_equal(input_source_lost(&f->base, 9.0, "gone again", err, sizeof err), -1);
    assert_string_equal(err, "input tracker: gone again; retrying every 0.5 s");
    f->base.close(&f->base);
}

/* The first answer is said; an answer without a reported outage before it is not; a
 * device that comes and goes is said RATELOG_BURST times, then once per interval with
 * the count of lines left out. */
static void test_first_answer_and_rate_limit(void **state)
{
    char err[256] = "";
    fake_source *f = input_source_alloc(sizeof *f, "tracker", "fake", no_poll, no_close);
    assert_int_equal(input_source_up(&f->base, 0.5, "connected", err, sizeof err), 1);
    assert_string_equal(err, "input tracker: connected");
    err[0] = 0;
    assert_int_equal(input_source_up(&f->base, 0.6, "connected", err, sizeof err), 0);
    assert_string_equal(err, "");
    int said = 0;
    double t = 1.0;
    for (int i = 0; i < 10; i++, t += 0.1) {
        said += input_source_lost(&f->base, t, "gone", err, sizeof err) != 0;
        said += input_source_up(&f->base, t + 0.05, "connected", err, sizeof err) != 0;
    }
    assert_int_equal(said, RATELOG_BURST - 1); /* the first answer was one of the burst */
    t += RATELOG_INTERVAL_MS / 1000.0;
    assert_int_equal(input_source_lost(&f->base, t, "gone", err, sizeof err), -1);
    assert_string_equal(err, "input tracker: gone (16 such lines left out)");
    f->base.close(&f->base);
}

static void test_no_retry(void **state)
{
    char err[256];
    fake_source *f = input_source_alloc(sizeof *f, NULL, "usb", no_poll, no_close);
    assert_false(input_source_retry_due(&f->base, 100.0));
    assert_int_equal(input_source_lost(&f->base, 1.0, "unplugged", err, sizeof err), -1);
    assert_string_equal(err, "input usb: unplugged");
    f->base.close(&f->base);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_alloc_names_and_zeroes),
        cmocka_unit_test(test_one_report_per_outage_and_retry),
        cmocka_unit_test(test_first_answer_and_rate_limit),
        cmocka_unit_test(test_no_retry),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
