/* input_state: the vocabulary every input source, the merge and the interaction layouts
 * share: logical buttons and axes (and the names input configs give them), a tracked
 * pose (and its maths), and the merged state of one poll.
 *
 * Poses are in CAVE space (metres, Y up, wand pointing along its -Z) once merged; a
 * tracker source's own poses are in tracker space until the merge maps them
 * (input_pose_transform()). This module holds types and pure functions only: no source,
 * no file, no clock. */
#ifndef CAVELIGHT_INPUT_STATE_H
#define CAVELIGHT_INPUT_STATE_H

#include <stdint.h>

/* Logical wand buttons, as the paper names them seen from the user, plus one extra. */
typedef enum input_button {
    INPUT_BUTTON_L = 0,   /* left */
    INPUT_BUTTON_M = 1,   /* middle */
    INPUT_BUTTON_R = 2,   /* right: next interaction layout */
    INPUT_BUTTON_C = 3,   /* control (trigger) */
    INPUT_BUTTON_AUX = 4, /* extra button: cycles lambda_incr in the settings layout */
    INPUT_BUTTON_NAMED = 5,
    INPUT_BUTTON_COUNT = 8
} input_button;
/* "L", "M", "R", "C", "AUX" as input configs name them; NULL for the unnamed ones. */
const char *input_button_name(int button);

typedef enum input_axis {
    INPUT_AXIS_X = 0,     /* left to right, [-1, 1] */
    INPUT_AXIS_Y = 1,     /* bottom to top, [-1, 1] */
    INPUT_AXIS_COUNT = 4
} input_axis;
/* "X", "Y", "Z", "W" as input configs name them; NULL outside [0, INPUT_AXIS_COUNT). */
const char *input_axis_name(int axis);

typedef struct input_pose {
    int valid;            /* 0 until the first sample */
    double time;          /* input clock, seconds, of the last sample */
    float position[3];    /* metres */
    float rotation[9];    /* 3x3, column-major: rotation[c*3+r] */
} input_pose;

typedef struct input_state {
    double time;          /* input clock at this poll (seconds since the input was
                             created, or the recording's clock during stepped playback) */
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

/* The pose as a column-major 4x4 matrix (rotation, then translation). */
void input_pose_to_mat4(const input_pose *p, float out[16]);
/* Applies the column-major transform m (rotation, uniform scale, translation; all zeros
 * = identity) to p in place: the position takes all of it, the orientation only the
 * rotation, so it stays orthonormal whatever the scale. */
void input_pose_transform(input_pose *p, const float m[16]);

#endif
