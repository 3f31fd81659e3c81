/* input_usb: a USB game controller or wand through libusb-1.0.
 *
 * The source opens the first device with the configured vendor and product ids, claims
 * the interface (detaching a kernel HID driver if one holds it), and keeps an interrupt-in
 * transfer pending; each HID input report is decoded with a configurable byte/bit map:
 * buttons are bits, axes are u8, s8, u16 or s16 (little-endian, as HID reports are)
 * scaled from [min, max] to [-1, 1]. The device gives no pose: use it beside a tracker.
 * A device that is missing, refuses access (a udev rule is the usual fix) or is unplugged
 * is a warning, not an error: the source looks for it again every retry_interval seconds
 * (buttons released, axes centred meanwhile) and says when it answers; the session goes on
 * with the other sources. input_usb_decode() is pure and needs no device. */
#ifndef CAVELIGHT_INPUT_USB_H
#define CAVELIGHT_INPUT_USB_H

#include <stddef.h>
#include <stdint.h>
#include "input_source.h"

enum { INPUT_USB_MAX_BUTTONS = 16, INPUT_USB_MAX_AXES = 4 };

typedef enum input_usb_format {
    INPUT_USB_U8 = 0, INPUT_USB_S8, INPUT_USB_U16, INPUT_USB_S16
} input_usb_format;

typedef struct input_usb_button {
    int byte, bit;             /* position in the report */
    int to;                    /* logical button */
} input_usb_button;

typedef struct input_usb_axis {
    int byte;
    input_usb_format format;
    float min, max;            /* raw range; both 0 = the format's full range */
    int to;                    /* logical axis */
    int invert;                /* flip the sign (HID Y axes usually grow downwards) */
} input_usb_axis;

typedef struct input_usb_desc {
    const char *name;
    uint16_t vendor, product;
    int interface_number;      /* default 0 */
    uint8_t endpoint;          /* interrupt-in endpoint address, 0 = the interface's first */
    int button_count;
    input_usb_button buttons[INPUT_USB_MAX_BUTTONS];
    int axis_count;
    input_usb_axis axes[INPUT_USB_MAX_AXES];
    double retry_interval;     /* seconds between looks for a missing device, 0 = the default */
} input_usb_desc;

/* Decodes one report. Fields beyond len are left out (buttons up, axes 0). */
void input_usb_decode(const input_usb_desc *desc, const uint8_t *report, size_t len,
                      uint32_t *buttons, float axes[INPUT_AXIS_COUNT]);

/* Never fails: the first poll looks for the device. */
input_source *input_usb_open(const input_usb_desc *desc);

#endif
