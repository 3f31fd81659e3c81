/* input_vrpn: a VRPN client over a TCP-only connection (no UDP), the protocol most CAVE
 * trackers speak.
 *
 * Protocol (public VRPN wire format): after connect() both sides send a 24-byte cookie
 * "vrpn: ver. 07.35  0" padded with NULs; only the major version must match. Then every
 * message is a 24-byte header of big-endian 32-bit fields (length = 24 + unpadded body
 * length, time seconds, time microseconds, sender id, type id, then 4 bytes of padding)
 * followed by the body padded to a multiple of 8. Sender and type ids are per connection:
 * the peer describes them with SENDER_DESCRIPTION (type -1) and TYPE_DESCRIPTION (type -2)
 * messages whose sender field is the id and whose body is a 32-bit length (with NUL) and
 * the NUL-terminated name. We read:
 *   "vrpn_Tracker Pos_Quat"  i32 sensor, i32 pad, f64 pos[3], f64 quat[4] (x, y, z, w)
 *   "vrpn_Button Change"     i32 button, i32 state
 *   "vrpn_Button States"     i32 count, i32 state[count]
 *   "vrpn_Analog Channel"    f64 count, f64 channel[count]
 * from the configured device names (the part before '@' in "Tracker0@host"). A NaN or
 * infinite value drops its message; a length outside [24, 64 KiB] or a bad cookie drops
 * the connection. The source reconnects every reconnect_interval seconds while the server
 * is away, and releases all buttons while disconnected. */
#ifndef CAVELIGHT_INPUT_VRPN_H
#define CAVELIGHT_INPUT_VRPN_H

#include <stddef.h>
#include <stdint.h>
#include "input_source.h"

#define INPUT_VRPN_COOKIE "vrpn: ver. 07.35"
enum {
    INPUT_VRPN_COOKIE_SIZE = 24,
    INPUT_VRPN_HEADER_SIZE = 24,
    INPUT_VRPN_MAX_MESSAGE = 65536,
    INPUT_VRPN_MAX_IDS = 256,          /* remote sender/type ids we remember */
    INPUT_VRPN_DEFAULT_PORT = 3883,
    INPUT_VRPN_SENDER_DESCRIPTION = -1,
    INPUT_VRPN_TYPE_DESCRIPTION = -2,
};

typedef struct input_vrpn_desc {
    const char *name;
    const char *host;             /* NULL = "localhost" */
    int port;                     /* 0 = 3883 */
    const char *tracker;          /* sender name of the tracker, NULL = "Tracker0" */
    int sensors_set;              /* 0: head sensor 0, wand sensor 1 (the defaults) */
    int head_sensor;              /* used when sensors_set; -1 none */
    int wand_sensor;
    const char *buttons;          /* sender name of the buttons, NULL = tracker name */
    const char *analog;           /* sender name of the analogs, NULL = buttons name */
    input_map button_map;         /* VRPN button -> logical button */
    input_map axis_map;           /* analog channel -> logical axis */
    double reconnect_interval;    /* seconds, 0 = INPUT_SOURCE_RETRY_INTERVAL */
} input_vrpn_desc;

/* One connection's decoding state: the peer's id tables and the raw button mask. */
typedef struct input_vrpn_session {
    char senders[INPUT_VRPN_MAX_IDS][64];
    char types[INPUT_VRPN_MAX_IDS][64];
    uint32_t raw_buttons;
    int messages;                 /* device messages applied */
    int dropped;                  /* messages dropped (bad values, unknown ids) */
} input_vrpn_session;

/* Decodes the complete messages at the start of buf (after the cookie) into st at input
 * clock t. Returns the bytes consumed (a trailing partial message is left for later), or
 * -1 with a reason in err if the stream is not VRPN (the connection must be dropped). */
long input_vrpn_decode(const input_vrpn_desc *desc, input_vrpn_session *s, const uint8_t *buf,
                       size_t len, input_source_state *st, double t, char *err, size_t errlen);
/* 1 if the 24 bytes are a VRPN cookie with our major version. */
int input_vrpn_cookie_ok(const uint8_t cookie[INPUT_VRPN_COOKIE_SIZE]);
void input_vrpn_write_cookie(uint8_t cookie[INPUT_VRPN_COOKIE_SIZE]);
/* Writes one framed message into out (capacity cap). Returns its padded size, or 0. */
size_t input_vrpn_frame(uint8_t *out, size_t cap, int32_t sender, int32_t type,
                        const void *body, size_t body_len);

input_source *input_vrpn_open(const input_vrpn_desc *desc, char *err, size_t errlen);
/* 1 while connected and past the cookie exchange (tests). */
int input_vrpn_connected(const input_source *s);
/* How many times the source has completed a connection (tests). */
int input_vrpn_connections(const input_source *s);

#endif
