/* scene_transform: where a scene stands in a CAVE (docs/cluster.md, "scene_transform").
 *
 * A model comes in its exporter's units, up axis and place; a CAVE wants metres, +y up and
 * the model where the viewer stands. The transform takes every point p of the file to
 *
 *     translation + R(rotation_deg) * (Y(yaw) * (scale * U(up) * p - anchor) + target)
 *
 * U turns a Z-up file to Y-up ((x, y, z) -> (x, z, -y)); the anchor is a point of the
 * scaled model that goes to the target, as `anchor` says:
 *   camera  the file's camera (scene.camera) to the viewer's untracked head (stage.home),
 *           turned about +y so that it looks at the front wall (-z);
 *   centre  the middle of the bounds' floor to the CAVE's origin (centre of its floor);
 *   none    the file's origin stays at the CAVE's origin;
 *   auto    (the default) camera when the scene has one, else centre.
 * `fit` instead scales the model to fit the box the screens span and stands it in the
 * middle of that box's floor (no `scale`, no `anchor` with it).
 *
 * Lights and cameras move with the model; a spot's or point light's intensity grows with
 * scale^2, so that the model looks lit as before (irradiance I / d^2 at the same place on
 * the model). Does not validate: the ranges below are the config parser's to check
 * (cluster_config.c), once. Does not load: scene_load_with() calls it. */
#ifndef CAVELIGHT_SCENE_TRANSFORM_H
#define CAVELIGHT_SCENE_TRANSFORM_H

#include <stddef.h>

#include "scene/scene.h"

typedef enum scene_up { SCENE_UP_Y = 0, SCENE_UP_Z, SCENE_UP_COUNT } scene_up;
typedef enum scene_anchor {
    SCENE_ANCHOR_AUTO = 0,
    SCENE_ANCHOR_CAMERA,
    SCENE_ANCHOR_CENTRE,
    SCENE_ANCHOR_NONE,
    SCENE_ANCHOR_COUNT
} scene_anchor;

/* "y", "z" and "auto", "camera", "centre", "none": the names configs and options use. */
extern const char *const scene_up_names[SCENE_UP_COUNT];
extern const char *const scene_anchor_names[SCENE_ANCHOR_COUNT];

/* The accepted ranges: scale in [MIN, MAX] (1e-6: micrometres, 1e6: thousands of km),
 * rotation_deg in [-360, 360], translation within +-TRANSLATION_MAX metres. */
#define SCENE_TRANSFORM_SCALE_MIN 1e-6
#define SCENE_TRANSFORM_SCALE_MAX 1e6
#define SCENE_TRANSFORM_TRANSLATION_MAX 1e4

/* Zero means the defaults: scale 1, up y, anchor auto, no fit, no rotation or translation. */
typedef struct scene_transform {
    float scale;            /* metres per file unit: 0.01 for centimetres; 0 = 1 */
    scene_up up;            /* the file's up axis */
    scene_anchor anchor;
    int fit;                /* 1: scale and anchor from the stage's box */
    float rotation_deg[3];  /* XYZ Euler degrees about the CAVE's origin, after the anchor */
    float translation[3];   /* metres, last */
} scene_transform;

/* Where the scene goes: CAVE space (metres, +y up, origin on the floor in the middle). */
typedef struct scene_stage {
    float home[3];                 /* the viewer's untracked head (observer.home) */
    float box_min[3], box_max[3];  /* the box every screen corner lies in */
} scene_stage;

/* Moves s (after scene_finish(); call scene_finish() again for its bounds). Returns 0, or
 * -1 with one line naming the field ("scene_transform.anchor: ...") when the scene or the
 * stage cannot take it: anchor camera without a camera, fit into a box without volume or
 * for a scene without extent. */
int scene_transform_apply(scene *s, const scene_transform *t, const scene_stage *stage,
                          char *err, size_t errlen);

#endif
