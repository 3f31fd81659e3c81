/* scene_keys: a scene's objects (scene_pose.h) as parameter-store keys.
 *
 * Object NAME has two keys: "object.NAME" (matrix: its offset, identity as loaded) and
 * "object.NAME.visible" (i32: 1 shown, 0 hidden). The master and every node add them from
 * the scene each loaded (scene_keys_add()), so the same file gives the same keys, and the
 * schema's hash in HELLO covers them: a node that loaded another scene is refused. The
 * master writes a pose into its store (only the changed keys get the new version), a node
 * reads the frame's pose back. Not here: who moves objects (master/grab.h, an
 * application), how they are drawn (the renderer). */
#ifndef CAVELIGHT_SCENE_KEYS_H
#define CAVELIGHT_SCENE_KEYS_H

#include <stddef.h>

#include "cluster/params.h"
#include "scene/scene_pose.h"

typedef struct scene_keys {
    int count;                            /* the scene's object_count */
    int offset_key[SCENE_MAX_OBJECTS];
    int visible_key[SCENE_MAX_OBJECTS];
} scene_keys;

/* Adds the two keys of each object of s to the schema. Returns 0, or -1 with one line in
 * err (the store is full). */
int scene_keys_add(params_schema *schema, const scene *s, scene_keys *out, char *err, size_t errlen);
/* The frame's pose from the store into out (start it with scene_pose_rest()). */
void scene_keys_read(const params_store *store, const scene_keys *k, scene_pose *out);
/* The pose into the store: only values that differ are stamped. */
void scene_keys_write(params_store *store, const scene_keys *k, const scene_pose *p);

#endif
