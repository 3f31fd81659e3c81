/* input: the master's merged tracking and wand input, from several sources at once.
 *
 * An input handle owns a list of sources (input_source.h: DTrack UDP, VRPN, USB, desk
 * simulator, playback of a recording) and merges them into one input_state
 * (input_state.h) per master frame:
 *
 *   input *in = input_open(&(input_desc){.path = "configs/input/art.json"}, err, sizeof err);
 *                                            (input_config.h: the sources a config names)
 *   each master frame: input_poll(in, &state, err, sizeof err);  -> interaction_update()
 *   input_close(in);
 *
 * Merging: the head and the wand take the most recently updated pose of any source; held
 * buttons are the OR over sources; presses are counted as edges so that a press and
 * release between two polls is not lost; axes come from the source that moved them last.
 * Tracker sources are mapped into CAVE space through desc.tracker_to_cave; playback and
 * the desk simulator are already in CAVE space. A recording (input_desc.record_path; its
 * folder is created) stores each merged state exactly as polled, so playing it back
 * stepped (one recorded poll per input_poll) reproduces the same interaction and parameter
 * stream bit for bit. This module reads no config and opens no device: see
 * input_config.h for that, docs/input.md for the file formats. */
#ifndef CAVELIGHT_INPUT_H
#define CAVELIGHT_INPUT_H

#include <stddef.h>

#include "input_state.h"

typedef struct input_desc {
    /* An input config (JSON, see configs/input/) or a recording (first line
     * "cavelight-input 1"), which is then played back stepped: input_open() only. */
    const char *path;
    /* Column-major tracker-to-CAVE transform from the cluster config; all zeros means
     * identity. Applied to tracker sources (DTrack, VRPN), not to playback or desk. */
    float tracker_to_cave[16];
    /* Record every merged state to this file (overrides the config's "record"), or NULL. */
    const char *record_path;
    /* Where a relative "record" of the input config goes (never beside the config, which
     * may be in the source tree); NULL = CLUSTER_DEFAULT_OUT. input_open() only. */
    const char *out_dir;
    /* input_open(): a key no part of the config reads is an error (else a warning). */
    int strict;
    /* input_open(): each warning line (an unknown key, with the nearest valid one); NULL
     * prints them on stderr. */
    void (*warn)(void *user, const char *line);
    void *warn_user;
} input_desc;

typedef struct input input;
typedef struct input_source input_source;

/* An input handle with no source yet; add sources with input_add_source(). Returns NULL
 * with a one-line reason in err (the recording cannot be created). */
input *input_create(const input_desc *desc, char *err, size_t errlen);
/* Takes ownership of src (from one of the input_*_open() source constructors). */
int input_add_source(input *in, input_source *src, char *err, size_t errlen);
/* Reads everything the sources have received and merges it. Returns 0; -1 with a
 * one-line warning (a source failed or went silent; the others keep working, and so does
 * the session); or 1 with a one-line notice (a source connected, or its data resumed).
 * Several sources' lines are joined with "; ". */
int input_poll(input *in, input_state *out, char *err, size_t errlen);
void input_close(input *in);

#endif
