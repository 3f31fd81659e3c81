/* input_playback: recording of merged input states to a text file, and playback of it.
 *
 * Format (one record a line, '#' starts a comment, numbers in C locale; floats with 9 and
 * doubles with 17 significant digits so that values round-trip exactly):
 *
 *   cavelight-input 1                        first line, format and version
 *   head <t> <x y z> <r0 .. r8>              pose sampled at input time t (metres,
 *   wand <t> <x y z> <r0 .. r8>                column-major 3x3 rotation, CAVE space)
 *   buttons <t> <held> <pressed>             logical button masks, hexadecimal
 *   axes <t> <a0 a1 a2 a3>                   logical axes in [-1, 1]
 *   poll <time> <dt>                         closes the block of one input_poll();
 *                                            0 < dt <= INPUT_PLAYBACK_MAX_DT (dt = 0
 *                                            only on the first poll: nothing elapsed)
 *
 * A block holds only what changed since the previous poll. Playback is either stepped
 * (each input_poll() consumes one block and takes its clock: deterministic, the default)
 * or realtime (blocks are released when their poll time has passed since the source was
 * opened). Playback sources are in CAVE space: no tracker transform is applied. */
#ifndef CAVELIGHT_INPUT_PLAYBACK_H
#define CAVELIGHT_INPUT_PLAYBACK_H

#include <stddef.h>
#include "input_source.h"

#define INPUT_PLAYBACK_MAGIC "cavelight-input 1"
/* Longest step a recording may hold, seconds: a poll gap beyond it is no frame step. */
#define INPUT_PLAYBACK_MAX_DT 10.0

typedef struct input_playback_desc {
    const char *name;
    const char *path;
    int realtime;        /* 0: stepped (one block per poll) */
    int loop;            /* realtime only: start again at the end */
} input_playback_desc;

input_source *input_playback_open(const input_playback_desc *desc, char *err, size_t errlen);

/* 1 if the file at path starts with the recording magic line. */
int input_playback_is_recording(const char *path);

typedef struct input_playback_recorder input_playback_recorder;
input_playback_recorder *input_playback_record_open(const char *path, char *err, size_t errlen);
/* Appends the block of one polled state. Returns 0 or -1 with a reason. */
int input_playback_record(input_playback_recorder *r, const input_state *s, char *err, size_t errlen);
void input_playback_record_close(input_playback_recorder *r);

#endif
