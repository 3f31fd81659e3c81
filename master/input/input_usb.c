/* input_usb: HID game controller through libusb-1.0, asynchronous interrupt transfers. */
#include "input_usb.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <libusb.h>

void input_usb_decode(const input_usb_desc *desc, const uint8_t *r, size_t len,
                      uint32_t *buttons, float axes[INPUT_AXIS_COUNT])
{
    *buttons = 0;
    for (int i = 0; i < INPUT_AXIS_COUNT; i++)
        axes[i] = 0.0f;
    for (int i = 0; i < desc->button_count && i < INPUT_USB_MAX_BUTTONS; i++) {
        const input_usb_button *b = &desc->buttons[i];
        if (b->byte < 0 || (size_t)b->byte >= len || b->bit < 0 || b->bit > 7 ||
            b->to < 0 || b->to >= INPUT_BUTTON_COUNT)
            continue;
        if ((r[b->byte] >> b->bit) & 1u)
            *buttons |= 1u << b->to;
    }
    for (int i = 0; i < desc->axis_count && i < INPUT_USB_MAX_AXES; i++) {
        const input_usb_axis *a = &desc->axes[i];
        size_t w = a->format == INPUT_USB_U16 || a->format == INPUT_USB_S16 ? 2 : 1;
        if (a->byte < 0 || (size_t)a->byte + w > len || a->to < 0 || a->to >= INPUT_AXIS_COUNT)
            continue;
        float v, lo, hi;
        uint16_t u16 = (uint16_t)(r[a->byte] | (w == 2 ? r[a->byte + 1] << 8 : 0));
        switch (a->format) {
        case INPUT_USB_S8: v = (float)(int8_t)r[a->byte]; lo = -128; hi = 127; break;
        case INPUT_USB_U16: v = (float)u16; lo = 0; hi = 65535; break;
        case INPUT_USB_S16: v = (float)(int16_t)u16; lo = -32768; hi = 32767; break;
        default: v = (float)r[a->byte]; lo = 0; hi = 255; break;
        }
        if (a->min != 0 || a->max != 0) {
            lo = a->min;
            hi = a->max;
        }
        if (hi == lo)
            continue;
        float x = 2.0f * (v - lo) / (hi - lo) - 1.0f;
        x = x < -1 ? -1 : x > 1 ? 1 : x;
        axes[a->to] = a->invert ? -x : x;
    }
}

typedef struct usb_source {
    input_source base;
    input_usb_desc desc;
    libusb_context *ctx;
    libusb_device_handle *dev; /* NULL while the device is missing */
    struct libusb_transfer *xfer;
    int kernel_detached;
    int failed;               /* the transfer failed: the device is lost */
    int error_code;
    int fresh;                /* a report arrived since the last poll */
    int report_len;
    uint8_t report[64];
    uint8_t buf[64];
} usb_source;

static void LIBUSB_CALL on_report(struct libusb_transfer *t)
{
    usb_source *u = t->user_data;
    if (t->status == LIBUSB_TRANSFER_COMPLETED) {
        memcpy(u->report, t->buffer, (size_t)t->actual_length);
        u->report_len = t->actual_length;
        u->fresh = 1;
    } else if (t->status != LIBUSB_TRANSFER_TIMED_OUT) {
        u->failed = 1;
        u->error_code = t->status;
        return; /* not resubmitted: the device is gone or broken */
    }
    if (libusb_submit_transfer(t) != 0)
        u->failed = 1;
}

/* Lets go of the device (the libusb context stays for the next attempt). */
static void release_device(usb_source *u)
{
    if (u->xfer) {
        /* Cancel and let the callback run before freeing the transfer. */
        if (!u->failed && libusb_cancel_transfer(u->xfer) == 0) {
            struct timeval tv = {0, 100000};
            libusb_handle_events_timeout_completed(u->ctx, &tv, NULL);
        }
        libusb_free_transfer(u->xfer);
        u->xfer = NULL;
    }
    if (u->dev) {
        libusb_release_interface(u->dev, u->desc.interface_number);
        if (u->kernel_detached)
            libusb_attach_kernel_driver(u->dev, u->desc.interface_number);
        libusb_close(u->dev);
        u->dev = NULL;
    }
    u->kernel_detached = 0;
    u->failed = 0;
    u->fresh = 0;
}

/* The first interrupt-in endpoint of the interface, or 0. */
static uint8_t find_endpoint(libusb_device *dev, int iface, int *max_packet)
{
    struct libusb_config_descriptor *cfg;
    uint8_t ep = 0;
    if (libusb_get_active_config_descriptor(dev, &cfg) != 0)
        return 0;
    for (int i = 0; i < cfg->bNumInterfaces && !ep; i++) {
        const struct libusb_interface *in = &cfg->interface[i];
        for (int a = 0; a < in->num_altsetting && !ep; a++) {
            const struct libusb_interface_descriptor *d = &in->altsetting[a];
            if (d->bInterfaceNumber != iface)
                continue;
            for (int e = 0; e < d->bNumEndpoints; e++) {
                const struct libusb_endpoint_descriptor *x = &d->endpoint[e];
                if ((x->bmAttributes & 3) == LIBUSB_TRANSFER_TYPE_INTERRUPT &&
                    (x->bEndpointAddress & LIBUSB_ENDPOINT_IN)) {
                    ep = x->bEndpointAddress;
                    *max_packet = x->wMaxPacketSize;
                    break;
                }
            }
        }
    }
    libusb_free_config_descriptor(cfg);
    return ep;
}

