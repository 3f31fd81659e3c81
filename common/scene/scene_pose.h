/* scene_pose: where a scene's objects (scene_object, scene.h) are in one frame.
 *
 * Each object has an offset, a transform of its triangles as loaded (in the scene's space,
 * after placement), applied after its parent's: model(o) = model(parent) * offset(o), so
 * moving a parent moves its children. Identity everywhere is the scene as loaded. An
 * object is shown when it and every ancestor are visible. The master sets offsets and
 * flags (an application, the wand's grab, the file's animations: scene_pose_animate());
 * every node draws with scene_pose_models(). Plain values: equal poses give every node
 * the same matrices bit for bit. No GL, no store (cluster/scene_keys.h maps a pose to
 * parameter-store keys). */
#ifndef CAVELIGHT_SCENE_POSE_H
#define CAVELIGHT_SCENE_POSE_H

#include <stdint.h>

#include "scene/scene.h"

typedef struct scene_pose {
    int count;                              /* the scene's object_count */
    float offset[SCENE_MAX_OBJECTS][16];    /* column-major */
    int32_t visible[SCENE_MAX_OBJECTS];     /* 0 hides the object and its descendants */
} scene_pose;

/* Every offset identity, every object visible. */
void scene_pose_rest(const scene *s, scene_pose *p);
/* Each object's model matrix (column-major) and whether it is shown (1) or hidden (0).
 * model and shown hold s->object_count entries. */
void scene_pose_models(const scene *s, const scene_pose *p, float (*model)[16], uint8_t *shown);
/* The offsets of the animated objects at time t seconds (the animations loop over
 * s->anim_duration; t < 0 is 0); objects without channels keep p's offsets. The file's
 * keyframes replace the node's rest translation, rotation or scale; between keys linear
 * (rotations: shortest-arc slerp), STEP holds a key. Returns how many objects it set. */
int scene_pose_animate(const scene *s, double t, scene_pose *p);
/* 1 when object o (or an ancestor) differs between a and b in offset or visibility: what
 * moved between two frames. */
int scene_pose_object_changed(const scene *s, const scene_pose *a, const scene_pose *b, int o);

#endif
