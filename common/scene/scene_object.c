/* scene_object: the scene's named movable parts and their animation channels (scene.h).
 * The builders only; where the parts are in a frame is scene_pose.c's. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

int scene_object_find(const scene *s, const char *name)
{
    for (int i = 0; i < s->object_count; i++)
        if (strcmp(s->objects[i].name, name) == 0)
            return i;
    return -1;
}

/* name made printable ASCII without spaces (a key name, a log line) and cut to fit, with
 * room left for a "#N" that makes it unique. */
static void clean_name(const char *name, char *out)
{
    size_t n = 0, room = SCENE_NAME_MAX - 5;
    for (const unsigned char *p = (const unsigned char *)(name ? name : ""); *p && n < room; p++)
        out[n++] = *p > 0x20 && *p < 0x7f ? (char)*p : '_';
    out[n] = '\0';
}

int scene_begin_object(scene *s, const char *name, int parent)
{
    if (s->object_count >= SCENE_MAX_OBJECTS)
        return -1;
    /* not xalloc: a scene file's count: its import refuses the file, never exits */
    scene_object *q = realloc(s->objects, (size_t)(s->object_count + 1) * sizeof *q);
    if (!q)
        return -1;
    s->objects = q;
    scene_object *o = &q[s->object_count];
    memset(o, 0, sizeof *o);
    char base[SCENE_NAME_MAX - 4];
    clean_name(name, base);
    if (!base[0])
        snprintf(base, sizeof base, "object%d", s->object_count);
    snprintf(o->name, sizeof o->name, "%s", base);
    for (int k = 2; scene_object_find(s, o->name) >= 0 && k < 1000; k++)
        snprintf(o->name, sizeof o->name, "%s#%d", base, k);
    o->parent = parent >= 0 && parent < s->object_count ? parent : -1;
    o->rest_rotation[3] = 1.0f;
    for (int a = 0; a < 3; a++)
        o->rest_scale[a] = 1.0f;
    memcpy(o->rest_world, identity, sizeof identity);
    s->adding_object = s->object_count + 1;
    return s->object_count++;
}

void scene_end_object(scene *s, int object)
{
    s->adding_object = object >= 0 && object < s->object_count ? object + 1 : 0;
}

int scene_add_anim_channel(scene *s, const scene_anim_channel *c)
{
    /* not xalloc: a scene file's count: its import refuses the file, never exits */
    scene_anim_channel *q = realloc(s->anim_channels, (s->anim_channel_count + 1) * sizeof *q);
    if (!q)
        return -1;
    s->anim_channels = q;
    q[s->anim_channel_count++] = *c;
    if (c->count && c->times[c->count - 1] > s->anim_duration)
        s->anim_duration = c->times[c->count - 1];
    return 0;
}