/* One attempt to find, open and start reading the device. Returns 0, or -1 with why. */
static int open_device(usb_source *u, char *why, size_t cap)
{
    const input_usb_desc *desc = &u->desc;
    int rc = u->ctx ? 0 : libusb_init(&u->ctx);
    if (rc != 0) {
        u->ctx = NULL;
        snprintf(why, cap, "cannot start libusb: %s (is /dev/bus/usb available?)", libusb_strerror(rc));
        return -1;
    }
    libusb_device **list;
    ssize_t n = libusb_get_device_list(u->ctx, &list);
    libusb_device *found = NULL;
    for (ssize_t i = 0; i < n && !found; i++) {
        struct libusb_device_descriptor dd;
        if (libusb_get_device_descriptor(list[i], &dd) == 0 && dd.idVendor == desc->vendor &&
            dd.idProduct == desc->product)
            found = list[i];
    }
    if (!found) {
        snprintf(why, cap, "no USB device %04x:%04x found (%zd devices seen); plug it in, check "
                 "\"vendor\"/\"product\" in the input config against lsusb", desc->vendor, desc->product,
                 n < 0 ? (ssize_t)0 : n);
        if (n >= 0)
            libusb_free_device_list(list, 1);
        return -1;
    }
    int max_packet = (int)sizeof u->buf;
    uint8_t ep = desc->endpoint ? desc->endpoint : find_endpoint(found, desc->interface_number, &max_packet);
    rc = libusb_open(found, &u->dev);
    libusb_free_device_list(list, 1);
    if (rc != 0) {
        u->dev = NULL;
        snprintf(why, cap, "cannot open USB device %04x:%04x: %s%s", desc->vendor, desc->product,
                 libusb_strerror(rc), rc == LIBUSB_ERROR_ACCESS ? " (add a udev rule giving your user access, "
                 "e.g. MODE=\"0660\", GROUP=\"plugdev\", then replug)" : "");
        return -1;
    }
    if (libusb_kernel_driver_active(u->dev, desc->interface_number) == 1 &&
        libusb_detach_kernel_driver(u->dev, desc->interface_number) == 0)
        u->kernel_detached = 1;
    rc = libusb_claim_interface(u->dev, desc->interface_number);
    if (rc != 0 || !ep) {
        snprintf(why, cap, "USB device %04x:%04x: %s", desc->vendor, desc->product,
                 rc ? libusb_strerror(rc) : "no interrupt-in endpoint on the interface; set \"interface\" or "
                 "\"endpoint\" in the input config");
        release_device(u);
        return -1;
    }
    u->xfer = libusb_alloc_transfer(0);
    int len = max_packet > 0 && max_packet < (int)sizeof u->buf ? max_packet : (int)sizeof u->buf;
    libusb_fill_interrupt_transfer(u->xfer, u->dev, ep, u->buf, len, on_report, u, 0);
    rc = libusb_submit_transfer(u->xfer);
    if (rc != 0) {
        snprintf(why, cap, "cannot read USB device %04x:%04x: %s", desc->vendor, desc->product,
                 libusb_strerror(rc));
        u->failed = 1; /* nothing pending to cancel */
        release_device(u);
        return -1;
    }
    return 0;
}

static int usb_poll(input_source *s, double now, char *err, size_t errlen)
{
    usb_source *u = (usb_source *)s;
    char why[512];
    if (!u->dev) {
        if (!input_source_retry_due(s, now))
            return 0;
        if (open_device(u, why, sizeof why) != 0)
            return input_source_lost(s, now, why, err, errlen);
        snprintf(why, sizeof why, "USB device %04x:%04x opened", u->desc.vendor, u->desc.product);
        return input_source_up(s, now, why, err, errlen);
    }
    struct timeval zero = {0, 0};
    libusb_handle_events_timeout_completed(u->ctx, &zero, NULL);
    if (u->fresh) {
        uint32_t buttons;
        float axes[INPUT_AXIS_COUNT];
        input_usb_decode(&u->desc, u->report, (size_t)u->report_len, &buttons, axes);
        input_source_set_buttons(&s->st, buttons, now);
        input_source_set_axes(&s->st, axes, INPUT_AXIS_COUNT, now);
        u->fresh = 0;
    }
    if (u->failed) {
        snprintf(why, sizeof why, "USB device %04x:%04x stopped reporting (transfer status %d); unplugged?",
                 u->desc.vendor, u->desc.product, u->error_code);
        release_device(u);
        float still[INPUT_AXIS_COUNT] = {0};
        input_source_set_axes(&s->st, still, INPUT_AXIS_COUNT, now); /* no stick stays pushed */
        return input_source_lost(s, now, why, err, errlen);
    }
    return 0;
}

static void usb_close(input_source *s)
{
    usb_source *u = (usb_source *)s;
    release_device(u);
    if (u->ctx)
        libusb_exit(u->ctx);
    free(u);
}

input_source *input_usb_open(const input_usb_desc *desc)
{
    usb_source *u = input_source_alloc(sizeof *u, desc->name, "usb", usb_poll, usb_close);
    u->desc = *desc;
    u->desc.name = NULL;
    u->base.retry_interval = desc->retry_interval > 0 ? desc->retry_interval : INPUT_SOURCE_RETRY_INTERVAL;
    return &u->base; /* the first poll looks for the device */
}
