/* input_source: what every input source implements, and the skeleton they share.
 *
 * A source keeps its own input_source_state (poses, held buttons, press edges, axes, each
 * with the input clock time of its last change). input_poll() calls poll() on every
 * source, then merges their states (see input.h) and clears each source's press edges.
 * A source never blocks in poll(): it reads what has arrived and returns.
 *
 * The skeleton of a device source (DTrack, VRPN, USB), once: input_source_alloc() makes
 * it (name from the config or a fallback, poll and close); when its device goes away,
 * input_source_lost() releases its buttons (nothing stays held, e.g. C = fly), schedules
 * the next attempt retry_interval seconds later (0: the source does not retry) and reports
 * the first loss of an outage in one line; input_source_retry_due() says when to try
 * again and input_source_up() ends the outage with one line (and says when the device
 * first answers). A device that comes and goes cannot flood the log: these lines share
 * one ratelog per source.
 *
 * poll() returns 0 with nothing to say, -1 with a warning or error in err (a loss, a
 * refused sender, a failed read) or 1 with a notice (connected, data again). */
#ifndef CAVELIGHT_INPUT_SOURCE_H
#define CAVELIGHT_INPUT_SOURCE_H

#include <stddef.h>
#include <stdint.h>
#include "base/ratelog.h"
#include "input_state.h"

typedef struct input_source input_source;

enum { INPUT_MAP_SIZE = 32 };
/* Seconds between a device source's attempts to reach a missing device, by default. */
#define INPUT_SOURCE_RETRY_INTERVAL 1.0

typedef struct input_source_state {
    input_pose head;
    input_pose wand;
    uint32_t buttons;          /* logical buttons held */
    uint32_t pressed;          /* logical press edges since the last merge */
    double buttons_time;
    float axes[INPUT_AXIS_COUNT];
    double axes_time;          /* 0 = never moved */
} input_source_state;

struct input_source {
    char name[64];             /* from the config, for messages */
    int cave_space;            /* poses already in CAVE space (no tracker transform) */
    int stepped;               /* stepped playback: drives the input clock */
    int finished;              /* stepped playback ran out */
    int failed;                /* playback stopped on a malformed file */
    double step_time;          /* stepped playback: clock of the current step */
    double step_dt;
    double retry_interval;     /* seconds between attempts after a loss; 0 = no retry */
    double next_attempt;       /* input clock of the next attempt */
    int outage_reported;       /* the current outage was reported: stay quiet until up */
    double outage_since;       /* input clock when the current outage began */
    int ups;                   /* times the device answered (connects, first data) */
    ratelog log;               /* this source's loss and recovery lines */
    input_source_state st;
    /* now: input clock, seconds. Returns 0, -1 with a warning or 1 with a notice (one
     * line in err). */
    int (*poll)(input_source *s, double now, char *err, size_t errlen);
    void (*close)(input_source *s);
};

typedef int (*input_source_poll_fn)(input_source *s, double now, char *err, size_t errlen);
typedef void (*input_source_close_fn)(input_source *s);

/* A zeroed source of `size` bytes (a struct that starts with its input_source), named
 * `name` or else `fallback` (xcalloc(): never NULL). */
void *input_source_alloc(size_t size, const char *name, const char *fallback,
                         input_source_poll_fn poll, input_source_close_fn close);
/* The device went away (why: what happened). Returns -1 with "input NAME: WHY[; retrying
 * every S s]" for the first loss of an outage, 0 for the later ones and for lines the
 * rate limit leaves out. */
int input_source_lost(input_source *s, double now, const char *why, char *err, size_t errlen);
/* 1 when a retrying source may try to reach its device again. */
int input_source_retry_due(const input_source *s, double now);
/* The device answers (what: e.g. "connected to VRPN server h:3883"). Returns 1 with
 * "input NAME: WHAT" the first time, or with "input NAME: WHAT again after S s" at the end
 * of a reported outage; otherwise (or rate-limited) 0. The next loss is reported. */
int input_source_up(input_source *s, double now, const char *what, char *err, size_t errlen);

/* Sets the held buttons at time t and records press edges. */
void input_source_set_buttons(input_source_state *st, uint32_t held, double t);
/* Sets axis values at time t (NaN and out-of-range values are clamped to [-1, 1], NaN to 0). */
void input_source_set_axes(input_source_state *st, const float *axes, int count, double t);

/* Raw-to-logical maps: map[raw] = logical index, or -1 to ignore. An all-zero map (the
 * zero-initialised default) means identity. */
typedef struct input_map {
    int8_t to[INPUT_MAP_SIZE];
    int set;                   /* 0: identity */
} input_map;
uint32_t input_map_buttons(const input_map *m, uint32_t raw);
/* Maps raw axes (count values) to logical axes; unmapped logical axes are 0. */
void input_map_axes(const input_map *m, const float *raw, int count, float out[INPUT_AXIS_COUNT]);

#endif
