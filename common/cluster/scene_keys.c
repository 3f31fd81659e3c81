/* scene_keys: objects' offsets and visibility as store keys (scene_keys.h). */
#include "cluster/scene_keys.h"

#include <stdio.h>
#include <string.h>

int scene_keys_add(params_schema *schema, const scene *s, scene_keys *out, char *err, size_t errlen)
{
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const int32_t shown = 1;
    memset(out, 0, sizeof *out);
    for (int o = 0; o < s->object_count; o++) {
        char name[PARAMS_NAME_MAX], why[200];
        snprintf(name, sizeof name, "object.%s", s->objects[o].name);
        out->offset_key[o] = params_schema_add_key(schema, name, PARAMS_T_MAT4, 0, identity, why, sizeof why);
        snprintf(name, sizeof name, "object.%s.visible", s->objects[o].name);
        out->visible_key[o] = out->offset_key[o] < 0 ? -1 :
            params_schema_add_key(schema, name, PARAMS_T_I32, 0, &shown, why, sizeof why);
        if (out->visible_key[o] < 0) {
            snprintf(err, errlen, "scene object %s: %s", s->objects[o].name, why);
            return -1;
        }
        out->count = o + 1;
    }
    return 0;
}

void scene_keys_read(const params_store *store, const scene_keys *k, scene_pose *out)
{
    for (int o = 0; o < k->count; o++) {
        params_get(store, k->offset_key[o], out->offset[o], sizeof out->offset[o]);
        out->visible[o] = params_get_i32(store, k->visible_key[o]) != 0;
    }
}

void scene_keys_write(params_store *store, const scene_keys *k, const scene_pose *p)
{
    for (int o = 0; o < k->count; o++) {
        params_set_mat4(store, k->offset_key[o], p->offset[o]);
        params_set_i32(store, k->visible_key[o], p->visible[o] != 0);
    }
}
