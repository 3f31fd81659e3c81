/* input_state: button and axis names, pose maths (input_state.h). */
#include "input_state.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

static const char *const button_names[INPUT_BUTTON_NAMED] = {"L", "M", "R", "C", "AUX"};
static const char *const axis_names[INPUT_AXIS_COUNT] = {"X", "Y", "Z", "W"};

const char *input_button_name(int button)
{
    return button >= 0 && button < INPUT_BUTTON_NAMED ? button_names[button] : NULL;
}

const char *input_axis_name(int axis)
{
    return axis >= 0 && axis < INPUT_AXIS_COUNT ? axis_names[axis] : NULL;
}

void input_pose_to_mat4(const input_pose *p, float out[16])
{
    for (int c = 0; c < 3; c++) {
        for (int r = 0; r < 3; r++)
            out[c * 4 + r] = p->rotation[c * 3 + r];
        out[c * 4 + 3] = 0.0f;
    }
    for (int r = 0; r < 3; r++)
        out[12 + r] = p->position[r];
    out[15] = 1.0f;
}

static int is_zero16(const float m[16])
{
    for (int i = 0; i < 16; i++)
        if (m[i] != 0.0f)
            return 0;
    return 1;
}

void input_pose_transform(input_pose *p, const float m[16])
{
    if (is_zero16(m))
        return;
    float pos[3], rot[9];
    for (int r = 0; r < 3; r++) {
        pos[r] = m[12 + r];
        for (int k = 0; k < 3; k++)
            pos[r] += m[k * 4 + r] * p->position[k];
    }
    /* m's 3x3 is a rotation times a uniform scale (units, e.g. 0.001 for millimetres):
     * positions take the scale, an orientation only the rotation (the columns' unit
     * vectors), or the head-to-eye offset would shrink with it. */
    float inv_scale[3];
    for (int k = 0; k < 3; k++) {
        float len = sqrtf(m[k * 4] * m[k * 4] + m[k * 4 + 1] * m[k * 4 + 1] + m[k * 4 + 2] * m[k * 4 + 2]);
        inv_scale[k] = len > 0.0f ? 1.0f / len : 0.0f;
    }
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++) {
            float s = 0.0f;
            for (int k = 0; k < 3; k++)
                s += m[k * 4 + r] * inv_scale[k] * p->rotation[c * 3 + k];
            rot[c * 3 + r] = s;
        }
    memcpy(p->position, pos, sizeof pos);
    memcpy(p->rotation, rot, sizeof rot);
}
