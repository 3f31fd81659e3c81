/* USB controller source: report decoding with a configurable map, and a clear one-line
 * message when no device matches (this machine has none). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "input/input.h"
#include "input/input_config.h"
#include "input/input_usb.h"

/* A typical gamepad report: byte 0 report id, byte 1 buttons, bytes 2-3 u8 sticks,
 * bytes 4-5 an s16 trigger. */
static input_usb_desc pad(void)
{
    input_usb_desc d = {.name = "pad", .vendor = 0x046d, .product = 0xc21d};
    d.button_count = 4;
    d.buttons[0] = (input_usb_button){.byte = 1, .bit = 0, .to = INPUT_BUTTON_L};
    d.buttons[1] = (input_usb_button){.byte = 1, .bit = 1, .to = INPUT_BUTTON_M};
    d.buttons[2] = (input_usb_button){.byte = 1, .bit = 2, .to = INPUT_BUTTON_R};
    d.buttons[3] = (input_usb_button){.byte = 1, .bit = 7, .to = INPUT_BUTTON_C};
    d.axis_count = 3;
    d.axes[0] = (input_usb_axis){.byte = 2, .format = INPUT_USB_U8, .to = INPUT_AXIS_X};
    d.axes[1] = (input_usb_axis){.byte = 3, .format = INPUT_USB_U8, .to = INPUT_AXIS_Y, .invert = 1};
    d.axes[2] = (input_usb_axis){.byte = 4, .format = INPUT_USB_S16, .min = -1000, .max = 1000,
                                 .to = 2};
    return d;
}

static void test_decode(void **state)
{
    input_usb_desc d = pad();
    uint32_t b;
    float ax[INPUT_AXIS_COUNT];
    const uint8_t r1[6] = {1, 0x85, 255, 0, 0xf4, 0x01};     /* s16 500 */
    input_usb_decode(&d, r1, sizeof r1, &b, ax);
    assert_int_equal(b, (1u << INPUT_BUTTON_L) | (1u << INPUT_BUTTON_R) | (1u << INPUT_BUTTON_C));
    assert_float_equal(ax[INPUT_AXIS_X], 1.0f, 0);
    assert_float_equal(ax[INPUT_AXIS_Y], 1.0f, 0);            /* 0 is up: inverted */
    assert_float_equal(ax[2], 0.5f, 1e-6);                    /* 500 in [-1000, 1000] */
    const uint8_t r2[6] = {1, 0x02, 128, 64, 0x30, 0xf8};     /* s16 -2000: clamped */
    input_usb_decode(&d, r2, sizeof r2, &b, ax);
    assert_int_equal(b, 1u << INPUT_BUTTON_M);
    assert_float_equal(ax[INPUT_AXIS_X], 2.0f * 128 / 255 - 1, 1e-6);
    assert_float_equal(ax[INPUT_AXIS_Y], -(2.0f * 64 / 255 - 1), 1e-6);
    assert_float_equal(ax[2], -1.0f, 0);
    /* a short report leaves out what it does not hold */
    input_usb_decode(&d, r1, 3, &b, ax);
    assert_int_equal(b, (1u << INPUT_BUTTON_L) | (1u << INPUT_BUTTON_R) | (1u << INPUT_BUTTON_C));
    assert_float_equal(ax[INPUT_AXIS_X], 1.0f, 0);
    assert_float_equal(ax[INPUT_AXIS_Y], 0.0f, 0);
    assert_float_equal(ax[2], 0.0f, 0);
    /* s8 and u16 full ranges */
    input_usb_desc d2 = {.axis_count = 2};
    d2.axes[0] = (input_usb_axis){.byte = 0, .format = INPUT_USB_S8, .to = 0};
    d2.axes[1] = (input_usb_axis){.byte = 1, .format = INPUT_USB_U16, .to = 1};
    const uint8_t r3[3] = {0x80, 0xff, 0xff};
    input_usb_decode(&d2, r3, sizeof r3, &b, ax);
    assert_float_equal(ax[0], -1.0f, 0);
    assert_float_equal(ax[1], 1.0f, 0);
}

/* A missing device is a warning with a retry: the source exists, says once what is wrong
 * and that it retries, stays quiet while the device stays away, and keeps nothing held. */
static void test_no_device(void **state)
{
    char err[512] = "";
    input_usb_desc d = pad();
    d.vendor = 0xfffe;        /* no such vendor is assigned */
    d.product = 0x1234;
    d.retry_interval = 0.5;
    input_source *s = input_usb_open(&d);
    assert_non_null(s);
    assert_int_equal(s->poll(s, 0.0, err, sizeof err), -1);
    assert_null(strchr(err, '\n'));
    if (!strstr(err, "input pad: no USB device fffe:1234 found") && !strstr(err, "input pad: cannot start libusb"))
        fail_msg("unexpected message: %s", err);
    assert_non_null(strstr(err, "; retrying every 0.5 s"));
    printf("message: %s\n", err);
    err[0] = 0;
    assert_int_equal(s->poll(s, 0.1, err, sizeof err), 0);   /* not due yet */
    assert_int_equal(s->poll(s, 0.6, err, sizeof err), 0);   /* tried again, still away: quiet */
    assert_string_equal(err, "");
    assert_int_equal(s->st.buttons, 0);
    s->close(s);

    /* the same through an input config: the input opens, the first poll warns */
    char path[1024];
    snprintf(path, sizeof path, "%s/test_usb_config.json", CAVELIGHT_BINARY_DIR);
    FILE *f = fopen(path, "wb");
    fputs("{\"sources\": [{\"type\": \"usb\", \"name\": \"wand\", \"vendor\": \"0xfffe\", "
          "\"product\": \"0x1234\", \"reconnect\": 2, \"buttons\": [{\"byte\": 1, \"bit\": 0, \"to\": \"C\"}], "
          "\"axes\": [{\"byte\": 2, \"format\": \"u8\", \"to\": \"X\"}]}]}", f);
    fclose(f);
    input *in = input_open(&(input_desc){.path = path}, err, sizeof err);
    assert_non_null(in);
    input_state st;
    assert_int_equal(input_poll(in, &st, err, sizeof err), -1);
    assert_non_null(strstr(err, "input wand: "));
    assert_true(strstr(err, "fffe:1234") || strstr(err, "libusb"));
    assert_non_null(strstr(err, "retrying every 2 s"));
    input_close(in);
    /* a mistake in the map is reported before any device is looked for */
    f = fopen(path, "wb");
    fputs("{\"sources\": [{\"type\": \"usb\", \"vendor\": 1, \"product\": 2, "
          "\"axes\": [{\"byte\": 2, \"format\": \"u12\", \"to\": \"X\"}]}]}", f);
    fclose(f);
    assert_null(input_open(&(input_desc){.path = path}, err, sizeof err));
    assert_non_null(strstr(err, "\"u12\""));
    remove(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_decode),
        cmocka_unit_test(test_no_device),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
