/* input_dtrack: ART DTrack2 ASCII UDP output.
 *
 * input_dtrack_parse() is a pure function over one datagram (no NUL needed): it reads the
 * lines fr, ts, 6dcal, 6d (bodies), 6df2 (flysticks: buttons, controllers) and 3d
 * (markers), converts millimetres to metres and keeps the 3x3 rotations column-wise as
 * DTrack sends them. Unknown line types and extra values (inside a block or after the
 * last block) are ignored. A line that is truncated, non-numeric, holds NaN/inf or a
 * count that does not fit is dropped whole and counted in lines_bad; the parser never
 * reads outside buf.
 *
 * input_dtrack_open() makes a source that listens on a UDP port and maps one 6d body to
 * the head and one flystick (or body) to the wand, the flystick's buttons and
 * controllers to logical buttons and axes. The port is bound without SO_REUSEADDR, so no
 * other program can share it (and read the datagrams instead); on the address of `bind`
 * (an IPv4 address or an interface name) or on every interface. With `sender` set, only
 * datagrams from that host count; others are dropped, counted and logged, rate-limited.
 * When no datagram has arrived for silence_s seconds the source says so once, releases
 * its buttons and the session goes on without tracking; the first datagram after that
 * says so too (input_source_lost() and input_source_up()). */
#ifndef CAVELIGHT_INPUT_DTRACK_H
#define CAVELIGHT_INPUT_DTRACK_H

#include <stddef.h>
#include <stdint.h>
#include "input_source.h"

enum {
    INPUT_DTRACK_MAX_BODIES = 32,
    INPUT_DTRACK_MAX_FLYSTICKS = 8,
    INPUT_DTRACK_MAX_MARKERS = 64,
    INPUT_DTRACK_MAX_BUTTONS = 32,      /* per flystick; more are dropped */
    INPUT_DTRACK_MAX_CONTROLLERS = 8,   /* per flystick; more are ignored */
    INPUT_DTRACK_DEFAULT_PORT = 5000,
};
#define INPUT_DTRACK_SILENCE_S 1.0      /* default: no datagram this long is an outage */

typedef struct input_dtrack_body {
    int id;
    float quality;                      /* < 0: not tracked, pose meaningless */
    float position[3];                  /* metres */
    float rotation[9];                  /* column-major */
} input_dtrack_body;

typedef struct input_dtrack_flystick {
    int id;
    float quality;
    float position[3];
    float rotation[9];
    int button_count;
    uint32_t buttons;                   /* bit i: button i pressed */
    int controller_count;
    float controllers[INPUT_DTRACK_MAX_CONTROLLERS]; /* [-1, 1] */
} input_dtrack_flystick;

typedef struct input_dtrack_marker {
    int id;
    float quality;
    float position[3];
} input_dtrack_marker;

typedef struct input_dtrack_frame {
    int has_frame;
    uint32_t frame;
    int has_timestamp;
    double timestamp;                   /* seconds since midnight (tracker clock) */
    int calibrated_bodies;              /* from 6dcal, -1 if absent */
    int body_count;
    input_dtrack_body bodies[INPUT_DTRACK_MAX_BODIES];
    int flystick_count;
    input_dtrack_flystick flysticks[INPUT_DTRACK_MAX_FLYSTICKS];
    int marker_count;
    input_dtrack_marker markers[INPUT_DTRACK_MAX_MARKERS];
    int lines_parsed;                   /* known lines accepted */
    int lines_ignored;                  /* unknown line types, empty lines */
    int lines_bad;                      /* dropped: malformed or over the limits */
} input_dtrack_frame;

/* Parses one datagram into out (cleared first). Returns lines_bad. */
int input_dtrack_parse(const char *buf, size_t len, input_dtrack_frame *out);

typedef enum input_dtrack_wand {
    INPUT_DTRACK_WAND_FLYSTICK = 0,     /* wand = 6df2 flystick wand_id (default) */
    INPUT_DTRACK_WAND_BODY = 1,         /* wand = 6d body wand_id, no buttons */
} input_dtrack_wand;

typedef struct input_dtrack_desc {
    const char *name;
    int port;                           /* UDP port; 0 = any free port (tests) */
    const char *bind;                   /* IPv4 address or interface; NULL = all interfaces */
    const char *sender;                 /* only datagrams from this host; NULL = any */
    double silence_s;                   /* outage after this long without data; 0 = default */
    int head_id;                        /* 6d body id of the head, default 0; -1 none */
    int wand_id;                        /* flystick or body id of the wand, default 0 */
    input_dtrack_wand wand_kind;
    input_map buttons;                  /* flystick button -> logical button */
    input_map axes;                     /* flystick controller -> logical axis */
} input_dtrack_desc;

input_source *input_dtrack_open(const input_dtrack_desc *desc, char *err, size_t errlen);
/* The UDP port the source listens on (useful with port 0). */
int input_dtrack_port(const input_source *s);
/* Datagrams used, and dropped for coming from another host than `sender`. */
uint64_t input_dtrack_datagrams(const input_source *s);
uint64_t input_dtrack_refused(const input_source *s);
/* Applies one parsed frame to a source state at input clock t (exposed for tests). */
void input_dtrack_apply(const input_dtrack_desc *desc, const input_dtrack_frame *f,
                        input_source_state *st, double t);

#endif
