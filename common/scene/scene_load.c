/* scene_load: the loaders by name, then placement and the automatic light (scene_load.h).
 * Kept apart from scene.c (the model and its builders) and scene_place.c (views and
 * lights), which it calls and which never call back. */
#include "scene/scene_load.h"

#include <stdio.h>
#include <string.h>

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    if (n < m)
        return 0;
    for (size_t i = 0; i < m; i++) {
        char c = s[n - m + i];
        if (c >= 'A' && c <= 'Z')
            c = (char)(c - 'A' + 'a');
        if (c != suffix[i])
            return 0;
    }
    return 1;
}

static const struct {
    const char *name;
    int (*build)(scene *s, char *err, size_t errlen);
} builtin[] = {
    {"default", scene_default_build},
    {"corridor", scene_corridor_build},
    {"doorway", scene_doorway_build},
    {"courtyard", scene_courtyard_build},
    {"arcades", scene_arcades_build},
    {"leak-lid", scene_leak_lid_build},
    {"leak-panel", scene_leak_panel_build},
    {"leak-wall", scene_leak_wall_build},
};

const char *scene_builtin_name(int i)
{
    return i >= 0 && i < (int)(sizeof builtin / sizeof builtin[0]) ? builtin[i].name : NULL;
}

/* The loader for path: a built-in scene's builder or the glTF importer. */
static int build(const char *path, const scene_load_desc *d, scene *out, char *err, size_t errlen)
{
    for (int i = 0; scene_builtin_name(i); i++)
        if (strcmp(path, scene_builtin_name(i)) == 0)
            return builtin[i].build(out, err, errlen);
    if (ends_with(path, ".gltf") || ends_with(path, ".glb"))
        return gltf_import(path, d->allow_outside_paths, out, err, errlen);
    char names[200] = "";
    for (int i = 0; scene_builtin_name(i); i++)
        snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", i ? ", " : "",
                 scene_builtin_name(i));
    snprintf(err, errlen, "scene %s: unknown format (give a .gltf or .glb file, or a "
             "built-in scene: %s)", path, names);
    return -1;
}

/* scene_finish(), then the transform and scene_finish() again, with "scene PATH: " errors. */
static int finish_and_place(const char *path, const scene_load_desc *d, scene *out, char *err,
                            size_t errlen)
{
    char why[300];
    int rc = scene_finish(out, why, sizeof why);
    if (rc == 0 && d->transform) {
        rc = scene_transform_apply(out, d->transform, &d->stage, why, sizeof why);
        if (rc == 0)
            rc = scene_finish(out, why, sizeof why);
    }
    if (rc != 0)
        snprintf(err, errlen, "scene %s: %s", path, why);
    return rc;
}

int scene_load_with(const char *path, const scene_load_desc *desc, scene *out, char *err,
                    size_t errlen)
{
    static const scene_load_desc none;
    const scene_load_desc *d = desc ? desc : &none;
    memset(out, 0, sizeof *out);
    int rc = build(path, d, out, err, errlen);
    if (rc == 0)
        rc = finish_and_place(path, d, out, err, errlen);
    if (rc != 0) {
        scene_free(out);
        return rc;
    }
    if (out->light_count == 0 && !scene_has_emitter(out)) {
        scene_light l;
        scene_default_light(out, &l);
        scene_add_light(out, &l);
        out->light_added = 1;
    }
    return 0;
}

int scene_load(const char *path, scene *out, char *err, size_t errlen)
{
    return scene_load_with(path, NULL, out, err, errlen);
}
