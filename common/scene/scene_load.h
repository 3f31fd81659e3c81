/* scene_load: a scene by name or file, placed and lit (scene.h has the model).
 *
 *   scene_load_desc d = {.transform = &t, .stage = cave};  zero: as modelled, files only
 *   scene s;                                                from the scene file's folder
 *   if (scene_load_with("model.glb", &d, &s, err, sizeof err) != 0) ...
 *
 * In this order: the loader (a built-in scene's builder, or gltf_import() for .gltf/.glb),
 * scene_finish(), the transform (scene_transform.h) and scene_finish() again, then the
 * light for a scene with neither lights nor emitters (scene_default_light(), light_added).
 * Every program that loads a scene the cluster shares (master and nodes) calls it with the
 * same desc (cluster_config_scene_desc()), so all of them place it alike. Prints nothing:
 * the caller shows scene.warning and scene_light_added_note(). */
#ifndef CAVELIGHT_SCENE_LOAD_H
#define CAVELIGHT_SCENE_LOAD_H

#include <stddef.h>

#include "scene/scene.h"
#include "scene/scene_transform.h"

typedef struct scene_load_desc {
    const scene_transform *transform; /* NULL: the scene as modelled */
    scene_stage stage;                /* where the transform places it */
    int allow_outside_paths;          /* 1: glTF buffers and images from anywhere */
} scene_load_desc;

/* desc NULL: all zero. Returns 0, or -1 with one line in err (and *out empty). */
int scene_load_with(const char *path, const scene_load_desc *desc, scene *out, char *err,
                    size_t errlen);

#endif
