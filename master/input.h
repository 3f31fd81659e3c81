/* input: the master's tracking and wand input, from several sources at once.
 *
 * An input handle owns the sources named in an input config (DTrack UDP, VRPN, USB, desk
 * simulator, playback of a recording) and merges them into one input_state per master
 * frame:
 *
 *   input *in = input_open(&(input_desc){.path = "configs/input/art.json"}, err, sizeof err);
 *   each master frame: input_poll(in, &state, err, sizeof err);  -> interaction_update()
 *   input_close(in);
 *
 * Merging: the head and the wand take the most recently updated pose of any source; held
 * buttons are the OR over sources; presses are counted as edges so that a press and
 * release between two polls is not lost; axes come from the source that moved them last.
 * Poses are in CAVE space (metres, Y up, wand pointing along its -Z): tracker sources are
 * mapped through desc.tracker_to_cave, playback and the desk simulator are already in CAVE
 * space. A recording (input_desc.record_path, or the config's "record" inside
 * input_desc.out_dir; its folder is created) stores each merged state exactly as polled,
 * so playing it back stepped (one recorded poll per input_poll) reproduces the same
 * interaction and parameter stream bit for bit. See docs/input.md for the file formats. */
#ifndef CAVELIGHT_INPUT_H
#define CAVELIGHT_INPUT_H

#include <stddef.h>
#include <stdint.h>

/* Logical wand buttons, as the paper names them seen from the user, plus one extra. */
typedef enum input_button {
    INPUT_BUTTON_L = 0,   /* left */
    INPUT_BUTTON_M = 1,   /* middle */
    INPUT_BUTTON_R = 2,   /* right: next interaction layout */
    INPUT_BUTTON_C = 3,   /* control (trigger) */
    INPUT_BUTTON_AUX = 4, /* extra button: cycles lambda_incr in the settings layout */
    INPUT_BUTTON_COUNT = 8
} input_button;
/* "L", "M", "R", "C", "AUX" as input configs name them; NULL for the unnamed ones. */
const char *input_button_name(int button);

typedef enum input_axis {
    INPUT_AXIS_X = 0,     /* left to right, [-1, 1] */
    INPUT_AXIS_Y = 1,     /* bottom to top, [-1, 1] */
    INPUT_AXIS_COUNT = 4
} input_axis;

typedef struct input_pose {
    int valid;            /* 0 until the first sample */
    double time;          /* input clock, seconds, of the last sample */
    float position[3];    /* metres */
    float rotation[9];    /* 3x3, column-major: rotation[c*3+r] */
} input_pose;

typedef struct input_state {
    double time;          /* input clock at this poll (seconds since input_open, or the
                             recording's clock during stepped playback) */
    double dt;            /* time since the previous poll, 0 on the first */
    input_pose head;
    input_pose wand;
    uint32_t buttons;     /* bit b: logical button b held now */
    uint32_t pressed;     /* bit b: button b went down since the previous poll */
    double buttons_time;
    float axes[INPUT_AXIS_COUNT];
    double axes_time;
    int finished;         /* a stepped playback source has reached its end */
    int failed;           /* a playback source stopped on a malformed file: the session
                             must end with an error (input_poll's message says where) */
} input_state;

typedef struct input_desc {
    /* An input config (JSON, see configs/input/) or a recording (first line
     * "cavelight-input 1"), which is then played back stepped. */
    const char *path;
    /* Column-major tracker-to-CAVE transform from the cluster config; all zeros means
     * identity. Applied to tracker sources (DTrack, VRPN), not to playback or desk. */
    float tracker_to_cave[16];
    /* Record every merged state to this file (overrides the config's "record"), or NULL. */
    const char *record_path;
    /* Where a relative "record" of the input config goes (never beside the config, which
     * may be in the source tree); NULL = CLUSTER_DEFAULT_OUT. */
    const char *out_dir;
} input_desc;

typedef struct input input;
typedef struct input_source input_source;

/* Returns NULL with a one-line reason in err. */
input *input_open(const input_desc *desc, char *err, size_t errlen);
/* Takes ownership of src (from one of the input_*_open() source constructors). */
int input_add_source(input *in, input_source *src, char *err, size_t errlen);
/* Reads everything the sources have received and merges it. Returns 0; -1 with a
 * one-line warning (a source failed or went silent; the others keep working, and so does
 * the session); or 1 with a one-line notice (a source connected, or its data resumed).
 * Several sources' lines are joined with "; ". */
int input_poll(input *in, input_state *out, char *err, size_t errlen);
void input_close(input *in);

/* An input handle with no source yet (tests, benchmarks); add sources with
 * input_add_source(). */
input *input_create(const input_desc *desc, char *err, size_t errlen);

/* Pose helpers shared by sources and layouts. */
void input_pose_to_mat4(const input_pose *p, float out[16]);
/* Applies the column-major transform m (rotation, uniform scale, translation; all zeros
 * = identity) to p in place: the position takes all of it, the orientation only the
 * rotation, so it stays orthonormal whatever the scale. */
void input_pose_transform(input_pose *p, const float m[16]);

#endif
