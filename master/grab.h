/* grab: the wand's grab layout (INTERACTION_GRAB, interaction.h): pressing C picks the
 * scene object the wand's ray meets first (the nearest triangle of a shown object, in the
 * frame's pose) and, while C is held, carries it as if fixed to the wand: its model is
 * W_now W_grab^-1 model_grab, with W the wand in world space (navigation * wand). The
 * object keeps the offset it was left at. Only the object's offset changes (scene_pose.h);
 * its parent's motion still applies. No GL, no store: the session writes the pose. */
#ifndef CAVELIGHT_GRAB_H
#define CAVELIGHT_GRAB_H

#include "frame/frame_params.h"
#include "input/input_state.h"
#include "scene/scene_pose.h"

typedef struct grab {
    int object;               /* held, or -1 */
    float wand_start[16];     /* world wand pose when it was picked */
    float model_start[16];    /* its model then */
} grab;

void grab_init(grab *g);
/* One frame: active says the grab layout is the current one (a layout switch drops the
 * object). f holds the frame's navigation; in the wand and the buttons. Returns 1 while
 * an object is held. */
int grab_update(grab *g, const scene *s, scene_pose *pose, const frame_params *f, const input_state *in,
                int active);
/* The object the ray from origin along dir (world space) meets first among the shown
 * objects, and its distance; -1 when none. */
int grab_pick(const scene *s, const scene_pose *pose, const float origin[3], const float dir[3], float *distance);

#endif
